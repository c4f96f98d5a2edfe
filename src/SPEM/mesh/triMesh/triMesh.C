#include "triMesh.H"
#include "error.H"

#include <algorithm>
#include <cstdint>

namespace Foam
{
    const word triMesh::meshSubDir = "spemMesh";
}

// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::triMesh::orient()
{
    const label nTri = nTriangles();
    for (label t = 0; t < nTri; ++t)
    {
        const scalar a = triangleArea(t);
        if (a < 0)
        {
            std::swap(triangles_[3*t + 1], triangles_[3*t + 2]);
        }
        else if (a == 0)
        {
            FatalErrorInFunction
                << "Triangle " << t << " has zero area" << exit(FatalError);
        }
    }
}


void Foam::triMesh::buildTopology()
{
    std::vector<std::uint64_t> key;
    const std::vector<label> order = sortedHalfEdges(key);
    buildEdges(key, order);
    buildNodeTriangles();
    orientSegments();
}


std::vector<Foam::label> Foam::triMesh::sortedHalfEdges
(
    std::vector<std::uint64_t>& key
) const
{
    const label nTri = nTriangles();
    const label nPts = nPoints();

    // Sort the 3*nTri half-edges by their node pair; equal pairs are shared
    key.assign(3*nTri, 0);
    for (label t = 0; t < nTri; ++t)
    {
        for (label i = 0; i < 3; ++i)
        {
            std::uint64_t a = triangles_[3*t + i];
            std::uint64_t b = triangles_[3*t + (i + 1)%3];
            if (a > b) std::swap(a, b);
            key[3*t + i] = (a*std::uint64_t(nPts) + b)*4 + 0;
        }
    }
    std::vector<label> order(3*nTri);
    for (label i = 0; i < 3*nTri; ++i) order[i] = i;
    std::sort
    (
        order.begin(), order.end(),
        [&key](label i, label j) { return key[i] < key[j]; }
    );
    return order;
}


void Foam::triMesh::buildEdges
(
    const std::vector<std::uint64_t>& key,
    const std::vector<label>& order
)
{
    const label nTri = nTriangles();

    edges_.clear();
    edgeTriangles_.clear();
    triangleEdges_.assign(3*nTri, -1);
    edges_.reserve(3*nTri);
    edgeTriangles_.reserve(3*nTri);

    for (label k = 0; k < 3*nTri; )
    {
        const label h = order[k];
        const label t = h/3, i = h%3;
        label a = triangles_[3*t + i];
        label b = triangles_[3*t + (i + 1)%3];
        const label e = label(edges_.size()/2);
        edges_.push_back(std::min(a, b));
        edges_.push_back(std::max(a, b));
        edgeTriangles_.push_back(t);
        triangleEdges_[h] = e;
        label second = -1;
        label m = k + 1;
        while (m < 3*nTri && key[order[m]] == key[h])
        {
            if (second != -1)
            {
                FatalErrorInFunction
                    << "Edge (" << a << ' ' << b << ") is shared by more"
                    << " than two triangles" << exit(FatalError);
            }
            second = order[m]/3;
            triangleEdges_[order[m]] = e;
            ++m;
        }
        edgeTriangles_.push_back(second);
        k = m;
    }
}


void Foam::triMesh::buildNodeTriangles()
{
    const label nTri = nTriangles();
    const label nPts = nPoints();

    // Node-triangle adjacency (compressed rows)
    nodeTriangleStart_.assign(nPts + 1, 0);
    for (label v : triangles_) ++nodeTriangleStart_[v + 1];
    for (label n = 0; n < nPts; ++n)
    {
        nodeTriangleStart_[n + 1] += nodeTriangleStart_[n];
    }
    nodeTriangles_.assign(3*nTri, -1);
    std::vector<label> fill(nodeTriangleStart_.begin(), nodeTriangleStart_.end() - 1);
    for (label h = 0; h < 3*nTri; ++h)
    {
        nodeTriangles_[fill[triangles_[h]]++] = h;
    }
}


void Foam::triMesh::orientSegments()
{
    // Boundary segments: find their edge, orient them with the triangle on
    // the left (outward normal = (dy, -dx)/length)
    const label nSeg = nSegments();
    segmentEdge_.assign(nSeg, -1);
    for (label s = 0; s < nSeg; ++s)
    {
        const label a = segments_[2*s], b = segments_[2*s + 1];
        for (label j = nodeTriangleStart_[a]; j < nodeTriangleStart_[a + 1]; ++j)
        {
            const label t = nodeTriangles_[j]/3, i = nodeTriangles_[j]%3;
            const label next = triangles_[3*t + (i + 1)%3];
            const label prev = triangles_[3*t + (i + 2)%3];
            if (next == b)
            {
                segmentEdge_[s] = triangleEdges_[3*t + i];
                break;
            }
            if (prev == b)
            {
                segmentEdge_[s] = triangleEdges_[3*t + (i + 2)%3];
                std::swap(segments_[2*s], segments_[2*s + 1]);
                break;
            }
        }
        if (segmentEdge_[s] < 0)
        {
            FatalErrorInFunction
                << "Boundary segment " << s << " (" << a << ' ' << b
                << ") of patch " << patchNames_[segmentPatch_[s]]
                << " is not an edge of the mesh" << exit(FatalError);
        }
        if (edgeTriangles_[2*segmentEdge_[s] + 1] != -1)
        {
            FatalErrorInFunction
                << "Boundary segment " << s << " of patch "
                << patchNames_[segmentPatch_[s]]
                << " is an interior edge of the mesh" << exit(FatalError);
        }
    }
}


void Foam::triMesh::check() const
{
    if (points_.size() % 2 || triangles_.size() % 3 || segments_.size() % 2)
    {
        FatalErrorInFunction << "Inconsistent mesh array sizes"
            << exit(FatalError);
    }
    if (label(triangleRegion_.size()) != nTriangles())
    {
        FatalErrorInFunction
            << "triangleRegion has " << label(triangleRegion_.size())
            << " entries for " << nTriangles() << " triangles"
            << exit(FatalError);
    }
    if (label(segmentPatch_.size()) != nSegments())
    {
        FatalErrorInFunction
            << "segmentPatch has " << label(segmentPatch_.size())
            << " entries for " << nSegments() << " segments"
            << exit(FatalError);
    }
    for (label v : triangles_)
    {
        if (v < 0 || v >= nPoints())
        {
            FatalErrorInFunction << "Triangle node label " << v
                << " out of range 0.." << nPoints() - 1 << exit(FatalError);
        }
    }
    for (label v : segments_)
    {
        if (v < 0 || v >= nPoints())
        {
            FatalErrorInFunction << "Segment node label " << v
                << " out of range 0.." << nPoints() - 1 << exit(FatalError);
        }
    }
    for (label r : triangleRegion_)
    {
        if (r < 0 || r >= nRegions())
        {
            FatalErrorInFunction << "Triangle region " << r
                << " out of range 0.." << nRegions() - 1 << exit(FatalError);
        }
    }
    for (label p : segmentPatch_)
    {
        if (p < 0 || p >= nPatches())
        {
            FatalErrorInFunction << "Segment patch " << p
                << " out of range 0.." << nPatches() - 1 << exit(FatalError);
        }
    }
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::triMesh::triMesh
(
    std::vector<scalar> points,
    std::vector<label> triangles,
    std::vector<label> triangleRegion,
    const wordList& regionNames,
    std::vector<label> segments,
    std::vector<label> segmentPatch,
    const wordList& patchNames
)
:
    points_(std::move(points)),
    triangles_(std::move(triangles)),
    triangleRegion_(std::move(triangleRegion)),
    regionNames_(regionNames),
    segments_(std::move(segments)),
    segmentPatch_(std::move(segmentPatch)),
    patchNames_(patchNames)
{
    check();
    orient();
    buildTopology();
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::label Foam::triMesh::findRegion(const word& name) const
{
    return regionNames_.find(name);
}


Foam::label Foam::triMesh::findPatch(const word& name) const
{
    return patchNames_.find(name);
}


Foam::scalar Foam::triMesh::triangleArea(const label t) const
{
    const scalar* p0 = &points_[2*triangles_[3*t]];
    const scalar* p1 = &points_[2*triangles_[3*t + 1]];
    const scalar* p2 = &points_[2*triangles_[3*t + 2]];
    return 0.5*((p1[0] - p0[0])*(p2[1] - p0[1]) - (p2[0] - p0[0])*(p1[1] - p0[1]));
}


Foam::scalar Foam::triMesh::regionArea(const label region) const
{
    scalar sum = 0;
    for (label t = 0; t < nTriangles(); ++t)
    {
        if (region < 0 || triangleRegion_[t] == region)
        {
            sum += triangleArea(t);
        }
    }
    return sum;
}


// ************************************************************************* //
