#include "elementParticleCoupling.H"
#include "parallelLoop.H"
#include "elementModel.H"
#include "sphFluid.H"
#include "checkKeywords.H"
#include "Switch.H"

#include <algorithm>
#include <cmath>
#include <type_traits>

// * * * * * * * * * * * * * * * Static Data  * * * * * * * * * * * * * * * //

const Foam::Enum<Foam::elementParticleCoupling::interfaceForceType>
Foam::elementParticleCoupling::interfaceForceTypeNames
({
    {interfaceForceType::interfaceReaction, "interfaceReaction"},
    {interfaceForceType::ghostReaction, "ghostReaction"},
    {interfaceForceType::traction, "traction"},
    {interfaceForceType::balancedTraction, "balancedTraction"},
    {interfaceForceType::balancedParticles, "balancedParticles"},
    {interfaceForceType::balancedFluid, "balancedFluid"},
});


const Foam::Enum<Foam::elementParticleCoupling::ghostSearchType>
Foam::elementParticleCoupling::ghostSearchTypeNames
({
    {ghostSearchType::particleSupport, "particleSupport"},
    {ghostSearchType::pairReach, "pairReach"},
});


// * * * * * * * * * * * * * Static Member Functions * * * * * * * * * * * //

Foam::scalar Foam::elementParticleCoupling::readVelocityCorrection
(
    const dictionary& schemesDict
)
{
    const dictionary& d = schemesDict.subOrEmptyDict("coupling");
    const scalar phi =
        d.getOrDefault<scalar>("interfaceVelocityCorrection", 0.1);
    if (!(phi >= 0 && phi <= 1))
    {
        FatalIOErrorInFunction(d)
            << "coupling/interfaceVelocityCorrection (phi of eq. 26)"
            << " must lie in [0, 1], found " << phi << exit(FatalIOError);
    }
    return phi;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::elementParticleCoupling::elementParticleCoupling
(
    const dictionary& schemesDict,
    const scalar smoothingLengthRatio,
    const scalar refinedRadiusRatio
)
:
    // Exchanged equal and opposite; split ghosts found by the pair reach
    interfaceForce_
    (
        refinedRadiusRatio > 0
      ? interfaceForceType::balancedParticles
      : interfaceForceType::balancedFluid
    ),
    ghostSearch_
    (
        refinedRadiusRatio > 0
      ? ghostSearchType::pairReach
      : ghostSearchType::particleSupport
    ),
    imbalance_{0, 0},
    spread_{0, 0},
    velocityCorrection_(readVelocityCorrection(schemesDict)),
    interfaceSuction_(true),
    smoothingLengthRatio_(smoothingLengthRatio),
    refinedRadiusRatio_(refinedRadiusRatio)
{
    const dictionary* d = schemesDict.findDict("coupling");
    if (d)
    {
        checkKeywords
        (
            *d,
            {
                "interfaceVelocityCorrection", "interfaceForce",
                "ghostSearch", "interfaceSuction"
            }
        );
        interfaceSuction_ =
            d->getOrDefault<Switch>("interfaceSuction", interfaceSuction_);
        ghostSearch_ =
            getCheckedEnum
            (
                *d, "ghostSearch", ghostSearchTypeNames, ghostSearch_
            );
        interfaceForce_ =
            getCheckedEnum
            (
                *d, "interfaceForce", interfaceForceTypeNames, interfaceForce_
            );
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::elementParticleCoupling::update
(
    const triMesh& mesh,
    const elementModel& elements,
    const List<patchType>& patchTypes
)
{
    const std::vector<label>& tri = mesh.triangles();
    const std::vector<label>& triEdges = mesh.triangleEdges();
    const std::vector<label>& edgeTri = mesh.edgeTriangles();

    // Patch of each boundary edge (-1: internal)
    std::vector<label> edgePatch(mesh.nEdges(), -1);
    for (label s = 0; s < mesh.nSegments(); ++s)
    {
        edgePatch[mesh.segmentEdge()[s]] = mesh.segmentPatch()[s];
    }

    // The sides that can be open: a fluid element's side that is a
    // smoothing domain of its own has no element of its region across it
    // (a pass over the domains, not one over every triangle's sides)
    std::vector<label>& sides = sideScratch_;
    elements.fluidBoundarySides(sides);

    segments_.clear();
    for (const label side : sides)
    {
        const label t = side/3, i = side % 3;
        const label k = triEdges[3*t + i];
        const label other = edgeTri[2*k] == t ? edgeTri[2*k + 1] : edgeTri[2*k];
        bool open;
        if (other < 0)
        {
            open = patchTypes[edgePatch[k]] == patchType::freeSurface;
        }
        else
        {
            open = elements.removed(other);
        }
        if (!open) continue;
        // Edge i joins nodes i and i+1 of the counter-clockwise triangle:
        // the element is on its left
        segments_.push_back(tri[3*t + i]);
        segments_.push_back(tri[3*t + (i + 1) % 3]);
    }

    interfaceNodes_ = segments_;
    std::sort(interfaceNodes_.begin(), interfaceNodes_.end());
    interfaceNodes_.erase
    (
        std::unique(interfaceNodes_.begin(), interfaceNodes_.end()),
        interfaceNodes_.end()
    );
    nodePressure_.assign(elements.nNodes(), 0);
    nodeReached_.assign(elements.nNodes(), 0);

    // The nodes on a wall patch (balancedFluid): 2 on a patch that holds
    // its nodes (noSlipWall, clamped), else 1 on a slipWall, with the sum
    // n n^T of the unit normals of its slip-wall sides
    wallNode_.assign(mesh.nPoints(), 0);
    wallNormals_.assign(3*mesh.nPoints(), 0);
    const std::vector<scalar>& x = mesh.points();
    for (label s = 0; s < mesh.nSegments(); ++s)
    {
        const patchType type = patchTypes[mesh.segmentPatch()[s]];
        if (type == patchType::freeSurface) continue;
        const label a = mesh.segments()[2*s], b = mesh.segments()[2*s + 1];
        if (type != patchType::slipWall)
        {
            wallNode_[a] = wallNode_[b] = 2;
            continue;
        }
        const scalar tx = x[2*b] - x[2*a], ty = x[2*b + 1] - x[2*a + 1];
        const scalar l2 = tx*tx + ty*ty;
        if (!(l2 > 0)) continue;
        for (const label n : {a, b})
        {
            if (!wallNode_[n]) wallNode_[n] = 1;
            // n = (ty, -tx)/l: n n^T
            wallNormals_[3*n] += ty*ty/l2;
            wallNormals_[3*n + 1] -= tx*ty/l2;
            wallNormals_[3*n + 2] += tx*tx/l2;
        }
    }

    // The connected interfaces: segments that share a node, by union-find
    // over the interface nodes
    const auto nodeIndex = [&](const label n)
    {
        return label
        (
            std::lower_bound(interfaceNodes_.begin(), interfaceNodes_.end(), n)
          - interfaceNodes_.begin()
        );
    };
    std::vector<label> parent(interfaceNodes_.size());
    for (label i = 0; i < label(parent.size()); ++i) parent[i] = i;
    const auto root = [&](label i)
    {
        while (parent[i] != i)
        {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        return i;
    };
    const label nSegments = nInterfaceSegments();
    for (label s = 0; s < nSegments; ++s)
    {
        const label a = root(nodeIndex(segments_[2*s]));
        const label b = root(nodeIndex(segments_[2*s + 1]));
        if (a != b) parent[max(a, b)] = min(a, b);
    }
    std::vector<label> componentOfRoot(interfaceNodes_.size(), -1);
    nComponents_ = 0;
    segmentComponent_.resize(nSegments);
    for (label s = 0; s < nSegments; ++s)
    {
        const label r = root(nodeIndex(segments_[2*s]));
        if (componentOfRoot[r] < 0) componentOfRoot[r] = nComponents_++;
        segmentComponent_[s] = componentOfRoot[r];
    }
}


void Foam::elementParticleCoupling::binParticles(const sphFluid& particles)
{
    const particleSet& ps = particles.particles();
    cells_.update(ps, particles.kernel().support()*ps.maxSmoothingLength());
}


void Foam::elementParticleCoupling::correctVelocities
(
    elementModel& elements,
    sphFluid& particles,
    const scalar dt
)
{
    if (velocityCorrection_ == 0) return;
    const particleSet& ps = particles.particles();
    const std::vector<scalar>& x = elements.positions();
    const std::vector<scalar>& v = elements.velocities();
    const std::vector<scalar>& mNode = elements.nodeMass();
    const std::vector<elementModel::constraint>& c = elements.constraints();
    const scalar phi = velocityCorrection_;
    particleDv_.assign(2*ps.size(), 0);

    particles.kernel().visit
    (
        [&](const auto& k)
        {
            using Kernel = std::decay_t<decltype(k)>;
            for (const label n : interfaceNodes_)
            {
                // Walls and clamps keep their own velocity
                if (c[n] != elementModel::constraint::free) continue;
                const scalar un = v[2*n], vn = v[2*n + 1];
                scalar du = 0, dv = 0;
                cells_.forEachParticleNear
                (
                    ps, x[2*n], x[2*n + 1], Kernel::support,
                    [&](const label j, const scalar, const scalar, const scalar r)
                    {
                        if (ps.kinds()[j] != particleSet::kind::fluid) return;
                        const scalar VW =
                            ps.mass()[j]/ps.density()[j]
                           *Kernel::W(r, ps.smoothingLength()[j]);
                        const scalar ex = phi*VW*(un - ps.velocities()[2*j]);
                        const scalar ey =
                            phi*VW*(vn - ps.velocities()[2*j + 1]);
                        du -= ex;
                        dv -= ey;
                        // The particle gives the momentum the node gains
                        const scalar share = mNode[n]/ps.mass()[j];
                        particleDv_[2*j] += share*ex;
                        particleDv_[2*j + 1] += share*ey;
                    }
                );
                // Eq. (26)
                elements.correctVelocity(n, du, dv, dt);
            }
        }
    );
    for (label j = 0; j < ps.size(); ++j)
    {
        if (particleDv_[2*j] != 0 || particleDv_[2*j + 1] != 0)
        {
            particles.correctVelocity
            (
                j, particleDv_[2*j], particleDv_[2*j + 1], dt
            );
        }
    }
}


void Foam::elementParticleCoupling::setGhosts
(
    const elementModel& elements,
    sphFluid& particles
)
{
    const particleSet& ps = particles.particles();
    const std::vector<scalar>& x = elements.positions();
    const std::vector<scalar>& v = elements.velocities();
    const std::vector<label>& nodes = elements.elementNodes();
    const std::vector<scalar>& mass = elements.elementMass();
    const std::vector<scalar>& area = elements.elementArea();
    const scalar kappa = particles.kernel().support();

    ghostElement_.clear();
    ghostCorner_.clear();
    ghostX_.clear();
    ghostV_.clear();
    ghostRho_.clear();
    ghostM_.clear();
    ghostH_.clear();

    // Within the pair reach kappa h_ij of a fluid particle, or within its
    // support kappa h_j: a search that stops at the first fluid particle
    const auto reachesFluid =
        [&](const scalar gx, const scalar gy, const scalar hGhost)
        {
            const auto fluid =
                [&ps](const label j, const scalar, const scalar, const scalar)
                {
                    return ps.kinds()[j] == particleSet::kind::fluid;
                };
            if (ghostSearch_ == ghostSearchType::pairReach)
            {
                return cells_.anyParticleInReach(ps, gx, gy, hGhost, kappa, fluid);
            }
            return cells_.anyParticleNear(ps, gx, gy, kappa, fluid);
        };
    // The element's density as its own stress takes it: the mean over its
    // three smoothing domains (eqs. 2, 5), not its bare m_e/A_e; each
    // domain's density carried from the domain's centroid to the
    // element's with the hydrostatic gradient, d rho = rho g.dx/c^2, so
    // that the mean is exact at rest also where a domain is the element
    // alone (an interface or boundary side)
    const std::vector<label>& domains = elements.elementDomains();
    const std::vector<label>& domainElems = elements.domainElements();
    const std::vector<scalar>& domainMass = elements.domainMass();
    const std::vector<scalar>& domainArea = elements.domainArea();
    const scalar* gravity = elements.gravity();
    const scalar invC2 = 1/sqr(particles.c());
    const auto centroid = [&](const label el, scalar c[2])
    {
        const label* n = &nodes[3*el];
        c[0] = (x[2*n[0]] + x[2*n[1]] + x[2*n[2]])/3;
        c[1] = (x[2*n[0] + 1] + x[2*n[1] + 1] + x[2*n[2] + 1])/3;
    };
    const auto smoothedDensity = [&](const label el)
    {
        scalar c[2];
        centroid(el, c);
        scalar rho = 0;
        for (label a = 0; a < 3; ++a)
        {
            const label k = domains[3*el + a];
            scalar dc[2] = {0, 0}, A = 0;
            for (label s = 0; s < 2; ++s)
            {
                const label e = domainElems[2*k + s];
                if (e < 0) continue;
                scalar ce[2];
                centroid(e, ce);
                dc[0] += area[e]*ce[0];
                dc[1] += area[e]*ce[1];
                A += area[e];
            }
            const scalar rhoK = domainMass[k]/domainArea[k];
            rho +=
                rhoK
               *(
                    1
                  + (
                        gravity[0]*(c[0] - dc[0]/A)
                      + gravity[1]*(c[1] - dc[1]/A)
                    )*invC2
                );
        }
        return rho/3;
    };

    // Split ghosts: the element's refined particles (eqs. 19-22, as
    // appendParticlesFromElements makes them); else one at the centroid
    const bool split = refinedRadiusRatio_ > 0;
    const label perElement = split ? 3 : 1;

    // Positions and smoothing length of the ghosts of element el
    const auto candidates =
        [&](const label el, scalar gx[3], scalar gy[3], scalar& hg)
        {
            const label* n = &nodes[3*el];
            scalar c[2];
            centroid(el, c);
            if (split)
            {
                for (label k = 0; k < 3; ++k)
                {
                    gx[k] = 0.5*(x[2*n[k]] + c[0]);
                    gy[k] = 0.5*(x[2*n[k] + 1] + c[1]);
                }
                hg =
                    smoothingLengthRatio_*refinedRadiusRatio_
                   *std::sqrt(area[el]);
            }
            else
            {
                gx[0] = c[0];
                gy[0] = c[1];
                hg = smoothingLengthRatio_*std::sqrt(area[el]);
            }
        };

    // The box of the fluid particles: a ghost farther from it than its
    // largest reach, kappa max(h_ghost, h_max), reaches none (most of the
    // elements, which need no search)
    scalar box[4] = {GREAT, GREAT, -GREAT, -GREAT};
    scalar hFluid = 0;
    {
        const scalar* xp = ps.positions().data();
        const scalar* hp = ps.smoothingLength().data();
        const particleSet::kind* kind = ps.kinds().data();
        for (label j = 0; j < ps.size(); ++j)
        {
            if (kind[j] != particleSet::kind::fluid) continue;
            box[0] = min(box[0], xp[2*j]);
            box[1] = min(box[1], xp[2*j + 1]);
            box[2] = max(box[2], xp[2*j]);
            box[3] = max(box[3], xp[2*j + 1]);
            hFluid = max(hFluid, hp[j]);
        }
    }
    const auto outOfReach =
        [&box, hFluid, kappa](const scalar gx, const scalar gy, const scalar hg)
        {
            const scalar d = kappa*max(hg, hFluid);
            return
                gx < box[0] - d || gy < box[1] - d
             || gx > box[2] + d || gy > box[3] + d;
        };

    // Rounding margin for the elements' test below: far above the
    // rounding of a node mean, far below a spacing
    const scalar boxSlack =
        1e-9*(mag(box[0]) + mag(box[1]) + mag(box[2]) + mag(box[3]) + 1);

    // Cells of side D = kappa h_max over the box (and a cell round it),
    // each marked if a fluid particle lies in it or in one of its eight
    // neighbours: a ghost of h_ghost <= h_max reaches particles within
    // kappa max(h_ghost, h_max) = D only, all in the 3x3 cells round its
    // own, so an unmarked cell has none in reach (most ghosts in the box:
    // a byte instead of a search). Not laid where the cells would
    // outnumber the particles by far (particles scattered far apart)
    const scalar D = kappa*hFluid;
    label gridNx = 0, gridNy = 0;
    if (D > 0 && box[0] <= box[2])
    {
        const scalar nx = (box[2] - box[0])/D + 3, ny = (box[3] - box[1])/D + 3;
        if (nx*ny < 4.0*ps.size() + 4096)
        {
            gridNx = label(nx);
            gridNy = label(ny);
        }
    }
    const scalar gridX0 = box[0] - D, gridY0 = box[1] - D;
    const scalar invD = gridNx ? 1/D : 0;
    if (gridNx)
    {
        cellHasFluid_.assign(gridNx*gridNy, 0);
        cellNearFluid_.assign(gridNx*gridNy, 0);
        const scalar* xp = ps.positions().data();
        const particleSet::kind* kind = ps.kinds().data();
        for (label j = 0; j < ps.size(); ++j)
        {
            if (kind[j] != particleSet::kind::fluid) continue;
            const label ix = std::min(label((xp[2*j] - gridX0)*invD), gridNx - 1);
            const label iy =
                std::min(label((xp[2*j + 1] - gridY0)*invD), gridNy - 1);
            cellHasFluid_[iy*gridNx + ix] = 1;
        }
        for (label iy = 0; iy < gridNy; ++iy)
        {
            for (label ix = 0; ix < gridNx; ++ix)
            {
                if (!cellHasFluid_[iy*gridNx + ix]) continue;
                for (label jy = max(iy - 1, 0); jy <= min(iy + 1, gridNy - 1); ++jy)
                {
                    for
                    (
                        label jx = max(ix - 1, 0);
                        jx <= min(ix + 1, gridNx - 1);
                        ++jx
                    )
                    {
                        cellNearFluid_[jy*gridNx + jx] = 1;
                    }
                }
            }
        }
    }
    const unsigned char* nearFluid = cellNearFluid_.data();
    const auto noFluidNear =
        [=](const scalar gx, const scalar gy, const scalar hg)
        {
            if (!gridNx || hg > hFluid) return false;
            const scalar fx = (gx - gridX0)*invD, fy = (gy - gridY0)*invD;
            if (!(fx >= 0 && fy >= 0 && fx < gridNx && fy < gridNy))
            {
                return false;   // left to the box and the search
            }
            return !nearFluid[label(fy)*gridNx + label(fx)];
        };

    // The largest reach of a ghost, kappa max(h_max, h of the largest
    // fluid element), with a rounding margin: an element farther than that
    // from the box has no ghost in reach of a particle (its ghosts lie
    // between its nodes)
    scalar largest[4] = {0, 0, 0, 0};
    for (label r = 0; r < elements.regions().size(); ++r)
    {
        if (!elements.hasMaterial(r) || !elements.material(r).isFluid())
        {
            continue;
        }
        // Four maxima: no chain of dependent comparisons
        const label end = elements.regions()[r].elemEnd;
        label el = elements.regions()[r].elemBegin;
        for (; el + 3 < end; el += 4)
        {
            for (label k = 0; k < 4; ++k)
            {
                largest[k] = max(largest[k], area[el + k]);
            }
        }
        for (; el < end; ++el) largest[0] = max(largest[0], area[el]);
    }
    const scalar largestArea =
        max(max(largest[0], largest[1]), max(largest[2], largest[3]));
    const scalar d =
        kappa*max(hFluid, smoothingLengthRatio_*std::sqrt(largestArea))
      + boxSlack;
    const scalar left = box[0] - d, below = box[1] - d;
    const scalar right = box[2] + d, above = box[3] + d;

    // Which of element el's ghosts reach a fluid particle (bit k: ghost
    // k): a search per ghost in reach of the box, as costly as a
    // particle's
    const auto ghostsReaching = [&](const label el)
    {
        scalar gx[3], gy[3], hg;
        candidates(el, gx, gy, hg);
        unsigned char reached = 0;
        for (label k = 0; k < perElement; ++k)
        {
            if
            (
                !outOfReach(gx[k], gy[k], hg)
             && !noFluidNear(gx[k], gy[k], hg)
             && reachesFluid(gx[k], gy[k], hg)
            )
            {
                reached |= 1u << k;
            }
        }
        return reached;
    };

    // The ghosts of element el that reach particles, in the order of
    // their corners
    const auto addGhosts = [&](const label el, const unsigned char reached)
    {
        scalar gx[3], gy[3], hg;
        candidates(el, gx, gy, hg);
        const label* n = &nodes[3*el];
        // Eqs. (18, 20), with the density the element acts with (see the
        // Description)
        const scalar rhoGhost = smoothedDensity(el);
        for (label k = 0; k < perElement; ++k)
        {
            if (!(reached & (1u << k))) continue;
            ghostElement_.push_back(el);
            ghostCorner_.push_back(split ? k : -1);
            ghostX_.push_back(gx[k]);
            ghostX_.push_back(gy[k]);
            // Eq. (17) with equal nodal shares: the nodes' mean. A split
            // ghost at (x_k + x_c)/2 moves at (v_k + v_c)/2, and that is
            // the velocity it carries (see Description)
            const scalar uc = (v[2*n[0]] + v[2*n[1]] + v[2*n[2]])/3;
            const scalar vc =
                (v[2*n[0] + 1] + v[2*n[1] + 1] + v[2*n[2] + 1])/3;
            ghostV_.push_back(split ? 0.5*(v[2*n[k]] + uc) : uc);
            ghostV_.push_back(split ? 0.5*(v[2*n[k] + 1] + vc) : vc);
            ghostRho_.push_back(rhoGhost);
            ghostM_.push_back(split ? mass[el]/3 : mass[el]);
            ghostH_.push_back(hg);
        }
    };

    // The elements that may have a ghost in reach, from the grid of the
    // probes: each asked, in increasing order, so that the ghosts come in
    // element order as from the pass over every element below. A ghost of
    // h_ghost <= h_max that reaches a particle lies within D of it, so in
    // one of the closed cells marked near fluid (all inside the grid): the
    // elements over those cells (runs of them along a row, a rectangle
    // each). The elements of h_ghost > h_max, which the cells do not
    // rule out, are added whatever their place (few: larger than any
    // particle's element). Without the cells, the box's rectangle
    nearRectangles_.clear();
    if (gridNx)
    {
        const scalar slack = boxSlack;
        for (label iy = 0; iy < gridNy; ++iy)
        {
            const unsigned char* row = nearFluid + iy*gridNx;
            for (label ix = 0; ix < gridNx; ++ix)
            {
                if (!row[ix]) continue;
                label ix1 = ix;
                while (ix1 + 1 < gridNx && row[ix1 + 1]) ++ix1;
                nearRectangles_.insert
                (
                    nearRectangles_.end(),
                    {
                        gridX0 + ix*D - slack, gridY0 + iy*D - slack,
                        gridX0 + (ix1 + 1)*D + slack,
                        gridY0 + (iy + 1)*D + slack
                    }
                );
                ix = ix1;
            }
        }
    }
    else
    {
        nearRectangles_.insert
        (
            nearRectangles_.end(), {left, below, right, above}
        );
    }
    if (elements.elementsNear(nearRectangles_, nearBox_))
    {
        // The elements of h_ghost > h_max: an area above
        // (h_max/(ratio r))^2, less a rounding margin, then h_ghost as
        // candidates() takes it
        if (gridNx)
        {
            const scalar hPerRootArea =
                smoothingLengthRatio_*(split ? refinedRadiusRatio_ : 1);
            const scalar areaBelow =
                (1 - 1e-9)*sqr(hFluid/hPerRootArea);
            largeElements_.clear();
            if (largestArea > areaBelow)
            {
                for (label r = 0; r < elements.regions().size(); ++r)
                {
                    if
                    (
                        !elements.hasMaterial(r)
                     || !elements.material(r).isFluid()
                    )
                    {
                        continue;
                    }
                    const label end = elements.regions()[r].elemEnd;
                    for
                    (
                        label el = elements.regions()[r].elemBegin;
                        el < end;
                        ++el
                    )
                    {
                        if
                        (
                            area[el] > areaBelow
                         && hPerRootArea*std::sqrt(area[el]) > hFluid
                        )
                        {
                            largeElements_.push_back(el);
                        }
                    }
                }
            }
            if (!largeElements_.empty())
            {
                const std::size_t n = nearBox_.size();
                nearBox_.insert
                (
                    nearBox_.end(), largeElements_.begin(), largeElements_.end()
                );
                std::inplace_merge
                (
                    nearBox_.begin(), nearBox_.begin() + n, nearBox_.end()
                );
                nearBox_.erase
                (
                    std::unique(nearBox_.begin(), nearBox_.end()),
                    nearBox_.end()
                );
            }
        }
        for (label r = 0; r < elements.regions().size(); ++r)
        {
            if (!elements.hasMaterial(r) || !elements.material(r).isFluid())
            {
                continue;
            }
            const label* all = nearBox_.data();
            const label* allEnd = all + nearBox_.size();
            const label* first =
                std::lower_bound(all, allEnd, elements.regions()[r].elemBegin);
            const label* last =
                std::lower_bound(first, allEnd, elements.regions()[r].elemEnd);
            const label nNear = label(last - first);
            ghostReaches_.assign(nNear, 0);
            unsigned char* reaches = ghostReaches_.data();
            #pragma omp parallel for schedule(static) if(nNear > minParallelParticles)
            for (label i = 0; i < nNear; ++i)
            {
                reaches[i] = ghostsReaching(first[i]);
            }
            for (label i = 0; i < nNear; ++i)
            {
                if (reaches[i]) addGhosts(first[i], reaches[i]);
            }
        }
        particles.setGhosts
        (
            label(ghostM_.size()), ghostX_.data(), ghostV_.data(),
            ghostRho_.data(), ghostM_.data(), ghostH_.data()
        );
        return;
    }

    // No grid (a node not finite): every element. The side of the box
    // each node lies beyond by more than d (bits: left, below, right,
    // above); the three nodes of an element beyond one side: so are its
    // ghosts, and none reaches a particle. A byte per node, once, instead
    // of six coordinates per element
    {
        const label nNodes = elements.nNodes();
        nodeBeyond_.resize(nNodes);
        unsigned char* beyond = nodeBeyond_.data();
        const scalar* xn = x.data();
        for (label n = 0; n < nNodes; ++n)
        {
            const scalar px = xn[2*n], py = xn[2*n + 1];
            beyond[n] =
                (px < left) | (py < below) << 1 | (px > right) << 2
              | (py > above) << 3;
        }
    }
    const unsigned char* beyond = nodeBeyond_.data();

    for (label r = 0; r < elements.regions().size(); ++r)
    {
        if (!elements.hasMaterial(r) || !elements.material(r).isFluid())
        {
            continue;
        }
        const label begin = elements.regions()[r].elemBegin;
        const label end = elements.regions()[r].elemEnd;

        // On every thread; then the ghosts in element order, as one thread
        // made them
        ghostReaches_.assign(end - begin, 0);
        unsigned char* reaches = ghostReaches_.data();
        #pragma omp parallel for schedule(static) if(end - begin > minParallelParticles)
        for (label el = begin; el < end; ++el)
        {
            const label* n = &nodes[3*el];
            if (beyond[n[0]] & beyond[n[1]] & beyond[n[2]]) continue;
            reaches[el - begin] = ghostsReaching(el);
        }
        for (label el = begin; el < end; ++el)
        {
            const unsigned char reached = reaches[el - begin];
            if (reached) addGhosts(el, reached);
        }
    }

    particles.setGhosts
    (
        label(ghostM_.size()), ghostX_.data(), ghostV_.data(),
        ghostRho_.data(), ghostM_.data(), ghostH_.data()
    );
}


void Foam::elementParticleCoupling::interfaceTraction
(
    const elementModel& elements,
    const sphFluid& particles,
    std::vector<scalar>& segmentForce
)
{
    segmentForce.assign(segments_.size(), 0);
    if (segments_.empty()) return;

    const particleSet& ps = particles.particles();
    const std::vector<scalar>& x = elements.positions();

    // The particles' pressure at the nodes. The particles lie on one side
    // of the interface, and their Shepard mean alone is the pressure about
    // h/2 inside the particle region. Each particle's pressure is carried
    // to the node with the hydrostatic gradient, as for the wall particles
    // (Adami et al. 2012), exact at rest:
    //     p_n = sum_j [p_j + rho_j g . (x_n - x_j)] V_j W_nj / sum_j V_j W_nj
    // (measurements and alternatives dropped: src/SPEM/sph/README.md)
    const scalar gx = particles.gx(), gy = particles.gy();
    nUnreachedNodes_ = 0;
    particles.kernel().visit
    (
        [&](const auto& k)
        {
            using Kernel = std::decay_t<decltype(k)>;
            for (const label n : interfaceNodes_)
            {
                scalar sumW = 0, sumP = 0;
                particles.cells().forEachParticleNear
                (
                    ps, x[2*n], x[2*n + 1], Kernel::support,
                    [&](const label j, const scalar dx, const scalar dy, const scalar r)
                    {
                        if (ps.kinds()[j] != particleSet::kind::fluid) return;
                        const scalar VW =
                            ps.mass()[j]/ps.density()[j]
                           *Kernel::W(r, ps.smoothingLength()[j]);
                        // (dx, dy) = x_n - x_j
                        sumW += VW;
                        sumP +=
                            VW
                           *(
                                ps.pressure()[j]
                              + ps.density()[j]*(gx*dx + gy*dy)
                            );
                    }
                );
                // No particle in reach: a free surface, or a hole
                if (!(sumW > 0)) ++nUnreachedNodes_;
                nodeReached_[n] = sumW > 0;
                const scalar pn = sumW > 0 ? sumP/sumW : 0;
                nodePressure_[n] = interfaceSuction_ ? pn : max(pn, scalar(0));
            }
        }
    );

    // Eq. (25) with sigma = -p I: F = -l (p_P + p_Q)/2 n
    for (label s = 0; s < nInterfaceSegments(); ++s)
    {
        const label P = segments_[2*s], Q = segments_[2*s + 1];
        const scalar dx = x[2*Q] - x[2*P], dy = x[2*Q + 1] - x[2*P + 1];
        // l n = (dy, -dx)
        const scalar pMean = 0.5*(nodePressure_[P] + nodePressure_[Q]);
        segmentForce[2*s] = -pMean*dy;
        segmentForce[2*s + 1] = pMean*dx;
    }
}


void Foam::elementParticleCoupling::ghostReaction
(
    elementModel& elements,
    const sphFluid& particles,
    scalar added[2]
) const
{
    std::vector<scalar>& f = elements.externalForce();
    const std::vector<label>& nodes = elements.elementNodes();
    const std::vector<scalar>& F = particles.ghostParticleForce();
    for (label g = 0; g < label(ghostElement_.size()); ++g)
    {
        const label* n = &nodes[3*ghostElement_[g]];
        for (label a = 0; a < 3; ++a)
        {
            // d x_g/d x_a: 1/3 at the centroid; at (x_k + x_c)/2, 2/3
            // for node k and 1/6 for the others
            const label k = ghostCorner_[g];
            const scalar w = k < 0 ? 1.0/3 : (a == k ? 2.0/3 : 1.0/6);
            f[2*n[a]] += w*F[2*g];
            f[2*n[a] + 1] += w*F[2*g + 1];
            added[0] += w*F[2*g];
            added[1] += w*F[2*g + 1];
        }
    }
}


template<class Visitor>
void Foam::elementParticleCoupling::forEachInterfaceShare
(
    const elementModel& elements,
    const sphFluid& particles,
    const Visitor& visit
)
{
    if (segments_.empty()) return;
    const std::vector<scalar>& x = elements.positions();
    const particleSet& ps = particles.particles();
    const std::vector<scalar>& aGhost = particles.ghostAccelerations();

    // The midpoints of the interface segments as points of smoothing
    // length h_g,max: the reach kappa (h_i + h_g,max)/2 covers every ghost
    // of particle i. A particle's share of a segment in reach is
    // l_s W(r_is) over the sum for all of them, so that a force given to
    // the segments and then half to each segment's node loads the nodes
    // as a traction would: on a staircase interface, weights on the nodes
    // themselves load the nodes nearer the particles more than the others
    // and shear the interface elements (cylinderWaterExit at t = 0: 350
    // and 116 N/m on the two nodes of a side segment, against 239 and 227
    // N/m by eq. 25).
    const scalar hGhost =
        ghostH_.empty()
      ? 0 : *std::max_element(ghostH_.begin(), ghostH_.end());
    const label nSegments = nInterfaceSegments();
    segmentPoints_.clear();
    segmentLength_.resize(nSegments);
    for (label s = 0; s < nSegments; ++s)
    {
        const label P = segments_[2*s], Q = segments_[2*s + 1];
        segmentPoints_.append
        (
            0.5*(x[2*P] + x[2*Q]), 0.5*(x[2*P + 1] + x[2*Q + 1]),
            0, 0, 1, 0, 1, hGhost
        );
        segmentLength_[s] =
            std::sqrt(sqr(x[2*Q] - x[2*P]) + sqr(x[2*Q + 1] - x[2*P + 1]));
    }
    // No ghost: no particle feels an element
    if (ghostH_.empty()) return;
    const scalar kappa = particles.kernel().support();
    segmentCells_.update
    (
        segmentPoints_, kappa*std::max(hGhost, ps.maxSmoothingLength())
    );

    particles.kernel().visit
    (
        [&](const auto& k)
        {
            using Kernel = std::decay_t<decltype(k)>;
            for (label i = 0; i < ps.size(); ++i)
            {
                if (aGhost[2*i] == 0 && aGhost[2*i + 1] == 0) continue;
                const scalar xi = ps.positions()[2*i];
                const scalar yi = ps.positions()[2*i + 1];
                const scalar hi = ps.smoothingLength()[i];
                const scalar hij = 0.5*(hi + hGhost);
                scalar sumW = 0;
                segmentCells_.forEachParticleInReach
                (
                    segmentPoints_, xi, yi, hi, Kernel::support,
                    [&](const label s, const scalar, const scalar, const scalar r)
                    {
                        sumW += segmentLength_[s]*Kernel::W(r, hij);
                    }
                );
                if (sumW > 0)
                {
                    segmentCells_.forEachParticleInReach
                    (
                        segmentPoints_, xi, yi, hi, Kernel::support,
                        [&](const label s, const scalar, const scalar, const scalar r)
                        {
                            visit(i, s, segmentLength_[s]*Kernel::W(r, hij)/sumW);
                        }
                    );
                    continue;
                }
                // No interface segment in reach: the nearest one
                label nearest = 0;
                scalar best = GREAT;
                for (label s = 0; s < nSegments; ++s)
                {
                    const scalar d =
                        sqr(segmentPoints_.positions()[2*s] - xi)
                      + sqr(segmentPoints_.positions()[2*s + 1] - yi);
                    if (d < best)
                    {
                        best = d;
                        nearest = s;
                    }
                }
                visit(i, nearest, scalar(1));
            }
        }
    );
}


void Foam::elementParticleCoupling::interfaceReaction
(
    const elementModel& elements,
    const sphFluid& particles,
    std::vector<scalar>& segmentForce
)
{
    segmentForce.assign(segments_.size(), 0);
    const particleSet& ps = particles.particles();
    const std::vector<scalar>& aGhost = particles.ghostAccelerations();
    forEachInterfaceShare
    (
        elements, particles,
        [&](const label i, const label s, const scalar w)
        {
            segmentForce[2*s] -= w*ps.mass()[i]*aGhost[2*i];
            segmentForce[2*s + 1] -= w*ps.mass()[i]*aGhost[2*i + 1];
        }
    );
}


void Foam::elementParticleCoupling::balanceTraction
(
    std::vector<scalar>& traction,
    const std::vector<scalar>& reaction
)
{
    // Per connected interface c: D_c = sum_s (R_s - T_s), given to its
    // segments in proportion to |T_s| (to l_s where no segment is loaded)
    const label nSegments = nInterfaceSegments();
    componentSum_.assign(4*nComponents_, 0);
    for (label s = 0; s < nSegments; ++s)
    {
        scalar* c = &componentSum_[4*segmentComponent_[s]];
        c[0] += reaction[2*s] - traction[2*s];
        c[1] += reaction[2*s + 1] - traction[2*s + 1];
        c[2] += std::hypot(traction[2*s], traction[2*s + 1]);
        c[3] += segmentLength_[s];
    }
    for (label s = 0; s < nSegments; ++s)
    {
        const scalar* c = &componentSum_[4*segmentComponent_[s]];
        const scalar w =
            c[2] > 0
          ? std::hypot(traction[2*s], traction[2*s + 1])/c[2]
          : segmentLength_[s]/c[3];
        traction[2*s] += w*c[0];
        traction[2*s + 1] += w*c[1];
    }
}


void Foam::elementParticleCoupling::shareGhostForces
(
    const elementModel& elements,
    const sphFluid& particles
)
{
    const particleSet& ps = particles.particles();
    const std::vector<scalar>& aGhost = particles.ghostAccelerations();
    const label nSegments = nInterfaceSegments();
    shares_.clear();
    forEachInterfaceShare
    (
        elements, particles,
        [&](const label i, const label s, const scalar w)
        {
            shares_.push_back(interfaceShare{i, s, w});
        }
    );
    reactionForce_.assign(2*nSegments, 0);
    shareSum_.assign(nSegments, 0);
    for (const interfaceShare& sh : shares_)
    {
        const scalar m = ps.mass()[sh.i];
        reactionForce_[2*sh.s] -= sh.w*m*aGhost[2*sh.i];
        reactionForce_[2*sh.s + 1] -= sh.w*m*aGhost[2*sh.i + 1];
        shareSum_[sh.s] += sh.w;
    }
}


void Foam::elementParticleCoupling::balanceParticles
(
    const elementModel& elements,
    sphFluid& particles,
    std::vector<scalar>& traction
)
{
    // The particles' ghost forces shared to the segments as
    // interfaceReaction shares them, reversed: R_s. The difference
    // T_s - R_s is what the ghosts, an SPH sum, miss of the traction the
    // elements get; summed over a connected interface (per segment it is
    // noise that throws the particles about: see the header), the
    // particles sharing its segments take its reverse in proportion to
    // their shares, so that the exchange is equal and opposite and the
    // elements keep eq. (25)'s load
    const particleSet& ps = particles.particles();
    const label nSegments = nInterfaceSegments();
    shareGhostForces(elements, particles);
    // Per connected interface c: D_c = sum_s (T_s - R_s) over the weight
    // of all its shares; an interface no particle shares has no ghost
    // force to balance: its traction (from particles in reach of its nodes
    // that touch no ghost) is dropped, so that the exchange stays equal
    // and opposite
    componentSum_.assign(3*nComponents_, 0);
    for (label s = 0; s < nSegments; ++s)
    {
        scalar* c = &componentSum_[3*segmentComponent_[s]];
        c[0] += traction[2*s] - reactionForce_[2*s];
        c[1] += traction[2*s + 1] - reactionForce_[2*s + 1];
        c[2] += shareSum_[s];
    }
    for (label s = 0; s < nSegments; ++s)
    {
        const scalar* c = &componentSum_[3*segmentComponent_[s]];
        for (label d = 0; d < 2; ++d)
        {
            if (c[2] > 0)
            {
                reactionForce_[2*s + d] = c[d]/c[2];
            }
            else
            {
                traction[2*s + d] = reactionForce_[2*s + d];   // zero
                reactionForce_[2*s + d] = 0;
            }
        }
    }
    particleCorrection_.assign(2*ps.size(), 0);
    for (const interfaceShare& sh : shares_)
    {
        const scalar invM = 1/ps.mass()[sh.i];
        particleCorrection_[2*sh.i] -= sh.w*reactionForce_[2*sh.s]*invM;
        particleCorrection_[2*sh.i + 1] -= sh.w*reactionForce_[2*sh.s + 1]*invM;
    }
    particles.addInterfaceAcceleration(particleCorrection_);
}


bool Foam::elementParticleCoupling::markComponentsAtWalls()
{
    componentAtWall_.assign(nComponents_, 0);
    componentNormals_.assign(3*nComponents_, 0);
    junctionNodes_.clear();
    bool anyAtWall = false;
    for (label s = 0; s < nInterfaceSegments(); ++s)
    {
        const label c = segmentComponent_[s];
        for (label k = 0; k < 2; ++k)
        {
            const label n = segments_[2*s + k];
            if (wallNode_[n] && nodeReached_[n])
            {
                junctionNodes_.push_back(c);
                junctionNodes_.push_back(n);
                componentAtWall_[c] =
                    std::max(componentAtWall_[c], wallNode_[n]);
                anyAtWall = true;
                for (label d = 0; d < 3; ++d)
                {
                    componentNormals_[3*c + d] += wallNormals_[3*n + d];
                }
            }
        }
    }
    return anyAtWall;
}


void Foam::elementParticleCoupling::spreadImbalance
(
    elementModel& elements,
    sphFluid& particles,
    scalar added[2]
)
{
    // D: what the traction and the ghosts' force on the particles leave
    // over
    const scalar* ghost = particles.ghostForce();
    scalar D[2] = {added[0] - ghost[0], added[1] - ghost[1]};
    const particleSet& ps = particles.particles();

    // Less the part of the connected interfaces that meet a wall where
    // particles reach it (a wall node of the interface with particles in
    // reach; free-surface sides join an interface to walls far from any
    // particle): the sum of T_s - R_s over their segments, R_s the
    // particles' ghost forces shared to the segments as interfaceReaction
    // shares them; of that, what the walls can carry (wallPart): all of it
    // where a wall holds the junction's nodes; where the junction's walls
    // are slip walls, the normal part of the corner's difference (below).
    // The rest is spread
    const label nSegments = nInterfaceSegments();
    if (markComponentsAtWalls())
    {
        shareGhostForces(elements, particles);
        // The corner's part of a slip-wall junction: each segment's
        // difference weighted by the Wendland C2 kernel's shape (whichever
        // kernel the particles use), w(q) = (1 - q)^4 (1 + 4q), of its
        // midpoint's distance from the nearest junction node over the
        // particles' pair reach kappa h_max
        const scalar R =
            particles.kernel().support()*ps.maxSmoothingLength();
        const std::vector<scalar>& x = elements.positions();
        junctionSum_.assign(2*nComponents_, 0);
        for (label s = 0; s < nSegments; ++s)
        {
            const label c = segmentComponent_[s];
            const scalar Dx = segmentForce_[2*s] - reactionForce_[2*s];
            const scalar Dy = segmentForce_[2*s + 1] - reactionForce_[2*s + 1];
            if (componentAtWall_[c] == 2)
            {
                D[0] -= Dx;
                D[1] -= Dy;
                continue;
            }
            if (componentAtWall_[c] != 1) continue;
            const label P = segments_[2*s], Q = segments_[2*s + 1];
            const scalar mx = 0.5*(x[2*P] + x[2*Q]);
            const scalar my = 0.5*(x[2*P + 1] + x[2*Q + 1]);
            scalar w = 0;
            for (std::size_t k = 0; k < junctionNodes_.size(); k += 2)
            {
                if (junctionNodes_[k] != c) continue;
                const label J = junctionNodes_[k + 1];
                const scalar q = std::hypot(mx - x[2*J], my - x[2*J + 1])/R;
                if (q < 1) w = std::max(w, pow4(1 - q)*(1 + 4*q));
            }
            junctionSum_[2*c] += w*Dx;
            junctionSum_[2*c + 1] += w*Dy;
        }
        for (label c = 0; c < nComponents_; ++c)
        {
            if (componentAtWall_[c] != 1) continue;
            scalar carried[2];
            wallPart(&componentNormals_[3*c], &junctionSum_[2*c], carried);
            D[0] -= carried[0];
            D[1] -= carried[1];
        }
    }

    // M: the fluid's mass that can move (fluid particles, and the nodes of
    // the remaining fluid elements that are no solid's); each gets -D/M.
    // The sum over the nodes continues the particles' sum: the same as
    // the last step's if that started from the same value and the
    // elements are the same (a pass over every node less)
    const std::vector<scalar>& nodeMass = elements.nodeMass();
    scalar M = 0;
    for (label i = 0; i < ps.size(); ++i)
    {
        if (ps.kinds()[i] == particleSet::kind::fluid) M += ps.mass()[i];
    }
    if
    (
        M == spreadParticleMass_
     && elements.topologyVersion() == spreadVersion_
    )
    {
        M = spreadMass_;
    }
    else
    {
        spreadParticleMass_ = M;
        scalar nodes = 0;
        for (label n = 0; n < elements.nNodes(); ++n)
        {
            if (elements.solidNode(n)) continue;
            M += nodeMass[n];
            nodes += nodeMass[n];
        }
        spreadMass_ = M;
        spreadNodeMass_ = nodes;
        spreadVersion_ = elements.topologyVersion();
    }
    if (!(M > 0)) return;
    spread_[0] = D[0];
    spread_[1] = D[1];
    const scalar a[2] = {-D[0]/M, -D[1]/M};
    particleCorrection_.assign(2*ps.size(), 0);
    for (label i = 0; i < ps.size(); ++i)
    {
        if (ps.kinds()[i] != particleSet::kind::fluid) continue;
        particleCorrection_[2*i] = a[0];
        particleCorrection_[2*i + 1] = a[1];
    }
    particles.addInterfaceAcceleration(particleCorrection_);
    // The nodes' share, and what it adds to the exchange's sum (for the
    // reported imbalance: the nodes' mass times a, not node by node)
    std::vector<scalar>& f = elements.externalForce();
    for (label n = 0; n < elements.nNodes(); ++n)
    {
        if (elements.solidNode(n) || !(nodeMass[n] > 0)) continue;
        f[2*n] += nodeMass[n]*a[0];
        f[2*n + 1] += nodeMass[n]*a[1];
    }
    added[0] += spreadNodeMass_*a[0];
    added[1] += spreadNodeMass_*a[1];
}


void Foam::elementParticleCoupling::wallPart
(
    const scalar N[3],
    const scalar D[2],
    scalar carried[2]
)
{
    carried[0] = D[0];
    carried[1] = D[1];
    // N = sum n n^T: its larger eigenvalue's direction is the normal; the
    // walls span one direction if the smaller is below 1e-4 of it (for two
    // normals at angle theta the ratio is tan^2(theta/2): theta below
    // 1.15 degrees)
    const scalar mean = 0.5*(N[0] + N[2]);
    const scalar half = 0.5*(N[0] - N[2]);
    const scalar radius = std::sqrt(half*half + N[1]*N[1]);
    const scalar larger = mean + radius, smaller = mean - radius;
    if (!(larger > 0) || smaller > 1e-4*larger) return;
    // Eigenvector of the larger eigenvalue
    scalar nx = N[1], ny = larger - N[0];
    if (half > 0)
    {
        nx = larger - N[2];
        ny = N[1];
    }
    const scalar l = std::sqrt(nx*nx + ny*ny);
    nx /= l;
    ny /= l;
    const scalar Dn = D[0]*nx + D[1]*ny;
    carried[0] = Dn*nx;
    carried[1] = Dn*ny;
}


void Foam::elementParticleCoupling::addSegmentForces
(
    elementModel& elements,
    const std::vector<scalar>& segmentForce,
    scalar added[2]
) const
{
    std::vector<scalar>& f = elements.externalForce();
    for (label s = 0; s < nInterfaceSegments(); ++s)
    {
        const label P = segments_[2*s], Q = segments_[2*s + 1];
        const scalar Fx = segmentForce[2*s], Fy = segmentForce[2*s + 1];
        f[2*P] += 0.5*Fx;
        f[2*P + 1] += 0.5*Fy;
        f[2*Q] += 0.5*Fx;
        f[2*Q + 1] += 0.5*Fy;
        added[0] += Fx;
        added[1] += Fy;
    }
}


// * * * * * * * * * * * * * * * * * * Hooks * * * * * * * * * * * * * * * * //

void Foam::elementParticleCoupling::afterConversion(couplingStep& s)
{
    update(s.mesh, *s.elements, s.patchTypes);
}


void Foam::elementParticleCoupling::beforeElementEvaluate(couplingStep& s)
{
    binParticles(*s.particles);
    if (s.lastDeltaT > 0)
    {
        correctVelocities(*s.elements, *s.particles, s.lastDeltaT);
    }
}


void Foam::elementParticleCoupling::beforeParticleEvaluate(couplingStep& s)
{
    setGhosts(*s.elements, *s.particles);
}


void Foam::elementParticleCoupling::afterParticleEvaluate(couplingStep& s)
{
    scalar added[2] = {0, 0};
    spread_[0] = spread_[1] = 0;
    switch (interfaceForce_)
    {
        case interfaceForceType::interfaceReaction:
            interfaceReaction(*s.elements, *s.particles, segmentForce_);
            addSegmentForces(*s.elements, segmentForce_, added);
            break;
        case interfaceForceType::ghostReaction:
            ghostReaction(*s.elements, *s.particles, added);
            break;
        case interfaceForceType::traction:
            interfaceTraction(*s.elements, *s.particles, segmentForce_);
            addSegmentForces(*s.elements, segmentForce_, added);
            break;
        case interfaceForceType::balancedTraction:
            interfaceTraction(*s.elements, *s.particles, segmentForce_);
            interfaceReaction(*s.elements, *s.particles, reactionForce_);
            balanceTraction(segmentForce_, reactionForce_);
            addSegmentForces(*s.elements, segmentForce_, added);
            break;
        case interfaceForceType::balancedParticles:
            interfaceTraction(*s.elements, *s.particles, segmentForce_);
            balanceParticles(*s.elements, *s.particles, segmentForce_);
            addSegmentForces(*s.elements, segmentForce_, added);
            break;
        case interfaceForceType::balancedFluid:
            interfaceTraction(*s.elements, *s.particles, segmentForce_);
            addSegmentForces(*s.elements, segmentForce_, added);
            spreadImbalance(*s.elements, *s.particles, added);
            break;
    }
    for (int k = 0; k < 2; ++k)
    {
        imbalance_[k] = added[k] - s.particles->ghostForce()[k];
    }
}


// ************************************************************************* //
