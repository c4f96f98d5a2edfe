#include "rigidBodyMotion.H"
#include "rigidBodyShape.H"
#include "primitiveEntry.H"

namespace Foam
{
    defineTypeNameAndDebug(rigidBodyMotion, 0);
    defineRunTimeSelectionTable(rigidBodyMotion, dictionary);
}


namespace
{

// dictionary::set(key, value) goes through text at the default precision
// (6 digits); entries made of number tokens keep every bit for a restart

//- Entry key: the scalar value, exactly
void setExact(Foam::dictionary& dict, const Foam::word& key, const Foam::scalar value)
{
    dict.set(new Foam::primitiveEntry(key, Foam::token(value)));
}

//- Entry key: the OpenFOAM vector (x y 0) of v, exactly
void setExact(Foam::dictionary& dict, const Foam::word& key, const Foam::vector2D& v)
{
    Foam::List<Foam::token> tokens(5);
    tokens[0] = Foam::token::BEGIN_LIST;
    tokens[1] = Foam::token(v.x());
    tokens[2] = Foam::token(v.y());
    tokens[3] = Foam::token(Foam::scalar(0));
    tokens[4] = Foam::token::END_LIST;
    dict.set(new Foam::primitiveEntry(key, std::move(tokens)));
}

} // End anonymous namespace


Foam::vector2D Foam::rigidBodyMotion::get2D
(
    const dictionary& dict,
    const word& key,
    const valueRange& range
)
{
    const vector v(getCheckedVector(dict, key, range));
    return vector2D(v.x(), v.y());
}


Foam::vector2D Foam::rigidBodyMotion::getOrDefault2D
(
    const dictionary& dict,
    const word& key,
    const vector2D& deflt,
    const valueRange& range
)
{
    return
        dict.found(key, keyType::LITERAL) ? get2D(dict, key, range) : deflt;
}


Foam::rigidBodyMotion::rigidBodyMotion
(
    const dictionary& dict,
    const rigidBodyShape& shape
)
:
    placement_
    (
        getOrDefault2D
        (
            dict, "centreOfMass", shape.centroid(), saneRange::length
        )
    ),
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
    setExact(dict, "position", position());
    setExact(dict, "angle", angle());
    setExact(dict, "velocity", velocity_);
    setExact(dict, "angularVelocity", angularVelocity_);
    setExact(dict, "force", force_);
    setExact(dict, "moment", moment_);
    setExact(dict, "previousDeltaT", previousDeltaT_);
}


void Foam::rigidBodyMotion::readState(const dictionary& dict)
{
    // A restart state: each value finite and sane, as the dictionaries
    placement_.set
    (
        get2D(dict, "position", saneRange::length),
        getChecked(dict, "angle", saneRange::stateValue)
    );
    velocity_ = get2D(dict, "velocity", saneRange::speed);
    angularVelocity_ =
        getChecked(dict, "angularVelocity", saneRange::angularVelocity);
    force_ = get2D(dict, "force", saneRange::stateMagnitude);
    moment_ = getChecked(dict, "moment", saneRange::stateValue);
    previousDeltaT_ = getChecked(dict, "previousDeltaT", saneRange::stateMagnitude);
}
