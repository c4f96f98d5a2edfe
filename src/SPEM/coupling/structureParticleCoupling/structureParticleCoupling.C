#include "structureParticleCoupling.H"
#include "elementModel.H"
#include "sphFluid.H"
#include "tankBoundary.H"

#include <algorithm>
#include <cmath>
#include <climits>
#include <unordered_map>

namespace
{
    using Foam::label;
    using Foam::scalar;

    //- Buckets of a square grid over the plane: items by cell
    class bucketGrid
    {
        scalar x0_, y0_, size_;
        std::unordered_map<long long, std::vector<label>> cells_;

        long long key(const long long i, const long long j) const
        {
            return (i << 32) ^ (j & 0xffffffffLL);
        }

    public:

        bucketGrid(const scalar x0, const scalar y0, const scalar size)
        :
            x0_(x0), y0_(y0), size_(size)
        {}

        long long ix(const scalar x) const { return std::floor((x - x0_)/size_); }
        long long iy(const scalar y) const { return std::floor((y - y0_)/size_); }

        void insert(const long long i, const long long j, const label item)
        {
            cells_[key(i, j)].push_back(item);
        }

        const std::vector<label>* cell(const long long i, const long long j) const
        {
            const auto it = cells_.find(key(i, j));
            return it == cells_.end() ? nullptr : &it->second;
        }
    };


    //- True if triangle t is of a solid (not a fluid) material region
    bool isSolid
    (
        const Foam::triMesh& mesh,
        const Foam::elementModel& elements,
        const label t
    )
    {
        const label r = mesh.triangleRegion()[t];
        return elements.hasMaterial(r) && !elements.material(r).isFluid();
    }


    //- The solid triangles, their largest edge length and the lower left
    //  corner of their bounding box
    struct solidTriangles
    {
        std::vector<label> triangles;
        scalar edgeMax = 0, xMin = Foam::GREAT, yMin = Foam::GREAT;

        solidTriangles
        (
            const Foam::triMesh& mesh,
            const Foam::elementModel& elements
        )
        {
            const std::vector<scalar>& X = mesh.points();
            const std::vector<label>& tri = mesh.triangles();
            for (label t = 0; t < mesh.nTriangles(); ++t)
            {
                if (!isSolid(mesh, elements, t)) continue;
                triangles.push_back(t);
                for (label a = 0; a < 3; ++a)
                {
                    const label p = tri[3*t + a], q = tri[3*t + (a + 1) % 3];
                    edgeMax = std::max
                    (
                        edgeMax,
                        std::hypot(X[2*q] - X[2*p], X[2*q + 1] - X[2*p + 1])
                    );
                    xMin = std::min(xMin, X[2*p]);
                    yMin = std::min(yMin, X[2*p + 1]);
                }
            }
        }
    };


    //- Barycentric coordinates of a point in triangle t (outside it some
    //  are negative: a linear extrapolation of the triangle's field)
    void barycentric
    (
        const std::vector<scalar>& X,
        const label* n,
        const scalar px,
        const scalar py,
        scalar lambda[3]
    )
    {
        const scalar x0 = X[2*n[0]], y0 = X[2*n[0] + 1];
        const scalar x1 = X[2*n[1]], y1 = X[2*n[1] + 1];
        const scalar x2 = X[2*n[2]], y2 = X[2*n[2] + 1];
        const scalar det = (x1 - x0)*(y2 - y0) - (x2 - x0)*(y1 - y0);
        lambda[1] = ((px - x0)*(y2 - y0) - (x2 - x0)*(py - y0))/det;
        lambda[2] = ((x1 - x0)*(py - y0) - (px - x0)*(y1 - y0))/det;
        lambda[0] = 1 - lambda[1] - lambda[2];
    }


    //- Point location among the solid triangles, in buckets of the largest
    //  solid edge length
    class solidLocator
    {
        const std::vector<scalar>& X_;
        const std::vector<label>& tri_;
        bucketGrid triangles_;

    public:

        solidLocator(const Foam::triMesh& mesh, const solidTriangles& solid)
        :
            X_(mesh.points()),
            tri_(mesh.triangles()),
            triangles_(solid.xMin, solid.yMin, solid.edgeMax)
        {
            for (const label t : solid.triangles)
            {
                long long i0 = LLONG_MAX, i1 = LLONG_MIN;
                long long j0 = LLONG_MAX, j1 = LLONG_MIN;
                for (label a = 0; a < 3; ++a)
                {
                    const label p = tri_[3*t + a];
                    i0 = std::min(i0, triangles_.ix(X_[2*p]));
                    i1 = std::max(i1, triangles_.ix(X_[2*p]));
                    j0 = std::min(j0, triangles_.iy(X_[2*p + 1]));
                    j1 = std::max(j1, triangles_.iy(X_[2*p + 1]));
                }
                for (long long i = i0; i <= i1; ++i)
                {
                    for (long long j = j0; j <= j1; ++j) triangles_.insert(i, j, t);
                }
            }
        }

        //- The solid triangle holding a point (-1: none), and its
        //  barycentric coordinates
        label locate(const scalar px, const scalar py, scalar lambda[3]) const
        {
            const std::vector<scalar>& X = X_;
            const std::vector<label>* cell =
                triangles_.cell(triangles_.ix(px), triangles_.iy(py));
            if (!cell) return label(-1);
            for (const label t : *cell)
            {
                barycentric(X, &tri_[3*t], px, py, lambda);
                const scalar tol = 1e-12;
                if (lambda[0] >= -tol && lambda[1] >= -tol && lambda[2] >= -tol)
                {
                    return t;
                }
            }
            return label(-1);
        }
    };


    //- The solid segments that fluid can reach, as triples first node,
    //  second node (the solid on their left), solid triangle
    std::vector<label> reachableSegments
    (
        const Foam::triMesh& mesh,
        const Foam::elementModel& elements,
        const Foam::List<Foam::patchType>& patchTypes,
        const std::vector<label>& solidTriangles
    )
    {
        const std::vector<label>& tri = mesh.triangles();
        const std::vector<label>& edgeTri = mesh.edgeTriangles();
        const std::vector<label>& triEdges = mesh.triangleEdges();

        // Patch of each boundary edge (-1: internal)
        std::vector<label> edgePatch(mesh.nEdges(), -1);
        for (label s = 0; s < mesh.nSegments(); ++s)
        {
            edgePatch[mesh.segmentEdge()[s]] = mesh.segmentPatch()[s];
        }

        // The faces next to fluid or void elements first, then those on
        // open patches: where the layers of two faces of a thin plate
        // overlap, the face the water touches keeps its first layer
        std::vector<label> segments;
        for (const bool onPatch : {false, true})
        {
            for (const label t : solidTriangles)
            {
                for (label a = 0; a < 3; ++a)
                {
                    const label k = triEdges[3*t + a];
                    const label other =
                        edgeTri[2*k] == t ? edgeTri[2*k + 1] : edgeTri[2*k];
                    if ((other < 0) != onPatch) continue;
                    const bool reachable =
                        other >= 0
                      ? !isSolid(mesh, elements, other)
                      : patchTypes[edgePatch[k]] == Foam::patchType::freeSurface;
                    if (!reachable) continue;
                    // Edge a runs from local node a to a + 1 of the
                    // counter-clockwise triangle
                    segments.push_back(tri[3*t + a]);
                    segments.push_back(tri[3*t + (a + 1) % 3]);
                    segments.push_back(t);
                }
            }
        }
        return segments;
    }


    //- True if a particle kept before is closer than minDistance to (px, py)
    bool tooClose
    (
        const bucketGrid& kept,
        const std::vector<scalar>& keptX,
        const scalar px,
        const scalar py,
        const scalar minDistance
    )
    {
        const long long i = kept.ix(px), j = kept.iy(py);
        for (long long di = -1; di <= 1; ++di)
        {
            for (long long dj = -1; dj <= 1; ++dj)
            {
                const std::vector<label>* cell = kept.cell(i + di, j + dj);
                if (!cell) continue;
                for (const label o : *cell)
                {
                    if
                    (
                        std::hypot(keptX[2*o] - px, keptX[2*o + 1] - py)
                      < minDistance
                    )
                    {
                        return true;
                    }
                }
            }
        }
        return false;
    }
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::structureParticleCoupling::structureParticleCoupling
(
    const triMesh& mesh,
    const elementModel& elements,
    const List<patchType>& patchTypes,
    const scalar spacing,
    const label nLayers,
    const scalar rho0,
    const scalar smoothingLength
)
:
    smoothingLength_(smoothingLength),
    force_{0, 0}
{
    const std::vector<scalar>& X = mesh.points();
    const std::vector<label>& tri = mesh.triangles();

    const solidTriangles solid(mesh, elements);
    if (solid.triangles.empty() || spacing <= 0 || nLayers <= 0) return;
    const scalar xMin = solid.xMin, yMin = solid.yMin;

    const solidLocator locator(mesh, solid);
    // Where a layer that leaves the solid may go on: outside the mesh
    // beyond an open face, within the layers' depth of it
    const tankBoundary tank(mesh, patchTypes, nLayers*spacing);
    const std::vector<label> segments =
        reachableSegments(mesh, elements, patchTypes, solid.triangles);

    // Layers behind the segments, the particles closer than dx/2 to one
    // kept before dropped. Layer by layer over all segments: where the
    // layers of two faces overlap (a thin plate, a corner), the layer
    // nearest its face is kept; face by face, the deep layers of the
    // first face would displace the first layer of the opposite one.
    const scalar minDistance = 0.5*spacing;
    bucketGrid kept(xMin, yMin, minDistance);
    std::vector<scalar> keptX;
    for (label layer = 0; layer < nLayers; ++layer)
    {
        const scalar depth = (layer + 0.5)*spacing;
        for (size_t seg = 0; seg < segments.size(); seg += 3)
        {
            const label p = segments[seg];
            const label q = segments[seg + 1];
            const label own = segments[seg + 2];
            const scalar ex = X[2*q] - X[2*p], ey = X[2*q + 1] - X[2*p + 1];
            const scalar length = std::hypot(ex, ey);
            const scalar nx = -ey/length, ny = ex/length;
            // At most dx apart along the segment, so that no point of a
            // layer is farther than dx/sqrt(2) from a particle; each
            // carries the volume it stands for, (l/nAlong) dx: the
            // momentum sums weigh a wall by its volume (particles of
            // volume dx^2 at 0.71 dx pushed 41 % too hard on a plate
            // with l = 1.41 dx)
            const label nAlong =
                std::max(label(1), label(std::ceil(length/spacing - 1e-9)));
            const scalar volume = length/nAlong*spacing;
            {
                for (label s = 0; s < nAlong; ++s)
                {
                    const scalar u = (s + 0.5)/nAlong;
                    const scalar px = X[2*p] + u*ex + depth*nx;
                    const scalar py = X[2*p + 1] + u*ey + depth*ny;
                    scalar lambda[3];
                    label holder = locator.locate(px, py, lambda);
                    if (holder < 0)
                    {
                        // Behind a solid thinner than the layers, outside
                        // the mesh beyond an open face (where no fluid
                        // is): tied to the segment's element, extrapolated
                        tankBoundary::nearestPoint q;
                        if
                        (
                            !tank.nearest(px, py, q)
                         || q.wall || q.signedDistance <= 0
                        )
                        {
                            continue;
                        }
                        holder = own;
                        barycentric(X, &tri[3*own], px, py, lambda);
                    }

                    if (tooClose(kept, keptX, px, py, minDistance)) continue;

                    const long long i = kept.ix(px), j = kept.iy(py);
                    kept.insert(i, j, label(triangle_.size()));
                    keptX.push_back(px);
                    keptX.push_back(py);
                    triangle_.push_back(holder);
                    m_.push_back(rho0*volume);
                    nodes_.insert(nodes_.end(), &tri[3*holder], &tri[3*holder] + 3);
                    weight_.insert(weight_.end(), lambda, lambda + 3);
                }
            }
        }
    }

    acceleration_.resize(size());
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::structureParticleCoupling::appendParticles
(
    const elementModel& elements,
    const scalar dt,
    std::vector<scalar>& xOut,
    std::vector<scalar>& vOut,
    std::vector<scalar>& aOut,
    std::vector<scalar>& mOut,
    std::vector<scalar>& hOut
)
{
    const label n = size();
    const std::vector<scalar>& x = elements.positions();
    const std::vector<scalar>& v = elements.velocities();
    for (label k = 0; k < n; ++k)
    {
        const label* nodes = &nodes_[3*k];
        const scalar* w = &weight_[3*k];
        scalar px = 0, py = 0, vx = 0, vy = 0;
        for (label a = 0; a < 3; ++a)
        {
            px += w[a]*x[2*nodes[a]];
            py += w[a]*x[2*nodes[a] + 1];
            vx += w[a]*v[2*nodes[a]];
            vy += w[a]*v[2*nodes[a] + 1];
        }
        xOut.push_back(px);
        xOut.push_back(py);
        vOut.push_back(vx);
        vOut.push_back(vy);
        // The nodes' velocities are those of the last half step: the
        // acceleration over the last step from their difference
        scalar ax, ay;
        acceleration_.update(k, vx, vy, dt, ax, ay);
        aOut.push_back(ax);
        aOut.push_back(ay);
        mOut.push_back(m_[k]);
        hOut.push_back(smoothingLength_);
    }
    acceleration_.endUpdate();
}


void Foam::structureParticleCoupling::applyForces
(
    elementModel& elements,
    const scalar* F
)
{
    force_[0] = 0;
    force_[1] = 0;
    std::vector<scalar>& f = elements.externalForce();
    for (label k = 0; k < size(); ++k)
    {
        const label* nodes = &nodes_[3*k];
        const scalar* w = &weight_[3*k];
        for (label a = 0; a < 3; ++a)
        {
            f[2*nodes[a]] += w[a]*F[2*k];
            f[2*nodes[a] + 1] += w[a]*F[2*k + 1];
        }
        force_[0] += F[2*k];
        force_[1] += F[2*k + 1];
    }
}


// * * * * * * * * * * * * * * * * * * Hooks * * * * * * * * * * * * * * * * //

void Foam::structureParticleCoupling::beforeParticleEvaluate(couplingStep& s)
{
    structureParticles& p = s.structure;
    first_ = p.size();
    appendParticles(*s.elements, s.lastDeltaT, p.x, p.v, p.a, p.m, p.h);
}


void Foam::structureParticleCoupling::afterParticleEvaluate(couplingStep& s)
{
    applyForces
    (
        *s.elements, s.particles->structureParticleForce().data() + 2*first_
    );
}


// ************************************************************************* //
