#include "bodyParticleCoupling.H"
#include "sphFluid.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::bodyParticleCoupling::bodyParticleCoupling
(
    const rigidBodies& bodies,
    const scalar spacing,
    const label nLayers,
    const scalar rho0,
    const scalar smoothingLength
)
:
    mass_(rho0*spacing*spacing),
    smoothingLength_(smoothingLength),
    force_(2*bodies.size(), 0),
    moment_(bodies.size(), 0)
{
    forAll(bodies, b)
    {
        const bodyWallParticles wall = bodies[b].wallParticles(spacing, nLayers);
        for (label k = 0; k < wall.size(); ++k)
        {
            body_.push_back(b);
            reference_.push_back(wall.positions[2*k]);
            reference_.push_back(wall.positions[2*k + 1]);
        }
    }
    acceleration_.resize(size());
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::bodyParticleCoupling::appendParticles
(
    const rigidBodies& bodies,
    const scalar dt,
    std::vector<scalar>& x,
    std::vector<scalar>& v,
    std::vector<scalar>& a,
    std::vector<scalar>& m,
    std::vector<scalar>& h
)
{
    for (label k = 0; k < size(); ++k)
    {
        const rigidBody& body = bodies[body_[k]];
        const vector2D X(reference_[2*k], reference_[2*k + 1]);
        const vector2D xk = body.toCurrent(X);
        const vector2D vk = body.velocityAt(xk.x(), xk.y());
        x.push_back(xk.x());
        x.push_back(xk.y());
        v.push_back(vk.x());
        v.push_back(vk.y());
        // The body's velocity is that of the last half step: the
        // acceleration of this material point over the last step
        scalar ax, ay;
        acceleration_.update(k, vk.x(), vk.y(), dt, ax, ay);
        a.push_back(ax);
        a.push_back(ay);
        m.push_back(mass_);
        h.push_back(smoothingLength_);
    }
    acceleration_.endUpdate();
}


void Foam::bodyParticleCoupling::applyForces
(
    const rigidBodies& bodies,
    const scalar* x,
    const scalar* F
)
{
    std::fill(force_.begin(), force_.end(), 0);
    std::fill(moment_.begin(), moment_.end(), 0);
    for (label k = 0; k < size(); ++k)
    {
        const label b = body_[k];
        const vector2D& c = bodies[b].position();
        force_[2*b] += F[2*k];
        force_[2*b + 1] += F[2*k + 1];
        // (x - c) x F, about the centre of mass
        moment_[b] +=
            (x[2*k] - c.x())*F[2*k + 1] - (x[2*k + 1] - c.y())*F[2*k];
    }
}


// * * * * * * * * * * * * * * * * * * Hooks * * * * * * * * * * * * * * * * //

void Foam::bodyParticleCoupling::beforeParticleEvaluate(couplingStep& s)
{
    structureParticles& p = s.structure;
    first_ = p.size();
    appendParticles(s.bodies, s.lastDeltaT, p.x, p.v, p.a, p.m, p.h);
}


void Foam::bodyParticleCoupling::afterParticleEvaluate(couplingStep& s)
{
    applyForces
    (
        s.bodies, s.structure.x.data() + 2*first_,
        s.particles->structureParticleForce().data() + 2*first_
    );
}


void Foam::bodyParticleCoupling::addBodyLoad
(
    const label b,
    scalar F[2],
    scalar& M
) const
{
    addLoad(force_, moment_, b, F, M);
}


// ************************************************************************* //
