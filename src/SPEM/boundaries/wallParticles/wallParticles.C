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
    const std::vector<label>& seg = mesh.segments();
    const label nSeg = mesh.nSegments();

    // Wall segments: kind, outward unit normal and unit tangent
    std::vector<label> wallSeg;
    std::vector<particleSet::kind> segKind(nSeg, particleSet::kind::fluid);
    std::vector<scalar> normal(2*nSeg, 0), tangent(2*nSeg, 0);
    for (label s = 0; s < nSeg; ++s)
    {
        const patchType type = patchTypes[mesh.segmentPatch()[s]];
        if (type == patchType::freeSurface) continue;
        segKind[s] =
            type == patchType::slipWall
          ? particleSet::kind::slipWall
          : particleSet::kind::wall;
        wallSeg.push_back(s);

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
        normal[2*s] = nx; normal[2*s + 1] = ny;
        tangent[2*s] = tx; tangent[2*s + 1] = ty;
    }

    // Segments of each node, to join straight runs and find corners
    std::unordered_map<label, std::vector<label>> nodeSegs;
    for (const label s : wallSeg)
    {
        nodeSegs[seg[2*s]].push_back(s);
        nodeSegs[seg[2*s + 1]].push_back(s);
    }
    auto parallel = [&](const label s1, const label s2)
    {
        return
            segKind[s1] == segKind[s2]
         && normal[2*s1]*normal[2*s2] + normal[2*s1+1]*normal[2*s2+1]
          > 1 - 1e-9;
    };

    // Straight runs: wall segments joined at nodes with the same normal
    std::vector<label> parent(nSeg);
    std::iota(parent.begin(), parent.end(), 0);
    for (const auto& ns : nodeSegs)
    {
        const std::vector<label>& s = ns.second;
        for (size_t i = 0; i < s.size(); ++i)
        {
            for (size_t j = i + 1; j < s.size(); ++j)
            {
                if (parallel(s[i], s[j]))
                {
                    parent[findRoot(parent, s[i])] = findRoot(parent, s[j]);
                }
            }
        }
    }

    // Candidate particles: (x, y, kind) in order of creation
    std::vector<scalar> cand;
    std::vector<particleSet::kind> candKind;
    auto add = [&](const scalar px, const scalar py, const particleSet::kind k)
    {
        cand.push_back(px);
        cand.push_back(py);
        candKind.push_back(k);
    };

    // Each run: evenly spaced along its extent, nLayers deep
    std::unordered_map<label, std::pair<scalar, scalar>> runExtent;
    for (const label s : wallSeg)
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
    for (const label s : wallSeg)
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
                add(u*tx + off*nx, u*ty + off*ny, segKind[s]);
            }
        }
    }

    // Convex corners between runs: fill the gap between their layers
    for (const auto& ns : nodeSegs)
    {
        const scalar* p = &x[2*ns.first];
        const std::vector<label>& s = ns.second;
        for (size_t i = 0; i < s.size(); ++i)
        {
            for (size_t j = 0; j < s.size(); ++j)
            {
                const label s1 = s[i], s2 = s[j];
                if (i == j || parallel(s1, s2)) continue;
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
                        add
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
