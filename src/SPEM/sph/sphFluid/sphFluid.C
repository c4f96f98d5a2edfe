#include "sphFluid.H"
#include "Switch.H"
#include "dictionary.H"
#include "checkKeywords.H"
#include "parallelLoop.H"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <type_traits>

namespace
{
    using Foam::minParallelLoop;
    using Foam::minParallelParticles;

    //- Particles per chunk of the neighbour passes, dealt to the threads in
    //  turn: the particles are sorted by cell, so halves of the range are
    //  regions of the flow, and a region near the free surface (fewer
    //  neighbours) left one thread idle; a fixed deal keeps the result
    //  the same from run to run
    constexpr int passChunk = 64;

    using Foam::scalar;
    using Foam::label;
    using Foam::particleSet;

    //- What the momentum equation reads of the fluid particle i
    struct fluidSide
    {
        scalar vx, vy, rho, pr;   // pr = p/rho^2
        scalar cxx, cxy, cyy;     // C_i (momentumGradient symmetrisedCorrection)
    };

    //- The correction C_i that particle i stored, or I without one; pr:
    //  p/rho^2 of every particle (the momentum pass's pOverRho2_)
    inline fluidSide makeFluidSide
    (
        const label i,
        const scalar* __restrict__ v,
        const scalar* __restrict__ rho,
        const scalar* __restrict__ pr,
        const scalar* __restrict__ C
    )
    {
        const scalar* Ci = C ? &C[3*i] : nullptr;
        return fluidSide
        {
            v[2*i], v[2*i + 1], rho[i], pr[i],
            Ci ? Ci[0] : 1, Ci ? Ci[1] : 0, Ci ? Ci[2] : 1
        };
    }

    //- A shift (sx, sy) of a free-surface particle loses its component
    //  along grad C, the surface normal: surface particles move along the
    //  surface only
    inline void tangentialShift
    (
        const scalar gCx,
        const scalar gCy,
        scalar& sx,
        scalar& sy
    )
    {
        const scalar g2 = gCx*gCx + gCy*gCy;
        if (g2 > 0)
        {
            const scalar sn = (sx*gCx + sy*gCy)/g2;
            sx -= sn*gCx;
            sy -= sn*gCy;
        }
    }

    //- The volume a neighbour j lends to sums at the start of a step: a
    //  fluid particle's m/rho of the step before, a ghost's its element's
    //  m/rho, a wall or structure particle's its lattice cell m/rho0
    inline scalar neighbourVolume
    (
        const particleSet::kind k,
        const scalar m,
        const scalar rho,
        const scalar rhoOld,
        const scalar rho0
    )
    {
        const bool fluid = k == particleSet::kind::fluid;
        const bool ghost = k == particleSet::kind::ghost;
        return m/(fluid ? rhoOld : (ghost ? rho : rho0));
    }

    //- One relaxation shift -beta h^2 grad C (tangential at the free
    //  surface, div r below threshold), at most cap h; returns its length
    //  in smoothing lengths, at most cap
    inline scalar relaxationShift
    (
        const scalar gCx,
        const scalar gCy,
        const scalar divR,
        const scalar h,
        const scalar beta,
        const scalar threshold,
        const scalar cap,
        scalar& sx,
        scalar& sy
    )
    {
        const scalar D = beta*h*h;
        sx = -D*gCx;
        sy = -D*gCy;
        if (divR < threshold)
        {
            tangentialShift(gCx, gCy, sx, sy);
        }
        const scalar s = std::sqrt(sx*sx + sy*sy)/h;
        if (s > cap)
        {
            sx *= cap/s;
            sy *= cap/s;
        }
        return std::min(s, cap);
    }

    //- The pressure term of eq. (16): the acceleration of fluid particle i
    //  due to the pressure of particle j, with (dx, dy) = x_i - x_j and F
    //  = F(r, h_ij) of the kernel. With the kernel gradient as the paper
    //  writes it (C null), or with G_ij = (C_i + C_j)/2 grad_i W_ij (C: 3
    //  per particle, C_j = I for dummies and ghosts; see sphFluid.H,
    //  momentumGradient). Either is antisymmetric in i, j.
    inline void pairPressureAcceleration
    (
        const fluidSide& fi,
        const label j,
        const scalar gxw,
        const scalar gyw,
        const scalar* __restrict__ m,
        const scalar* __restrict__ pr,
        const particleSet::kind* __restrict__ kind,
        const scalar* __restrict__ C,
        scalar& fx,
        scalar& fy
    )
    {
        const scalar pf = -m[j]*(fi.pr + pr[j]);
        if (C)
        {
            const bool corrected = kind[j] == particleSet::kind::fluid;
            const scalar* Cj = &C[3*j];
            const scalar bxx = corrected ? Cj[0] : 1;
            const scalar bxy = corrected ? Cj[1] : 0;
            const scalar byy = corrected ? Cj[2] : 1;
            fx = 0.5*pf*((fi.cxx + bxx)*gxw + (fi.cxy + bxy)*gyw);
            fy = 0.5*pf*((fi.cxy + bxy)*gxw + (fi.cyy + byy)*gyw);
        }
        else
        {
            fx = pf*gxw;
            fy = pf*gyw;
        }
    }

    //- Eq. (16): the acceleration of fluid particle i due to particle j,
    //  pressure and viscous terms, with (dx, dy) = x_i - x_j at distance
    //  r and F = F(r, h_ij) of the kernel; its pressure part in (fpx,
    //  fpy). Shared by the momentum pass and the reaction passes, so that
    //  a structure or a ghost gets exactly the opposite of the fluid's
    //  pair forces.
    inline void pairAcceleration
    (
        const fluidSide& fi,
        const label j,
        const scalar dx,
        const scalar dy,
        const scalar r,
        const scalar hij,
        const scalar F,
        const scalar* __restrict__ v,
        const scalar* __restrict__ m,
        const scalar* __restrict__ rho,
        const scalar* __restrict__ pr,
        const particleSet::kind* __restrict__ kind,
        const scalar* __restrict__ C,
        const scalar mu,
        scalar& fx,
        scalar& fy,
        scalar& fpx,
        scalar& fpy
    )
    {
        const scalar gxw = dx*F, gyw = dy*F;
        pairPressureAcceleration(fi, j, gxw, gyw, m, pr, kind, C, fpx, fpy);
        fx = fpx;
        fy = fpy;

        // Viscous: no viscous stress at a free-slip wall
        if (kind[j] != particleSet::kind::slipWall)
        {
            const scalar rs = fi.rho + rho[j];
            const scalar vf =
                4*m[j]*2*mu*(dx*gxw + dy*gyw)
               /(rs*rs*(r*r + 0.01*hij*hij));
            fx += vf*(fi.vx - v[2*j]);
            fy += vf*(fi.vy - v[2*j + 1]);
        }
    }

    //- The neighbour sums of the density pass for fluid particle i
    struct densitySums
    {
        //- Moments sum (x_j - x_i) (x) grad_i W V_j (symmetric)
        scalar Mxx = 0, Mxy = 0, Myy = 0;

        //- Continuity sum m_j v_ij (x) grad_i W
        scalar Sxx = 0, Sxy = 0, Syx = 0, Syy = 0;

        //- grad C, div r and the density diffusion sum
        scalar gCx = 0, gCy = 0, div = 0, diffusion = 0;

        //- Add neighbour j's moments, grad C and div r: (dx, dy) = x_i - x_j,
        //  (gx, gy) = grad_i W_ij, Vj its volume
        inline void addMoments
        (
            const scalar dx,
            const scalar dy,
            const scalar gx,
            const scalar gy,
            const scalar Vj
        )
        {
            Mxx -= dx*gx*Vj;
            Mxy -= dx*gy*Vj;
            Myy -= dy*gy*Vj;
            gCx += gx*Vj;
            gCy += gy*Vj;
            div -= (dx*gx + dy*gy)*Vj;
        }

        //- Add neighbour j's continuity term, (wx, wy) = m_j v_ij
        inline void addContinuity
        (
            const scalar wx,
            const scalar wy,
            const scalar gx,
            const scalar gy
        )
        {
            Sxx += wx*gx;
            Sxy += wx*gy;
            Syx += wy*gx;
            Syy += wy*gy;
        }

        //- Eq. (16) without diffusion: sum m_j v_ij . C_i grad_i W_ij
        inline scalar continuity
        (
            const scalar cxx,
            const scalar cxy,
            const scalar cyy
        ) const
        {
            return cxx*Sxx + cxy*(Sxy + Syx) + cyy*Syy;
        }
    };

    //- The density at the end of the step from rhoOld at its start; free
    //  surface: the fluid cannot pull on the air, so a surface particle's
    //  density (pressure) stays at or above rho0 (0): splashes and thin
    //  jets keep finite volumes and do not clump
    inline scalar advancedDensity
    (
        const scalar rhoOld,
        const scalar drho,
        const scalar dt,
        const bool freeSurface,
        const scalar rho0
    )
    {
        scalar rhoNew = rhoOld + dt*drho;
        if (freeSurface) rhoNew = std::max(rhoNew, rho0);
        return rhoNew;
    }

    //- Stable steps of a fluid particle at Courant number 1, each limit
    //  apart so that the smallest can be named: the acoustic, force and
    //  viscous minima dt[0..2] are lowered to this particle's (see
    //  sphFluid::stableDeltaT())
    inline void particleDeltaT
    (
        const scalar speed,
        const scalar acc,
        const scalar h,
        const scalar c,
        const scalar nu,
        scalar& dtAcoustic,
        scalar& dtForce,
        scalar& dtViscous
    )
    {
        dtAcoustic =
            std::min(dtAcoustic, Foam::sphFluid::acousticFactor*h/(c + speed));
        if (acc > 0)
        {
            dtForce = std::min
            (
                dtForce, Foam::sphFluid::forceFactor*std::sqrt(h/acc)
            );
        }
        if (nu > 0)
        {
            dtViscous =
                std::min(dtViscous, Foam::sphFluid::viscousFactor*h*h/nu);
        }
    }
}

const Foam::Enum<Foam::gradientCorrectionType>
Foam::sphFluid::gradientCorrectionTypeNames
({
    { gradientCorrectionType::none, "none" },
    { gradientCorrectionType::decoupledFPM, "decoupledFPM" },
    { gradientCorrectionType::FPM, "FPM" },
});


const Foam::Enum<Foam::sphFluid::momentumGradientType>
Foam::sphFluid::momentumGradientTypeNames
({
    { momentumGradientType::kernel, "kernel" },
    { momentumGradientType::symmetrisedCorrection, "symmetrisedCorrection" },
});


// * * * * * * * * * * * * * * * * * controls  * * * * * * * * * * * * * * * //

void Foam::sphFluid::controls::readEntries(const dictionary& d)
{
    smoothingLengthRatio =
        d.getOrDefault<scalar>("smoothingLengthRatio", smoothingLengthRatio);
    gradientCorrection =
        getCheckedEnum
        (
            d, "gradientCorrection", gradientCorrectionTypeNames,
            gradientCorrection
        );
    densityDiffusion =
        d.getOrDefault<scalar>("densityDiffusion", densityDiffusion);
    shifting = d.getOrDefault<scalar>("shifting", shifting);
    freeSurfaceThreshold =
        d.getOrDefault<scalar>("freeSurfaceThreshold", freeSurfaceThreshold);
    wallLayers = d.getOrDefault<label>("wallLayers", wallLayers);
    momentumGradient =
        getCheckedEnum
        (
            d, "momentumGradient", momentumGradientTypeNames, momentumGradient
        );
    initialRelaxation =
        d.getOrDefault<label>("initialRelaxation", initialRelaxation);
    relaxationCoefficient =
        d.getOrDefault<scalar>
        (
            "relaxationCoefficient", relaxationCoefficient
        );
    conversionRelaxation =
        d.getOrDefault<label>("conversionRelaxation", conversionRelaxation);
    structureSuction =
        d.getOrDefault<Switch>("structureSuction", structureSuction);
    pairCache = d.getOrDefault<Switch>("pairCache", pairCache);
}


Foam::sphFluid::controls
Foam::sphFluid::controls::read(const dictionary& schemesDict)
{
    controls c;
    const dictionary* d = schemesDict.findDict("sph");
    if (!d) return c;

    checkKeywords
    (
        *d,
        {
            "smoothingLengthRatio", "gradientCorrection", "densityDiffusion",
            "shifting", "freeSurfaceThreshold", "wallLayers",
            "momentumGradient", "initialRelaxation", "relaxationCoefficient",
            "conversionRelaxation", "lostParticleDistance",
            "structureSuction", "pairCache"
        }
    );
    c.readEntries(*d);

    auto bad = [&](const char* key, const char* what)
    {
        FatalIOErrorInFunction(*d)
            << "sph/" << key << ' ' << what << exit(FatalIOError);
    };
    if (!(c.smoothingLengthRatio >= 0.5 && c.smoothingLengthRatio <= 3))
    {
        bad("smoothingLengthRatio", "must lie in [0.5, 3] (typically 1.2-1.5)");
    }
    if (!(c.densityDiffusion >= 0 && c.densityDiffusion <= 1))
    {
        bad("densityDiffusion", "must lie in [0, 1] (typically 0.1)");
    }
    if (!(c.shifting >= 0 && c.shifting <= 10))
    {
        bad("shifting", "must lie in [0, 10] (typically 2)");
    }
    if (!(c.freeSurfaceThreshold >= 0 && c.freeSurfaceThreshold <= 2))
    {
        bad("freeSurfaceThreshold", "must lie in [0, 2] (div r is 2 in the bulk)");
    }
    if (c.wallLayers < 0 || c.wallLayers > 10)
    {
        bad("wallLayers", "must lie in [0, 10] (0: enough for the support)");
    }
    if (c.initialRelaxation < 0 || c.initialRelaxation > 100000)
    {
        bad("initialRelaxation", "must lie in [0, 100000] iterations (0: off)");
    }
    if (c.conversionRelaxation < 0 || c.conversionRelaxation > 10000)
    {
        bad
        (
            "conversionRelaxation",
            "must lie in [0, 10000] iterations (0: off)"
        );
    }
    if (!(c.relaxationCoefficient > 0 && c.relaxationCoefficient <= 0.2))
    {
        bad("relaxationCoefficient", "must lie in (0, 0.2] (typically 0.1)");
    }
    if (d->found("lostParticleDistance"))
    {
        // Replaced by the tank: an old case should not run with a check
        // it no longer gets
        bad
        (
            "lostParticleDistance",
            "is no longer read: a particle farther than a kernel support"
            " outside the tank (its walls) has left it; choose what then"
            " happens with tank/leaving (stop, remove, warn) in"
            " constant/spemProperties"
        );
    }
    return c;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::sphFluid::sphFluid
(
    const dictionary& schemesDict,
    particleSet&& particles,
    const scalar rho0,
    const scalar c,
    const scalar mu,
    const scalar gx,
    const scalar gy,
    const scalar boxMin[2],
    const scalar boxMax[2]
)
:
    controls_(controls::read(schemesDict)),
    kernel_(sphKernel::New(schemesDict)),
    rho0_(rho0),
    c_(c),
    mu_(mu),
    gx_(gx),
    gy_(gy),
    particles_(std::move(particles)),
    nFluid_(0),
    nWall_(0),
    nGhost_(0),
    nStructure_(0),
    nextId_(0),
    freshIdBegin_(0),
    stepIdBegin_(0),
    massDamping_(0),
    pendingDeltaT_(0),
    previousDeltaT_(0),
    oldPreviousDeltaT_(0),
    stepsSinceReorder_(reorderInterval),
    stableDeltaT_(GREAT),
    wallForce_{0, 0},
    ghostForce_{0, 0},
    structureForce_{0, 0},
    tank_(nullptr),
    leaving_(tankBoundary::leavingAction::stop),
    nOutside_(0),
    nRemovedLast_(0),
    nRemoved_(0),
    removedMassLast_(0),
    removedMass_(0),
    leftTank_(false)
{
    for (const particleSet::kind k : particles_.kinds())
    {
        if (k == particleSet::kind::fluid) ++nFluid_;
        else if (k == particleSet::kind::wall || k == particleSet::kind::slipWall)
        {
            ++nWall_;
        }
        else
        {
            FatalErrorInFunction
                << "Ghost and structure particles are set by setGhosts() and"
                << " setStructureParticles(), not given at construction"
                << exit(FatalError);
        }
    }
    for (const label id : particles_.id()) nextId_ = std::max(nextId_, id + 1);
    freshIdBegin_ = nextId_;
    stepIdBegin_ = nextId_;
    for (int k = 0; k < 2; ++k)
    {
        boxMin_[k] = boxMin[k];
        boxMax_[k] = boxMax[k];
    }

    resizeFields();
    oldPosition_ = particles_.positions();
    oldVelocity_ = particles_.velocities();
    oldDensity_ = particles_.density();
}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

bool Foam::sphFluid::checkParticles()
{
    const label n = particles_.size();
    const scalar* x = particles_.positions().data();
    const scalar* v = particles_.velocities().data();
    const scalar* rho = particles_.density().data();
    const particleSet::kind* kind = particles_.kinds().data();
    const tankBoundary* tank = tank_;
    // A weakly compressible fluid never flows faster than sound: a fluid
    // particle at Mach 1 was thrown by a blow-up (caught here before it
    // flies far enough to blow up the neighbour search's grid)
    const scalar c2 = c_*c_;
    label bad = -1, outside = -1, nOutside = 0;
    nRemovedLast_ = 0;
    removedMassLast_ = 0;
    leftTank_ = false;

    // Performance critical: every particle, every step (O(1) each)
    #pragma omp parallel for schedule(static) reduction(max: bad, outside) reduction(+: nOutside) if(n > minParallelLoop)
    for (label i = 0; i < n; ++i)
    {
        const bool ok =
            std::isfinite(v[2*i]) && std::isfinite(v[2*i + 1])
         && std::isfinite(rho[i]) && rho[i] > 0
         && x[2*i] >= boxMin_[0] && x[2*i] <= boxMax_[0]
         && x[2*i + 1] >= boxMin_[1] && x[2*i + 1] <= boxMax_[1]
         && (
                kind[i] != particleSet::kind::fluid
             || v[2*i]*v[2*i] + v[2*i + 1]*v[2*i + 1] < c2
            );
        if (!ok) bad = std::max(bad, i);
        if
        (
            tank && kind[i] == particleSet::kind::fluid
         && tank->outside(x[2*i], x[2*i + 1])
        )
        {
            outside = std::max(outside, i);
            ++nOutside;
        }
    }
    nOutside_ = nOutside;

    if (bad < 0 && outside >= 0)
    {
        if (leaving_ == tankBoundary::leavingAction::warn) return true;
        if (leaving_ == tankBoundary::leavingAction::remove)
        {
            // Rare (a particle leaves once): the compaction may loop over
            // every particle
            const std::vector<scalar>& px = particles_.positions();
            const std::vector<particleSet::kind>& pk = particles_.kinds();
            const std::vector<scalar>& pm = particles_.mass();
            removeIf
            (
                [&](const label i)
                {
                    const bool out =
                        pk[i] == particleSet::kind::fluid
                     && tank->outside(px[2*i], px[2*i + 1]);
                    if (out)
                    {
                        ++nRemovedLast_;
                        removedMassLast_ += pm[i];
                    }
                    return out;
                }
            );
            nFluid_ -= nRemovedLast_;
            nRemoved_ += nRemovedLast_;
            removedMass_ += removedMassLast_;
            nOutside_ = 0;
            resizeFields();
            return true;
        }
        std::ostringstream os;
        os  << nOutside << " fluid particle" << (nOutside > 1 ? "s are" : " is")
            << " outside the tank by more than a kernel support ("
            << tank->reach() << " m), e.g. particle "
            << particles_.id()[outside] << " at (" << x[2*outside] << ' '
            << x[2*outside + 1] << ") with velocity (" << v[2*outside] << ' '
            << v[2*outside + 1] << ')';
        failure_ = os.str();
        leftTank_ = true;
        return false;
    }
    if (bad < 0) return true;

    std::ostringstream os;
    os  << "particle " << particles_.id()[bad] << " at (" << x[2*bad] << ' '
        << x[2*bad + 1] << ") with velocity (" << v[2*bad] << ' '
        << v[2*bad + 1] << ") and density " << rho[bad];
    if (!(rho[bad] > 0) || !std::isfinite(v[2*bad]) || !std::isfinite(v[2*bad+1]))
    {
        os  << " is not finite or has a non-positive density";
    }
    else if (std::hypot(v[2*bad], v[2*bad + 1]) >= c_)
    {
        os  << " moves at " << std::hypot(v[2*bad], v[2*bad + 1])
            << " m/s, faster than sound (c " << c_ << " m/s): the step"
            << " blew up";
    }
    else
    {
        os  << " left the domain [(" << boxMin_[0] << ' ' << boxMin_[1]
            << "), (" << boxMax_[0] << ' ' << boxMax_[1] << ")]";
    }
    failure_ = os.str();
    return false;
}


void Foam::sphFluid::addInterfaceAcceleration(const std::vector<scalar>& a)
{
    const scalar* m = particles_.mass().data();
    for (label i = 0; i < particles_.size(); ++i)
    {
        if (a[2*i] == 0 && a[2*i + 1] == 0) continue;
        for (label d = 0; d < 2; ++d)
        {
            acceleration_[2*i + d] += a[2*i + d];
            ghostAcceleration_[2*i + d] += a[2*i + d];
            ghostForce_[d] -= m[i]*a[2*i + d];
        }
    }
}


void Foam::sphFluid::reorder()
{
    const std::vector<label>& order = cells_.sortOrder();
    // Kept for evaluationOrder(); the capacity stays, so this allocates
    // only when the particle count grows
    lastSortOrder_.assign(order.begin(), order.end());
    particles_.reorder(order);
    particles_.reorderField(order, 2, oldPosition_);
    particles_.reorderField(order, 2, oldVelocity_);
    particles_.reorderField(order, 1, oldDensity_);
    // Not reordered: acceleration_, correction_, gradC_ and divR_, which
    // the passes of this evaluate() recompute for every particle before
    // anything reads them
    cells_.particlesReordered();
}


void Foam::sphFluid::indexParticles()
{
    // One sequential sweep of a byte per particle: a small fraction of a
    // pass, which visits some 20-30 neighbours per particle
    fluidIndex_.clear();
    wallIndex_.clear();
    structureIndex_.clear();
    ghostIndex_.clear();
    const label n = particles_.size();
    const particleSet::kind* kind = particles_.kinds().data();
    for (label i = 0; i < n; ++i)
    {
        const particleSet::kind k = kind[i];
        if (k == particleSet::kind::fluid)
        {
            fluidIndex_.push_back(i);
            continue;
        }
        if (particleSet::isWall(k)) wallIndex_.push_back(i);
        if (k == particleSet::kind::structure) structureIndex_.push_back(i);
        else if (k == particleSet::kind::ghost) ghostIndex_.push_back(i);
    }
}


void Foam::sphFluid::resizeFields()
{
    const label n = particles_.size();
    acceleration_.resize(2*n, 0);
    ghostAcceleration_.resize(2*n, 0);
    wallElementShare_.resize(2*n, 0);
    wallElementForce_.resize(2*n, 0);
    if (controls_.momentumGradient == momentumGradientType::symmetrisedCorrection)
    {
        correction_.resize(3*n, 0);
    }
    gradC_.resize(2*n, 0);
    divR_.resize(n, 2);
}


template<class Kernel>
Foam::scalar Foam::sphFluid::relaxFreshPass(const Kernel&)
{
    const scalar kappa = Kernel::support;
    const scalar* __restrict__ m = particles_.mass().data();
    const scalar* __restrict__ h = particles_.smoothingLength().data();
    const scalar* __restrict__ rho = particles_.density().data();
    const particleSet::kind* __restrict__ kind = particles_.kinds().data();
    const scalar* __restrict__ rhoOld = oldDensity_.data();
    const scalar beta = controls_.relaxationCoefficient;
    const scalar threshold = controls_.freeSurfaceThreshold;
    const scalar rho0 = rho0_;

    const label n = label(fresh_.size());
    freshShift_.resize(2*n);
    scalar largest = 0;
    const label* __restrict__ fresh = fresh_.data();
    scalar* __restrict__ shift = freshShift_.data();
    #pragma omp parallel for schedule(static) reduction(max: largest) if(n > minParallelParticles)
    for (label f = 0; f < n; ++f)
    {
        const label i = fresh[f];
        densitySums sums;
        cells_.forEachNeighbour
        (
            particles_, i, kappa,
            [&](const label j, const scalar dx, const scalar dy, const scalar r)
            {
                const scalar F = Kernel::F(r, 0.5*(h[i] + h[j]));
                const scalar Vj =
                    neighbourVolume(kind[j], m[j], rho[j], rhoOld[j], rho0);
                sums.addMoments(dx, dy, dx*F, dy*F, Vj);
            }
        );
        scalar sx, sy;
        largest = std::max
        (
            largest,
            relaxationShift
            (
                sums.gCx, sums.gCy, sums.div, h[i], beta, threshold,
                relaxationMaxShift, sx, sy
            )
        );
        shift[2*f] = sx;
        shift[2*f + 1] = sy;
    }
    // Jacobi: every shift from the positions before the iteration
    scalar* __restrict__ x = particles_.positions().data();
    for (label f = 0; f < n; ++f)
    {
        const label i = fresh[f];
        x[2*i] += shift[2*f];
        x[2*i + 1] += shift[2*f + 1];
        oldPosition_[2*i] = x[2*i];
        oldPosition_[2*i + 1] = x[2*i + 1];
    }
    return largest;
}


template<class Kernel>
void Foam::sphFluid::densityPass(const Kernel&)
{
    const scalar kappa = Kernel::support;
    const scalar* __restrict__ v = particles_.velocities().data();
    const scalar* __restrict__ m = particles_.mass().data();
    const scalar* __restrict__ h = particles_.smoothingLength().data();
    const particleSet::kind* __restrict__ kind = particles_.kinds().data();
    const label* __restrict__ id = particles_.id().data();
    const label freshIdBegin = freshIdBegin_;
    scalar* __restrict__ rho = particles_.density().data();
    scalar* __restrict__ p = particles_.pressure().data();
    scalar* __restrict__ gradC = gradC_.data();
    scalar* __restrict__ divR = divR_.data();
    scalar* __restrict__ C = correctionData();
    const scalar* __restrict__ rhoOld = oldDensity_.data();

    const scalar dt = pendingDeltaT_;
    const scalar delta = controls_.densityDiffusion;
    const scalar threshold = controls_.freeSurfaceThreshold;
    const gradientCorrectionType correction = controls_.gradientCorrection;
    const scalar c = c_, c2 = c_*c_, rho0 = rho0_;
    // Hydrostatic density difference per unit distance, g rho0/c^2
    const scalar hx = rho0*gx_/c2, hy = rho0*gy_/c2;

    // The density of step n+1 needs the densities of step n of the
    // neighbours (volumes, diffusion): read rhoOld, write rho. An exact
    // restart needs both (setOldDensity()).
    // Performance critical: every fluid particle, every step.
    const label nFluid = label(fluidIndex_.size());
    const label* __restrict__ fluid = fluidIndex_.data();

    // The pairs for the momentum pass: slots for the most pairs of the
    // last step and a margin, but not more than twice the mean (a coarse
    // particle among fine ones can have many times the pairs of the
    // others: it walks the cells). Growing allocates; the same count does
    // not
    if (controls_.pairCache && pairCountMax_ > pairCapacity_)
    {
        const label most = std::min(pairCountMax_, 2*pairCountMean_ + 8);
        pairCapacity_ = std::max(pairCapacity_, most + most/8 + 2);
    }
    // Without the cache no slot: every count exceeds 0, the momentum pass
    // walks the cells
    const label K = controls_.pairCache ? pairCapacity_ : 0;
    pairCount_.resize(nFluid);
    const std::size_t slots = std::size_t(nFluid)*K;
    if (pairNeighbour_.size() < slots)
    {
        pairNeighbour_.resize(slots);
        pairF_.resize(slots);
    }
    label* __restrict__ pairCount = pairCount_.data();
    label* __restrict__ pairJ = pairNeighbour_.data();
    scalar* __restrict__ pairF = pairF_.data();

    // Volumes of the start of the step, once per particle (one division
    // less per pair); a wall particle's is its fixed lattice cell, a
    // ghost's its element's area. In the pass's parallel region (one
    // fork and join less per step); written, then read in the same block:
    // no restrict
    const label nAll = particles_.size();
    volume_.resize(nAll);
    scalar* volume = volume_.data();

    // The most and the sum of the pairs, for the slots of the next step
    label countMax = 0, countSum = 0;

    #pragma omp parallel if(nFluid > minParallelParticles)
    {
    #pragma omp for schedule(static)
    for (label j = 0; j < nAll; ++j)
    {
        volume[j] = neighbourVolume(kind[j], m[j], rho[j], rhoOld[j], rho0);
    }

    #pragma omp for schedule(static, passChunk) reduction(max: countMax) reduction(+: countSum)
    for (label f = 0; f < nFluid; ++f)
    {
        const label i = fluid[f];
        const scalar vxi = v[2*i], vyi = v[2*i + 1], rhoi = rhoOld[i];
        densitySums sums;
        label nPairs = 0;
        label* __restrict__ slotJ = pairJ + std::size_t(f)*K;
        scalar* __restrict__ slotF = pairF + std::size_t(f)*K;

        cells_.forEachNeighbour
        (
            particles_, i, kappa,
            [&](const label j, const scalar dx, const scalar dy, const scalar r)
            {
                const scalar hij = 0.5*(h[i] + h[j]);
                const scalar F = Kernel::F(r, hij);
                if (nPairs < K)
                {
                    slotJ[nPairs] = j;
                    slotF[nPairs] = F;
                }
                ++nPairs;
                // grad_i W_ij = (x_i - x_j) F
                const scalar gx = dx*F, gy = dy*F;
                const bool fluidj = kind[j] == particleSet::kind::fluid;
                const bool ghostj = kind[j] == particleSet::kind::ghost;
                const scalar Vj = volume[j];

                sums.addMoments(dx, dy, gx, gy, Vj);

                // Continuity: m_j v_ij (x) grad_i W (eqs. 16, 23). A wall
                // particle's velocity field holds the mirrored velocity of
                // the viscous term, the wall itself is at rest; a structure
                // particle's holds the structure's velocity until the wall
                // pass.
                const bool moving =
                    fluidj || ghostj || kind[j] == particleSet::kind::structure;
                const scalar wx = m[j]*(vxi - (moving ? v[2*j] : 0));
                const scalar wy = m[j]*(vyi - (moving ? v[2*j + 1] : 0));
                sums.addContinuity(wx, wy, gx, gy);

                // Density diffusion between fluid particles (ghosts are
                // fluid), hydrostatic part removed; psi_ij . grad_i W =
                // -2 drho F (x_j - x_i = -(dx, dy))
                if (fluidj || ghostj)
                {
                    const scalar rhoj = fluidj ? rhoOld[j] : rho[j];
                    const scalar dRho =
                        (rhoj - rhoi) + (hx*dx + hy*dy);
                    sums.diffusion -= 2*dRho*F*Vj*hij;
                }
            }
        );

        pairCount[f] = nPairs;
        countMax = max(countMax, nPairs);
        countSum += nPairs;

        // Correction C_i (symmetric: xx, xy, yy); identity at the surface
        scalar Ci[3];
        const scalar div = sums.div;
        gradientCorrectionMatrix
        (
            correction, div < threshold, sums.Mxx, sums.Mxy, sums.Myy, Ci
        );
        const scalar cxx = Ci[0], cxy = Ci[1], cyy = Ci[2];
        if (C)
        {
            C[3*i] = cxx;
            C[3*i + 1] = cxy;
            C[3*i + 2] = cyy;
        }
        gradC[2*i] = sums.gCx;
        gradC[2*i + 1] = sums.gCy;
        divR[i] = div;

        // Eq. (16): drho/dt = sum m_j v_ij . C_i grad_i W_ij
        const scalar drho =
            sums.continuity(cxx, cxy, cyy) + delta*c*sums.diffusion;
        // No step pending (start, restart, re-evaluation, or a particle
        // appended since the step): the density stays
        scalar rhoNew = rho[i];
        if (dt > 0 && id[i] < freshIdBegin)
        {
            rhoNew = advancedDensity(rhoi, drho, dt, div < threshold, rho0);
        }
        rho[i] = rhoNew;
        // Eq. (7)
        p[i] = c2*(rhoNew - rho0);
    }
    } // End of the parallel region
    pairCountMax_ = countMax;
    pairCountMean_ = nFluid > 0 ? countSum/nFluid : 0;
}


template<class Kernel>
void Foam::sphFluid::wallPass(const Kernel&)
{
    const scalar kappa = Kernel::support;
    const scalar* __restrict__ h = particles_.smoothingLength().data();
    const particleSet::kind* __restrict__ kind = particles_.kinds().data();
    scalar* __restrict__ v = particles_.velocities().data();
    scalar* __restrict__ rho = particles_.density().data();
    scalar* __restrict__ p = particles_.pressure().data();
    const label* __restrict__ id = particles_.id().data();
    const scalar* __restrict__ aStructure = structureAcceleration_.data();
    scalar* __restrict__ share = wallElementShare_.data();
    const scalar c2 = c_*c_, rho0 = rho0_;
    const bool structureSuction = controls_.structureSuction;
    const bool ghosts = nGhost_ > 0;

    // The cells that hold the fluid (particles and ghosts): most walls of
    // a tank whose water is mostly elements have none in reach, and skip
    // the search (the branch below without fluid, the same values)
    fluidCells_.assign(cells_.nCells(), 0);
    for (const std::vector<label>* index : {&fluidIndex_, &ghostIndex_})
    {
        for (const label i : *index) fluidCells_[cells_.cellOfParticle(i)] = 1;
    }
    const unsigned char* fluidCells = fluidCells_.data();

    const label nWalls = label(wallIndex_.size());
    const label* __restrict__ walls = wallIndex_.data();
    #pragma omp parallel for schedule(static, passChunk) if(nWalls > minParallelParticles)
    for (label k = 0; k < nWalls; ++k)
    {
        const label w = walls[k];

        // A structure moves: its velocity (set with it) and acceleration
        const bool structure = kind[w] == particleSet::kind::structure;
        const scalar uw = structure ? v[2*w] : 0;
        const scalar vw = structure ? v[2*w + 1] : 0;
        const scalar gx = gx_ - (structure ? aStructure[2*id[w]] : 0);
        const scalar gy = gy_ - (structure ? aStructure[2*id[w] + 1] : 0);

        scalar sumW = 0, sumP = 0, sumRhoX = 0, sumRhoY = 0, sumU = 0, sumV = 0;
        scalar sumGhostW = 0;
        if (cells_.anyMarkedCellAround(particles_, w, kappa, fluidCells))
        {
            cells_.forEachNeighbour
            (
                particles_, w, kappa,
                [&]
                (
                    const label f,
                    const scalar dx,
                    const scalar dy,
                    const scalar r
                )
                {
                    // The fluid: particles and the elements' ghosts
                    if
                    (
                        kind[f] != particleSet::kind::fluid
                     && kind[f] != particleSet::kind::ghost
                    )
                    {
                        return;
                    }
                    const scalar W = Kernel::W(r, 0.5*(h[w] + h[f]));
                    sumW += W;
                    sumP += p[f]*W;
                    // rho_f (x_w - x_f) W
                    sumRhoX += rho[f]*dx*W;
                    sumRhoY += rho[f]*dy*W;
                    sumU += v[2*f]*W;
                    sumV += v[2*f + 1]*W;
                    if (ghosts && kind[f] == particleSet::kind::ghost)
                    {
                        sumGhostW += W;
                    }
                }
            );
        }

        // A wall at rest whose pressure the elements make in part: their
        // share of its kernel sum, and the sum
        scalar* sw = &share[2*w];
        sw[0] = 0;
        if (sumGhostW > 0 && !structure)
        {
            sw[0] = sumGhostW/sumW;
            sw[1] = sumW;
        }

        if (sumW > 0)
        {
            // Adami et al. 2012, (g - a_w) with the wall's acceleration
            const scalar pExtrapolated =
                (sumP + gx*sumRhoX + gy*sumRhoY)/sumW;
            const scalar pw =
                structure && structureSuction
              ? pExtrapolated : std::max(pExtrapolated, scalar(0));
            p[w] = pw;
            rho[w] = rho0 + pw/c2;
            // No-slip: mirrored fluid velocity, 2 v_w - v_f; free-slip
            // walls do not use it
            v[2*w] = 2*uw - sumU/sumW;
            v[2*w + 1] = 2*vw - sumV/sumW;
        }
        else
        {
            p[w] = 0;
            rho[w] = rho0;
            v[2*w] = uw;
            v[2*w + 1] = vw;
        }
    }
}


template<class Kernel>
void Foam::sphFluid::momentumPass(const Kernel&)
{
    const scalar kappa = Kernel::support;
    const scalar* __restrict__ v = particles_.velocities().data();
    const scalar* __restrict__ m = particles_.mass().data();
    const scalar* __restrict__ h = particles_.smoothingLength().data();
    const scalar* __restrict__ rho = particles_.density().data();
    const scalar* __restrict__ p = particles_.pressure().data();
    // p/rho^2 of every particle, once (one division less per pair), for
    // this pass and the reaction passes after it; computed in the pass's
    // parallel region (one fork and join less per step). Written, then
    // read in the same block: no restrict
    const label nAll = particles_.size();
    pOverRho2_.resize(nAll);
    scalar* pOverRho2 = pOverRho2_.data();
    const scalar* pr = pOverRho2;
    const particleSet::kind* __restrict__ kind = particles_.kinds().data();
    const scalar* __restrict__ C = correctionData();
    scalar* __restrict__ a = acceleration_.data();
    scalar* __restrict__ aGhost = ghostAcceleration_.data();
    const scalar* __restrict__ share = wallElementShare_.data();
    const scalar* __restrict__ x = particles_.positions().data();
    const label K = controls_.pairCache ? pairCapacity_ : 0;
    const label* __restrict__ pairCount = pairCount_.data();
    const label* __restrict__ pairJ = pairNeighbour_.data();
    const scalar* __restrict__ pairF = pairF_.data();

    const scalar mu = mu_, gx = gx_, gy = gy_, c = c_;
    const scalar nu = mu_/rho0_;
    scalar fwx = 0, fwy = 0, fgx = 0, fgy = 0, fsx = 0, fsy = 0;
    scalar dtAcoustic = GREAT, dtForce = GREAT, dtViscous = GREAT;

    // Performance critical: every fluid particle, every step.
    // Only the fluid particles accelerate
    std::fill(acceleration_.begin(), acceleration_.end(), 0);
    std::fill(ghostAcceleration_.begin(), ghostAcceleration_.end(), 0);
    const label nFluid = label(fluidIndex_.size());
    const label* __restrict__ fluid = fluidIndex_.data();
    #pragma omp parallel if(nFluid > minParallelParticles)
    {
    #pragma omp for schedule(static)
    for (label j = 0; j < nAll; ++j)
    {
        pOverRho2[j] = p[j]/(rho[j]*rho[j]);
    }

    #pragma omp for schedule(static, passChunk) reduction(+: fwx, fwy, fgx, fgy, fsx, fsy) reduction(min: dtAcoustic, dtForce, dtViscous)
    for (label f = 0; f < nFluid; ++f)
    {
        const label i = fluid[f];
        const scalar vxi = v[2*i], vyi = v[2*i + 1];
        const fluidSide fi = makeFluidSide(i, v, rho, pr, C);
        scalar ax = 0, ay = 0, wx = 0, wy = 0, gfx = 0, gfy = 0, sx = 0, sy = 0;

        const auto pair =
            [&]
            (
                const label j,
                const scalar dx,
                const scalar dy,
                const scalar r,
                const scalar F
            )
            {
                scalar fx, fy, fpx, fpy;
                pairAcceleration
                (
                    fi, j, dx, dy, r, 0.5*(h[i] + h[j]), F,
                    v, m, rho, pr, kind, C, mu, fx, fy, fpx, fpy
                );
                ax += fx;
                ay += fy;
                if (kind[j] == particleSet::kind::structure)
                {
                    sx += fx;
                    sy += fy;
                }
                else if (particleSet::isWall(kind[j]))
                {
                    // Less the elements' part of the wall's push
                    const scalar tx = share[2*j]*fpx, ty = share[2*j]*fpy;
                    wx += fx - tx;
                    wy += fy - ty;
                    gfx += tx;
                    gfy += ty;
                }
                else if (kind[j] == particleSet::kind::ghost)
                {
                    gfx += fx;
                    gfy += fy;
                }
            };
        // The density pass's pairs, in its order; past the slots, the cells
        const label nPairs = pairCount[f];
        if (nPairs <= K)
        {
            const label* __restrict__ slotJ = pairJ + std::size_t(f)*K;
            const scalar* __restrict__ slotF = pairF + std::size_t(f)*K;
            const scalar xi = x[2*i], yi = x[2*i + 1];
            for (label k = 0; k < nPairs; ++k)
            {
                // As forEachNeighbour computes them: the same bits
                const label j = slotJ[k];
                const scalar dx = xi - x[2*j], dy = yi - x[2*j + 1];
                pair(j, dx, dy, std::sqrt(dx*dx + dy*dy), slotF[k]);
            }
        }
        else
        {
            cells_.forEachNeighbour
            (
                particles_, i, kappa,
                [&](const label j, const scalar dx, const scalar dy, const scalar r)
                {
                    pair(j, dx, dy, r, Kernel::F(r, 0.5*(h[i] + h[j])));
                }
            );
        }

        a[2*i] = ax + gx;
        a[2*i + 1] = ay + gy;
        aGhost[2*i] = gfx;
        aGhost[2*i + 1] = gfy;
        // Force of the fluid on the walls: minus the walls' force on it
        fwx -= m[i]*wx;
        fwy -= m[i]*wy;
        fgx -= m[i]*gfx;
        fgy -= m[i]*gfy;
        fsx -= m[i]*sx;
        fsy -= m[i]*sy;

        // Stable step of this particle at Courant number 1
        const scalar speed = std::sqrt(vxi*vxi + vyi*vyi);
        const scalar acc = std::sqrt(a[2*i]*a[2*i] + a[2*i + 1]*a[2*i + 1]);
        particleDeltaT
        (
            speed, acc, h[i], c, nu, dtAcoustic, dtForce, dtViscous
        );
    }
    } // End of the parallel region

    wallForce_[0] = fwx;
    wallForce_[1] = fwy;
    ghostForce_[0] = fgx;
    ghostForce_[1] = fgy;
    structureForce_[0] = fsx;
    structureForce_[1] = fsy;
    // The minimum of the three is the minimum over all particles and
    // limits, as one reduction gave it
    stableLimit_ = stepLimit();
    stableLimit_.keepSmaller(stepLimit::criterion::acoustic, dtAcoustic, -1, 0);
    stableLimit_.keepSmaller(stepLimit::criterion::bodyForce, dtForce, -1, 0);
    stableLimit_.keepSmaller(stepLimit::criterion::viscous, dtViscous, -1, 0);
    stableDeltaT_ = std::min({dtAcoustic, dtForce, dtViscous});
}


template<class Kernel>
void Foam::sphFluid::reactionPass
(
    const Kernel&,
    const particleSet::kind k,
    std::vector<scalar>& reaction
)
{
    const scalar kappa = Kernel::support;
    const scalar* __restrict__ v = particles_.velocities().data();
    const scalar* __restrict__ m = particles_.mass().data();
    const scalar* __restrict__ h = particles_.smoothingLength().data();
    const scalar* __restrict__ rho = particles_.density().data();
    const scalar* __restrict__ pr = pOverRho2_.data();
    const particleSet::kind* __restrict__ kind = particles_.kinds().data();
    const label* __restrict__ id = particles_.id().data();
    const scalar* __restrict__ C = correctionData();
    scalar* __restrict__ force = reaction.data();
    const scalar mu = mu_;
    // Ghosts also get the elements' part of the wall forces, in the
    // shares that made it (see wallElementPass)
    const bool ghosts = k == particleSet::kind::ghost;
    const scalar* __restrict__ share = wallElementShare_.data();
    const scalar* __restrict__ wallPart = wallElementForce_.data();

    // F_w = -sum_f m_f a_fw: the pair forces of the momentum pass, seen
    // from the particle w (a gather: no two threads write one w)
    const std::vector<label>& index =
        k == particleSet::kind::ghost ? ghostIndex_ : structureIndex_;
    const label nReacting = label(index.size());
    const label* __restrict__ reacting = index.data();
    #pragma omp parallel for schedule(static, passChunk) if(nReacting > minParallelParticles)
    for (label r = 0; r < nReacting; ++r)
    {
        const label w = reacting[r];
        scalar Fx = 0, Fy = 0;
        cells_.forEachNeighbour
        (
            particles_, w, kappa,
            [&](const label f, const scalar dx, const scalar dy, const scalar r)
            {
                if (kind[f] != particleSet::kind::fluid)
                {
                    if
                    (
                        ghosts
                     && particleSet::isWall(kind[f])
                     && share[2*f] > 0
                    )
                    {
                        const scalar W = Kernel::W(r, 0.5*(h[f] + h[w]));
                        // W over the ghosts' sum at wall f
                        const scalar s = W/(share[2*f]*share[2*f + 1]);
                        Fx += s*wallPart[2*f];
                        Fy += s*wallPart[2*f + 1];
                    }
                    return;
                }
                const fluidSide ff = makeFluidSide(f, v, rho, pr, C);
                scalar fx, fy, fpx, fpy;
                // (dx, dy) = x_w - x_f; the pair needs x_f - x_w
                const scalar hfw = 0.5*(h[f] + h[w]);
                pairAcceleration
                (
                    ff, w, -dx, -dy, r, hfw, Kernel::F(r, hfw),
                    v, m, rho, pr, kind, C, mu, fx, fy, fpx, fpy
                );
                Fx -= m[f]*fx;
                Fy -= m[f]*fy;
            }
        );
        force[2*id[w]] = Fx;
        force[2*id[w] + 1] = Fy;
    }
}


template<class Kernel>
void Foam::sphFluid::wallElementPass(const Kernel&)
{
    const scalar kappa = Kernel::support;
    const scalar* __restrict__ v = particles_.velocities().data();
    const scalar* __restrict__ m = particles_.mass().data();
    const scalar* __restrict__ h = particles_.smoothingLength().data();
    const scalar* __restrict__ rho = particles_.density().data();
    const scalar* __restrict__ pr = pOverRho2_.data();
    const particleSet::kind* __restrict__ kind = particles_.kinds().data();
    const scalar* __restrict__ C = correctionData();
    const scalar* __restrict__ share = wallElementShare_.data();
    scalar* __restrict__ force = wallElementForce_.data();

    // The elements' part of the pair forces of the momentum pass, seen
    // from the wall particle w (a gather: no two threads write one w)
    const label nWalls = label(wallIndex_.size());
    const label* __restrict__ walls = wallIndex_.data();
    #pragma omp parallel for schedule(static, passChunk) if(nWalls > minParallelParticles)
    for (label k = 0; k < nWalls; ++k)
    {
        const label w = walls[k];
        if (!(share[2*w] > 0)) continue;
        scalar Fx = 0, Fy = 0;
        cells_.forEachNeighbour
        (
            particles_, w, kappa,
            [&](const label f, const scalar dx, const scalar dy, const scalar r)
            {
                if (kind[f] != particleSet::kind::fluid) return;
                const fluidSide ff = makeFluidSide(f, v, rho, pr, C);
                // (dx, dy) = x_w - x_f; the pair needs x_f - x_w
                const scalar F = Kernel::F(r, 0.5*(h[f] + h[w]));
                scalar fpx, fpy;
                pairPressureAcceleration
                (
                    ff, w, -dx*F, -dy*F, m, pr, kind, C, fpx, fpy
                );
                Fx -= m[f]*share[2*w]*fpx;
                Fy -= m[f]*share[2*w]*fpy;
            }
        );
        force[2*w] = Fx;
        force[2*w + 1] = Fy;
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

bool Foam::sphFluid::evaluate()
{
    failure_.clear();
    if (!checkParticles()) return false;

    {
        std::optional<costBreakdown::scope> timed;
        if (cost_) timed.emplace(*cost_, costBreakdown::search);
        const scalar kappa = kernel_->support();
        if
        (
            !cells_.tryUpdate(particles_, kappa*particles_.maxSmoothingLength())
        )
        {
            failure_ = cells_.failure();
            return false;
        }
        lastSortOrder_.clear();
        if (++stepsSinceReorder_ >= reorderInterval)
        {
            reorder();
            stepsSinceReorder_ = 0;
        }
    }
    indexParticles();

    // Particles made by conversion since the last evaluation (not those
    // of the start, before the first step): open their close pairs before
    // their first density pass (see controls::conversionRelaxation)
    if
    (
        controls_.conversionRelaxation > 0
     && previousDeltaT_ > 0
     && nextId_ > freshIdBegin_
    )
    {
        relaxFresh(controls_.conversionRelaxation);
    }

    kernel_->visit([this](const auto& k) { densityPass(k); });
    pendingDeltaT_ = 0;
    freshIdBegin_ = nextId_;
    kernel_->visit([this](const auto& k) { wallPass(k); });
    kernel_->visit([this](const auto& k) { momentumPass(k); });
    if (nStructure_ > 0)
    {
        kernel_->visit
        (
            [this](const auto& k)
            {
                reactionPass
                (
                    k, particleSet::kind::structure, structureParticleForce_
                );
            }
        );
    }
    if (nGhost_ > 0)
    {
        kernel_->visit([this](const auto& k) { wallElementPass(k); });
        kernel_->visit
        (
            [this](const auto& k)
            {
                reactionPass(k, particleSet::kind::ghost, ghostParticleForce_);
            }
        );
    }

    // A density that went non-positive or non-finite: the step failed
    const label n = particles_.size();
    const scalar* rho = particles_.density().data();
    const scalar* a = acceleration_.data();
    label bad = -1;
    #pragma omp parallel for schedule(static) reduction(max: bad) if(n > minParallelLoop)
    for (label i = 0; i < n; ++i)
    {
        if (!(rho[i] > 0) || !std::isfinite(a[2*i]) || !std::isfinite(a[2*i + 1]))
        {
            bad = std::max(bad, i);
        }
    }
    if (bad >= 0)
    {
        std::ostringstream os;
        os  << "particle " << particles_.id()[bad] << " at ("
            << particles_.positions()[2*bad] << ' '
            << particles_.positions()[2*bad + 1] << ") has density "
            << rho[bad] << " and acceleration (" << a[2*bad] << ' '
            << a[2*bad + 1] << ')';
        failure_ = os.str();
        return false;
    }
    return true;
}


bool Foam::sphFluid::advance(const scalar dt)
{
    oldPosition_ = particles_.positions();
    oldVelocity_ = particles_.velocities();
    oldDensity_ = particles_.density();

    scalar* __restrict__ x = particles_.positions().data();
    scalar* __restrict__ v = particles_.velocities().data();
    const scalar* __restrict__ a = acceleration_.data();
    const scalar* __restrict__ h = particles_.smoothingLength().data();
    const scalar* __restrict__ gradC = gradC_.data();
    const scalar* __restrict__ divR = divR_.data();
    const scalar A = controls_.shifting;
    const scalar threshold = controls_.freeSurfaceThreshold;
    // The velocity spans dt^n = (dt^{n-1/2} + dt^{n+1/2})/2, from the
    // half step before to the half step after the accelerations' time;
    // implicit mass-proportional damping, as the element half
    const scalar span = 0.5*(previousDeltaT_ + dt);
    const scalar keep = 1/(1 + massDamping_*span), gain = span*keep;

    indexParticles();
    const label nFluid = label(fluidIndex_.size());
    const label* __restrict__ fluid = fluidIndex_.data();
    #pragma omp parallel for schedule(static) if(nFluid > minParallelParticles)
    for (label f = 0; f < nFluid; ++f)
    {
        const label i = fluid[f];
        scalar keepI = keep, gainI = gain;
        if (absorbing_.active())
        {
            absorbing_.dampingFactors
            (
                x[2*i], x[2*i + 1], massDamping_, span, keepI, gainI
            );
        }
        const scalar vx = keepI*v[2*i] + gainI*a[2*i];
        const scalar vy = keepI*v[2*i + 1] + gainI*a[2*i + 1];
        v[2*i] = vx;
        v[2*i + 1] = vy;

        // Particle shifting, tangential only at the free surface
        const scalar D = A*h[i]*std::sqrt(vx*vx + vy*vy)*dt;
        scalar sx = -D*gradC[2*i], sy = -D*gradC[2*i + 1];
        if (divR[i] < threshold)
        {
            tangentialShift(gradC[2*i], gradC[2*i + 1], sx, sy);
        }
        x[2*i] += dt*vx + sx;
        x[2*i + 1] += dt*vy + sy;
    }
    pendingDeltaT_ = dt;
    oldPreviousDeltaT_ = previousDeltaT_;
    previousDeltaT_ = dt;
    stepIdBegin_ = nextId_;
    return true;
}


Foam::scalar Foam::sphFluid::relax(const label iterations)
{
    const scalar kappa = kernel_->support();
    const scalar beta = controls_.relaxationCoefficient;
    const scalar threshold = controls_.freeSurfaceThreshold;
    const scalar cap = relaxationMaxShift;
    scalar largest = 0;
    // Binning the cells reorders nothing: the indices hold for every
    // iteration
    indexParticles();
    for (label it = 0; it < iterations; ++it)
    {
        cells_.update(particles_, kappa*particles_.maxSmoothingLength());
        // No step pending: the density pass keeps every density and only
        // measures grad C and div r at the current positions
        pendingDeltaT_ = 0;
        kernel_->visit([this](const auto& k) { densityPass(k); });

        scalar* __restrict__ x = particles_.positions().data();
        const scalar* __restrict__ h = particles_.smoothingLength().data();
        const scalar* __restrict__ gradC = gradC_.data();
        const scalar* __restrict__ divR = divR_.data();
        largest = 0;
        const label nFluid = label(fluidIndex_.size());
        const label* __restrict__ fluid = fluidIndex_.data();
        #pragma omp parallel for schedule(static) reduction(max: largest) if(nFluid > minParallelParticles)
        for (label f = 0; f < nFluid; ++f)
        {
            const label i = fluid[f];
            scalar sx, sy;
            largest = std::max
            (
                largest,
                relaxationShift
                (
                    gradC[2*i], gradC[2*i + 1], divR[i], h[i], beta,
                    threshold, cap, sx, sy
                )
            );
            x[2*i] += sx;
            x[2*i + 1] += sy;
        }
    }
    oldPosition_ = particles_.positions();
    return largest;
}


void Foam::sphFluid::relaxFresh(const label iterations)
{
    // The fluid particles appended since the last evaluation
    fresh_.clear();
    const label* __restrict__ id = particles_.id().data();
    for (const label i : fluidIndex_)
    {
        if (id[i] >= freshIdBegin_) fresh_.push_back(i);
    }
    if (fresh_.empty()) return;
    const scalar kappa = kernel_->support();
    scalar last = 0;
    for (label it = 0; it < iterations; ++it)
    {
        kernel_->visit([this, &last](const auto& k) { last = relaxFreshPass(k); });
        // A shift is at most relaxationMaxShift h: the cells, of side
        // kappa h_max, are binned again every rebinInterval iterations and
        // after the last (binning reorders nothing: the indices hold)
        if ((it + 1) % rebinInterval == 0 || it + 1 == iterations)
        {
            cells_.update(particles_, kappa*particles_.maxSmoothingLength());
        }
    }
    Info<< "    relaxation of the " << label(fresh_.size())
        << " particles made by conversion: " << iterations
        << " iterations, last shift at most " << last
        << " smoothing lengths" << nl;
}


void Foam::sphFluid::appendFluid(const particleSet& newParticles)
{
    const label n = newParticles.size();
    for (label k = 0; k < n; ++k)
    {
        const scalar* x = &newParticles.positions()[2*k];
        const scalar* v = &newParticles.velocities()[2*k];
        const label i = particles_.append
        (
            x[0], x[1], v[0], v[1], newParticles.density()[k],
            newParticles.pressure()[k], newParticles.mass()[k],
            newParticles.smoothingLength()[k], particleSet::kind::fluid,
            newParticles.level()[k]
        );
        particles_.id()[i] = nextId_++;
        oldPosition_.push_back(x[0]);
        oldPosition_.push_back(x[1]);
        oldVelocity_.push_back(v[0]);
        oldVelocity_.push_back(v[1]);
        oldDensity_.push_back(newParticles.density()[k]);
    }
    nFluid_ += n;
    resizeFields();
}


Foam::label Foam::sphFluid::removeParticles(const particleSet::kind kind)
{
    const std::vector<particleSet::kind>& pk = particles_.kinds();
    return removeIf([&](const label i) { return pk[i] == kind; });
}


template<class Predicate>
Foam::label Foam::sphFluid::removeIf(const Predicate& remove)
{
    const label nOld = particles_.size();
    std::vector<scalar>& px = particles_.positions();
    std::vector<scalar>& pv = particles_.velocities();
    std::vector<scalar>& prho = particles_.density();
    std::vector<scalar>& pp = particles_.pressure();
    std::vector<scalar>& pm = particles_.mass();
    std::vector<scalar>& ph = particles_.smoothingLength();
    std::vector<particleSet::kind>& pk = particles_.kinds();
    std::vector<unsigned char>& pl = particles_.level();
    std::vector<label>& pid = particles_.id();
    label k = 0;
    for (label i = 0; i < nOld; ++i)
    {
        // remove(i) reads particle i before anything overwrites it (k <= i)
        if (remove(i)) continue;
        if (k != i)
        {
            for (int c = 0; c < 2; ++c)
            {
                px[2*k + c] = px[2*i + c];
                pv[2*k + c] = pv[2*i + c];
                oldPosition_[2*k + c] = oldPosition_[2*i + c];
                oldVelocity_[2*k + c] = oldVelocity_[2*i + c];
            }
            prho[k] = prho[i];
            pp[k] = pp[i];
            pm[k] = pm[i];
            ph[k] = ph[i];
            pk[k] = pk[i];
            pl[k] = pl[i];
            pid[k] = pid[i];
            oldDensity_[k] = oldDensity_[i];
        }
        ++k;
    }
    particles_.resize(k);
    oldPosition_.resize(2*k);
    oldVelocity_.resize(2*k);
    oldDensity_.resize(k);
    return k;
}


Foam::label Foam::sphFluid::appendParticles
(
    const particleSet::kind kind,
    const label n,
    const scalar* x,
    const scalar* v,
    const scalar* m,
    const scalar* h
)
{
    const label first = particles_.size();
    particles_.resize(first + n);
    oldPosition_.resize(2*(first + n));
    oldVelocity_.resize(2*(first + n));
    oldDensity_.resize(first + n);
    for (label k = 0; k < n; ++k)
    {
        const label i = first + k;
        for (int c = 0; c < 2; ++c)
        {
            particles_.positions()[2*i + c] = x[2*k + c];
            particles_.velocities()[2*i + c] = v[2*k + c];
            oldPosition_[2*i + c] = x[2*k + c];
            oldVelocity_[2*i + c] = v[2*k + c];
        }
        particles_.mass()[i] = m[k];
        particles_.smoothingLength()[i] = h[k];
        particles_.kinds()[i] = kind;
        particles_.level()[i] = 0;
    }
    resizeFields();
    return first;
}


void Foam::sphFluid::setStructureParticles
(
    const label n,
    const scalar* x,
    const scalar* v,
    const scalar* a,
    const scalar* m,
    const scalar* h
)
{
    if (nStructure_ > 0) removeParticles(particleSet::kind::structure);
    nStructure_ = 0;

    const label first = appendParticles(particleSet::kind::structure, n, x, v, m, h);
    structureAcceleration_.assign(a, a + 2*n);
    structureParticleForce_.assign(2*n, 0);
    for (label k = 0; k < n; ++k)
    {
        const label i = first + k;
        // Pressure and density follow from the fluid in the wall pass
        particles_.density()[i] = rho0_;
        oldDensity_[i] = rho0_;
        particles_.pressure()[i] = 0;
        particles_.id()[i] = k;
    }
    nStructure_ = n;
}


void Foam::sphFluid::setGhosts
(
    const label n,
    const scalar* x,
    const scalar* v,
    const scalar* rho,
    const scalar* m,
    const scalar* h
)
{
    if (nGhost_ > 0) removeParticles(particleSet::kind::ghost);
    nGhost_ = 0;

    const label first = appendParticles(particleSet::kind::ghost, n, x, v, m, h);
    const scalar c2 = c_*c_;
    for (label g = 0; g < n; ++g)
    {
        const label i = first + g;
        particles_.density()[i] = rho[g];
        oldDensity_[i] = rho[g];
        // Eq. (7), as the element's pressure
        particles_.pressure()[i] = c2*(rho[g] - rho0_);
        particles_.id()[i] = g;
    }
    ghostParticleForce_.assign(2*n, 0);
    nGhost_ = n;
}


void Foam::sphFluid::setOldDensity(const std::vector<scalar>& rhoOld)
{
    oldDensity_ = rhoOld;
}


void Foam::sphFluid::evaluationOrder(std::vector<label>& order) const
{
    const label n = particles_.size();
    const std::vector<particleSet::kind>& kind = particles_.kinds();
    const auto keep = [&](const label i)
    {
        return
            kind[i] == particleSet::kind::fluid
         || kind[i] == particleSet::kind::wall
         || kind[i] == particleSet::kind::slipWall;
    };
    order.clear();
    if (label(lastSortOrder_.size()) != n)
    {
        for (label i = 0; i < n; ++i)
        {
            if (keep(i)) order.push_back(i);
        }
        return;
    }
    // The particle now at i was at lastSortOrder_[i] before the sort
    std::vector<label> before(n);
    for (label i = 0; i < n; ++i) before[lastSortOrder_[i]] = i;
    for (const label i : before)
    {
        if (keep(i)) order.push_back(i);
    }
}


void Foam::sphFluid::restoreOrder
(
    const std::vector<label>& newToOld,
    const label stepsSinceReorder
)
{
    const label n = particles_.size();
    std::vector<label> order(newToOld);
    std::vector<bool> placed(n, false);
    for (const label i : newToOld) placed[i] = true;
    for (label i = 0; i < n; ++i)
    {
        if (!placed[i]) order.push_back(i);
    }
    particles_.reorder(order);
    particles_.reorderField(order, 2, oldPosition_);
    particles_.reorderField(order, 2, oldVelocity_);
    particles_.reorderField(order, 1, oldDensity_);
    // evaluate() counts this step before it decides to sort: one less,
    // and a sort there (0) is the step before reorderInterval
    stepsSinceReorder_ =
        stepsSinceReorder > 0 ? stepsSinceReorder - 1 : reorderInterval - 1;
}


void Foam::sphFluid::revert()
{
    particles_.positions() = oldPosition_;
    particles_.velocities() = oldVelocity_;
    particles_.density() = oldDensity_;
    pendingDeltaT_ = 0;
    previousDeltaT_ = oldPreviousDeltaT_;

    // The fluid particles appended since the advance (elements converted
    // in the failed step) were not there before it. Their ids, given in
    // order, find them wherever the sort by cell has put them
    if (nextId_ > stepIdBegin_)
    {
        const std::vector<particleSet::kind>& pk = particles_.kinds();
        const std::vector<label>& pid = particles_.id();
        const label first = stepIdBegin_;
        const label nBefore = particles_.size();
        const label n = removeIf
        (
            [&](const label i)
            {
                return pk[i] == particleSet::kind::fluid && pid[i] >= first;
            }
        );
        nFluid_ -= nBefore - n;
        nextId_ = stepIdBegin_;
        // The per-particle results are those of no evaluation now
        resizeFields();
        lastSortOrder_.clear();
    }
    freshIdBegin_ = nextId_;
}


void Foam::sphFluid::momentum(scalar& px, scalar& py) const
{
    px = 0;
    py = 0;
    const label n = particles_.size();
    for (label i = 0; i < n; ++i)
    {
        if (particles_.kinds()[i] != particleSet::kind::fluid) continue;
        px += particles_.mass()[i]*particles_.velocities()[2*i];
        py += particles_.mass()[i]*particles_.velocities()[2*i + 1];
    }
}


Foam::scalar Foam::sphFluid::kineticEnergy() const
{
    scalar e = 0;
    const label n = particles_.size();
    for (label i = 0; i < n; ++i)
    {
        if (particles_.kinds()[i] != particleSet::kind::fluid) continue;
        const scalar* v = &particles_.velocities()[2*i];
        e += 0.5*particles_.mass()[i]*(v[0]*v[0] + v[1]*v[1]);
    }
    return e;
}


bool Foam::sphFluid::interpolatePressure
(
    const scalar x,
    const scalar y,
    scalar& p
) const
{
    const particleSet& ps = particles_;
    return kernel_->visit
    (
        [&](const auto& k)
        {
            using Kernel = std::decay_t<decltype(k)>;
            scalar sumW = 0, sumP = 0;
            cells_.forEachParticleNear
            (
                ps, x, y, Kernel::support,
                [&](const label j, const scalar, const scalar, const scalar r)
                {
                    if (ps.kinds()[j] == particleSet::kind::ghost) return;
                    const scalar WV =
                        Kernel::W(r, ps.smoothingLength()[j])
                       *ps.mass()[j]/ps.density()[j];
                    sumW += WV;
                    sumP += ps.pressure()[j]*WV;
                }
            );
            if (!(sumW > 0)) return false;
            p = sumP/sumW;
            return true;
        }
    );
}


std::size_t Foam::sphFluid::memoryBytes() const
{
    auto bytes = [](const auto& f)
    {
        return f.capacity()*sizeof(f[0]);
    };
    return
        particles_.memoryBytes() + cells_.memoryBytes()
      + bytes(acceleration_) + bytes(correction_) + bytes(gradC_)
      + bytes(divR_) + bytes(oldPosition_) + bytes(oldVelocity_)
      + bytes(oldDensity_) + bytes(pairCount_) + bytes(pairNeighbour_)
      + bytes(pairF_) + bytes(volume_) + bytes(pOverRho2_)
      + bytes(fluidCells_);
}


// ************************************************************************* //
