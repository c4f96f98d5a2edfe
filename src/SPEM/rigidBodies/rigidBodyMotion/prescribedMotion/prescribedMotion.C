#include "prescribedMotion.H"
#include "Tuple2.H"
#include "vector.H"
#include "addToRunTimeSelectionTable.H"

#include <algorithm>

namespace Foam
{
    defineTypeNameAndDebug(prescribedMotion, 0);
    addToRunTimeSelectionTable(rigidBodyMotion, prescribedMotion, dictionary);
}


Foam::prescribedMotion::prescribedMotion
(
    const dictionary& dict,
    const rigidBodyShape& shape
)
:
    rigidBodyMotion(dict, shape),
    omega_
    (
        getCheckedOrDefault
        (
            dict, "angularVelocity", 0, saneRange::angularVelocity
        )
    )
{
    const bool constant = dict.found("velocity", keyType::LITERAL);
    const bool table = dict.found("velocityTable", keyType::LITERAL);
    if (constant == table)
    {
        FatalIOErrorInFunction(dict)
            << "Give one of the entries 'velocity' (constant) and"
            << " 'velocityTable' in " << dict.name() << ", "
            << (constant ? "not both" : "none given") << exit(FatalIOError);
    }

    if (constant)
    {
        times_.push_back(0);
        velocities_.push_back(get2D(dict, "velocity", saneRange::speed));
    }
    else
    {
        const List<Tuple2<scalar, vector>> entries
        (
            dict.get<List<Tuple2<scalar, vector>>>("velocityTable")
        );
        if (entries.empty())
        {
            FatalIOErrorInFunction(dict)
                << "Entry 'velocityTable' of " << dict.name()
                << " is empty" << exit(FatalIOError);
        }
        for (const Tuple2<scalar, vector>& e : entries)
        {
            // Written to reject NaN as well
            if (!times_.empty() && !(e.first() > times_.back()))
            {
                FatalIOErrorInFunction(dict)
                    << "Times of entry 'velocityTable' of " << dict.name()
                    << " must increase: " << e.first() << " follows "
                    << times_.back() << exit(FatalIOError);
            }
            const vector& v = e.second();
            const scalar speed =
                std::sqrt(sqr(v.x()) + sqr(v.y()) + sqr(v.z()));
            if (!std::isfinite(e.first()) || !saneRange::speed.holds(speed))
            {
                outOfRange
                (
                    dict, "velocityTable",
                    std::isfinite(e.first()) ? speed : e.first(),
                    saneRange::speed,
                    "a time or a speed of the table (at time "
                  + std::to_string(e.first()) + ")"
                );
            }
            times_.push_back(e.first());
            velocities_.push_back(vector2D(v.x(), v.y()));
        }
    }

    velocity_ = velocityAt(0);
    angularVelocity_ = omega_;
}


Foam::wordList Foam::prescribedMotion::keywords() const
{
    wordList words(rigidBodyMotion::keywords());
    words.append(wordList({"velocity", "velocityTable", "angularVelocity"}));
    return words;
}


Foam::vector2D Foam::prescribedMotion::velocityAt(const scalar t) const
{
    if (t <= times_.front())
    {
        return velocities_.front();
    }
    if (t >= times_.back())
    {
        return velocities_.back();
    }
    // First time after t; t lies in [times_[i - 1], times_[i])
    const label i = label
    (
        std::upper_bound(times_.begin(), times_.end(), t) - times_.begin()
    );
    const scalar w = (t - times_[i - 1])/(times_[i] - times_[i - 1]);
    return (1 - w)*velocities_[i - 1] + w*velocities_[i];
}


void Foam::prescribedMotion::updateVelocity
(
    const scalar time,
    const scalar deltaT,
    const vector2D&
)
{
    velocity_ = velocityAt(time + 0.5*deltaT);
    angularVelocity_ = omega_;
}
