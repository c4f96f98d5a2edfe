#include "wallParticles.H"
#include "error.H"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * * //

namespace
{

using Foam::label;
using Foam::scalar;

//- Point-in-mesh test through a uniform grid of triangle bounding boxes
class meshLocator
{
    const std::vector<scalar>& x_;
    const std::vector<label>& tri_;
    scalar x0_, y0_, inv_;
    label nx_, ny_;
    std::vector<label> start_, items_;

    label cellX(const scalar x) const
    {
        return std::clamp(label((x - x0_)*inv_), label(0), nx_ - 1);
    }
    label cellY(const scalar y) const
    {
        return std::clamp(label((y - y0_)*inv_), label(0), ny_ - 1);
    }

public:

    meshLocator(const std::vector<scalar>& x, const std::vector<label>& tri)
    :
        x_(x), tri_(tri)
    {
        const label nTri = label(tri.size()/3);
        scalar xMin = x[0], xMax = x[0], yMin = x[1], yMax = x[1];
        for (size_t i = 0; i < x.size()/2; ++i)
        {
            xMin = std::min(xMin, x[2*i]); xMax = std::max(xMax, x[2*i]);
            yMin = std::min(yMin, x[2*i+1]); yMax = std::max(yMax, x[2*i+1]);
        }
        // About one triangle per cell
        const scalar size =
            std::max(std::sqrt((xMax - xMin)*(yMax - yMin)/std::max(nTri, label(1))), 1e-12);
        x0_ = xMin; y0_ = yMin; inv_ = 1/size;
        nx_ = label((xMax - xMin)*inv_) + 1;
        ny_ = label((yMax - yMin)*inv_) + 1;

        // Two passes: count, then fill (compressed rows)
        start_.assign(nx_*ny_ + 1, 0);
        for (int pass = 0; pass < 2; ++pass)
        {
            std::vector<label> fill;
            if (pass == 1)
            {
                std::partial_sum(start_.begin(), start_.end(), start_.begin());
                items_.resize(start_.back());
                fill.assign(start_.begin(), start_.end() - 1);
            }
            for (label t = 0; t < nTri; ++t)
            {
                scalar bx0 = GREAT_, bx1 = -GREAT_, by0 = GREAT_, by1 = -GREAT_;
                for (int k = 0; k < 3; ++k)
                {
                    const label n = tri[3*t + k];
                    bx0 = std::min(bx0, x[2*n]); bx1 = std::max(bx1, x[2*n]);
                    by0 = std::min(by0, x[2*n+1]); by1 = std::max(by1, x[2*n+1]);
                }
                for (label iy = cellY(by0); iy <= cellY(by1); ++iy)
                {
                    for (label ix = cellX(bx0); ix <= cellX(bx1); ++ix)
                    {
                        const label c = iy*nx_ + ix;
                        if (pass == 0) ++start_[c + 1];
                        else items_[fill[c]++] = t;
                    }
                }
            }
        }
    }

    static constexpr scalar GREAT_ = 1e300;

    //- True if the point lies inside (not on the boundary of) a triangle
    bool inside(const scalar px, const scalar py, const scalar tol) const
    {
        if (px < x0_ - tol || py < y0_ - tol) return false;
        const label ix = label((px - x0_)*inv_), iy = label((py - y0_)*inv_);
        if (ix >= nx_ || iy >= ny_) return false;
        const label c = iy*nx_ + ix;
        for (label k = start_[c]; k < start_[c + 1]; ++k)
        {
            const label* n = &tri_[3*items_[k]];
            scalar s[3];
            bool neg = false, pos = false;
            for (int e = 0; e < 3; ++e)
            {
                const scalar* a = &x_[2*n[e]];
                const scalar* b = &x_[2*n[(e + 1) % 3]];
                const scalar len = std::hypot(b[0] - a[0], b[1] - a[1]);
                s[e] = ((b[0] - a[0])*(py - a[1]) - (b[1] - a[1])*(px - a[0]))/len;
                neg = neg || s[e] < -tol;
                pos = pos || s[e] > tol;
            }
            // Strictly on one side of all three edges (either orientation)
            if (!(neg && pos) && (neg || pos)
             && std::min({std::abs(s[0]), std::abs(s[1]), std::abs(s[2])}) > tol)
            {
                return true;
            }
        }
        return false;
    }
};


//- Union-find root with path halving
label findRoot(std::vector<label>& parent, label i)
{
    while (parent[i] != i)
    {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}

//- The wall segments of the mesh (all but free-surface ones), their
//  straight runs and the wall segments at each node
struct wallGeometry
{
    //- Wall segments in mesh order
    std::vector<label> segments;

    //- Kind of the particles behind each segment (fluid: not a wall)
    std::vector<Foam::particleSet::kind> kind;

    //- Outward unit normal and unit tangent of each segment
    std::vector<scalar> normal, tangent;

    //- The wall segments of each node
    std::unordered_map<label, std::vector<label>> nodeSegments;

    //- Union-find forest of the straight runs (root: the run's segment)
    std::vector<label> runParent;
};


//- Candidate dummy particles: (x, y, kind) in order of creation
struct wallCandidates
{
    std::vector<scalar> positions;
    std::vector<Foam::particleSet::kind> kind;

    void add(const scalar px, const scalar py, const Foam::particleSet::kind k)
    {
        positions.push_back(px);
        positions.push_back(py);
        kind.push_back(k);
    }
};


//- True if two wall segments are of the same kind and parallel (the same
//  outward normal)
bool parallel(const wallGeometry& walls, const label s1, const label s2)
{
    const std::vector<scalar>& normal = walls.normal;
    return
        walls.kind[s1] == walls.kind[s2]
     && normal[2*s1]*normal[2*s2] + normal[2*s1+1]*normal[2*s2+1]
      > 1 - 1e-9;
}


//- Wall segments: kind, outward unit normal and unit tangent
void findWallSegments
(
    const Foam::triMesh& mesh,
    const Foam::List<Foam::patchType>& patchTypes,
    wallGeometry& walls
)
{
    using Foam::particleSet;
    using Foam::patchType;

    const std::vector<scalar>& x = mesh.points();
    const std::vector<label>& seg = mesh.segments();
    const label nSeg = mesh.nSegments();

    walls.kind.assign(nSeg, particleSet::kind::fluid);
    walls.normal.assign(2*nSeg, 0);
    walls.tangent.assign(2*nSeg, 0);
    for (label s = 0; s < nSeg; ++s)
    {
        const patchType type = patchTypes[mesh.segmentPatch()[s]];
        if (type == patchType::freeSurface) continue;
        walls.kind[s] =
            type == patchType::slipWall
          ? particleSet::kind::slipWall
          : particleSet::kind::wall;
        walls.segments.push_back(s);

        const scalar* a = &x[2*seg[2*s]];
        const scalar* b = &x[2*seg[2*s + 1]];
        const scalar len = std::hypot(b[0] - a[0], b[1] - a[1]);
        scalar tx = (b[0] - a[0])/len, ty = (b[1] - a[1])/len;
        scalar nx = ty, ny = -tx;

        // Outward: away from the centroid of the segment's triangle
        const label e = mesh.segmentEdge()[s];
        const label t = mesh.edgeTriangles()[2*e];
        scalar cx = 0, cy = 0;
        for (int k = 0; k < 3; ++k)
        {
            cx += x[2*mesh.triangles()[3*t + k]]/3;
            cy += x[2*mesh.triangles()[3*t + k] + 1]/3;
        }
        if (nx*(0.5*(a[0] + b[0]) - cx) + ny*(0.5*(a[1] + b[1]) - cy) < 0)
        {
            nx = -nx;
            ny = -ny;
        }
        walls.normal[2*s] = nx; walls.normal[2*s + 1] = ny;
        walls.tangent[2*s] = tx; walls.tangent[2*s + 1] = ty;
    }
}


//- Segments of each node, and the straight runs: wall segments joined at
//  nodes with the same normal
void findStraightRuns(const Foam::triMesh& mesh, wallGeometry& walls)
{
    const std::vector<label>& seg = mesh.segments();
    for (const label s : walls.segments)
    {
        walls.nodeSegments[seg[2*s]].push_back(s);
        walls.nodeSegments[seg[2*s + 1]].push_back(s);
    }

    std::vector<label>& parent = walls.runParent;
    parent.resize(mesh.nSegments());
    std::iota(parent.begin(), parent.end(), 0);
    for (const auto& ns : walls.nodeSegments)
    {
        const std::vector<label>& s = ns.second;
        for (size_t i = 0; i < s.size(); ++i)
        {
            for (size_t j = i + 1; j < s.size(); ++j)
            {
                if (parallel(walls, s[i], s[j]))
                {
                    parent[findRoot(parent, s[i])] = findRoot(parent, s[j]);
                }
            }
        }
    }
}


//- Each straight run: candidates evenly spaced along its extent, nLayers
//  deep
void appendRunCandidates
(
    const Foam::triMesh& mesh,
    wallGeometry& walls,
    const scalar spacing,
    const label nLayers,
    wallCandidates& candidates
)
{
    const std::vector<scalar>& x = mesh.points();
    const std::vector<label>& seg = mesh.segments();
    std::vector<label>& parent = walls.runParent;
    const std::vector<scalar>& normal = walls.normal;
    const std::vector<scalar>& tangent = walls.tangent;

    std::unordered_map<label, std::pair<scalar, scalar>> runExtent;
    for (const label s : walls.segments)
    {
        const label r = findRoot(parent, s);
        const scalar tx = tangent[2*r], ty = tangent[2*r + 1];
        for (int k = 0; k < 2; ++k)
        {
            const scalar* p = &x[2*seg[2*s + k]];
            const scalar u = p[0]*tx + p[1]*ty;
            auto it = runExtent.find(r);
            if (it == runExtent.end()) runExtent[r] = {u, u};
            else
            {
                it->second.first = std::min(it->second.first, u);
                it->second.second = std::max(it->second.second, u);
            }
        }
    }
    for (const label s : walls.segments)
    {
        if (findRoot(parent, s) != s) continue;
        const auto ext = runExtent[s];
        const scalar tx = tangent[2*s], ty = tangent[2*s + 1];
        const scalar nx = normal[2*s], ny = normal[2*s + 1];
        // The line of the run: offset along the normal
        const scalar* p0 = &x[2*seg[2*s]];
        const scalar d = p0[0]*nx + p0[1]*ny;
        const scalar length = ext.second - ext.first;
        const label n = std::max(label(1), label(std::lround(length/spacing)));
        for (label layer = 0; layer < nLayers; ++layer)
        {
            const scalar off = d + (layer + 0.5)*spacing;
            for (label k = 0; k < n; ++k)
            {
                const scalar u = ext.first + (k + 0.5)*length/n;
                candidates.add(u*tx + off*nx, u*ty + off*ny, walls.kind[s]);
            }
        }
    }
}


//- Convex corners between runs: candidates filling the gap between their
//  layers, node + (a + 1/2) spacing n_1 + (b + 1/2) spacing n_2
void appendCornerCandidates
(
    const Foam::triMesh& mesh,
    const wallGeometry& walls,
    const scalar spacing,
    const label nLayers,
    wallCandidates& candidates
)
{
    using Foam::particleSet;

    const std::vector<scalar>& x = mesh.points();
    const std::vector<label>& seg = mesh.segments();
    const std::vector<scalar>& normal = walls.normal;
    const std::vector<particleSet::kind>& segKind = walls.kind;

    for (const auto& ns : walls.nodeSegments)
    {
        const scalar* p = &x[2*ns.first];
        const std::vector<label>& s = ns.second;
        for (size_t i = 0; i < s.size(); ++i)
        {
            for (size_t j = 0; j < s.size(); ++j)
            {
                const label s1 = s[i], s2 = s[j];
                if (i == j || parallel(walls, s1, s2)) continue;
                // Direction along s1 away from the node
                const label other = seg[2*s1] == ns.first ? seg[2*s1 + 1] : seg[2*s1];
                const scalar ax = x[2*other] - p[0], ay = x[2*other + 1] - p[1];
                const scalar n2x = normal[2*s2], n2y = normal[2*s2 + 1];
                if (i > j || ax*n2x + ay*n2y >= -1e-9*std::hypot(ax, ay))
                {
                    continue;
                }
                const scalar n1x = normal[2*s1], n1y = normal[2*s1 + 1];
                const particleSet::kind k =
                    segKind[s1] == particleSet::kind::wall
                 || segKind[s2] == particleSet::kind::wall
                  ? particleSet::kind::wall
                  : particleSet::kind::slipWall;
                for (label a = 0; a < nLayers; ++a)
                {
                    for (label b = 0; b < nLayers; ++b)
                    {
                        candidates.add
                        (
                            p[0] + (a + 0.5)*spacing*n1x + (b + 0.5)*spacing*n2x,
                            p[1] + (a + 0.5)*spacing*n1y + (b + 0.5)*spacing*n2y,
                            k
                        );
                    }
                }
            }
        }
    }
}


} // End anonymous namespace


// * * * * * * * * * * * * * * * Global Functions  * * * * * * * * * * * * * //

Foam::label Foam::appendWallParticles
(
    const triMesh& mesh,
    const List<patchType>& patchTypes,
    const scalar spacing,
    const label nLayers,
    const scalar rho0,
    const scalar h,
    particleSet& particles
)
{
    if (!(spacing > 0) || nLayers < 1)
    {
        FatalErrorInFunction
            << "Wall particle spacing " << spacing << " and layers " << nLayers
            << " must be positive" << exit(FatalError);
    }

    const std::vector<scalar>& x = mesh.points();

    wallGeometry walls;
    findWallSegments(mesh, patchTypes, walls);
    findStraightRuns(mesh, walls);

    wallCandidates candidates;
    appendRunCandidates(mesh, walls, spacing, nLayers, candidates);
    appendCornerCandidates(mesh, walls, spacing, nLayers, candidates);
    const std::vector<scalar>& cand = candidates.positions;
    const std::vector<particleSet::kind>& candKind = candidates.kind;

    // Keep candidates outside the mesh and not too close to a kept one
    const meshLocator locator(x, mesh.triangles());
    const scalar minDist2 = 0.25*spacing*spacing;
    const scalar inv = 1/spacing;
    std::unordered_map<long long, std::vector<label>> grid;
    auto key = [](const long long ix, const long long iy)
    {
        return (ix << 32) ^ (iy & 0xffffffffLL);
    };

    const scalar rhoW = rho0, mW = rho0*spacing*spacing;
    label nAdded = 0;
    for (size_t c = 0; c < candKind.size(); ++c)
    {
        const scalar px = cand[2*c], py = cand[2*c + 1];
        if (locator.inside(px, py, 1e-6*spacing)) continue;

        const long long ix = std::llround(std::floor(px*inv));
        const long long iy = std::llround(std::floor(py*inv));
        bool close = false;
        for (long long jy = iy - 1; jy <= iy + 1 && !close; ++jy)
        {
            for (long long jx = ix - 1; jx <= ix + 1 && !close; ++jx)
            {
                auto it = grid.find(key(jx, jy));
                if (it == grid.end()) continue;
                for (const label q : it->second)
                {
                    const scalar dx = particles.positions()[2*q] - px;
                    const scalar dy = particles.positions()[2*q + 1] - py;
                    if (dx*dx + dy*dy < minDist2) { close = true; break; }
                }
            }
        }
        if (close) continue;

        const label q = particles.append(px, py, 0, 0, rhoW, 0, mW, h, candKind[c]);
        grid[key(ix, iy)].push_back(q);
        ++nAdded;
    }
    return nAdded;
}


// ************************************************************************* //
