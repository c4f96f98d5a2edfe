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
    element_(-1),
    weights_{0, 0, 0}
{
    read(dict);
    writeColumns({"Dx", "Dy"});
}


bool Foam::functionObjects::pointDisplacement::read(const dictionary& dict)
{
    writeFile::read(dict);
    readPoint(dict, "point", px_, py_);
    element_ = -1;
    return true;
}


bool Foam::functionObjects::pointDisplacement::write()
{
    const elementModel& em = elements();
    if (element_ < 0)
    {
        element_ = em.locate(px_, py_, true, weights_);
        if (element_ < 0)
        {
            FatalErrorInFunction
                << "Function object " << name() << ": point (" << px_ << ' '
                << py_ << ") is outside the mesh" << exit(FatalError);
        }
    }
    const label* n = &em.elementNodes()[3*element_];
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
