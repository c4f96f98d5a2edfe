#include "circleShape.H"
#include "addToRunTimeSelectionTable.H"
#include "saneRanges.H"
#include "mathematicalConstants.H"

#include <cmath>

namespace Foam
{
    defineTypeNameAndDebug(circleShape, 0);
    addToRunTimeSelectionTable(rigidBodyShape, circleShape, dictionary);
}


Foam::circleShape::circleShape(const dictionary& dict)
:
    rigidBodyShape(),
    centre_(Zero),
    radius_(getChecked(dict, "radius", saneRange::radius))
{
    const vector centre(getCheckedVector(dict, "centre", saneRange::length));
    centre_ = vector2D(centre.x(), centre.y());
}


Foam::wordList Foam::circleShape::keywords() const
{
    return wordList({"centre", "radius"});
}


Foam::scalar Foam::circleShape::area() const
{
    return constant::mathematical::pi*sqr(radius_);
}


Foam::scalar Foam::circleShape::polarMomentOfArea(const vector2D& p) const
{
    // pi R^4/2 about the centre, parallel-axis shift to p
    return area()*(0.5*sqr(radius_) + magSqr(centre_ - p));
}


bool Foam::circleShape::contains(const scalar X, const scalar Y) const
{
    return sqr(X - centre_.x()) + sqr(Y - centre_.y()) < sqr(radius_);
}


Foam::scalar Foam::circleShape::signedDistance
(
    const scalar X,
    const scalar Y
) const
{
    return std::hypot(X - centre_.x(), Y - centre_.y()) - radius_;
}


Foam::scalar Foam::circleShape::signedDistance
(
    const scalar X,
    const scalar Y,
    vector2D& closestPoint,
    vector2D& normal
) const
{
    const vector2D r(X - centre_.x(), Y - centre_.y());
    const scalar magR = std::hypot(r.x(), r.y());

    // Every direction is closest from the centre: take +x
    normal = magR > 0 ? r/magR : vector2D(1, 0);
    closestPoint = centre_ + radius_*normal;
    return magR - radius_;
}


Foam::boundBox Foam::circleShape::bounds
(
    const rigidTransform2D& placement
) const
{
    const vector2D c = placement.toCurrent(centre_);
    return boundBox
    (
        point(c.x() - radius_, c.y() - radius_, 0),
        point(c.x() + radius_, c.y() + radius_, 0)
    );
}


Foam::bodyWallParticles Foam::circleShape::wallParticles
(
    const scalar spacing,
    const label nLayers
) const
{
    bodyWallParticles particles;
    const scalar twoPi = constant::mathematical::twoPi;

    for (label layer = 0; layer < nLayers; ++layer)
    {
        const scalar depth = (layer + 0.5)*spacing;
        const scalar ringRadius = radius_ - depth;

        // A ring this small would crowd its particles: one at the centre
        if (ringRadius < 0.5*spacing)
        {
            particles.append
            (
                centre_,
                centre_ + vector2D(radius_, 0),
                vector2D(1, 0),
                radius_,
                layer
            );
            break;
        }

        const label n = nIntervals(twoPi*ringRadius, spacing);
        for (label i = 0; i < n; ++i)
        {
            const scalar angle = twoPi*i/n;
            const vector2D normal(std::cos(angle), std::sin(angle));
            particles.append
            (
                centre_ + ringRadius*normal,
                centre_ + radius_*normal,
                normal,
                depth,
                layer
            );
        }
    }

    // A ring a little over spacing/2 from the centre particle of the next
    // layer would not be: drop such crowding
    return keepApart(particles, 0.5*spacing);
}


std::vector<Foam::scalar> Foam::circleShape::surfacePoints
(
    const scalar spacing
) const
{
    const scalar twoPi = constant::mathematical::twoPi;
    const label n =
        std::max(label(3), label(std::ceil(twoPi*radius_/spacing)));

    std::vector<scalar> points;
    points.reserve(2*n);
    for (label i = 0; i < n; ++i)
    {
        const scalar angle = twoPi*i/n;
        points.push_back(centre_.x() + radius_*std::cos(angle));
        points.push_back(centre_.y() + radius_*std::sin(angle));
    }
    return points;
}
