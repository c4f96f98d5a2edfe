#include "freeMotion.H"
#include "rigidBodyShape.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
    defineTypeNameAndDebug(freeMotion, 0);
    addToRunTimeSelectionTable(rigidBodyMotion, freeMotion, dictionary);
}


Foam::freeMotion::freeMotion
(
    const dictionary& dict,
    const rigidBodyShape& shape
)
:
    rigidBodyMotion(dict, shape),
    mass_(getChecked(dict, "mass", saneRange::bodyMass)),
    momentOfInertia_(0),
    held_{false, false, false}
{
    // A uniform body: I = (m/A) integral of |X - c|^2 over the shape
    momentOfInertia_ = getCheckedOrDefault
    (
        dict, "momentOfInertia",
        mass_/shape.area()*shape.polarMomentOfArea(position0()),
        saneRange::momentOfInertia
    );
    if (!(momentOfInertia_ > 0))
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'momentOfInertia " << momentOfInertia_ << "' of "
            << dict.name() << " must be positive" << exit(FatalIOError);
    }

    velocity_ = getOrDefault2D
    (
        dict, "initialVelocity", vector2D::zero, saneRange::speed
    );
    angularVelocity_ = getCheckedOrDefault
    (
        dict, "initialAngularVelocity", 0, saneRange::angularVelocity
    );

    const wordList constraints
    (
        dict.getOrDefault<wordList>("constraints", wordList())
    );
    const wordList dofNames({"x", "y", "rotation"});
    for (const word& name : constraints)
    {
        const label dof = dofNames.find(name);
        if (dof < 0)
        {
            FatalIOErrorInFunction(dict)
                << "Unknown degree of freedom '" << name
                << "' in entry 'constraints' of " << dict.name() << nl
                << "Valid ones: " << dofNames << exit(FatalIOError);
        }
        held_[dof] = true;
    }
}


Foam::wordList Foam::freeMotion::keywords() const
{
    wordList words(rigidBodyMotion::keywords());
    words.append
    (
        wordList
        ({
            "mass",
            "momentOfInertia",
            "initialVelocity",
            "initialAngularVelocity",
            "constraints"
        })
    );
    return words;
}


void Foam::freeMotion::updateVelocity
(
    const scalar,
    const scalar deltaT,
    const vector2D& gravity
)
{
    // Span from the previous half step (t = 0 before the first step: a
    // half kick) to the next one
    const scalar span = 0.5*(previousDeltaT_ + deltaT);

    if (!held_[0])
    {
        velocity_.x() += span*(force_.x()/mass_ + gravity.x());
    }
    if (!held_[1])
    {
        velocity_.y() += span*(force_.y()/mass_ + gravity.y());
    }
    if (!held_[2])
    {
        angularVelocity_ += span*moment_/momentOfInertia_;
    }
}


Foam::scalar Foam::freeMotion::inverseMassAlong
(
    const vector2D& p,
    const vector2D& n
) const
{
    const vector2D r = p - position();
    const scalar rxn = r.x()*n.y() - r.y()*n.x();
    return
        (held_[0] ? 0 : n.x()*n.x()/mass_)
      + (held_[1] ? 0 : n.y()*n.y()/mass_)
      + (held_[2] ? 0 : rxn*rxn/momentOfInertia_);
}


void Foam::freeMotion::applyImpulse(const vector2D& p, const vector2D& J)
{
    const vector2D r = p - position();
    if (!held_[0]) velocity_.x() += J.x()/mass_;
    if (!held_[1]) velocity_.y() += J.y()/mass_;
    if (!held_[2])
    {
        angularVelocity_ += (r.x()*J.y() - r.y()*J.x())/momentOfInertia_;
    }
}


void Foam::freeMotion::translate(const vector2D& d)
{
    placement_.set
    (
        placement_.centre()
      + vector2D(held_[0] ? 0 : d.x(), held_[1] ? 0 : d.y()),
        placement_.angle()
    );
}


// ************************************************************************* //
