#include "rigidBodyMotion.H"
#include "rigidBodyShape.H"

namespace Foam
{
    defineTypeNameAndDebug(rigidBodyMotion, 0);
    defineRunTimeSelectionTable(rigidBodyMotion, dictionary);
}


namespace
{

//- An OpenFOAM vector (z = 0) from (x, y)
Foam::vector to3D(const Foam::vector2D& v)
{
    return Foam::vector(v.x(), v.y(), 0);
}

} // End anonymous namespace


Foam::vector2D Foam::rigidBodyMotion::get2D
(
    const dictionary& dict,
    const word& key
)
{
    const vector v(dict.get<vector>(key));
    return vector2D(v.x(), v.y());
}


Foam::vector2D Foam::rigidBodyMotion::getOrDefault2D
(
    const dictionary& dict,
    const word& key,
    const vector2D& deflt
)
{
    return dict.found(key, keyType::LITERAL) ? get2D(dict, key) : deflt;
}


Foam::rigidBodyMotion::rigidBodyMotion
(
    const dictionary& dict,
    const rigidBodyShape& shape
)
:
    placement_(getOrDefault2D(dict, "centreOfMass", shape.centroid())),
    velocity_(Zero),
    angularVelocity_(0),
    force_(Zero),
    moment_(0),
    previousDeltaT_(0)
{}


Foam::wordList Foam::rigidBodyMotion::keywords() const
{
    return wordList({"centreOfMass"});
}


void Foam::rigidBodyMotion::advance
(
    const scalar time,
    const scalar deltaT,
    const scalar Fx,
    const scalar Fy,
    const scalar Mz,
    const scalar gx,
    const scalar gy
)
{
    force_ = vector2D(Fx, Fy);
    moment_ = Mz;

    updateVelocity(time, deltaT, vector2D(gx, gy));

    placement_.set
    (
        placement_.centre() + deltaT*velocity_,
        placement_.angle() + deltaT*angularVelocity_
    );
    previousDeltaT_ = deltaT;
}


void Foam::rigidBodyMotion::writeState(dictionary& dict) const
{
    dict.set("position", to3D(position()));
    dict.set("angle", angle());
    dict.set("velocity", to3D(velocity_));
    dict.set("angularVelocity", angularVelocity_);
    dict.set("force", to3D(force_));
    dict.set("moment", moment_);
    dict.set("previousDeltaT", previousDeltaT_);
}


void Foam::rigidBodyMotion::readState(const dictionary& dict)
{
    placement_.set(get2D(dict, "position"), dict.get<scalar>("angle"));
    velocity_ = get2D(dict, "velocity");
    angularVelocity_ = dict.get<scalar>("angularVelocity");
    force_ = get2D(dict, "force");
    moment_ = dict.get<scalar>("moment");
    previousDeltaT_ = dict.get<scalar>("previousDeltaT");
}
