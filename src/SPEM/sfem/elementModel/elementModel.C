#include "elementModel.H"
#include "parallelLoop.H"
#include "simdLanes.H"
#include "error.H"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * * //

namespace
{

using Foam::scalar;
using Foam::label;
namespace simd = Foam::simd;

//- Area and A*grad(N_a) of a triangle: A grad N_a is half the opposite edge
//  rotated outward, so no division is needed. Returns the area. V: scalar,
//  or simd::pair for two triangles (simdLanes.H), as the helpers below
template<class V>
inline V triangleAreaGradN
(
    const V* x0, const V* x1, const V* x2, V* AgradN
)
{
    AgradN[0] = 0.5*(x1[1] - x2[1]);
    AgradN[1] = 0.5*(x2[0] - x1[0]);
    AgradN[2] = 0.5*(x2[1] - x0[1]);
    AgradN[3] = 0.5*(x0[0] - x2[0]);
    AgradN[4] = 0.5*(x0[1] - x1[1]);
    AgradN[5] = 0.5*(x1[0] - x0[0]);
    return 0.5*((x1[0] - x0[0])*(x2[1] - x0[1]) - (x2[0] - x0[0])*(x1[1] - x0[1]));
}

//- Square of the longest edge of a triangle
template<class V>
inline V longestEdgeSqr
(
    const V* x0, const V* x1, const V* x2
)
{
    auto len2 = [](const V* a, const V* b)
    {
        return (a[0] - b[0])*(a[0] - b[0]) + (a[1] - b[1])*(a[1] - b[1]);
    };
    // std::max({a, b, c})
    return simd::max(simd::max(len2(x0, x1), len2(x1, x2)), len2(x2, x0));
}

//- Smallest altitude of a triangle, the length of its stability limit
template<class V>
inline V minAltitude
(
    const V* x0, const V* x1, const V* x2, const V area
)
{
    return 2.0*area/simd::sqrt(longestEdgeSqr(x0, x1, x2));
}

//- A_e grad w = sum_a w_a (x) A grad N_a, row-major g[2i + j] = dw_i/dx_j
template<class V>
inline void areaGradient
(
    const V* AgradN, const V* w0, const V* w1, const V* w2, V* g
)
{
    for (int i = 0; i < 2; ++i)
    {
        for (int j = 0; j < 2; ++j)
        {
            g[2*i + j] = w0[i]*AgradN[j] + w1[i]*AgradN[2 + j] + w2[i]*AgradN[4 + j];
        }
    }
}

} // End anonymous namespace


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::elementModel::build(const triMesh& mesh)
{
    // Unique among all models: a model built anew at the same address
    // (a test, a restart) does not pass for the old one
    static std::atomic<label> builds(0);
    buildStamp_ = ++builds;
    const label nReg = mesh.nRegions();

    if (materials_.size() != nReg)
    {
        FatalErrorInFunction
            << "Mesh has " << nReg << " regions but " << materials_.size()
            << " materials were given" << exit(FatalError);
    }

    const std::vector<label> triElem = orderElements(mesh);
    std::vector<std::vector<std::array<label, 3>>> regionDomains =
        smoothingDomains(mesh, triElem);
    numberDomains(mesh, regionDomains);
    buildFromNumbering();
}


void Foam::elementModel::buildFromNumbering()
{
    buildNodeElements();
    buildReferenceGeometry();
    buildSolidPartition();
}


void Foam::elementModel::buildSolidPartition()
{
    // No solid region: no solid node or element, no interface, as the
    // passes below find them. After the first build only the element
    // count can change (a conversion), and subX_ and subV_ have stayed
    // zero: they are written at the interface nodes only
    bool solid = false;
    for (label r = 0; r < regions_.size(); ++r) solid = solid || isSolidRegion(r);
    if
    (
        !solid
     && label(solidNode_.size()) == nNodes_
     && label(subX_.size()) == 2*nNodes_
    )
    {
        solidElement_.assign(elemTriangle_.size(), 0);
        fluidLoad_.clear();
        fluidLoadRate_.clear();
        haveFluidLoad_ = false;
        return;
    }
    solidNode_.assign(nNodes_, 0);
    for (label r = 0; r < regions_.size(); ++r)
    {
        if (!materials_.set(r) || materials_[r].isFluid()) continue;
        for (label el = regions_[r].elemBegin; el < regions_[r].elemEnd; ++el)
        {
            for (label a = 0; a < 3; ++a) solidNode_[elemNodes_[3*el + a]] = 1;
        }
    }
    solidNodes_.clear();
    for (label n = 0; n < nNodes_; ++n)
    {
        if (solidNode_[n]) solidNodes_.push_back(n);
    }
    solidElement_.assign(elemTriangle_.size(), 0);
    for (label r = 0; r < regions_.size(); ++r)
    {
        if (!materials_.set(r) || materials_[r].isFluid()) continue;
        for (label el = regions_[r].elemBegin; el < regions_[r].elemEnd; ++el)
        {
            solidElement_[el] = 1;
        }
    }
    // interpolated: the fluid elements with a solid node, their domains and
    // the elements and nodes these need
    interfaceElems_.clear();
    interfaceDomains_.clear();
    interfaceDomainRegion_.clear();
    interfaceDomainElems_.clear();
    interfaceNodes_.clear();
    std::vector<char> domainIn(domainArea_.size(), 0);
    std::vector<char> elemIn(elemTriangle_.size(), 0), nodeIn(nNodes_, 0);
    for (label r = 0; r < regions_.size(); ++r)
    {
        if (!materials_.set(r) || !materials_[r].isFluid()) continue;
        for (label el = regions_[r].elemBegin; el < regions_[r].elemEnd; ++el)
        {
            const label* en = &elemNodes_[3*el];
            if (!solidNode_[en[0]] && !solidNode_[en[1]] && !solidNode_[en[2]])
            {
                continue;
            }
            interfaceElems_.push_back(el);
            for (label i = 0; i < 3; ++i)
            {
                const label k = elemDomains_[3*el + i];
                if (domainIn[k]) continue;
                domainIn[k] = 1;
                interfaceDomains_.push_back(k);
                interfaceDomainRegion_.push_back(r);
                for (label side = 0; side < 2; ++side)
                {
                    const label e = domainElems_[2*k + side];
                    if (e < 0 || elemIn[e]) continue;
                    elemIn[e] = 1;
                    interfaceDomainElems_.push_back(e);
                    for (label a = 0; a < 3; ++a)
                    {
                        const label n = elemNodes_[3*e + a];
                        if (!nodeIn[n]) interfaceNodes_.push_back(n);
                        nodeIn[n] = 1;
                    }
                }
            }
        }
    }
    subX_.assign(2*nNodes_, 0);
    subV_.assign(2*nNodes_, 0);

    // The fluid's load jumps where fluid elements became particles: its
    // rate starts again
    fluidLoad_.assign(2*solidNodes_.size(), 0);
    fluidLoadRate_.assign(2*solidNodes_.size(), 0);
    haveFluidLoad_ = false;
}


std::vector<Foam::label> Foam::elementModel::orderElements
(
    const triMesh& mesh
)
{
    const label nMeshTri = mesh.nTriangles();
    const std::vector<label>& tri = mesh.triangles();
    const std::vector<label>& triRegion = mesh.triangleRegion();

    // Elements: the triangles not removed, ordered by region (stable:
    // keeps the mesh's locality)
    elemTriangle_.clear();
    for (label t = 0; t < nMeshTri; ++t)
    {
        if (!removedTriangle_[t]) elemTriangle_.push_back(t);
    }
    const label nTri = label(elemTriangle_.size());
    // (A mesh numbered region by region is in order already: no sort)
    const auto byRegion =
        [&](label a, label b) { return triRegion[a] < triRegion[b]; };
    if (!std::is_sorted(elemTriangle_.begin(), elemTriangle_.end(), byRegion))
    {
        std::stable_sort(elemTriangle_.begin(), elemTriangle_.end(), byRegion);
    }
    std::vector<label> triElem(nMeshTri, -1);
    for (label e = 0; e < nTri; ++e) triElem[elemTriangle_[e]] = e;

    elemNodes_.resize(3*nTri);
    for (label e = 0; e < nTri; ++e)
    {
        for (label a = 0; a < 3; ++a)
        {
            elemNodes_[3*e + a] = tri[3*elemTriangle_[e] + a];
        }
    }
    return triElem;
}


std::vector<std::vector<std::array<Foam::label, 3>>>
Foam::elementModel::smoothingDomains
(
    const triMesh& mesh,
    const std::vector<label>& triElem
) const
{
    // Smoothing domains: one per (edge, region) pair, ordered by region
    const label nReg = mesh.nRegions();
    const std::vector<label>& triRegion = mesh.triangleRegion();
    const std::vector<label>& edgeTri = mesh.edgeTriangles();
    const label nEdge = mesh.nEdges();

    // For each region, the domains as (edge, element pair)
    std::vector<std::vector<std::array<label, 3>>> regionDomains(nReg);
    for (label k = 0; k < nEdge; ++k)
    {
        // A removed triangle is no neighbour: its edges bound the rest
        label t0 = edgeTri[2*k], t1 = edgeTri[2*k + 1];
        if (t1 >= 0 && triElem[t1] < 0) t1 = -1;
        if (triElem[t0] < 0)
        {
            // Keep the other side only (swapping would hand the removed
            // triangle's region a domain without an element)
            t0 = t1;
            t1 = -1;
        }
        if (t0 < 0) continue;
        if (t1 >= 0 && triRegion[t0] == triRegion[t1])
        {
            regionDomains[triRegion[t0]].push_back
            ({k, triElem[t0], triElem[t1]});
        }
        else
        {
            regionDomains[triRegion[t0]].push_back({k, triElem[t0], -1});
            if (t1 >= 0)
            {
                regionDomains[triRegion[t1]].push_back({k, triElem[t1], -1});
            }
        }
    }
    return regionDomains;
}


void Foam::elementModel::numberDomains
(
    const triMesh& mesh,
    std::vector<std::vector<std::array<label, 3>>>& regionDomains
)
{
    const label nReg = mesh.nRegions();
    const label nTri = label(elemTriangle_.size());
    const std::vector<label>& triRegion = mesh.triangleRegion();
    const std::vector<label>& triEdges = mesh.triangleEdges();

    regions_.setSize(nReg);
    label nDom = 0;
    for (label r = 0; r < nReg; ++r) nDom += label(regionDomains[r].size());
    domainElems_.assign(2*nDom, -1);
    elemDomains_.assign(3*nTri, -1);
    label d = 0, e = 0;
    for (label r = 0; r < nReg; ++r)
    {
        region& reg = regions_[r];
        reg.name = mesh.regionNames()[r];
        reg.elemBegin = e;
        while (e < nTri && triRegion[elemTriangle_[e]] == r) ++e;
        reg.elemEnd = e;
        reg.domainBegin = d;
        for (const auto& dom : regionDomains[r])
        {
            domainElems_[2*d] = dom[1];
            domainElems_[2*d + 1] = dom[2];
            for (label side = 1; side < 3; ++side)
            {
                const label el = dom[side];
                if (el < 0) continue;
                const label t = elemTriangle_[el];
                for (label i = 0; i < 3; ++i)
                {
                    if (triEdges[3*t + i] == dom[0]) elemDomains_[3*el + i] = d;
                }
            }
            ++d;
        }
        reg.domainEnd = d;
        regionDomains[r].clear();
        regionDomains[r].shrink_to_fit();
    }
}


void Foam::elementModel::buildNodeElements()
{
    const label nTri = label(elemTriangle_.size());

    nodeElemStart_.assign(nNodes_ + 1, 0);
    for (label n : elemNodes_) ++nodeElemStart_[n + 1];
    for (label n = 0; n < nNodes_; ++n) nodeElemStart_[n + 1] += nodeElemStart_[n];
    nodeElems_.resize(3*nTri);
    {
        std::vector<label> fill(nodeElemStart_.begin(), nodeElemStart_.end() - 1);
        for (label h = 0; h < 3*nTri; ++h) nodeElems_[fill[elemNodes_[h]]++] = h;
    }
}


void Foam::elementModel::buildReferenceGeometry()
{
    const label nReg = label(regions_.size());
    const label nTri = label(elemTriangle_.size());
    const std::vector<scalar>& density = initialDensity_;

    // Reference geometry, lumped masses, domain masses, solid time scale
    elemArea_.resize(nTri);
    elemReferenceArea_.resize(nTri);
    elemMass_.resize(nTri);
    clearElementState();
    nodeMass_.assign(nNodes_, 0);
    solidTimeScale_ = std::numeric_limits<scalar>::max();
    solidLimit_ = stepLimit();

    // Initial density of an element: from initialDensity or rho0
    const auto rhoOf = [&](const label el, const scalar rho0)
    {
        return density.empty() ? rho0 : density[elemTriangle_[el]];
    };
    for (label r = 0; r < nReg; ++r)
    {
        if (!materials_.set(r)) continue;   // void: no elements
        const spemMaterial& mat = materials_[r];
        const scalar rho0 = mat.rho();
        for (label el = regions_[r].elemBegin; el < regions_[r].elemEnd; ++el)
        {
            const scalar rho = rhoOf(el, rho0);
            const label* n = &elemNodes_[3*el];
            scalar AgradN[6];
            const scalar A = triangleAreaGradN
            (
                &X_[2*n[0]], &X_[2*n[1]], &X_[2*n[2]], AgradN
            );
            elemArea_[el] = A;
            elemReferenceArea_[el] = A;
            elemMass_[el] = rho*A;
            for (label a = 0; a < 3; ++a) nodeMass_[n[a]] += rho*A/3;
            // A geometrically linear solid's stiffness never changes: its
            // step is the reference one (the others' come from the state)
            if (!mat.isFluid() && mat.isGeometricallyLinear())
            {
                const scalar h = minAltitude(&X_[2*n[0]], &X_[2*n[1]], &X_[2*n[2]], A);
                solidTimeScale_ = std::min(solidTimeScale_, h/mat.waveSpeed());
                solidLimit_.keepSmaller
                (
                    stepLimit::criterion::solidWave, h/mat.waveSpeed(), r, h
                );
            }
        }
    }
    domainAreasAndMasses();
}


void Foam::elementModel::clearElementState()
{
    const label nTri = label(elemTriangle_.size());
    const label nDom = label(domainElems_.size()/2);
    elemAreaGrad_.assign(4*nTri, 0);
    elemForce_.assign(6*nTri, 0);
    domainGrad_.assign(4*nDom, 0);
    domainGradBehind_ = false;   // as elemAreaGrad_: zero
    domainStress_.assign(4*nDom, 0);
}


void Foam::elementModel::domainAreasAndMasses()
{
    // A third of the areas and masses of a domain's elements (every
    // domain: those of void regions have none)
    const label nDom = label(domainElems_.size()/2);
    domainArea_.resize(nDom);
    domainMass_.resize(nDom);
    for (label k = 0; k < nDom; ++k)
    {
        const label e0 = domainElems_[2*k], e1 = domainElems_[2*k + 1];
        scalar A = elemArea_[e0], m = elemMass_[e0];
        if (e1 >= 0)
        {
            A += elemArea_[e1];
            m += elemMass_[e1];
        }
        domainArea_[k] = A/3;
        domainMass_[k] = m/3;
    }
}


void Foam::elementModel::referenceGeometryAfterRemoval
(
    const triMesh& mesh,
    const std::vector<label>& triangles
)
{
    // Each element left keeps its reference area and mass
    // (removeRemovedElements() carried them along); the solid elements
    // are those before, and so is their time scale. A node's mass is the
    // sum of its elements' thirds in increasing element number, as the
    // pass over the regions adds them: summed again at the nodes of the
    // triangles taken out only, it is the same number
    elemArea_ = elemReferenceArea_;
    clearElementState();
    const std::vector<label>& tri = mesh.triangles();
    for (const label t : triangles)
    {
        for (label a = 0; a < 3; ++a)
        {
            const label n = tri[3*t + a];
            scalar m = 0;
            for (label j = nodeElemStart_[n]; j < nodeElemStart_[n + 1]; ++j)
            {
                m += elemMass_[nodeElems_[j]/3]/3;
            }
            nodeMass_[n] = m;
        }
    }
    domainAreasAndMasses();
}


inline bool Foam::elementModel::solidElementGradient
(
    const label el,
    const spemMaterial& mat,
    const bool fromState,
    const scalar* x,
    scalar& least
)
{
    const scalar* X = X_.data();
    const label* n = &elemNodes_[3*el];
    scalar u[3][2];
    for (label a = 0; a < 3; ++a)
    {
        u[a][0] = x[2*n[a]] - X[2*n[a]];
        u[a][1] = x[2*n[a] + 1] - X[2*n[a] + 1];
    }
    // Reference A grad N: recomputing it is cheaper than streaming it from
    // memory
    scalar AgradN[6];
    const scalar A0 = triangleAreaGradN
    (
        X + 2*n[0], X + 2*n[1], X + 2*n[2], AgradN
    );
    scalar* Ag = &elemAreaGrad_[4*el];
    areaGradient(AgradN, u[0], u[1], u[2], Ag);
    if (!fromState) return true;

    // The element's F = I + grad u; its current area is J A0
    const scalar invA0 = 1/A0;
    const scalar F[4] =
    {
        1 + Ag[0]*invA0, Ag[1]*invA0, Ag[2]*invA0, 1 + Ag[3]*invA0
    };
    const scalar J = F[0]*F[3] - F[1]*F[2];
    if (!(J > 0)) return false;
    const scalar A = J*A0;
    least = std::min
    (
        least,
        A*A
       /(
            longestEdgeSqr(x + 2*n[0], x + 2*n[1], x + 2*n[2])
           *mat.longitudinalModulus(F)
        )
    );
    return true;
}


bool Foam::elementModel::elementPass()
{
    const scalar* x = x_[cur_].data();
    const scalar* v = v_[cur_].data();
    bool ok = true;
    scalar timeScale = solidTimeScale_;
    stepLimit limit = solidLimit_;
    // The halves' own limits, for the solid sub-cycling
    stepLimit fluidLimit, solidLimit = solidLimit_;

    for (label r = 0; r < regions_.size(); ++r)
    {
        if (!materials_.set(r)) continue;   // void: no elements
        const spemMaterial& mat = materials_[r];
        const label begin = regions_[r].elemBegin, end = regions_[r].elemEnd;
        // A fluid region may have become particles entirely
        if (begin == end) continue;

        if (mat.isFluid())
        {
            // Performance critical: every fluid element, every step
            const scalar c = mat.waveSpeed();
            const scalar nu = mat.kinematicViscosity();
            const scalar b1 = mat.bulkViscosity();
            // The smallest altitude; with a bulk viscosity, each times
            // the factor of its damping ratio b1 sqrt(A)/h
            scalar hMin = std::numeric_limits<scalar>::max();
            // Two elements at a time (simdLanes.H)
            const bool regionOk = simd::parallelAllMinPairs
            (
                begin, end, hMin,
                [&](const auto tag, const label el, scalar& least)
                {
                    using V = typename decltype(tag)::type;
                    V X[3][2], U[3][2];
                    simd::gatherCorners(elemNodes_.data(), el, x, X);
                    simd::gatherCorners(elemNodes_.data(), el, v, U);
                    V AgradN[6];
                    const V A = triangleAreaGradN(X[0], X[1], X[2], AgradN);
                    simd::scatter
                    (
                        A, [&](const label l) -> scalar& { return elemArea_[el + l]; }
                    );
                    const V h = minAltitude(X[0], X[1], X[2], A);
                    const V limit =
                        b1 > 0
                      ? h*spemMaterial::dampedStepFactor(b1*simd::sqrt(A)/h)
                      : h;
                    for (label l = 0; l < simd::lanes<V>::size; ++l)
                    {
                        least = std::min(least, simd::lane(limit, l));
                    }
                    V g[4];
                    areaGradient(AgradN, U[0], U[1], U[2], g);
                    for (label i = 0; i < 4; ++i)
                    {
                        simd::scatter
                        (
                            g[i],
                            [&](const label l) -> scalar&
                            {
                                return elemAreaGrad_[4*(el + l) + i];
                            }
                        );
                    }
                    const auto positive = A > 0.0;
                    bool ok = true;
                    for (label l = 0; l < simd::lanes<V>::size; ++l)
                    {
                        ok = ok && simd::isTrue(positive, l);
                    }
                    return ok;
                }
            );
            if (!regionOk || !std::isfinite(hMin))
            {
                std::ostringstream os;
                os  << "an element of fluid region " << regions_[r].name
                    << " is inverted or degenerate (zero or negative area)";
                failure_ = os.str();
                ok = false;
            }
            timeScale = std::min(timeScale, hMin/c);
            limit.keepSmaller(stepLimit::criterion::acoustic, hMin/c, r, hMin);
            fluidLimit.keepSmaller
            (
                stepLimit::criterion::acoustic, hMin/c, r, hMin
            );
            // Explicit viscous diffusion limit
            if (nu > 0)
            {
                timeScale = std::min(timeScale, 0.25*hMin*hMin/nu);
                limit.keepSmaller
                (
                    stepLimit::criterion::viscous, 0.25*hMin*hMin/nu, r, hMin
                );
                fluidLimit.keepSmaller
                (
                    stepLimit::criterion::viscous, 0.25*hMin*hMin/nu, r, hMin
                );
            }
        }
        else
        {
            // Performance critical: every solid element, every step
            // The stable step of a solid whose stiffness changes with the
            // state (hyperelastic: it stiffens in compression while its
            // elements shrink) is the current smallest altitude h over the
            // current tangent wave speed c; linearElastic's force is
            // linear on the reference configuration, its stiffness and so
            // its step constant: solidTimeScale_ of build(). The loop
            // takes the least (h/c)^2 = 4 A^2 rho0/(l_max^2 M), the square
            // root once per region: divisions and square roots bound it.
            const bool fromState = !mat.isGeometricallyLinear();
            scalar minRatio = std::numeric_limits<scalar>::max();
            const bool regionOk = parallelAllMin
            (
                begin, end, minRatio, [&](const label el, scalar& least)
                {
                    return solidElementGradient(el, mat, fromState, x, least);
                }
            );
            if (fromState)
            {
                timeScale =
                    std::min(timeScale, std::sqrt(4*mat.rho()*minRatio));
                // h is not known apart from the ratio: no length
                limit.keepSmaller
                (
                    stepLimit::criterion::solidWave,
                    std::sqrt(4*mat.rho()*minRatio), r, 0
                );
                solidLimit.keepSmaller
                (
                    stepLimit::criterion::solidWave,
                    std::sqrt(4*mat.rho()*minRatio), r, 0
                );
            }
            if (!regionOk)
            {
                failure_ = "an element of solid region " + regions_[r].name
                  + " is inverted (det F <= 0)";
                ok = false;
            }
        }
    }
    // The solids' own limit after every evaluation, also within a
    // sub-cycled step (a crushed element's step falls within one)
    solidStableLimit_ = solidLimit;
    solidStableDeltaT_ =
        solidLimit.which == stepLimit::criterion::none
      ? GREAT : solidLimit.deltaT;
    stableDeltaT_ = timeScale;
    stableLimit_ = limit;
    fluidStableLimit_ = fluidLimit;
    fluidStableDeltaT_ =
        fluidLimit.which == stepLimit::criterion::none
      ? GREAT : fluidLimit.deltaT;
    return ok;
}


inline Foam::scalar Foam::elementModel::smoothedGradient
(
    const label k,
    scalar g[4]
) const
{
    return smoothedGradients<scalar>(k, g);
}


template<class V>
inline V Foam::elementModel::smoothedGradients(const label k, scalar* g) const
{
    // Element j (0, 1) of each lane's domain: its area and A_e grad v
    const label* e = &domainElems_[2*k];
    const label nLanes = simd::lanes<V>::size;
    const scalar* area[nLanes][2];
    const scalar* grad[nLanes][2];
    for (label l = 0; l < nLanes; ++l)
    {
        for (label j = 0; j < 2; ++j)
        {
            const label el = std::max(e[2*l + j], label(0));
            area[l][j] = &elemArea_[el];
            grad[l][j] = &elemAreaGrad_[4*el];
        }
    }
    const auto ofElement = [&](const label j, const scalar* const (*field)[2], const label i)
    {
        return simd::gather<V>([&](const label l) { return field[l][j][i]; });
    };
    V A = ofElement(0, area, 0);
    V G[4];
    for (label i = 0; i < 4; ++i) G[i] = ofElement(0, grad, i);
    // e[1] < 0: a domain of one element (a boundary edge); domainPass()
    // pairs only domains of two
    if (simd::lanes<V>::size > 1 || e[1] >= 0)
    {
        A += ofElement(1, area, 0);
        for (label i = 0; i < 4; ++i) G[i] += ofElement(1, grad, i);
    }
    const V invA = 1.0/A;
    for (label i = 0; i < 4; ++i)
    {
        G[i] *= invA;
        simd::scatter(G[i], [&](const label l) -> scalar& { return g[4*l + i]; });
    }
    return A;
}


inline Foam::scalar Foam::elementModel::smoothDomainGradient(const label k)
{
    return smoothedGradient(k, &domainGrad_[4*k]);
}


void Foam::elementModel::catchUpDomainGradients
(
    const label begin,
    const label end
) const
{
    if (!domainGradBehind_) return;
    for (label r = 0; r < regions_.size(); ++r)
    {
        if (!materials_.set(r) || !materials_[r].isFluid()) continue;
        parallelFor
        (
            std::max(begin, regions_[r].domainBegin),
            std::min(end, regions_[r].domainEnd),
            [&](const label k) { smoothedGradient(k, &domainGrad_[4*k]); }
        );
    }
    // Behind no more only if every domain was asked for
    if (begin <= 0 && end >= nDomains()) domainGradBehind_ = false;
}


inline void Foam::elementModel::elementForce(const label el, const scalar* x)
{
    elementForces<scalar>(el, x);
}


template<class V>
inline void Foam::elementModel::elementForces(const label el, const scalar* x)
{
    const scalar third = 1.0/3.0;
    // The stresses of domain j of each lane's element
    const label* d = &elemDomains_[3*el];
    const scalar* S[simd::lanes<V>::size][3];
    for (label l = 0; l < simd::lanes<V>::size; ++l)
    {
        for (label j = 0; j < 3; ++j) S[l][j] = &domainStress_[4*d[3*l + j]];
    }
    V P[4];
    for (label i = 0; i < 4; ++i)
    {
        const auto stress = [&](const label j)
        {
            return simd::gather<V>([&](const label l) { return S[l][j][i]; });
        };
        P[i] = third*(stress(0) + stress(1) + stress(2));
    }
    V X[3][2];
    simd::gatherCorners(elemNodes_.data(), el, x, X);
    V AgradN[6];
    triangleAreaGradN(X[0], X[1], X[2], AgradN);
    scalar* f = &elemForce_[6*el];
    for (label a = 0; a < 3; ++a)
    {
        const V fx = -(P[0]*AgradN[2*a] + P[1]*AgradN[2*a + 1]);
        const V fy = -(P[2]*AgradN[2*a] + P[3]*AgradN[2*a + 1]);
        simd::scatter(fx, [&](const label l) -> scalar& { return f[6*l + 2*a]; });
        simd::scatter
        (
            fy, [&](const label l) -> scalar& { return f[6*l + 2*a + 1]; }
        );
    }
}


bool Foam::elementModel::domainPass()
{
    bool ok = true;
    for (label r = 0; r < regions_.size(); ++r)
    {
        if (!materials_.set(r)) continue;   // void: no elements
        const label begin = regions_[r].domainBegin, end = regions_[r].domainEnd;
        const bool fluid = materials_[r].isFluid();

        // Performance critical: every domain, every step (eq. 2). A fluid
        // without solid nodes: the gradients of a block of domains on the
        // stack, their stresses from there (see domainGradBehind_; 0.91 of
        // the element half's time on Table 1's multi-resolution wedge)
        if (fluid && interfaceDomainElems_.empty())
        {
            constexpr label block = 256;
            const spemMaterial& mat = materials_[r];
            const bool fine = parallelAll
            (
                0, (end - begin + block - 1)/block, [&](const label i)
                {
                    const label b = begin + i*block;
                    const label e = std::min(end, b + block);
                    scalar grad[4*block];
                    // Two domains at a time where both have two elements
                    // (simdLanes.H)
                    for (label k = b; k < e;)
                    {
                        if
                        (
                            k + 1 < e && domainElems_[2*k + 1] >= 0
                         && domainElems_[2*k + 3] >= 0
                        )
                        {
                            const simd::pair A = smoothedGradients<simd::pair>
                            (
                                k, grad + 4*(k - b)
                            );
                            domainArea_[k] = A[0]/3;
                            domainArea_[k + 1] = A[1]/3;
                            k += 2;
                        }
                        else
                        {
                            domainArea_[k] =
                                smoothedGradient(k, grad + 4*(k - b))/3;
                            ++k;
                        }
                    }
                    // The material's stress depends on the domains'
                    // arrays only: the block's, from its first domain
                    return mat.stress
                    (
                        0, e - b, grad, domainArea_.data() + b,
                        domainMass_.data() + b, domainStress_.data() + 4*b
                    );
                },
                minParallelLoop/block
            );
            domainGradBehind_ = true;
            if (!fine)
            {
                failure_ = "a smoothing domain of fluid region "
                  + regions_[r].name + " is inverted";
                ok = false;
            }
            continue;
        }
        parallelFor(begin, end, [&](const label k)
        {
            const scalar A = smoothDomainGradient(k);
            if (fluid) domainArea_[k] = A/3;
        });

        if
        (
            !materials_[r].stress
            (
                begin, end, domainGrad_.data(), domainArea_.data(),
                domainMass_.data(), domainStress_.data()
            )
        )
        {
            failure_ = "a smoothing domain of solid region " + regions_[r].name
              + " is inverted (det F <= 0)";
            ok = false;
        }
    }
    return ok;
}


void Foam::elementModel::forcePass()
{
    for (label r = 0; r < regions_.size(); ++r)
    {
        if (!materials_.set(r)) continue;   // void: no elements
        // Current configuration for fluids, reference for solids
        const scalar* x =
            materials_[r].isFluid() ? x_[cur_].data() : X_.data();
        const label begin = regions_[r].elemBegin, end = regions_[r].elemEnd;

        // Performance critical: every element, every step (eq. 5); two
        // elements at a time (simdLanes.H)
        simd::parallelForPairs
        (
            begin, end, [&](const auto tag, const label el)
            {
                elementForces<typename decltype(tag)::type>(el, x);
            }
        );
    }
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::elementModel::elementModel
(
    const triMesh& mesh,
    PtrList<spemMaterial>&& materials,
    const std::vector<scalar>& density
)
:
    materials_(std::move(materials)),
    nNodes_(mesh.nPoints()),
    X_(mesh.points()),
    x_{mesh.points(), mesh.points()},
    v_{std::vector<scalar>(2*nNodes_, 0), std::vector<scalar>(2*nNodes_, 0)},
    cur_(0),
    previousDeltaT_{0, 0},
    nodeConstraint_(nNodes_, constraint::free),
    nodeNormal_(2*nNodes_, 0),
    nodeNormalSpeed_(nNodes_, 0),
    nodeReaction_(2*nNodes_, 0),
    gravity_{0, 0},
    massDamping_(0),
    solidTimeScale_(0),
    stableDeltaT_(0),
    fluidStableDeltaT_(GREAT),
    solidStableDeltaT_(GREAT),
    previousSubStep_{0, 0},
    load_(subCycleLoad::held),
    haveFluidLoad_(false),
    nTeamSlots_(0)
{
    if (!density.empty() && label(density.size()) != mesh.nTriangles())
    {
        FatalErrorInFunction
            << density.size() << " initial densities for "
            << mesh.nTriangles() << " triangles" << exit(FatalError);
    }
    initialDensity_ = density;
    // Triangles of void regions (empty space) are no elements
    removedTriangle_.assign(mesh.nTriangles(), false);
    for (label t = 0; t < mesh.nTriangles(); ++t)
    {
        removedTriangle_[t] =
            materials_.size() == mesh.nRegions()
         && !materials_.set(mesh.triangleRegion()[t]);
    }
    externalForce_.assign(2*nNodes_, 0);
    build(mesh);
    reserveTeamSlots(maxThreads());
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::elementModel::setConstraints
(
    std::vector<constraint> c,
    std::vector<scalar> normals
)
{
    if (label(c.size()) != nNodes_ || label(normals.size()) != 2*nNodes_)
    {
        FatalErrorInFunction << "Constraint arrays have the wrong size"
            << exit(FatalError);
    }
    nodeConstraint_ = std::move(c);
    nodeNormal_ = std::move(normals);
    nodeNormalSpeed_.assign(nNodes_, 0);
}


void Foam::elementModel::setMovingSlip
(
    const label n,
    const scalar nx,
    const scalar ny,
    const scalar normalSpeed
)
{
    nodeConstraint_[n] = constraint::slip;
    nodeNormal_[2*n] = nx;
    nodeNormal_[2*n + 1] = ny;
    nodeNormalSpeed_[n] = normalSpeed;
}


void Foam::elementModel::setPosition(const label n, const scalar x, const scalar y)
{
    x_[cur_][2*n] = x;
    x_[cur_][2*n + 1] = y;
    ++positionsVersion_;
}


void Foam::elementModel::setGravity(const scalar gx, const scalar gy)
{
    gravity_[0] = gx;
    gravity_[1] = gy;
}


void Foam::elementModel::setState
(
    const std::vector<scalar>& x,
    const std::vector<scalar>& v
)
{
    if (label(x.size()) != 2*nNodes_ || label(v.size()) != 2*nNodes_)
    {
        FatalErrorInFunction << "State arrays have " << label(x.size()/2)
            << " and " << label(v.size()/2) << " nodes, the mesh "
            << nNodes_ << exit(FatalError);
    }
    x_[cur_] = x;
    v_[cur_] = v;
    x_[1 - cur_] = x;
    v_[1 - cur_] = v;
    ++positionsVersion_;
}


void Foam::elementModel::setVelocity(const std::vector<scalar>& v)
{
    setState(x_[cur_], v);
}


bool Foam::elementModel::evaluate()
{
    failure_.clear();
    if (!elementPass()) return false;
    if (!domainPass()) return false;
    forcePass();
    return true;
}


inline bool Foam::elementModel::integrateNode
(
    const label n,
    const scalar* x,
    const scalar* v,
    scalar* xNew,
    scalar* vNew,
    const scalar span,
    const scalar keep,
    const scalar gain,
    const scalar dt,
    scalar* reaction,
    const scalar* extraForce
) const
{
    const scalar* force = elemForce_.data();
    const scalar* external = externalForce_.data();
    scalar f[2] = {external[2*n], external[2*n + 1]};
    if (extraForce)
    {
        f[0] += extraForce[0];
        f[1] += extraForce[1];
    }
    for (label j = nodeElemStart_[n]; j < nodeElemStart_[n + 1]; ++j)
    {
        const label h = nodeElems_[j];
        f[0] += force[2*h];
        f[1] += force[2*h + 1];
    }
    const scalar invM = 1/nodeMass_[n];
    scalar keepN = keep, gainN = gain;
    if (absorbing_.active() && !solidNode_[n])
    {
        absorbing_.dampingFactors
        (
            x[2*n], x[2*n + 1], massDamping_, span, keepN, gainN
        );
    }
    scalar vn[2] =
    {
        keepN*v[2*n] + gainN*(f[0]*invM + gravity_[0]),
        keepN*v[2*n + 1] + gainN*(f[1]*invM + gravity_[1])
    };
    if (nodeConstraint_[n] != constraint::free)
    {
        const scalar vFree[2] = {vn[0], vn[1]};
        if (nodeConstraint_[n] == constraint::slip)
        {
            const scalar* nn = &nodeNormal_[2*n];
            const scalar vnn =
                vn[0]*nn[0] + vn[1]*nn[1] - nodeNormalSpeed_[n];
            vn[0] -= vnn*nn[0];
            vn[1] -= vnn*nn[1];
            // A fixed no-slip wall's shear, -k v_t, implicit over the
            // span: stable for any k (patchConditions)
            if (!wallFriction_.empty() && wallFriction_[n] > 0)
            {
                const scalar hold =
                    1/(1 + span*wallFriction_[n]*invM);
                vn[0] *= hold;
                vn[1] *= hold;
            }
        }
        else
        {
            vn[0] = vn[1] = 0;
        }
        // The force that removed the constrained velocity
        const scalar mOverGain = nodeMass_[n]/gainN;
        reaction[0] = mOverGain*(vn[0] - vFree[0]);
        reaction[1] = mOverGain*(vn[1] - vFree[1]);
    }
    vNew[2*n] = vn[0];
    vNew[2*n + 1] = vn[1];
    xNew[2*n] = x[2*n] + dt*vn[0];
    xNew[2*n + 1] = x[2*n + 1] + dt*vn[1];
    return std::isfinite(vn[0]) && std::isfinite(vn[1]);
}


bool Foam::elementModel::advance(const scalar dt)
{
    const scalar* x = x_[cur_].data();
    const scalar* v = v_[cur_].data();
    scalar* xNew = x_[1 - cur_].data();
    scalar* vNew = v_[1 - cur_].data();
    // The velocity spans dt^n = (dt^{n-1/2} + dt^{n+1/2})/2, from the
    // half step before to the half step after the forces' time.
    // Implicit mass-proportional damping: stable for any alpha dt
    const scalar span = 0.5*(previousDeltaT_[cur_] + dt);
    const scalar keep = 1/(1 + massDamping_*span), gain = span*keep;
    scalar* reaction = nodeReaction_.data();

    // Performance critical: every node, every step. In blocks of nodes,
    // each with its largest speed (for the locator's bound) in a register
    // (OpenMP's min reduction per node was no faster; a pass after the
    // loop would read the velocities again): about 1.1 times the loop
    // without it (elementStepBenchmark advanceOnly), against the pass over
    // every node coordinate that currentLocator() no longer makes
    constexpr label block = 256;
    const label nBlocks = (nNodes_ + block - 1)/block;
    blockFastest_.resize(nBlocks);
    const bool finite = parallelAll
    (
        0, nBlocks,
        [&](const label b)
        {
            bool ok = true;
            scalar fastest = 0;
            const label end = std::min(nNodes_, (b + 1)*block);
            for (label n = b*block; n < end; ++n)
            {
                // A node without elements (all became particles) stays
                // where it is
                if (nodeMass_[n] == 0)
                {
                    vNew[2*n] = vNew[2*n + 1] = 0;
                    xNew[2*n] = x[2*n];
                    xNew[2*n + 1] = x[2*n + 1];
                    continue;
                }
                ok = integrateNode
                (
                    n, x, v, xNew, vNew, span, keep, gain, dt, reaction + 2*n
                ) && ok;
                const scalar speed =
                    std::max(std::abs(vNew[2*n]), std::abs(vNew[2*n + 1]));
                fastest = speed > fastest ? speed : fastest;
            }
            blockFastest_[b] = fastest;
            return ok;
        },
        minParallelLoop/block
    );
    cur_ = 1 - cur_;
    if (finite)
    {
        scalar fastest = 0;
        for (const scalar s : blockFastest_) fastest = std::max(fastest, s);
        positionsMoved(std::abs(dt)*fastest);
    }
    else
    {
        ++positionsVersion_;     // (a NaN speed is no bound)
    }
    previousDeltaT_[cur_] = dt;
    previousSubStep_[cur_] = dt;
    // A step without sub-steps: the next sub-cycled one starts the
    // extrapolated load again
    haveFluidLoad_ = false;
    if (!finite)
    {
        failure_ = "a node velocity is not finite";
        return false;
    }
    return true;
}


bool Foam::elementModel::advanceFluidPartition(const scalar dt)
{
    // The sub-steps that follow may run in a team of this many threads
    reserveTeamSlots(maxThreads());
    const scalar* x = x_[cur_].data();
    const scalar* v = v_[cur_].data();
    scalar* xNew = x_[1 - cur_].data();
    scalar* vNew = v_[1 - cur_].data();
    const scalar span = 0.5*(previousDeltaT_[cur_] + dt);
    const scalar keep = 1/(1 + massDamping_*span), gain = span*keep;
    scalar* reaction = nodeReaction_.data();

    // Performance critical: every node, every fluid step
    const bool finite = parallelAll(0, nNodes_, [&](const label n)
    {
        // The solid partition keeps its state for the sub-steps; a node
        // without elements stays where it is
        if (solidNode_[n] || nodeMass_[n] == 0)
        {
            vNew[2*n] = solidNode_[n] ? v[2*n] : 0;
            vNew[2*n + 1] = solidNode_[n] ? v[2*n + 1] : 0;
            xNew[2*n] = x[2*n];
            xNew[2*n + 1] = x[2*n + 1];
            return true;
        }
        return integrateNode
        (
            n, x, v, xNew, vNew, span, keep, gain, dt, reaction + 2*n
        );
    });
    // The fluid's load on the solid nodes and its rate from the last
    // fluid step (extrapolated load)
    if (load_ != subCycleLoad::held)
    {
        // interpolated: the fluid elements' forces come from the
        // sub-steps, the external forces are extrapolated
        const bool withElements = load_ == subCycleLoad::extrapolated;
        const scalar previousDt = previousDeltaT_[cur_];
        const bool rate = haveFluidLoad_ && previousDt > 0;
        const scalar* force = elemForce_.data();
        const scalar* external = externalForce_.data();
        for (size_t i = 0; i < solidNodes_.size(); ++i)
        {
            const label n = solidNodes_[i];
            scalar F[2] = {external[2*n], external[2*n + 1]};
            for (label j = nodeElemStart_[n]; j < nodeElemStart_[n + 1]; ++j)
            {
                const label h = nodeElems_[j];
                if (!withElements || solidElement_[h/3]) continue;
                F[0] += force[2*h];
                F[1] += force[2*h + 1];
            }
            for (label c = 0; c < 2; ++c)
            {
                fluidLoadRate_[2*i + c] =
                    rate ? (F[c] - fluidLoad_[2*i + c])/previousDt : 0;
                fluidLoad_[2*i + c] = F[c];
            }
        }
        haveFluidLoad_ = true;
    }

    const scalar subStep = previousSubStep_[cur_];
    cur_ = 1 - cur_;
    ++positionsVersion_;
    previousDeltaT_[cur_] = dt;
    previousSubStep_[cur_] = subStep;
    if (!finite)
    {
        failure_ = "a node velocity is not finite";
        return false;
    }
    return true;
}


Foam::label Foam::elementModel::nSolidElements() const
{
    label n = 0;
    for (label r = 0; r < regions_.size(); ++r)
    {
        if (isSolidRegion(r)) n += regions_[r].elemEnd - regions_[r].elemBegin;
    }
    return n;
}


void Foam::elementModel::setFluidLoad(const std::vector<scalar>& load)
{
    if (load.empty())
    {
        haveFluidLoad_ = false;
        return;
    }
    if (load.size() != fluidLoad_.size())
    {
        FatalErrorInFunction
            << "The fluid's load of " << load.size()/2 << " solid nodes for "
            << solidNodes_.size() << exit(FatalError);
    }
    fluidLoad_ = load;
    haveFluidLoad_ = true;
}


bool Foam::elementModel::evaluateSolids(const scalar elapsed)
{
    if (inTeam())
    {
        FatalErrorInFunction
            << "evaluateSolids without a threadTeam inside a parallel region"
            << exit(FatalError);
    }
    threadTeam one;
    return evaluateSolids(elapsed, one);
}


bool Foam::elementModel::evaluateSolids
(
    const scalar elapsed,
    threadTeam& team
)
{
    // Every thread of the team runs this, each over its threadBlock of
    // every pass, with team.sync() between the passes; rank 0 sums up.
    // Each item is computed alike and the passes follow the order of one
    // thread's: the same results, and the same failure, on any number of
    // threads. Each thread writes its own slots of the flags.
    const label nReg = regions_.size();
    const label t = team.rank(), nT = team.size();
    checkTeamSlots(nT);
    const bool interpolated = load_ == subCycleLoad::interpolated;
    const scalar* x = x_[cur_].data();
    // Whether a thread cleared its flag of region r, and whether none did
    // for any solid region (after a sync)
    const auto anyThread = [&](const std::vector<char>& flags, const label r)
    {
        for (label i = 0; i < nT; ++i)
        {
            if (!flags[i*nReg + r]) return true;
        }
        return false;
    };
    const auto allOk = [&](const std::vector<char>& flags)
    {
        for (label r = 0; r < nReg; ++r)
        {
            if (isSolidRegion(r) && anyThread(flags, r)) return false;
        }
        return true;
    };

    // The solid elements' A_e grad u, and the least (h/c)^2 of those whose
    // stiffness follows the state; interpolated: the interface nodes at
    // elapsed
    for (label r = 0; r < nReg; ++r)
    {
        if (!isSolidRegion(r)) continue;
        const spemMaterial& mat = materials_[r];
        const bool fromState = !mat.isGeometricallyLinear();
        label b, e;
        threadBlock(regions_[r].elemBegin, regions_[r].elemEnd, b, e);
        scalar least = std::numeric_limits<scalar>::max();
        bool ok = true;
        for (label el = b; el < e; ++el)
        {
            ok = solidElementGradient(el, mat, fromState, x, least) && ok;
        }
        teamLeast_[t*nReg + r] = least;
        teamElemOk_[t*nReg + r] = ok;
    }
    if (interpolated) interfaceNodeState(elapsed);
    team.sync();
    bool ok = allOk(teamElemOk_);

    // Their domains: smoothed gradients and stresses
    if (ok)
    {
        for (label r = 0; r < nReg; ++r)
        {
            if (!isSolidRegion(r)) continue;
            label b, e;
            threadBlock(regions_[r].domainBegin, regions_[r].domainEnd, b, e);
            for (label k = b; k < e; ++k) smoothDomainGradient(k);
            teamDomainOk_[t*nReg + r] =
                b == e
             || materials_[r].stress
                (
                    b, e, domainGrad_.data(), domainArea_.data(),
                    domainMass_.data(), domainStress_.data()
                );
        }
        team.sync();
        ok = allOk(teamDomainOk_);
    }

    // The solid elements' forces (on the reference configuration, eq. 5);
    // interpolated: the geometry of the fluid elements next to them
    if (ok)
    {
        for (label r = 0; r < nReg; ++r)
        {
            if (!isSolidRegion(r)) continue;
            label b, e;
            threadBlock(regions_[r].elemBegin, regions_[r].elemEnd, b, e);
            for (label el = b; el < e; ++el) elementForce(el, X_.data());
        }
        teamInterfaceOk_[t] = !interpolated || interfaceElementGradients();
        team.sync();
        for (label i = 0; i < nT; ++i) ok = ok && teamInterfaceOk_[i];
    }

    // interpolated: the fluid domains and forces next to the solids
    if (ok && interpolated)
    {
        interfaceDomainStresses();
        team.sync();
        interfaceForces();
    }

    if (t == 0)
    {
        // The solids' own stable step, also within a sub-cycled step (a
        // crushed element's step falls within one)
        stepLimit solidLimit = solidLimit_;
        for (label r = 0; r < nReg; ++r)
        {
            if
            (
                !isSolidRegion(r)
             || regions_[r].elemBegin == regions_[r].elemEnd
             || materials_[r].isGeometricallyLinear()
            )
            {
                continue;
            }
            scalar least = std::numeric_limits<scalar>::max();
            for (label i = 0; i < nT; ++i)
            {
                least = std::min(least, teamLeast_[i*nReg + r]);
            }
            solidLimit.keepSmaller
            (
                stepLimit::criterion::solidWave,
                std::sqrt(4*materials_[r].rho()*least), r, 0
            );
        }
        solidStableLimit_ = solidLimit;
        solidStableDeltaT_ =
            solidLimit.which == stepLimit::criterion::none
          ? GREAT : solidLimit.deltaT;
        // The failure of the first pass that failed (only its flags are
        // of this call), its last region
        failure_.clear();
        for (label r = 0; r < nReg; ++r)
        {
            if (isSolidRegion(r) && anyThread(teamElemOk_, r))
            {
                failure_ = "an element of solid region "
                  + regions_[r].name + " is inverted (det F <= 0)";
            }
        }
        const bool elementsOk = failure_.empty();
        for (label r = 0; elementsOk && !ok && r < nReg; ++r)
        {
            if (isSolidRegion(r) && anyThread(teamDomainOk_, r))
            {
                failure_ = "a smoothing domain of solid region "
                  + regions_[r].name + " is inverted (det F <= 0)";
            }
        }
        if (failure_.empty() && !ok)
        {
            failure_ =
                "a fluid element next to a solid is inverted or degenerate"
                " (zero or negative area) inside a sub-cycled step";
        }
    }
    team.sync();
    return ok;
}


void Foam::elementModel::reserveTeamSlots(const label nThreads)
{
    const label nReg = regions_.size();
    if (nTeamSlots_ >= nThreads && label(teamLeast_.size()) == nTeamSlots_*nReg)
    {
        return;
    }
    nTeamSlots_ = max(nThreads, label(1));
    teamLeast_.assign(nTeamSlots_*nReg, 0);
    teamElemOk_.assign(nTeamSlots_*nReg, 1);
    teamDomainOk_.assign(nTeamSlots_*nReg, 1);
    teamInterfaceOk_.assign(nTeamSlots_, 1);
    teamFinite_.assign(nTeamSlots_, 1);
}


void Foam::elementModel::checkTeamSlots(const label nThreads) const
{
    if (nThreads > nTeamSlots_)
    {
        FatalErrorInFunction
            << "A team of " << nThreads << " threads for the sub-steps, slots"
            << " for " << nTeamSlots_ << " (advanceFluidPartition reserves"
            << " them for omp_get_max_threads())" << exit(FatalError);
    }
}


void Foam::elementModel::interfaceNodeState(const scalar elapsed)
{
    // After advanceFluidPartition: the other buffer holds x^n, the
    // current one the fluid nodes' v^{n+1/2} and the solid nodes' state
    const scalar* xOld = x_[1 - cur_].data();
    const scalar* x = x_[cur_].data();
    const scalar* v = v_[cur_].data();
    scalar* xs = subX_.data();
    scalar* vs = subV_.data();
    label b, e;
    threadBlock(0, label(interfaceNodes_.size()), b, e);
    for (label i = b; i < e; ++i)
    {
        const label n = interfaceNodes_[i];
        for (label c = 0; c < 2; ++c)
        {
            xs[2*n + c] =
                solidNode_[n] ? x[2*n + c] : xOld[2*n + c] + elapsed*v[2*n + c];
            vs[2*n + c] = v[2*n + c];
        }
    }
}


bool Foam::elementModel::interfaceElementGradients()
{
    // The elements of the interface domains: current area and A_e grad v
    const scalar* xs = subX_.data();
    const scalar* vs = subV_.data();
    label b, e;
    threadBlock(0, label(interfaceDomainElems_.size()), b, e);
    bool ok = true;
    for (label i = b; i < e; ++i)
    {
        const label el = interfaceDomainElems_[i];
        const label* n = &elemNodes_[3*el];
        scalar AgradN[6];
        const scalar A = triangleAreaGradN
        (
            xs + 2*n[0], xs + 2*n[1], xs + 2*n[2], AgradN
        );
        elemArea_[el] = A;
        ok = ok && A > 0;
        areaGradient
        (
            AgradN, vs + 2*n[0], vs + 2*n[1], vs + 2*n[2], &elemAreaGrad_[4*el]
        );
    }
    return ok;
}


void Foam::elementModel::interfaceDomainStresses()
{
    // Smoothed gradient, area and stress (eq. 2)
    label b, e;
    threadBlock(0, label(interfaceDomains_.size()), b, e);
    for (label i = b; i < e; ++i)
    {
        const label k = interfaceDomains_[i];
        domainArea_[k] = smoothDomainGradient(k)/3;
        materials_[interfaceDomainRegion_[i]].stress
        (
            k, k + 1, domainGrad_.data(), domainArea_.data(),
            domainMass_.data(), domainStress_.data()
        );
    }
}


void Foam::elementModel::interfaceForces()
{
    // The forces of the fluid elements with a solid node (eq. 5)
    label b, e;
    threadBlock(0, label(interfaceElems_.size()), b, e);
    const scalar* xs = subX_.data();
    for (label i = b; i < e; ++i) elementForce(interfaceElems_[i], xs);
}


bool Foam::elementModel::advanceSolidSubStep
(
    const scalar subDt,
    const scalar elapsed,
    const scalar dt
)
{
    if (inTeam())
    {
        FatalErrorInFunction
            << "advanceSolidSubStep without a threadTeam inside a parallel"
            << " region" << exit(FatalError);
    }
    threadTeam one;
    return advanceSolidSubStep(subDt, elapsed, dt, one);
}


bool Foam::elementModel::advanceSolidSubStep
(
    const scalar subDt,
    const scalar elapsed,
    const scalar dt,
    threadTeam& team
)
{
    const bool first = elapsed == 0;
    const bool extrapolate = load_ != subCycleLoad::held && !first;
    // In place: the other buffer holds the state at the start of the
    // fluid step (revert())
    scalar* x = x_[cur_].data();
    scalar* v = v_[cur_].data();
    // From the sub-step before, which may have been of another length (the
    // last of the fluid step before, or one before a re-split); the same
    // sub-step: exactly subDt
    const scalar span = 0.5*(previousSubStep_[cur_] + subDt);
    const scalar keep = 1/(1 + massDamping_*span), gain = span*keep;
    // The reactions are the mean force over the fluid step
    const scalar weight = subDt/dt;
    const label nSolid = label(solidNodes_.size());

    // Performance critical: every solid node, every sub-step. Run by every
    // thread of the team over its threadBlock (evaluateSolids)
    const label t = team.rank(), nT = team.size();
    checkTeamSlots(nT);
    const auto subStep = [&](const label i)
    {
        const label n = solidNodes_[i];
        scalar r[2] = {0, 0};
        // The fluid's load at the sub-step's time, F^n + elapsed dF/dt
        // (the evaluation holds F^n)
        const scalar extra[2] =
        {
            extrapolate ? elapsed*fluidLoadRate_[2*i] : 0,
            extrapolate ? elapsed*fluidLoadRate_[2*i + 1] : 0
        };
        const bool ok =
            integrateNode
            (
                n, x, v, x, v, span, keep, gain, subDt, r,
                extrapolate ? extra : nullptr
            );
        if (nodeConstraint_[n] == constraint::free) return ok;
        scalar* reaction = &nodeReaction_[2*n];
        reaction[0] = (first ? 0 : reaction[0]) + weight*r[0];
        reaction[1] = (first ? 0 : reaction[1]) + weight*r[1];
        return ok;
    };
    label b, e;
    threadBlock(0, nSolid, b, e);
    bool finite = true;
    for (label i = b; i < e; ++i) finite = subStep(i) && finite;
    teamFinite_[t] = finite;
    team.sync();
    for (label i = 0; i < nT; ++i) finite = finite && teamFinite_[i];
    if (t == 0)
    {
        previousSubStep_[cur_] = subDt;
        ++positionsVersion_;
        if (!finite) failure_ = "a node velocity is not finite";
    }
    team.sync();
    return finite;
}


void Foam::elementModel::removeTriangles
(
    const triMesh& mesh,
    const std::vector<label>& triangles
)
{
    if (mesh.nTriangles() != label(removedTriangle_.size()))
    {
        FatalErrorInFunction
            << "removeTriangles needs the mesh of construction"
            << exit(FatalError);
    }
    const label versionBefore = topologyVersion_;
    ++topologyVersion_;
    bool fluidOnly = true;
    for (const label t : triangles)
    {
        if (t < 0 || t >= mesh.nTriangles() || removedTriangle_[t])
        {
            FatalErrorInFunction
                << "Triangle " << t << " is not an element of the model"
                << exit(FatalError);
        }
        removedTriangle_[t] = true;
        const label r = mesh.triangleRegion()[t];
        fluidOnly = fluidOnly && !isSolidRegion(r);
    }
    // build(mesh) without the pass over the mesh's edges: 0.87 of the
    // conversions' time on Table 1's multi-resolution wedge, 57
    // conversions of 53,120 elements (benchmarks/README.md); nor the
    // counting sort of the node lists, nor the reference geometry of every
    // element when only fluid elements go
    const std::vector<label> oldToNew = removeRemovedElements();
    removeRemovedNodeElements(oldToNew);
    if (fluidOnly)
    {
        referenceGeometryAfterRemoval(mesh, triangles);
    }
    else
    {
        buildReferenceGeometry();
    }
    buildSolidPartition();
    // The probes' grid of the elements before: the elements left keep
    // their order and their nodes, so it holds them renumbered
    locator_.renumber(oldToNew, nElements(), versionBefore, topologyVersion_);

    // Nodes without elements rest: no mass, no momentum. In the current
    // state only: advance() writes the other buffer whole, and until then
    // it is the previous state, which a revert after a failed step makes
    // current again with its elements restored (restoreTriangles())
    std::vector<scalar>& v = v_[cur_];
    for (label n = 0; n < nNodes_; ++n)
    {
        if (nodeMass_[n] == 0) v[2*n] = v[2*n + 1] = 0;
    }
}


std::vector<Foam::label> Foam::elementModel::removeRemovedElements()
{
    // The elements left, renumbered in the same order: what
    // orderElements() makes of the new set (a subsequence of a list
    // stably sorted by region is the stable sort of the subsequence)
    const label nOld = nElements();
    std::vector<label> newElem(nOld, -1);
    label nNew = 0;
    for (label r = 0; r < regions_.size(); ++r)
    {
        region& reg = regions_[r];
        const label oldBegin = reg.elemBegin, oldEnd = reg.elemEnd;
        reg.elemBegin = nNew;
        for (label el = oldBegin; el < oldEnd; ++el)
        {
            const label t = elemTriangle_[el];
            if (removedTriangle_[t]) continue;
            newElem[el] = nNew;
            elemTriangle_[nNew] = t;
            elemMass_[nNew] = elemMass_[el];
            elemReferenceArea_[nNew] = elemReferenceArea_[el];
            for (label a = 0; a < 3; ++a)
            {
                elemNodes_[3*nNew + a] = elemNodes_[3*el + a];
                elemDomains_[3*nNew + a] = elemDomains_[3*el + a];
            }
            ++nNew;
        }
        reg.elemEnd = nNew;
    }
    elemTriangle_.resize(nNew);
    elemMass_.resize(nNew);
    elemReferenceArea_.resize(nNew);
    elemNodes_.resize(3*nNew);
    elemDomains_.resize(3*nNew);

    // The domains left, in the same order (by edge within each region):
    // those with an element left; one that lost its first element keeps
    // the second as its first, as smoothingDomains() would make it
    std::vector<label> newDomain(domainElems_.size()/2, -1);
    label nDom = 0;
    for (label r = 0; r < regions_.size(); ++r)
    {
        region& reg = regions_[r];
        const label oldBegin = reg.domainBegin, oldEnd = reg.domainEnd;
        reg.domainBegin = nDom;
        for (label k = oldBegin; k < oldEnd; ++k)
        {
            label e0 = newElem[domainElems_[2*k]];
            label e1 = domainElems_[2*k + 1];
            if (e1 >= 0) e1 = newElem[e1];
            if (e0 < 0)
            {
                e0 = e1;
                e1 = -1;
            }
            if (e0 < 0) continue;
            domainElems_[2*nDom] = e0;
            domainElems_[2*nDom + 1] = e1;
            newDomain[k] = nDom++;
        }
        reg.domainEnd = nDom;
    }
    domainElems_.resize(2*nDom);
    for (label& d : elemDomains_) d = newDomain[d];
    return newElem;
}


void Foam::elementModel::removeRemovedNodeElements
(
    const std::vector<label>& oldToNew
)
{
    // In place: a node's entries move to the front of what is left
    label out = 0;
    label begin = nodeElemStart_[0];
    for (label n = 0; n < nNodes_; ++n)
    {
        const label end = nodeElemStart_[n + 1];
        nodeElemStart_[n] = out;
        for (label j = begin; j < end; ++j)
        {
            const label h = nodeElems_[j];
            const label el = oldToNew[h/3];
            if (el >= 0) nodeElems_[out++] = 3*el + h%3;
        }
        begin = end;
    }
    nodeElemStart_[nNodes_] = out;
    nodeElems_.resize(out);
}


void Foam::elementModel::restoreTriangles
(
    const triMesh& mesh,
    const std::vector<label>& triangles
)
{
    if (mesh.nTriangles() != label(removedTriangle_.size()))
    {
        FatalErrorInFunction
            << "restoreTriangles needs the mesh of construction"
            << exit(FatalError);
    }
    ++topologyVersion_;
    for (const label t : triangles)
    {
        if (t < 0 || t >= mesh.nTriangles() || !removedTriangle_[t])
        {
            FatalErrorInFunction
                << "Triangle " << t << " was not taken out of the model"
                << exit(FatalError);
        }
        removedTriangle_[t] = false;
    }
    // The same set of removed triangles builds the same elements and
    // domains, in the same order, with the same masses
    build(mesh);
}


void Foam::elementModel::correctVelocity
(
    const label n,
    const scalar du,
    const scalar dv,
    const scalar dt
)
{
    v_[cur_][2*n] += du;
    v_[cur_][2*n + 1] += dv;
    x_[cur_][2*n] += dt*du;
    x_[cur_][2*n + 1] += dt*dv;
    positionsMoved(std::abs(dt)*std::max(std::abs(du), std::abs(dv)));
}


std::vector<Foam::scalar> Foam::elementModel::nodalForces() const
{
    std::vector<scalar> f(2*nNodes_, 0);
    for (label h = 0; h < label(elemNodes_.size()); ++h)
    {
        f[2*elemNodes_[h]] += elemForce_[2*h];
        f[2*elemNodes_[h] + 1] += elemForce_[2*h + 1];
    }
    return f;
}


void Foam::elementModel::domainCauchyStress
(
    const label begin,
    const label end,
    scalar* sigma6,
    scalar* pressure
) const
{
    // The gradients of these domains only (a probe asks for one)
    catchUpDomainGradients(begin, end);
    for (label r = 0; r < regions_.size(); ++r)
    {
        if (!materials_.set(r)) continue;   // void: no elements
        const label b = std::max(begin, regions_[r].domainBegin);
        const label e = std::min(end, regions_[r].domainEnd);
        if (b >= e) continue;
        materials_[r].cauchyStress
        (
            b, e, domainGrad_.data(), domainArea_.data(), domainMass_.data(),
            sigma6 + 6*(b - begin), pressure + (b - begin)
        );
    }
}


Foam::elementModel::elementFields Foam::elementModel::fields() const
{
    const label nDom = nDomains(), nEl = nElements();
    std::vector<scalar> sigma(6*nDom), p(nDom), rho(nDom);
    catchUpDomainGradients();
    domainCauchyStress(0, nDom, sigma.data(), p.data());
    for (label r = 0; r < regions_.size(); ++r)
    {
        if (!materials_.set(r)) continue;   // void: no elements
        const label b = regions_[r].domainBegin, e = regions_[r].domainEnd;
        materials_[r].density
        (
            b, e, domainGrad_.data(), domainArea_.data(), domainMass_.data(),
            rho.data() + b
        );
    }

    elementFields out;
    out.stress.assign(6*nEl, 0);
    out.pressure.assign(nEl, 0);
    out.density.assign(nEl, 0);
    out.vonMises.assign(nEl, 0);
    for (label el = 0; el < nEl; ++el)
    {
        for (label i = 0; i < 3; ++i)
        {
            const label k = elemDomains_[3*el + i];
            for (label c = 0; c < 6; ++c) out.stress[6*el + c] += sigma[6*k + c]/3;
            out.pressure[el] += p[k]/3;
            out.density[el] += rho[k]/3;
        }
        const scalar* s = &out.stress[6*el];
        out.vonMises[el] = std::sqrt
        (
            0.5*
            (
                (s[0] - s[1])*(s[0] - s[1]) + (s[1] - s[2])*(s[1] - s[2])
              + (s[2] - s[0])*(s[2] - s[0])
            )
          + 3*(s[3]*s[3] + s[4]*s[4] + s[5]*s[5])
        );
    }
    return out;
}


bool Foam::elementModel::currentLocator() const
{
    // Nothing moved and no element changed since the last check: the grid
    // holds without its pass over the nodes
    if
    (
        locatorCheckedAt_ == positionsVersion_
     && locator_.version() == topologyVersion_
    )
    {
        return true;
    }
    // The nodes provably within the grid's reach (the steps since the last
    // pass moved them too little): valid without the pass. A rebuild comes
    // when it did before, since a pass is made whenever the bound exceeds
    // the reach. Table 1's multi-resolution wedge run: 57 passes for 1,451
    // checks (benchmarks/README.md)
    if
    (
        locator_.version() == topologyVersion_
     && driftVersion_ == positionsVersion_
     && locatorDrift_ <= locator_.reach()
    )
    {
        locatorCheckedAt_ = positionsVersion_;
        return true;
    }
    const std::vector<scalar>& x = x_[cur_];
    const scalar drift = locator_.drift(x, nElements(), topologyVersion_);
    bool gridded = drift <= locator_.reach();
    // |a - b| of the pass is rounded (a relative half epsilon)
    constexpr scalar eps = std::numeric_limits<scalar>::epsilon();
    locatorDrift_ = drift + 2*eps*locator_.coordinateScale();
    if (!gridded)
    {
        gridded = locator_.build(x, elemNodes_, nElements(), topologyVersion_);
        locatorDrift_ = 0;
    }
    driftVersion_ = gridded ? positionsVersion_ : -1;
    locatorCheckedAt_ = gridded ? positionsVersion_ : -1;
    return gridded;
}


void Foam::elementModel::positionsMoved(const scalar move)
{
    if (driftVersion_ == positionsVersion_)
    {
        // x + dt v rounds by a half epsilon of |x| (at most the locator's
        // coordinate scale while its grid is valid), dt v and the bound's
        // sum by a relative one
        constexpr scalar eps = std::numeric_limits<scalar>::epsilon();
        locatorDrift_ +=
            move*(1 + 4*eps) + 2*eps*locator_.coordinateScale();
        // (a NaN move compares false in currentLocator(): no bound)
        ++driftVersion_;
    }
    ++positionsVersion_;
}


bool Foam::elementModel::elementsNear
(
    const std::vector<scalar>& rectangles,
    std::vector<label>& out
) const
{
    out.clear();
    if (!currentLocator()) return false;
    locator_.overlapping(rectangles, out);
    return true;
}


Foam::label Foam::elementModel::locateIn
(
    const bool gridded,
    const std::vector<scalar>& x,
    const scalar px,
    const scalar py,
    scalar bary[3]
) const
{
    if (gridded) return locator_.find(x, elemNodes_, px, py, bary);
    // The reference configuration (asked once per probe), or nodes that
    // are not finite: every element
    for (label el = 0; el < nElements(); ++el)
    {
        if (elementLocator::contains(x, &elemNodes_[3*el], px, py, bary))
        {
            return el;
        }
    }
    return -1;
}


Foam::label Foam::elementModel::locate
(
    const scalar px,
    const scalar py,
    const bool reference,
    scalar bary[3]
) const
{
    if (reference) return locateIn(false, X_, px, py, bary);
    return locateIn(currentLocator(), x_[cur_], px, py, bary);
}


void Foam::elementModel::locate
(
    const std::vector<scalar>& xy,
    std::vector<label>& elements,
    std::vector<scalar>& bary
) const
{
    const label nPoints = label(xy.size()/2);
    elements.resize(nPoints);
    bary.resize(3*nPoints);
    if (nPoints == 0) return;
    const bool gridded = currentLocator();
    for (label i = 0; i < nPoints; ++i)
    {
        elements[i] =
            locateIn(gridded, x_[cur_], xy[2*i], xy[2*i + 1], &bary[3*i]);
    }
}


void Foam::elementModel::fluidBoundarySides(std::vector<label>& sides) const
{
    sides.clear();
    for (label r = 0; r < regions_.size(); ++r)
    {
        if (!materials_.set(r) || !materials_[r].isFluid()) continue;
        for (label d = regions_[r].domainBegin; d < regions_[r].domainEnd; ++d)
        {
            if (domainElems_[2*d + 1] >= 0) continue;
            const label el = domainElems_[2*d];
            for (label i = 0; i < 3; ++i)
            {
                if (elemDomains_[3*el + i] == d)
                {
                    sides.push_back(3*elemTriangle_[el] + i);
                }
            }
        }
    }
    std::sort(sides.begin(), sides.end());
}


Foam::scalar Foam::elementModel::kineticEnergy() const
{
    const std::vector<scalar>& v = v_[cur_];
    scalar E = 0;
    for (label n = 0; n < nNodes_; ++n)
    {
        E += 0.5*nodeMass_[n]*(v[2*n]*v[2*n] + v[2*n + 1]*v[2*n + 1]);
    }
    return E;
}


Foam::scalar Foam::elementModel::strainEnergy() const
{
    catchUpDomainGradients();
    scalar E = 0;
    std::vector<scalar> w;
    for (label r = 0; r < regions_.size(); ++r)
    {
        if (!materials_.set(r)) continue;   // void: no elements
        const label b = regions_[r].domainBegin, e = regions_[r].domainEnd;
        w.resize(e - b);
        materials_[r].strainEnergyDensity(b, e, domainGrad_.data(), w.data());
        for (label k = b; k < e; ++k) E += w[k - b]*domainArea_[k];
    }
    return E;
}


// ************************************************************************* //
