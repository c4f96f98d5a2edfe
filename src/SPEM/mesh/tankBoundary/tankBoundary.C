#include "tankBoundary.H"
#include "error.H"

#include <algorithm>
#include <cmath>

const Foam::Enum<Foam::tankBoundary::leavingAction>
Foam::tankBoundary::leavingActionNames
({
    {leavingAction::stop, "stop"},
    {leavingAction::remove, "remove"},
    {leavingAction::warn, "warn"}
});


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

inline Foam::label Foam::tankBoundary::cellOf
(
    const scalar x,
    const scalar y
) const
{
    const scalar fx = (x - origin_[0])/cellSize_;
    const scalar fy = (y - origin_[1])/cellSize_;
    // Written to send NaN outside as well
    if (!(fx >= 0 && fy >= 0 && fx < nCells_[0] && fy < nCells_[1]))
    {
        return -1;
    }
    return label(fy)*nCells_[0] + label(fx);
}


inline Foam::scalar Foam::tankBoundary::closestOnEdge
(
    const label e,
    const scalar x,
    const scalar y,
    scalar& t
) const
{
    const scalar* a = &points_[2*edgeNodes_[2*e]];
    const scalar* b = &points_[2*edgeNodes_[2*e + 1]];
    const scalar dx = b[0] - a[0], dy = b[1] - a[1];
    t = ((x - a[0])*dx + (y - a[1])*dy)/(dx*dx + dy*dy);
    t = std::min(scalar(1), std::max(scalar(0), t));
    const scalar qx = a[0] + t*dx - x, qy = a[1] + t*dy - y;
    return qx*qx + qy*qy;
}


bool Foam::tankBoundary::beyondOpening(const scalar x, const scalar y) const
{
    for (std::size_t k = 0; k < openingLines_.size(); k += 4)
    {
        const scalar* l = &openingLines_[k];
        if ((x - l[0])*l[2] + (y - l[1])*l[3] > -reach_) return true;
    }
    for (label loop = 0; loop < nOpenLoops(); ++loop)
    {
        // Even-odd rule on the loop's polygon
        bool in = false;
        for
        (
            label j = openLoopStart_[loop];
            j < openLoopStart_[loop + 1];
            ++j
        )
        {
            const label e = openLoopEdges_[j];
            const scalar* a = &points_[2*edgeNodes_[2*e]];
            const scalar* b = &points_[2*edgeNodes_[2*e + 1]];
            if
            (
                (a[1] > y) != (b[1] > y)
             && x < a[0] + (y - a[1])*(b[0] - a[0])/(b[1] - a[1])
            )
            {
                in = !in;
            }
        }
        if (in != bool(openLoopIsOuter_[loop])) return true;
    }
    return false;
}


void Foam::tankBoundary::findOpenings()
{
    // The boundary edges leaving and entering each node (two or more at a
    // node where two parts of the mesh touch), compressed rows
    const label nNodes = label(points_.size()/2);
    std::vector<label> outStart(nNodes + 1, 0), inStart(nNodes + 1, 0);
    for (label e = 0; e < nEdges(); ++e)
    {
        ++outStart[edgeNodes_[2*e] + 1];
        ++inStart[edgeNodes_[2*e + 1] + 1];
    }
    for (label n = 0; n < nNodes; ++n)
    {
        outStart[n + 1] += outStart[n];
        inStart[n + 1] += inStart[n];
    }
    std::vector<label> outEdges(nEdges()), inEdges(nEdges());
    {
        std::vector<label> o(outStart.begin(), outStart.end() - 1);
        std::vector<label> i(inStart.begin(), inStart.end() - 1);
        for (label e = 0; e < nEdges(); ++e)
        {
            outEdges[o[edgeNodes_[2*e]]++] = e;
            inEdges[i[edgeNodes_[2*e + 1]]++] = e;
        }
    }

    std::vector<char> visited(nEdges(), 0);
    // The next unvisited open edge leaving node n, -1 if none
    auto nextOpen = [&](const label n)
    {
        for (label j = outStart[n]; j < outStart[n + 1]; ++j)
        {
            const label e = outEdges[j];
            if (!edgeIsWall_[e] && !visited[e]) return e;
        }
        return label(-1);
    };
    // The chain of open edges from edge e on, marked visited
    std::vector<label> chain;
    auto follow = [&](label e)
    {
        chain.clear();
        while (e >= 0)
        {
            visited[e] = 1;
            chain.push_back(e);
            e = nextOpen(edgeNodes_[2*e + 1]);
        }
    };
    auto addLoop = [&]()
    {
        // Shoelace area: positive for the outer boundary (the tank on the
        // left of a counter-clockwise loop), negative for a hole
        scalar area = 0;
        for (const label e : chain)
        {
            const scalar* a = &points_[2*edgeNodes_[2*e]];
            const scalar* b = &points_[2*edgeNodes_[2*e + 1]];
            area += a[0]*b[1] - b[0]*a[1];
        }
        if (openLoopStart_.empty()) openLoopStart_.push_back(0);
        openLoopEdges_.insert(openLoopEdges_.end(), chain.begin(), chain.end());
        openLoopStart_.push_back(label(openLoopEdges_.size()));
        openLoopIsOuter_.push_back(area > 0);
    };

    // Openings: chains that start where a wall edge ends
    for (const label e : openEdges_)
    {
        const label a = edgeNodes_[2*e];
        bool afterWall = inStart[a] == inStart[a + 1];
        for (label j = inStart[a]; j < inStart[a + 1]; ++j)
        {
            afterWall = afterWall || edgeIsWall_[inEdges[j]];
        }
        if (!afterWall || visited[e]) continue;
        follow(e);
        const label first = edgeNodes_[2*chain.front()];
        const label last = edgeNodes_[2*chain.back() + 1];
        const scalar dx = points_[2*last] - points_[2*first];
        const scalar dy = points_[2*last + 1] - points_[2*first + 1];
        const scalar len = std::hypot(dx, dy);
        if (first == last || !(len > 0))
        {
            // Back where it started: a loop that touches a wall at a node
            addLoop();
            continue;
        }
        // The right of the line from the first end to the last (an edge's
        // outward normal is on its right)
        openingLines_.push_back(points_[2*first]);
        openingLines_.push_back(points_[2*first + 1]);
        openingLines_.push_back(dy/len);
        openingLines_.push_back(-dx/len);
    }
    // What is left are loops without a wall
    for (const label e : openEdges_)
    {
        if (visited[e]) continue;
        follow(e);
        addLoop();
    }
}


void Foam::tankBoundary::classifyCells()
{
    cellInside_.assign(nCells_[0]*nCells_[1], 0);
    std::vector<scalar> crossings;
    for (label j = 0; j < nCells_[1]; ++j)
    {
        const scalar y = origin_[1] + (j + 0.5)*cellSize_;
        crossings.clear();
        for (label e = 0; e < nEdges(); ++e)
        {
            const scalar* a = &points_[2*edgeNodes_[2*e]];
            const scalar* b = &points_[2*edgeNodes_[2*e + 1]];
            // Half-open in y: a line through a node counts it once
            if ((a[1] > y) != (b[1] > y))
            {
                crossings.push_back
                (
                    a[0] + (y - a[1])*(b[0] - a[0])/(b[1] - a[1])
                );
            }
        }
        std::sort(crossings.begin(), crossings.end());
        std::size_t k = 0;
        for (label i = 0; i < nCells_[0]; ++i)
        {
            const scalar x = origin_[0] + (i + 0.5)*cellSize_;
            while (k < crossings.size() && crossings[k] < x) ++k;
            // Even-odd rule: inside after an odd number of crossings
            cellInside_[j*nCells_[0] + i] = k % 2;
        }
    }
}


void Foam::tankBoundary::listEdges()
{
    const label nCells = nCells_[0]*nCells_[1];
    cellStart_.assign(nCells + 1, 0);

    // The cells an edge's bounding box, grown by reach, overlaps: a
    // superset of the cells with a point within reach of the edge
    auto range = [&](const label e, label lo[2], label hi[2])
    {
        const scalar* a = &points_[2*edgeNodes_[2*e]];
        const scalar* b = &points_[2*edgeNodes_[2*e + 1]];
        for (int d = 0; d < 2; ++d)
        {
            const scalar mn = std::min(a[d], b[d]) - reach_;
            const scalar mx = std::max(a[d], b[d]) + reach_;
            lo[d] = std::max
            (
                label(0), label(std::floor((mn - origin_[d])/cellSize_))
            );
            hi[d] = std::min
            (
                nCells_[d] - 1, label(std::floor((mx - origin_[d])/cellSize_))
            );
        }
    };
    label lo[2], hi[2];
    for (label e = 0; e < nEdges(); ++e)
    {
        range(e, lo, hi);
        for (label j = lo[1]; j <= hi[1]; ++j)
        {
            for (label i = lo[0]; i <= hi[0]; ++i)
            {
                ++cellStart_[j*nCells_[0] + i + 1];
            }
        }
    }
    for (label c = 0; c < nCells; ++c) cellStart_[c + 1] += cellStart_[c];
    cellEdges_.assign(cellStart_[nCells], -1);
    std::vector<label> fill(cellStart_.begin(), cellStart_.end() - 1);
    for (label e = 0; e < nEdges(); ++e)
    {
        range(e, lo, hi);
        for (label j = lo[1]; j <= hi[1]; ++j)
        {
            for (label i = lo[0]; i <= hi[0]; ++i)
            {
                cellEdges_[fill[j*nCells_[0] + i]++] = e;
            }
        }
    }
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::tankBoundary::tankBoundary
(
    const triMesh& mesh,
    const List<patchType>& patchTypes,
    const scalar reach
)
:
    reach_(reach),
    points_(mesh.points()),
    nodeNormal_(mesh.points().size(), 0),
    cellSize_(0.7*reach),
    size_(0)
{
    if (!(reach > 0) || !std::isfinite(reach))
    {
        FatalErrorInFunction
            << "The query distance of the tank must be positive, not "
            << reach << exit(FatalError);
    }

    // The patch of each edge that is a boundary segment
    std::vector<label> edgePatch(mesh.nEdges(), -1);
    for (label s = 0; s < mesh.nSegments(); ++s)
    {
        edgePatch[mesh.segmentEdge()[s]] = mesh.segmentPatch()[s];
    }

    // Boundary edges (one triangle), oriented with the triangle on the
    // left: from local node i to local node i + 1 of that triangle
    const std::vector<label>& tri = mesh.triangles();
    for (label t = 0; t < mesh.nTriangles(); ++t)
    {
        for (label i = 0; i < 3; ++i)
        {
            const label k = mesh.triangleEdges()[3*t + i];
            if (mesh.edgeTriangles()[2*k + 1] >= 0) continue;
            const label a = tri[3*t + i], b = tri[3*t + (i + 1)%3];
            const scalar dx = points_[2*b] - points_[2*a];
            const scalar dy = points_[2*b + 1] - points_[2*a + 1];
            const scalar len = std::hypot(dx, dy);
            const label p = edgePatch[k];
            const bool wall =
                p < 0 || patchTypes[p] != patchType::freeSurface;
            if (!wall) openEdges_.push_back(label(edgeLength_.size()));
            edgeNodes_.push_back(a);
            edgeNodes_.push_back(b);
            edgeNormal_.push_back(dy/len);
            edgeNormal_.push_back(-dx/len);
            edgeLength_.push_back(len);
            edgeIsWall_.push_back(wall);
            nodeNormal_[2*a] += dy/len;
            nodeNormal_[2*a + 1] -= dx/len;
            nodeNormal_[2*b] += dy/len;
            nodeNormal_[2*b + 1] -= dx/len;
        }
    }

    // The grid over the bounding box of the boundary, grown by reach and
    // a cell so that every point within reach of an edge has a cell
    scalar lo[2] = {GREAT, GREAT}, hi[2] = {-GREAT, -GREAT};
    for (const label n : edgeNodes_)
    {
        for (int d = 0; d < 2; ++d)
        {
            lo[d] = std::min(lo[d], points_[2*n + d]);
            hi[d] = std::max(hi[d], points_[2*n + d]);
        }
    }
    if (edgeNodes_.empty())
    {
        FatalErrorInFunction << "The mesh has no boundary" << exit(FatalError);
    }
    size_ = std::hypot(hi[0] - lo[0], hi[1] - lo[1]);
    for (int d = 0; d < 2; ++d)
    {
        origin_[d] = lo[d] - reach_ - cellSize_;
        nCells_[d] =
            label(std::ceil((hi[d] - lo[d] + 2*(reach_ + cellSize_))/cellSize_));
    }
    const double nCells = double(nCells_[0])*double(nCells_[1]);
    if (nCells > 5e7)
    {
        FatalErrorInFunction
            << "The tank's grid of cells of " << cellSize_ << " m over "
            << hi[0] - lo[0] << " x " << hi[1] - lo[1] << " m would need "
            << nCells << " cells: the query distance " << reach_
            << " m is too small for the size of the mesh" << exit(FatalError);
    }
    classifyCells();
    listEdges();
    findOpenings();
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::label Foam::tankBoundary::nWallEdges() const
{
    return label(std::count(edgeIsWall_.begin(), edgeIsWall_.end(), 1));
}


bool Foam::tankBoundary::outside(const scalar x, const scalar y) const
{
    const label c = cellOf(x, y);
    if (c >= 0)
    {
        // The centre is within a half diagonal (< reach) of any point of
        // the cell: from an inside centre the point is within reach of the
        // meshed region
        if (cellInside_[c]) return false;
        const scalar r2 = reach_*reach_;
        scalar t;
        for (label j = cellStart_[c]; j < cellStart_[c + 1]; ++j)
        {
            if (closestOnEdge(cellEdges_[j], x, y, t) <= r2) return false;
        }
    }
    else if (!std::isfinite(x) || !std::isfinite(y))
    {
        return true;
    }
    return !beyondOpening(x, y);
}


bool Foam::tankBoundary::nearest
(
    const scalar x,
    const scalar y,
    nearestPoint& result,
    scalar* wallDistance
) const
{
    const label c = cellOf(x, y);
    if (c < 0) return false;
    label best = -1;
    scalar bestD2 = reach_*reach_, bestT = 0, wallD2 = reach_*reach_;
    for (label j = cellStart_[c]; j < cellStart_[c + 1]; ++j)
    {
        scalar t;
        const scalar d2 = closestOnEdge(cellEdges_[j], x, y, t);
        if (d2 < bestD2 || (best < 0 && d2 == bestD2))
        {
            best = cellEdges_[j];
            bestD2 = d2;
            bestT = t;
        }
        if (edgeIsWall_[cellEdges_[j]]) wallD2 = std::min(wallD2, d2);
    }
    if (wallDistance) *wallDistance = std::sqrt(wallD2);
    if (best < 0) return false;

    const label a = edgeNodes_[2*best], b = edgeNodes_[2*best + 1];
    const scalar* pa = &points_[2*a];
    const scalar* pb = &points_[2*b];
    result.x = pa[0] + bestT*(pb[0] - pa[0]);
    result.y = pa[1] + bestT*(pb[1] - pa[1]);
    // The normal that decides the side: the edge's inside it, the node's
    // pseudo-normal at an end
    const scalar* n =
        bestT <= 0 ? &nodeNormal_[2*a]
      : bestT >= 1 ? &nodeNormal_[2*b]
      : &edgeNormal_[2*best];
    const scalar dx = x - result.x, dy = y - result.y;
    const scalar d = std::sqrt(bestD2);
    const bool out = dx*n[0] + dy*n[1] > 0;
    result.signedDistance = out ? d : -d;
    if (bestT > 0 && bestT < 1)
    {
        result.nx = edgeNormal_[2*best];
        result.ny = edgeNormal_[2*best + 1];
    }
    else if (d > 0)
    {
        // At a node: along the line from it to the point, out of the tank
        const scalar s = out ? 1/d : -1/d;
        result.nx = s*dx;
        result.ny = s*dy;
    }
    else
    {
        const scalar len = std::hypot(n[0], n[1]);
        result.nx = n[0]/len;
        result.ny = n[1]/len;
    }
    result.wall = edgeIsWall_[best];
    return true;
}


// ************************************************************************* //
