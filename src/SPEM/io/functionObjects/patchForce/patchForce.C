#include "patchForce.H"
#include "Time.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
namespace functionObjects
{
    defineTypeNameAndDebug(patchForce, 0);
    addToRunTimeSelectionTable(functionObject, patchForce, dictionary);
}
}


Foam::functionObjects::patchForce::patchForce
(
    const word& name,
    const Time& runTime,
    const dictionary& dict
)
:
    spemFunctionObject(name, runTime, dict)
{
    read(dict);
    writeColumns({"Fx", "Fy"});
}


bool Foam::functionObjects::patchForce::read(const dictionary& dict)
{
    writeFile::read(dict);
    const wordList patches = dict.get<wordList>("patches");
    const triMesh& mesh = model().mesh();
    segments_.clear();
    for (const word& p : patches)
    {
        const label pi = mesh.findPatch(p);
        if (pi < 0)
        {
            FatalIOErrorInFunction(dict)
                << "Unknown patch " << p << " in 'patches'. Mesh patches: "
                << mesh.patchNames() << exit(FatalIOError);
        }
        for (label s = 0; s < mesh.nSegments(); ++s)
        {
            if (mesh.segmentPatch()[s] == pi) segments_.push_back(s);
        }
    }
    return true;
}


bool Foam::functionObjects::patchForce::write()
{
    const spemModel& m = model();
    const elementModel& em = m.elements();
    const triMesh& mesh = m.mesh();
    const std::vector<scalar>& stress = em.domainStress();

    scalar F[2] = {0, 0};
    for (const label s : segments_)
    {
        const label k = em.segmentDomain()[s];
        // The region of the domain decides the configuration
        label r = 0;
        while (k >= em.regions()[r].domainEnd) ++r;
        const std::vector<scalar>& x =
            em.material(r).isFluid() ? em.positions() : em.referencePositions();
        const label a = mesh.segments()[2*s], b = mesh.segments()[2*s + 1];
        // Outward normal times length: the element lies left of a -> b
        const scalar nA[2] =
        {
            x[2*b + 1] - x[2*a + 1],
            -(x[2*b] - x[2*a])
        };
        const scalar* P = &stress[4*k];
        F[0] -= P[0]*nA[0] + P[1]*nA[1];
        F[1] -= P[2]*nA[0] + P[3]*nA[1];
    }
    if (writeToFile())
    {
        file() << time_.value() << tab << F[0] << tab << F[1] << endl;
    }
    return true;
}
