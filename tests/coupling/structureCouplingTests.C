/*---------------------------------------------------------------------------*\
Description
    Unit tests of the fluid particle - structure coupling (paper eq. 27,
    structureParticleCoupling): where the virtual particles go, that they
    move with the solid, and that the structure gets exactly the opposite
    of the force the fluid gets.

    Scene: a plate 1 m x 0.2 m (10 x 2 cells) under a water layer 1 m x
    0.4 m (10 x 4 cells) whose elements all become particles.

\*---------------------------------------------------------------------------*/

#include "structureParticleCoupling.H"
#include "elementToParticle.H"
#include "elementModel.H"
#include "sphFluid.H"
#include "particleSet.H"
#include "IStringStream.H"
#include "testMeshes.H"
#include "testModels.H"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

namespace
{

using Foam::label;
using Foam::scalar;

const char* water = "model weaklyCompressibleNewtonian; rho 1000; c 20; mu 1e-3;";
const char* plate = "model linearElastic; rho 2700; E 1e9; nu 0.3;";

//- The plate under the water, as elements
struct scene
{
    Foam::triMesh mesh;
    std::unique_ptr<Foam::elementModel> elements;
    Foam::List<Foam::patchType> patchTypes;
    scalar spacing;

    scene()
    :
        mesh
        (
            testMeshes::build
            (
                {
                    {0, 1, 0, 0.2, 10, 2, "plate"},
                    {0, 1, 0.2, 0.6, 10, 4, "water"}
                }
            )
        ),
        elements(testModels::model(mesh, {{"water", water}, {"plate", plate}})),
        patchTypes(testModels::patchTypes(mesh, {})),
        spacing(std::sqrt(0.005))     // sqrt of a water triangle's area
    {}

    std::vector<label> waterTriangles() const
    {
        const label water = mesh.findRegion("water");
        std::vector<label> tris;
        for (label t = 0; t < mesh.nTriangles(); ++t)
        {
            if (mesh.triangleRegion()[t] == water) tris.push_back(t);
        }
        return tris;
    }
};

//- The coupling's virtual particles as the structure particles of fluid
void setStructureParticles
(
    Foam::structureParticleCoupling& coupling,
    const Foam::elementModel& elements,
    Foam::sphFluid& fluid
)
{
    std::vector<scalar> x, v, a, m, h;
    coupling.appendParticles(elements, 0, x, v, a, m, h);
    fluid.setStructureParticles
    (
        label(m.size()), x.data(), v.data(), a.data(), m.data(), h.data()
    );
}

} // End anonymous namespace


TEST(StructureParticleCoupling, virtualParticlesFillTheSolidBehindItsFacesAndNoMore)
{
    scene s;
    const label nLayers = 3;
    const Foam::structureParticleCoupling coupling
    (
        s.mesh, *s.elements, s.patchTypes, s.spacing, nLayers, 1000,
        1.3*s.spacing
    );
    ASSERT_GT(coupling.size(), 0);

    // Reference positions from the barycentric weights
    const std::vector<scalar>& X = s.mesh.points();
    std::vector<scalar> x(2*coupling.size());
    const label plateRegion = s.mesh.findRegion("plate");
    for (label k = 0; k < coupling.size(); ++k)
    {
        const label t = coupling.triangle(k);
        EXPECT_EQ(s.mesh.triangleRegion()[t], plateRegion) << k;
        const scalar* w = coupling.weights(k);
        EXPECT_NEAR(w[0] + w[1] + w[2], 1, 1e-12);
        for (label a = 0; a < 3; ++a)
        {
            EXPECT_GE(w[a], -1e-12);
            const label n = s.mesh.triangles()[3*t + a];
            x[2*k] += w[a]*X[2*n];
            x[2*k + 1] += w[a]*X[2*n + 1];
        }
        // Inside the plate
        EXPECT_GT(x[2*k], 0);
        EXPECT_LT(x[2*k], 1);
        EXPECT_GT(x[2*k + 1], 0);
        EXPECT_LT(x[2*k + 1], 0.2);
    }

    // No two closer than half the spacing
    scalar closest = 1;
    for (label k = 0; k < coupling.size(); ++k)
    {
        for (label l = k + 1; l < coupling.size(); ++l)
        {
            closest = std::min
            (
                closest,
                std::hypot(x[2*k] - x[2*l], x[2*k + 1] - x[2*l + 1])
            );
        }
    }
    EXPECT_GE(closest, 0.5*s.spacing - 1e-12);

    // Every point of the plate within nLayers spacings of its top (the
    // face under the water) has a virtual particle within 0.75 spacing
    scalar worst = 0;
    for (scalar px = 0.005; px < 1; px += 0.01)
    {
        for (scalar py = 0.2 - 0.005; py > 0.2 - std::min(0.2, nLayers*s.spacing); py -= 0.01)
        {
            scalar nearest = 1;
            for (label k = 0; k < coupling.size(); ++k)
            {
                nearest = std::min
                (
                    nearest, std::hypot(x[2*k] - px, x[2*k + 1] - py)
                );
            }
            worst = std::max(worst, nearest);
        }
    }
    std::cout << coupling.size() << " virtual particles, spacing "
        << s.spacing << ", closest pair " << closest
        << ", farthest point of the covered band from one " << worst
        << std::endl;
    EXPECT_LT(worst, 0.75*s.spacing);
}


TEST(StructureParticleCoupling, thinPlateOverAnOpenFaceGetsEveryLayerBehindIt)
{
    // A plate 0.04 m thick (one cell) under the water, its underside open
    // (a free-surface patch): the layers at 0.5, 1.5 and 2.5 spacings
    // (0.071 m) behind its top face reach 0.18 m below it. Those outside
    // the plate stay tied to the element of their face, so that the
    // particles above the plate see a full support of wall (a single
    // layer let the column of method SPH sink into the plate's support:
    // 35 % of its weight on hydrostaticElasticPlate at nx 20)
    const scalar thickness = 0.04;
    const Foam::triMesh mesh = testMeshes::build
    (
        {
            {0, 1, 0, thickness, 10, 1, "plate"},
            {0, 1, thickness, thickness + 0.4, 10, 4, "water"}
        }
    );
    const auto elements =
        testModels::model(mesh, {{"water", water}, {"plate", plate}});
    const scalar spacing = std::sqrt(0.005);
    const label nLayers = 3;
    const label plateRegion = mesh.findRegion("plate");
    const std::vector<scalar>& X = mesh.points();

    // Reference position of virtual particle k from its element's nodes
    // at (x, y) = (c X - s Y + tx, s X + c Y + ty)
    auto position = [&]
    (
        const Foam::structureParticleCoupling& coupling,
        const label k,
        const scalar c,
        const scalar sn,
        scalar& px,
        scalar& py
    )
    {
        const label t = coupling.triangle(k);
        const scalar* w = coupling.weights(k);
        px = 0;
        py = 0;
        for (label a = 0; a < 3; ++a)
        {
            const label n = mesh.triangles()[3*t + a];
            px += w[a]*(c*X[2*n] - sn*X[2*n + 1] + 0.1);
            py += w[a]*(sn*X[2*n] + c*X[2*n + 1] - 0.2);
        }
    };

    const Foam::structureParticleCoupling open
    (
        mesh, *elements, testModels::patchTypes(mesh, {}), spacing, nLayers,
        1000, 1.3*spacing
    );
    std::vector<scalar> x(2*open.size());
    label below = 0;
    for (label k = 0; k < open.size(); ++k)
    {
        EXPECT_EQ(mesh.triangleRegion()[open.triangle(k)], plateRegion) << k;
        const scalar* w = open.weights(k);
        EXPECT_NEAR(w[0] + w[1] + w[2], 1, 1e-12);
        position(open, k, 1, 0, x[2*k], x[2*k + 1]);
        x[2*k] -= 0.1;
        x[2*k + 1] += 0.2;
        // Never in the water
        EXPECT_LT(x[2*k + 1], thickness) << k;
        if (x[2*k + 1] < 0) ++below;
    }
    EXPECT_GT(below, 0) << "no layer behind the plate";

    // Every point of the band of nLayers spacings below the top face
    // (away from the plate's ends) within 0.75 spacing of one
    scalar worst = 0;
    for (scalar px = 0.1; px < 0.9; px += 0.01)
    {
        for (scalar py = thickness - 0.005; py > thickness - nLayers*spacing; py -= 0.01)
        {
            scalar nearest = 1;
            for (label k = 0; k < open.size(); ++k)
            {
                nearest = std::min
                (
                    nearest, std::hypot(x[2*k] - px, x[2*k + 1] - py)
                );
            }
            worst = std::max(worst, nearest);
        }
    }
    std::cout << open.size() << " virtual particles, " << below
        << " below the plate; farthest point of the band from one "
        << worst << std::endl;
    EXPECT_LT(worst, 0.75*spacing);

    // They move with the plate: a rigid rotation by 30 deg and a
    // translation, extrapolated exactly
    {
        const scalar c = std::cos(M_PI/6), sn = std::sin(M_PI/6);
        std::vector<scalar> nodes(X.size()), v(X.size(), 0);
        for (size_t n = 0; n < X.size()/2; ++n)
        {
            nodes[2*n] = c*X[2*n] - sn*X[2*n + 1] + 0.1;
            nodes[2*n + 1] = sn*X[2*n] + c*X[2*n + 1] - 0.2;
        }
        auto moved =
            testModels::model(mesh, {{"water", water}, {"plate", plate}});
        moved->setState(nodes, v);
        Foam::structureParticleCoupling coupling
        (
            mesh, *elements, testModels::patchTypes(mesh, {}), spacing,
            nLayers, 1000, 1.3*spacing
        );
        std::vector<scalar> px, pv, pa, pm, ph;
        coupling.appendParticles(*moved, 0, px, pv, pa, pm, ph);
        scalar worstX = 0;
        for (label k = 0; k < coupling.size(); ++k)
        {
            scalar rx, ry;
            position(coupling, k, c, sn, rx, ry);
            worstX = std::max
            (
                worstX, std::hypot(px[2*k] - rx, px[2*k + 1] - ry)
            );
        }
        EXPECT_LT(worstX, 1e-13);
    }

    // Under a wall, whose own dummy particles stand behind it: none
    // outside the plate
    const Foam::structureParticleCoupling onWall
    (
        mesh, *elements,
        testModels::patchTypes
        (
            mesh, {{"bottom", Foam::patchType::noSlipWall}}
        ),
        spacing, nLayers, 1000, 1.3*spacing
    );
    ASSERT_GT(onWall.size(), 0);
    for (label k = 0; k < onWall.size(); ++k)
    {
        scalar px, py;
        position(onWall, k, 1, 0, px, py);
        EXPECT_GE(py + 0.2, -1e-12) << k;
    }
}


TEST(WallAcceleration, lowPassKeepsASteadyAccelerationAndDropsStepToStepNoise)
{
    // A wall accelerating at a0 whose velocity also flips by +-eps from
    // step to step (the lagged structure-fluid loop): unsmoothed, the
    // acceleration given out swings by 2 eps/dt about a0 on alternate
    // steps; low-passed over tau = 100 dt, by at most 2 eps/dt x dt/tau
    // in the steady state, and a0 is kept
    const scalar dt = 1e-5, a0 = -3, eps = 1e-4, tau = 100*dt;
    Foam::wallAcceleration raw, smooth;
    raw.resize(1);
    smooth.resize(1);
    smooth.setSmoothingTime(tau);
    scalar swingRaw = 0, swingSmooth = 0, meanSmooth = 0;
    const label nSteps = 4000, nLast = 1000;
    for (label n = 0; n < nSteps; ++n)
    {
        const scalar v = a0*n*dt + (n % 2 ? eps : -eps);
        scalar ax, ay, sx, sy;
        raw.update(0, 0, v, n ? dt : 0, ax, ay);
        raw.endUpdate();
        smooth.update(0, 0, v, n ? dt : 0, sx, sy);
        smooth.endUpdate();
        if (n >= nSteps - nLast)
        {
            swingRaw = std::max(swingRaw, std::abs(ay - a0));
            swingSmooth = std::max(swingSmooth, std::abs(sy - a0));
            meanSmooth += sy/nLast;
        }
    }
    std::cout << "swing about a0: raw " << swingRaw << ", low-passed "
        << swingSmooth << " m/s2; low-passed mean " << meanSmooth
        << std::endl;
    EXPECT_NEAR(swingRaw, 2*eps/dt, 1e-6*eps/dt);
    EXPECT_LT(swingSmooth, 2*eps/dt*dt/tau*1.01);
    EXPECT_NEAR(meanSmooth, a0, 1e-3*std::abs(a0));
}


TEST(StructureParticleCoupling, virtualParticlesMoveWithTheSolid)
{
    scene s;
    Foam::structureParticleCoupling coupling
    (
        s.mesh, *s.elements, s.patchTypes, s.spacing, 3, 1000, 1.3*s.spacing
    );

    // A rigid rotation by 30 deg about the origin with a rotation rate:
    // each virtual particle keeps its place in the solid
    const scalar c = std::cos(M_PI/6), sn = std::sin(M_PI/6), omega = 2;
    const std::vector<scalar>& X = s.mesh.points();
    std::vector<scalar> x(X.size()), v(X.size());
    for (size_t n = 0; n < X.size()/2; ++n)
    {
        x[2*n] = c*X[2*n] - sn*X[2*n + 1];
        x[2*n + 1] = sn*X[2*n] + c*X[2*n + 1];
        v[2*n] = -omega*x[2*n + 1];
        v[2*n + 1] = omega*x[2*n];
    }
    s.elements->setState(x, v);

    Foam::particleSet ps;
    Foam::convertElements(s.mesh, s.waterTriangles(), 1.3, *s.elements, ps);
    const scalar lo[2] = {-2, -2}, hi[2] = {3, 3};
    Foam::IStringStream is("sph {}");
    Foam::sphFluid fluid(Foam::dictionary(is), std::move(ps), 1000, 20, 1e-3, 0, 0, lo, hi);
    setStructureParticles(coupling, *s.elements, fluid);
    ASSERT_EQ(fluid.nStructure(), coupling.size());

    const Foam::particleSet& all = fluid.particles();
    scalar worstX = 0, worstV = 0;
    for (label i = 0; i < all.size(); ++i)
    {
        if (all.kinds()[i] != Foam::particleSet::kind::structure) continue;
        const label k = all.id()[i];
        const label t = coupling.triangle(k);
        const scalar* w = coupling.weights(k);
        scalar Xk = 0, Yk = 0;
        for (label a = 0; a < 3; ++a)
        {
            const label n = s.mesh.triangles()[3*t + a];
            Xk += w[a]*X[2*n];
            Yk += w[a]*X[2*n + 1];
        }
        const scalar xk = c*Xk - sn*Yk, yk = sn*Xk + c*Yk;
        worstX = std::max
        (
            worstX,
            std::hypot(all.positions()[2*i] - xk, all.positions()[2*i + 1] - yk)
        );
        worstV = std::max
        (
            worstV,
            std::hypot
            (
                all.velocities()[2*i] + omega*yk,
                all.velocities()[2*i + 1] - omega*xk
            )
        );
    }
    EXPECT_LT(worstX, 1e-14);
    EXPECT_LT(worstV, 1e-13);
}


TEST(StructureParticleCoupling, structureGetsTheOppositeOfTheFluidForceToRoundOff)
{
    scene s;
    Foam::structureParticleCoupling coupling
    (
        s.mesh, *s.elements, s.patchTypes, s.spacing, 3, 1000, 1.3*s.spacing
    );

    // The water as particles, compressed by 1 % (p = c^2 10 = 4000 Pa) and
    // moving, so that both the pressure and the viscous terms act
    Foam::particleSet ps;
    Foam::convertElements(s.mesh, s.waterTriangles(), 1.3, *s.elements, ps);
    for (label i = 0; i < ps.size(); ++i)
    {
        ps.density()[i] = 1010;
        ps.velocities()[2*i] = 0.3 + 0.1*std::sin(7.0*i);
        ps.velocities()[2*i + 1] = -0.2;
    }
    const scalar lo[2] = {-2, -2}, hi[2] = {3, 3};
    Foam::IStringStream is("sph {}");
    Foam::sphFluid fluid
    (
        Foam::dictionary(is), std::move(ps), 1000, 20, 1e-3, 0, -9.81, lo, hi
    );

    setStructureParticles(coupling, *s.elements, fluid);
    ASSERT_TRUE(fluid.evaluate());
    std::vector<scalar>& f = s.elements->externalForce();
    std::fill(f.begin(), f.end(), 0);
    coupling.applyForces(*s.elements, fluid.structureParticleForce().data());

    // On the solid nodes, summed
    long double Fx = 0, Fy = 0;
    for (size_t n = 0; n < f.size()/2; ++n)
    {
        Fx += f[2*n];
        Fy += f[2*n + 1];
    }
    // On the fluid: minus the fluid's force on the structure, summed over
    // the fluid particles in the momentum pass
    const scalar* fluidSide = fluid.structureForce();
    const scalar scale = std::hypot(fluidSide[0], fluidSide[1]);
    std::cout << "force on the plate: nodes (" << double(Fx) << ' '
        << double(Fy) << "), from the fluid's side (" << fluidSide[0] << ' '
        << fluidSide[1] << ") N/m; difference " << double(Fx - fluidSide[0])
        << ' ' << double(Fy - fluidSide[1]) << std::endl;

    // The water presses the plate down with about p L = 4000 N/m, plus
    // the weight the virtual particles' pressure extrapolation adds (Adami:
    // rho g over the 0.1 m to the particles) and kernel truncation at the
    // plate's ends. Before the layers were placed layer by layer and
    // weighed by their volume this was 5813 N/m.
    EXPECT_LT(fluidSide[1], -0.8*4000);
    EXPECT_GT(fluidSide[1], -1.25*4000);
    EXPECT_LT(std::abs(double(Fx) - fluidSide[0]), 1e-12*scale);
    EXPECT_LT(std::abs(double(Fy) - fluidSide[1]), 1e-12*scale);
    EXPECT_NEAR(coupling.force()[0], fluidSide[0], 1e-12*scale);
    EXPECT_NEAR(coupling.force()[1], fluidSide[1], 1e-12*scale);
}


// ************************************************************************* //
