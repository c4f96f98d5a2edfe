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
    spemFunctionObject(name, runTime, dict, needs::elements)
{
    read(dict);
    writeColumns({"Fx", "Fy"});
}


bool Foam::functionObjects::patchForce::read(const dictionary& dict)
{
    writeFile::read(dict);
    const wordList patches = dict.get<wordList>("patches");
    const triMesh& mesh = model().mesh();
    std::vector<bool> selected(mesh.nPoints(), false);
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
            if (mesh.segmentPatch()[s] != pi) continue;
            selected[mesh.segments()[2*s]] = true;
            selected[mesh.segments()[2*s + 1]] = true;
        }
    }
    nodes_.clear();
    for (label n = 0; n < mesh.nPoints(); ++n)
    {
        if (selected[n]) nodes_.push_back(n);
    }
    return true;
}


bool Foam::functionObjects::patchForce::write()
{
    const std::vector<scalar>& R = elements().constraintReactions();
    scalar F[2] = {0, 0};
    for (const label n : nodes_)
    {
        F[0] -= R[2*n];
        F[1] -= R[2*n + 1];
    }
    if (writeToFile())
    {
        file() << time_.value() << tab << F[0] << tab << F[1] << endl;
    }
    return true;
}
