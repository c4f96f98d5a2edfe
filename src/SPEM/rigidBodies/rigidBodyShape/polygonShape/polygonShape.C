#include "polygonShape.H"
#include "vectorList.H"
#include "addToRunTimeSelectionTable.H"
#include "saneRanges.H"

#include <algorithm>
#include <cmath>

namespace Foam
{
    defineTypeNameAndDebug(polygonShape, 0);
    addToRunTimeSelectionTable(rigidBodyShape, polygonShape, dictionary);
}


// * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * * * //

namespace
{

using namespace Foam;

//- z-component of a x b
inline scalar cross2D(const vector2D& a, const vector2D& b)
{
    return a.x()*b.y() - a.y()*b.x();
}

//- Twice the signed area of the triangle a b c (> 0 counter-clockwise)
inline scalar orientation(const vector2D& a, const vector2D& b, const vector2D& c)
{
    return cross2D(b - a, c - a);
}

//- True if c, known to be on the line through a and b, lies within the
//  segment's bounding box
inline bool withinBox(const vector2D& a, const vector2D& b, const vector2D& c)
{
    return
        c.x() >= std::min(a.x(), b.x()) && c.x() <= std::max(a.x(), b.x())
     && c.y() >= std::min(a.y(), b.y()) && c.y() <= std::max(a.y(), b.y());
}

//- True if the segments a-b and c-d cross or touch; orientations within
//  tolerance of zero count as collinear
bool segmentsMeet
(
    const vector2D& a,
    const vector2D& b,
    const vector2D& c,
    const vector2D& d,
    const scalar tolerance
)
{
    auto sign = [tolerance](const scalar o)
    {
        return o > tolerance ? 1 : (o < -tolerance ? -1 : 0);
    };
    const int o1 = sign(orientation(a, b, c));
    const int o2 = sign(orientation(a, b, d));
    const int o3 = sign(orientation(c, d, a));
    const int o4 = sign(orientation(c, d, b));

    if (o1*o2 < 0 && o3*o4 < 0)
    {
        return true;
    }
    return
        (o1 == 0 && withinBox(a, b, c))
     || (o2 == 0 && withinBox(a, b, d))
     || (o3 == 0 && withinBox(c, d, a))
     || (o4 == 0 && withinBox(c, d, b));
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * Private Types * * * * * * * * * * * * * * //

//- A part of a layer curve: a moved edge (a segment) or an arc round a
//  concave vertex, over the parameter range [begin, end]: the distance
//  along the segment, or the angle turned along the arc (clockwise)
struct Foam::polygonShape::layerPiece
{
    bool arc;

    //- Segment: start of the moved edge; arc: the vertex
    vector2D origin;

    //- Segment: unit tangent
    vector2D tangent;

    //- Arc: radius and the angle of its start
    scalar radius;
    scalar angle0;

    //- Valid parameter range
    scalar begin = 0, end = 0;

    vector2D at(const scalar u) const
    {
        if (arc)
        {
            const scalar a = angle0 - u;
            return origin + radius*vector2D(std::cos(a), std::sin(a));
        }
        return origin + u*tangent;
    }

    //- Unit tangent in the direction of increasing parameter
    vector2D tangentAt(const scalar u) const
    {
        if (arc)
        {
            const scalar a = angle0 - u;
            return vector2D(std::sin(a), -std::cos(a));
        }
        return tangent;
    }

    scalar length() const
    {
        return arc ? radius*(end - begin) : end - begin;
    }

    //- Point at distance s along the valid part
    vector2D atLength(const scalar s) const
    {
        return at(begin + (arc ? s/radius : s));
    }
};


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::polygonShape::polygonShape(const dictionary& dict)
:
    rigidBodyShape(),
    size_(0),
    area_(0),
    centroid_(Zero)
{
    const vectorList points(dict.get<vectorList>("points"));
    points_.reserve(points.size());
    for (const vector& p : points)
    {
        const scalar r = std::sqrt(sqr(p.x()) + sqr(p.y()));
        if (!saneRange::length.holds(r))
        {
            outOfRange
            (
                dict, "points", r, saneRange::length,
                "the distance from the origin of a point"
            );
        }
        points_.push_back(vector2D(p.x(), p.y()));
    }

    checkAndOrient(dict);

    const label n = label(points_.size());
    tangents_.resize(n);
    normals_.resize(n);
    lengths_.resize(n);
    scalar centroidX = 0, centroidY = 0;
    for (label i = 0; i < n; ++i)
    {
        const vector2D& a = points_[i];
        const vector2D& b = points_[(i + 1) % n];
        lengths_[i] = mag(b - a);
        tangents_[i] = (b - a)/lengths_[i];
        // Counter-clockwise: the outside is on the right
        normals_[i] = vector2D(tangents_[i].y(), -tangents_[i].x());

        const scalar c = cross2D(a, b);
        area_ += 0.5*c;
        centroidX += (a.x() + b.x())*c;
        centroidY += (a.y() + b.y())*c;
    }
    centroid_ = vector2D(centroidX, centroidY)/(6*area_);
}


// * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * * //

void Foam::polygonShape::checkAndOrient(const dictionary& dict)
{
    const label n = label(points_.size());
    if (n < 3)
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'points' of " << dict.name() << " has " << n
            << " points: a polygon needs at least 3" << exit(FatalIOError);
    }

    min_ = max_ = points_[0];
    for (const vector2D& p : points_)
    {
        min_ = vector2D(std::min(min_.x(), p.x()), std::min(min_.y(), p.y()));
        max_ = vector2D(std::max(max_.x(), p.x()), std::max(max_.y(), p.y()));
    }
    size_ = std::max(max_.x() - min_.x(), max_.y() - min_.y());

    // Against round-off in the orientation tests: a fraction of size^2
    const scalar areaTolerance = 1e-12*sqr(size_);

    checkDistinctPoints(dict);
    const scalar twiceArea = checkEnclosedArea(dict, areaTolerance);
    checkSimple(dict, areaTolerance);

    if (twiceArea < 0)
    {
        std::reverse(points_.begin(), points_.end());
    }
}


void Foam::polygonShape::checkDistinctPoints(const dictionary& dict) const
{
    const label n = label(points_.size());
    for (label i = 0; i < n; ++i)
    {
        if (!(mag(points_[(i + 1) % n] - points_[i]) > 1e-12*size_))
        {
            FatalIOErrorInFunction(dict)
                << "Entry 'points' of " << dict.name() << " repeats point "
                << i << ' ' << points_[i] << " (or holds NaN)"
                << exit(FatalIOError);
        }
    }
}


Foam::scalar Foam::polygonShape::checkEnclosedArea
(
    const dictionary& dict,
    const scalar areaTolerance
) const
{
    const label n = label(points_.size());
    scalar twiceArea = 0;
    for (label i = 0; i < n; ++i)
    {
        twiceArea += cross2D(points_[i], points_[(i + 1) % n]);
    }
    if (!(std::abs(twiceArea) > areaTolerance))
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'points' of " << dict.name()
            << " encloses no area" << exit(FatalIOError);
    }
    return twiceArea;
}


void Foam::polygonShape::checkSimple
(
    const dictionary& dict,
    const scalar areaTolerance
) const
{
    const label n = label(points_.size());
    for (label i = 0; i < n; ++i)
    {
        const vector2D& a = points_[i];
        const vector2D& b = points_[(i + 1) % n];

        // Neighbouring edges share a point: they may only meet there, so
        // the polygon must not turn back on itself
        const vector2D& c = points_[(i + 2) % n];
        if
        (
            std::abs(orientation(a, b, c)) <= areaTolerance
         && ((b - a) & (c - b)) < 0
        )
        {
            FatalIOErrorInFunction(dict)
                << "Entry 'points' of " << dict.name()
                << " is self-intersecting: the polygon turns back on itself"
                << " at point " << (i + 1) % n << ' ' << b
                << exit(FatalIOError);
        }

        for (label j = i + 2; j < n; ++j)
        {
            if ((j + 1) % n == i)
            {
                continue;
            }
            if
            (
                segmentsMeet
                (
                    a, b, points_[j], points_[(j + 1) % n], areaTolerance
                )
            )
            {
                FatalIOErrorInFunction(dict)
                    << "Entry 'points' of " << dict.name()
                    << " is self-intersecting: edge " << a << ' ' << b
                    << " meets edge " << points_[j] << ' '
                    << points_[(j + 1) % n] << exit(FatalIOError);
            }
        }
    }
}


Foam::scalar Foam::polygonShape::closestEdge
(
    const scalar X,
    const scalar Y,
    label& edge,
    scalar& along,
    bool& inside
) const
{
    // One pass over the edges: the crossing number of the ray from (X, Y)
    // towards +x (half-open in y, so a vertex on the ray counts once) and
    // the closest point of each edge
    const label n = label(points_.size());
    scalar best = GREAT;
    edge = 0;
    along = 0;
    inside = false;
    for (label i = 0; i < n; ++i)
    {
        const vector2D& a = points_[i];
        const vector2D& b = points_[i + 1 < n ? i + 1 : 0];
        if
        (
            (a.y() > Y) != (b.y() > Y)
         && X < a.x() + (b.x() - a.x())*(Y - a.y())/(b.y() - a.y())
        )
        {
            inside = !inside;
        }

        const scalar dx = X - a.x(), dy = Y - a.y();
        const scalar t = std::min
        (
            std::max(dx*tangents_[i].x() + dy*tangents_[i].y(), scalar(0)),
            lengths_[i]
        );
        const scalar distance2 =
            sqr(dx - t*tangents_[i].x()) + sqr(dy - t*tangents_[i].y());
        if (distance2 < best)
        {
            best = distance2;
            edge = i;
            along = t;
        }
    }
    return best;
}


void Foam::polygonShape::appendParticle
(
    const vector2D& X,
    const label layer,
    bodyWallParticles& candidates
) const
{
    vector2D surfacePoint, normal;
    const scalar distance =
        signedDistance(X.x(), X.y(), surfacePoint, normal);
    if (distance < 0)
    {
        candidates.append(X, surfacePoint, normal, -distance, layer);
    }
}


bool Foam::polygonShape::onLayer
(
    const vector2D& p,
    const scalar depth
) const
{
    // A point of a moved edge or arc is on the layer when no other part of
    // the surface is closer than depth; the tolerance absorbs round-off
    const scalar tolerance = 1e-12*size_;
    return signedDistance(p.x(), p.y()) <= -depth + tolerance;
}


void Foam::polygonShape::appendValidParts
(
    layerPiece piece,
    const scalar range,
    const scalar depth,
    const scalar spacing,
    std::vector<layerPiece>& pieces
) const
{
    const scalar length = piece.arc ? piece.radius*range : range;
    // Fine enough that a valid part missed is much shorter than spacing
    const label nSamples =
        std::max(label(16), label(std::ceil(8*length/spacing)));
    auto valid = [&](const scalar u) { return onLayer(piece.at(u), depth); };

    // Bisection to round-off between a valid and an invalid parameter
    auto boundary = [&](scalar in, scalar out)
    {
        for (int iter = 0; iter < 100; ++iter)
        {
            const scalar mid = 0.5*(in + out);
            if (mid == in || mid == out)
            {
                break;
            }
            (valid(mid) ? in : out) = mid;
        }
        return in;
    };

    bool inRun = false;
    scalar runBegin = 0, uPrevious = 0;
    for (label k = 0; k <= nSamples; ++k)
    {
        const scalar u = range*k/nSamples;
        const bool v = valid(u);
        if (v && !inRun)
        {
            runBegin = k == 0 ? 0 : boundary(u, uPrevious);
            inRun = true;
        }
        else if (!v && inRun)
        {
            piece.begin = runBegin;
            piece.end = boundary(uPrevious, u);
            pieces.push_back(piece);
            inRun = false;
        }
        uPrevious = u;
    }
    if (inRun)
    {
        piece.begin = runBegin;
        piece.end = range;
        pieces.push_back(piece);
    }
}


std::vector<Foam::polygonShape::layerPiece> Foam::polygonShape::layerPieces
(
    const scalar depth,
    const scalar spacing
) const
{
    const label n = label(points_.size());

    // Moved edges and arcs in order round the polygon, each cut into its
    // parts that lie on the layer
    std::vector<layerPiece> pieces;
    for (label i = 0; i < n; ++i)
    {
        const label previous = (i + n - 1) % n;
        const scalar turn = cross2D(tangents_[previous], tangents_[i]);
        if (turn < 0)
        {
            // Concave vertex: the arc from the previous edge's inward
            // normal clockwise to this edge's
            layerPiece arc;
            arc.arc = true;
            arc.origin = points_[i];
            arc.tangent = Zero;
            arc.radius = depth;
            arc.angle0 =
                std::atan2(-normals_[previous].y(), -normals_[previous].x());
            const scalar angleTurned = std::acos
            (
                std::min
                (
                    std::max(normals_[previous] & normals_[i], scalar(-1)),
                    scalar(1)
                )
            );
            appendValidParts(arc, angleTurned, depth, spacing, pieces);
        }

        layerPiece segment;
        segment.arc = false;
        segment.origin = points_[i] - depth*normals_[i];
        segment.tangent = tangents_[i];
        segment.radius = 0;
        segment.angle0 = 0;
        appendValidParts(segment, lengths_[i], depth, spacing, pieces);
    }

    // Drop parts of zero length: the layer passes through them
    const scalar joinTolerance = 1e-8*size_;
    pieces.erase
    (
        std::remove_if
        (
            pieces.begin(),
            pieces.end(),
            [&](const layerPiece& p) { return p.length() < joinTolerance; }
        ),
        pieces.end()
    );
    return pieces;
}


std::vector<Foam::polygonShape::layerPiece> Foam::polygonShape::nextCurve
(
    const std::vector<layerPiece>& pieces,
    const label first,
    const scalar joinTolerance,
    std::vector<bool>& used,
    bool& closed
)
{
    const label nPieces = label(pieces.size());
    std::vector<label> chain(1, first);
    used[first] = true;
    closed = false;
    while (true)
    {
        const layerPiece& last = pieces[chain.back()];
        const vector2D end = last.at(last.end);
        if (mag(pieces[first].at(pieces[first].begin) - end) < joinTolerance
         && chain.size() > 1)
        {
            closed = true;
            break;
        }
        // The next part round the polygon first, any other after
        label next = -1;
        for (label k = 1; k <= nPieces && next < 0; ++k)
        {
            const label candidate = (chain.back() + k) % nPieces;
            const layerPiece& p = pieces[candidate];
            if
            (
                (!used[candidate] || candidate == first)
             && mag(p.at(p.begin) - end) < joinTolerance
            )
            {
                next = candidate;
            }
        }
        if (next == first)
        {
            closed = true;
            break;
        }
        if (next < 0)
        {
            break;
        }
        chain.push_back(next);
        used[next] = true;
    }

    std::vector<layerPiece> curve;
    curve.reserve(chain.size());
    for (const label k : chain)
    {
        curve.push_back(pieces[k]);
    }
    return curve;
}


std::vector<Foam::label> Foam::polygonShape::curveKinks
(
    const std::vector<layerPiece>& curve,
    const bool closed
)
{
    const label m = label(curve.size());
    auto kinkAfter = [&](const label k)
    {
        if (k == m - 1 && !closed)
        {
            return true;
        }
        const layerPiece& a = curve[k];
        const layerPiece& b = curve[(k + 1) % m];
        const vector2D ta = a.tangentAt(a.end);
        const vector2D tb = b.tangentAt(b.begin);
        // Angles below 1e-6 rad are round-off of collinear edges
        return std::abs(cross2D(ta, tb)) > 1e-6 || (ta & tb) < 0;
    };

    std::vector<label> kinks;
    for (label k = 0; k < m; ++k)
    {
        if (kinkAfter(k))
        {
            kinks.push_back(k);
        }
    }
    return kinks;
}


std::vector<Foam::vector2D> Foam::polygonShape::stretchPoints
(
    const std::vector<layerPiece>& curve,
    const label firstPiece,
    const label nParts,
    const bool withEnd,
    const scalar spacing
)
{
    const label m = label(curve.size());
    scalar length = 0;
    for (label k = 0; k < nParts; ++k)
    {
        length += curve[(firstPiece + k) % m].length();
    }
    const label nSteps = nIntervals(length, spacing);
    const label nPoints = withEnd ? nSteps + 1 : nSteps;
    std::vector<vector2D> points;
    points.reserve(nPoints);
    label part = 0;
    scalar partStart = 0;
    for (label j = 0; j < nPoints; ++j)
    {
        const scalar s = length*j/nSteps;
        while
        (
            part < nParts - 1
         && s > partStart + curve[(firstPiece + part) % m].length()
        )
        {
            partStart += curve[(firstPiece + part) % m].length();
            ++part;
        }
        const layerPiece& p = curve[(firstPiece + part) % m];
        points.push_back(p.atLength(std::min(s - partStart, p.length())));
    }
    return points;
}


void Foam::polygonShape::appendCurve
(
    const std::vector<layerPiece>& curve,
    const bool closed,
    const label layer,
    const scalar spacing,
    bodyWallParticles& candidates
) const
{
    const label m = label(curve.size());
    const std::vector<label> kinks = curveKinks(curve, closed);

    auto placeStretch =
        [&](const label firstPiece, const label nParts, const bool withEnd)
    {
        for
        (
            const vector2D& X
          : stretchPoints(curve, firstPiece, nParts, withEnd, spacing)
        )
        {
            appendParticle(X, layer, candidates);
        }
    };

    if (closed && kinks.empty())
    {
        placeStretch(0, m, false);
    }
    else if (closed)
    {
        for (size_t k = 0; k < kinks.size(); ++k)
        {
            const label begin = (kinks[k] + 1) % m;
            const label endKink = kinks[(k + 1) % kinks.size()];
            const label nParts = (endKink - kinks[k] + m - 1) % m + 1;
            placeStretch(begin, nParts, false);
        }
    }
    else
    {
        label begin = 0;
        for (size_t k = 0; k < kinks.size(); ++k)
        {
            placeStretch(begin, kinks[k] - begin + 1, k + 1 == kinks.size());
            begin = kinks[k] + 1;
        }
    }
}


void Foam::polygonShape::appendLayer
(
    const scalar depth,
    const label layer,
    const scalar spacing,
    bodyWallParticles& candidates
) const
{
    const std::vector<layerPiece> pieces = layerPieces(depth, spacing);

    // Chain the parts into closed curves (or open ones, should round-off
    // break a join) by matching the end of one to the start of the next
    const scalar joinTolerance = 1e-8*size_;
    const label nPieces = label(pieces.size());
    std::vector<bool> used(nPieces, false);
    for (label first = 0; first < nPieces; ++first)
    {
        if (used[first])
        {
            continue;
        }
        bool closed = false;
        const std::vector<layerPiece> curve =
            nextCurve(pieces, first, joinTolerance, used, closed);
        appendCurve(curve, closed, layer, spacing, candidates);
    }
}


void Foam::polygonShape::appendCornerTips
(
    const scalar spacing,
    bodyWallParticles& candidates
) const
{
    const label n = label(points_.size());
    for (label i = 0; i < n; ++i)
    {
        const label previous = (i + n - 1) % n;
        if (cross2D(tangents_[previous], tangents_[i]) <= 0)
        {
            continue;
        }
        const vector2D bisector = tangents_[i] - tangents_[previous];
        const scalar magBisector = mag(bisector);
        if (magBisector < SMALL)
        {
            continue;
        }
        // The bisector makes half the interior angle with either edge
        const scalar sinHalf =
            std::abs(cross2D(bisector/magBisector, tangents_[i]));
        const scalar firstMitre = 0.5*spacing/sinHalf;
        if (firstMitre <= spacing)
        {
            continue;
        }

        // From the first layer's mitre point to spacing/2 from the tip
        const scalar run = firstMitre - 0.5*spacing;
        const label nSteps = label(std::ceil(run/spacing));
        for (label j = 1; j <= nSteps; ++j)
        {
            appendParticle
            (
                points_[i] + (firstMitre - run*j/nSteps)*bisector/magBisector,
                0,
                candidates
            );
        }
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::wordList Foam::polygonShape::keywords() const
{
    return wordList({"points"});
}


Foam::scalar Foam::polygonShape::polarMomentOfArea(const vector2D& p) const
{
    // Second moments of a polygon about the origin (Green's theorem),
    // shifted to p: J_p = J_0 - 2 p.(A c) + A |p|^2
    const label n = label(points_.size());
    scalar J0 = 0;
    for (label i = 0; i < n; ++i)
    {
        const vector2D& a = points_[i];
        const vector2D& b = points_[(i + 1) % n];
        J0 += cross2D(a, b)
           *(
                sqr(a.x()) + a.x()*b.x() + sqr(b.x())
              + sqr(a.y()) + a.y()*b.y() + sqr(b.y())
            );
    }
    J0 /= 12;
    return J0 - 2*area_*(p & centroid_) + area_*magSqr(p);
}


bool Foam::polygonShape::contains(const scalar X, const scalar Y) const
{
    if (X <= min_.x() || X >= max_.x() || Y <= min_.y() || Y >= max_.y())
    {
        return false;
    }
    // Strictly: a point on an edge (to round-off) is not inside
    label edge;
    scalar along;
    bool inside;
    const scalar distance2 = closestEdge(X, Y, edge, along, inside);
    return inside && distance2 > sqr(1e-12*size_);
}


Foam::scalar Foam::polygonShape::signedDistance
(
    const scalar X,
    const scalar Y
) const
{
    label edge;
    scalar along;
    bool inside;
    const scalar distance = std::sqrt(closestEdge(X, Y, edge, along, inside));
    return inside ? -distance : distance;
}


Foam::scalar Foam::polygonShape::signedDistance
(
    const scalar X,
    const scalar Y,
    vector2D& closestPoint,
    vector2D& normal
) const
{
    label edge;
    scalar along;
    bool inside;
    const scalar distance = std::sqrt(closestEdge(X, Y, edge, along, inside));
    const scalar sign = inside ? -1 : 1;
    const label n = label(points_.size());

    closestPoint = points_[edge] + along*tangents_[edge];

    if (along > 0 && along < lengths_[edge])
    {
        normal = normals_[edge];
    }
    else if (distance > 1e-12*size_)
    {
        // In the fan of a vertex: the distance grows along X - vertex
        normal = sign/distance*(vector2D(X, Y) - closestPoint);
    }
    else
    {
        // On the vertex: the mean of its two edges' normals
        const label vertex = along > 0 ? (edge + 1) % n : edge;
        const vector2D sum = normals_[(vertex + n - 1) % n] + normals_[vertex];
        normal = sum/mag(sum);
    }

    return sign*distance;
}


Foam::boundBox Foam::polygonShape::bounds
(
    const rigidTransform2D& placement
) const
{
    vector2D lo(GREAT, GREAT), hi(-GREAT, -GREAT);
    for (const vector2D& p : points_)
    {
        const vector2D x = placement.toCurrent(p);
        lo = vector2D(std::min(lo.x(), x.x()), std::min(lo.y(), x.y()));
        hi = vector2D(std::max(hi.x(), x.x()), std::max(hi.y(), x.y()));
    }
    return boundBox(point(lo.x(), lo.y(), 0), point(hi.x(), hi.y(), 0));
}


Foam::bodyWallParticles Foam::polygonShape::wallParticles
(
    const scalar spacing,
    const label nLayers
) const
{
    bodyWallParticles candidates;
    for (label layer = 0; layer < nLayers; ++layer)
    {
        appendLayer((layer + 0.5)*spacing, layer, spacing, candidates);
    }
    appendCornerTips(spacing, candidates);

    return keepApart(candidates, 0.5*spacing);
}


std::vector<Foam::scalar> Foam::polygonShape::surfacePoints
(
    const scalar spacing
) const
{
    std::vector<scalar> points;
    const label n = label(points_.size());
    for (label i = 0; i < n; ++i)
    {
        // Round-off must not add a point next to the edge's end
        const label nSteps = std::max
        (
            label(1),
            label(std::ceil(lengths_[i]/spacing - 1e-9))
        );
        for (label j = 0; j < nSteps; ++j)
        {
            const vector2D p =
                points_[i] + (lengths_[i]*j/nSteps)*tangents_[i];
            points.push_back(p.x());
            points.push_back(p.y());
        }
    }
    return points;
}


// ************************************************************************* //
