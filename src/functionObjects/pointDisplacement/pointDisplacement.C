#include "pointDisplacement.H"
#include "Time.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
namespace functionObjects
{
    defineTypeNameAndDebug(pointDisplacement, 0);
    addToRunTimeSelectionTable(functionObject, pointDisplacement, dictionary);
}
}


Foam::functionObjects::pointDisplacement::pointDisplacement
(
    const word& name,
    const Time& runTime,
    const dictionary& dict
)
:
    spemFunctionObject(name, runTime, dict, needs::elements),
    px_(0),
    py_(0),
    nodes_{-1, -1, -1},
    weights_{0, 0, 0}
{
    read(dict);
    writeColumns({"Dx", "Dy"});
}


bool Foam::functionObjects::pointDisplacement::read(const dictionary& dict)
{
    writeFile::read(dict);
    readPoint(dict, "point", px_, py_);
    nodes_[0] = -1;
    return true;
}


bool Foam::functionObjects::pointDisplacement::write()
{
    const elementModel& em = elements();
    if (nodes_[0] < 0)
    {
        const label element = em.locate(px_, py_, true, weights_);
        if (element < 0)
        {
            FatalErrorInFunction
                << "Function object " << name() << ": point (" << px_ << ' '
                << py_ << ") is outside the mesh" << exit(FatalError);
        }
        for (label a = 0; a < 3; ++a)
        {
            nodes_[a] = em.elementNodes()[3*element + a];
        }
    }
    const label* n = nodes_;
    const std::vector<scalar>& x = em.positions();
    const std::vector<scalar>& X = em.referencePositions();
    scalar D[2] = {0, 0};
    for (label a = 0; a < 3; ++a)
    {
        for (label i = 0; i < 2; ++i)
        {
            D[i] += weights_[a]*(x[2*n[a] + i] - X[2*n[a] + i]);
        }
    }
    if (writeToFile())
    {
        file() << time_.value() << tab << D[0] << tab << D[1] << endl;
    }
    return true;
}
