#include "rigidBodyShape.H"

#include <cmath>
#include <unordered_map>

namespace Foam
{
    defineTypeNameAndDebug(rigidBodyShape, 0);
    defineRunTimeSelectionTable(rigidBodyShape, dictionary);
}


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
