#include "rigidBodyState.H"
#include "spemModel.H"
#include "Time.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
namespace functionObjects
{
    defineTypeNameAndDebug(rigidBodyState, 0);
    addToRunTimeSelectionTable(functionObject, rigidBodyState, dictionary);
}
}


Foam::functionObjects::rigidBodyState::rigidBodyState
(
    const word& name,
    const Time& runTime,
    const dictionary& dict
)
:
    spemFunctionObject(name, runTime, dict),
    body_(-1)
{
    read(dict);
    writeColumns({"x", "y", "angle", "u", "v", "omega", "Fx", "Fy", "Mz"});
}


bool Foam::functionObjects::rigidBodyState::read(const dictionary& dict)
{
    writeFile::read(dict);
    bodyName_ = dict.get<word>("body");
    body_ = -1;
    return true;
}


Foam::label Foam::functionObjects::rigidBodyState::body()
{
    if (body_ < 0)
    {
        const rigidBodies& bodies = model().bodies();
        body_ = bodies.findBody(bodyName_);
        if (body_ < 0)
        {
            wordList names(bodies.size());
            forAll(bodies, b) names[b] = bodies[b].name();
            FatalErrorInFunction
                << "Function object " << name() << ": no rigid body "
                << bodyName_ << " in constant/rigidBodyProperties; bodies: "
                << names << exit(FatalError);
        }
    }
    return body_;
}


bool Foam::functionObjects::rigidBodyState::execute()
{
    body();
    return true;
}


bool Foam::functionObjects::rigidBodyState::write()
{
    const label b = body();
    if (!writeToFile()) return true;
    const spemModel& m = model();
    const rigidBody& rb = m.bodies()[b];
    scalar F[2], M;
    m.bodyLoad(b, F, M);

    OFstream& os = file();
    os  << time_.value() << tab << rb.position().x() << tab
        << rb.position().y() << tab << rb.angle() << tab
        << rb.velocity().x() << tab << rb.velocity().y() << tab
        << rb.angularVelocity() << tab << F[0] << tab << F[1] << tab << M
        << endl;
    return true;
}


// ************************************************************************* //
