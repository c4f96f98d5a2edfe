#include "rigidBodyShape.H"

#include <cmath>
#include <unordered_map>

namespace Foam
{
    defineTypeNameAndDebug(rigidBodyShape, 0);
    defineRunTimeSelectionTable(rigidBodyShape, dictionary);
}


// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * * //

namespace
{

using namespace Foam;

//- A closed loop of points ((X, Y) interleaved, either orientation) for ear
//  clipping: its orientation and a round-off scale for areas
class earClippingLoop
{
    const std::vector<scalar>& loop_;
    scalar sign_;
    scalar tol_;

public:

    explicit earClippingLoop(const std::vector<scalar>& loop)
    :
        loop_(loop)
    {
        const label n = size();

        // Orientation (shoelace) and a round-off scale for areas
        scalar twiceArea = 0, xMin = GREAT, xMax = -GREAT, yMin = GREAT,
            yMax = -GREAT;
        for (label i = 0; i < n; ++i)
        {
            const label j = (i + 1) % n;
            twiceArea += X(i)*Y(j) - X(j)*Y(i);
            xMin = std::min(xMin, X(i));
            xMax = std::max(xMax, X(i));
            yMin = std::min(yMin, Y(i));
            yMax = std::max(yMax, Y(i));
        }
        sign_ = twiceArea < 0 ? -1 : 1;
        tol_ =
            1e-12*(sqr(xMax - xMin) + sqr(yMax - yMin));
    }

    label size() const { return label(loop_.size()/2); }
    scalar X(const label i) const { return loop_[2*i]; }
    scalar Y(const label i) const { return loop_[2*i + 1]; }

    //- +1 if the loop is counter-clockwise, -1 if clockwise
    scalar sign() const { return sign_; }

    //- Areas within this of zero are round-off
    scalar tol() const { return tol_; }

    //- Twice the signed area of (a, b, c), positive if counter-clockwise
    //  along the loop's own orientation
    scalar turn(const label a, const label b, const label c) const
    {
        return sign_
           *(
                (X(b) - X(a))*(Y(c) - Y(a)) - (Y(b) - Y(a))*(X(c) - X(a))
            );
    }

    //- True if no remaining vertex other than a, b, c lies in or on the
    //  triangle (a, b, c)
    bool isEar
    (
        const std::vector<label>& remaining,
        const label a,
        const label b,
        const label c
    ) const
    {
        const label m = label(remaining.size());
        bool ear = true;
        for (label q = 0; q < m && ear; ++q)
        {
            const label p = remaining[q];
            if (p == a || p == b || p == c) continue;
            ear =
                turn(a, b, p) < -tol_ || turn(b, c, p) < -tol_
             || turn(c, a, p) < -tol_;
        }
        return ear;
    }

    //- Append the triangle (a, b, c), counter-clockwise in the plane
    //  whatever the loop's orientation
    void emit
    (
        const label a,
        const label b,
        const label c,
        std::vector<label>& triangles
    ) const
    {
        triangles.push_back(a);
        triangles.push_back(sign_ > 0 ? b : c);
        triangles.push_back(sign_ > 0 ? c : b);
    }
};

} // End anonymous namespace


void Foam::bodyWallParticles::append
(
    const vector2D& position,
    const vector2D& surfacePoint,
    const vector2D& normal,
    const scalar depth,
    const label layer
)
{
    positions.push_back(position.x());
    positions.push_back(position.y());
    surfacePoints.push_back(surfacePoint.x());
    surfacePoints.push_back(surfacePoint.y());
    normals.push_back(normal.x());
    normals.push_back(normal.y());
    depths.push_back(depth);
    layers.push_back(layer);
}


Foam::label Foam::rigidBodyShape::nIntervals
(
    const scalar length,
    const scalar spacing
)
{
    // Longest interval allowed, in spacings: a point half-way between two
    // layers and two particles is then within sqrt(0.5^2 + 0.55^2) = 0.74
    // spacing of one
    constexpr scalar maxStretch = 1.1;

    const label nRound = label(std::round(length/spacing));
    const label nCapped = label(std::ceil(length/(maxStretch*spacing)));
    return std::max(label(1), std::max(nRound, nCapped));
}


Foam::bodyWallParticles Foam::rigidBodyShape::keepApart
(
    const bodyWallParticles& candidates,
    const scalar minDistance
)
{
    // Bins of size minDistance: a neighbour closer than minDistance is in
    // the same or an adjacent bin
    auto binOf = [minDistance](const scalar v)
    {
        return static_cast<long long>(std::floor(v/minDistance));
    };
    auto key = [](const long long i, const long long j)
    {
        return (static_cast<unsigned long long>(i) << 32)
            ^ (static_cast<unsigned long long>(j) & 0xffffffffULL);
    };

    std::unordered_map<unsigned long long, std::vector<label>> bins;
    bodyWallParticles kept;
    const scalar minDistance2 = sqr(minDistance);

    for (label p = 0; p < candidates.size(); ++p)
    {
        const scalar x = candidates.positions[2*p];
        const scalar y = candidates.positions[2*p + 1];
        const long long i = binOf(x), j = binOf(y);

        bool tooClose = false;
        for (long long di = -1; di <= 1 && !tooClose; ++di)
        {
            for (long long dj = -1; dj <= 1 && !tooClose; ++dj)
            {
                const auto found = bins.find(key(i + di, j + dj));
                if (found == bins.end())
                {
                    continue;
                }
                for (const label q : found->second)
                {
                    if
                    (
                        sqr(kept.positions[2*q] - x)
                      + sqr(kept.positions[2*q + 1] - y)
                      < minDistance2
                    )
                    {
                        tooClose = true;
                        break;
                    }
                }
            }
        }
        if (tooClose)
        {
            continue;
        }

        bins[key(i, j)].push_back(kept.size());
        kept.append
        (
            vector2D(x, y),
            vector2D
            (
                candidates.surfacePoints[2*p],
                candidates.surfacePoints[2*p + 1]
            ),
            vector2D(candidates.normals[2*p], candidates.normals[2*p + 1]),
            candidates.depths[p],
            candidates.layers[p]
        );
    }

    return kept;
}


std::vector<Foam::label> Foam::rigidBodyShape::triangulate
(
    const std::vector<scalar>& loop
)
{
    const earClippingLoop polygon(loop);
    const label n = polygon.size();
    const scalar tol = polygon.tol();

    std::vector<label> remaining(n);
    for (label i = 0; i < n; ++i) remaining[i] = i;

    std::vector<label> triangles;
    triangles.reserve(3*std::max(label(0), n - 2));

    while (remaining.size() > 3)
    {
        const label m = label(remaining.size());
        bool clipped = false;
        for (label k = 0; k < m && !clipped; ++k)
        {
            const label a = remaining[(k + m - 1) % m];
            const label b = remaining[k];
            const label c = remaining[(k + 1) % m];
            const scalar t = polygon.turn(a, b, c);
            if (std::abs(t) <= tol)
            {
                // b on a straight run (or a spike): drop it, no triangle
                remaining.erase(remaining.begin() + k);
                clipped = true;
                break;
            }
            if (t < 0) continue;    // reflex vertex

            // An ear if no other vertex lies in or on the triangle
            if (!polygon.isEar(remaining, a, b, c)) continue;
            polygon.emit(a, b, c, triangles);
            remaining.erase(remaining.begin() + k);
            clipped = true;
        }
        if (!clipped)
        {
            FatalErrorInFunction
                << "The polygon of " << n << " points is not simple: no ear"
                << " left with " << m << " points" << exit(FatalError);
        }
    }
    if (remaining.size() == 3)
    {
        const label a = remaining[0], b = remaining[1], c = remaining[2];
        if (std::abs(polygon.turn(a, b, c)) > tol)
        {
            polygon.emit(a, b, c, triangles);
        }
    }
    return triangles;
}
