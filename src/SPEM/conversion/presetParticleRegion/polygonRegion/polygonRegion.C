#include "polygonRegion.H"
#include "checkKeywords.H"
#include "vectorList.H"
#include "addToRunTimeSelectionTable.H"

#include <algorithm>
#include <cmath>

namespace Foam
{
    defineTypeNameAndDebug(polygonRegion, 0);
    addToRunTimeSelectionTable(presetParticleRegion, polygonRegion, dictionary);
}


Foam::polygonRegion::polygonRegion
(
    const word& name,
    const dictionary& dict,
    const triMesh& mesh,
    const bodySurfaces& bodies
)
:
    presetParticleRegion(name)
{
    checkKeywords(dict, {"type", "points"});

    const vectorList points(dict.get<vectorList>("points"));
    if (points.size() < 3)
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'points' of " << dict.name() << " has "
            << points.size() << " points: a polygon needs at least 3"
            << exit(FatalIOError);
    }

    points_.reserve(2*points.size());
    xMin_ = xMax_ = points[0].x();
    yMin_ = yMax_ = points[0].y();
    for (const vector& p : points)
    {
        points_.push_back(p.x());
        points_.push_back(p.y());
        xMin_ = std::min(xMin_, p.x());
        xMax_ = std::max(xMax_, p.x());
        yMin_ = std::min(yMin_, p.y());
        yMax_ = std::max(yMax_, p.y());
    }

    // Shoelace area, against collinear points (and NaN) that enclose nothing
    const label n = points.size();
    scalar twiceArea = 0;
    for (label i = 0, j = n - 1; i < n; j = i++)
    {
        twiceArea +=
            points_[2*j]*points_[2*i + 1] - points_[2*i]*points_[2*j + 1];
    }
    const scalar extent = std::max(xMax_ - xMin_, yMax_ - yMin_);
    if (!(std::abs(twiceArea) > SMALL*extent*extent))
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'points' of " << dict.name()
            << " encloses no area: " << points << exit(FatalIOError);
    }
}


bool Foam::polygonRegion::contains(const scalar x, const scalar y) const
{
    if (x < xMin_ || x > xMax_ || y < yMin_ || y > yMax_)
    {
        return false;
    }

    // Crossing number of the ray from (x, y) towards +x: each edge that
    // straddles the line through y (half-open in y, so a vertex on it is
    // counted once) and meets it right of x toggles the inside flag
    const label n = label(points_.size()/2);
    bool inside = false;
    for (label i = 0, j = n - 1; i < n; j = i++)
    {
        const scalar xi = points_[2*i], yi = points_[2*i + 1];
        const scalar xj = points_[2*j], yj = points_[2*j + 1];
        if ((yi > y) != (yj > y) && x < xi + (xj - xi)*(y - yi)/(yj - yi))
        {
            inside = !inside;
        }
    }
    return inside;
}
