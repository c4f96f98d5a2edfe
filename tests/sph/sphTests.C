/*---------------------------------------------------------------------------*\
Description
    Unit tests of the particle half (paper sect. 2.2), each on a handful to
    a few thousand particles with an exact answer:
      - the decoupled FPM gradient is exact for linear fields along each
        axis on an irregular particle set, FPM for every linear field, the
        uncorrected gradient for neither;
      - sphFluid's continuity equation reproduces drho/dt = -rho div v for
        a linear velocity field on irregular particles with FPM;
      - total momentum changes only by the impulse of gravity and the wall
        forces (internal forces cancel in pairs, also with the correction);
      - the symmetrised corrected momentum gradient carries a linear
        pressure exactly on a regular lattice, the kernel gradient not;
      - the initial relaxation opens the close pairs of converted
        barycentres and changes nothing but the fluid positions;
      - revert() after a step that appended particles gives back the
        particles before it;
      - wall particles fill layers and corners outside the mesh;
      - element -> particle conversion conserves mass and momentum and puts
        the particle at the barycentre (eqs. 17-18);
      - particles of two resolutions (a mesh with some elements split into
        three refined particles, eqs. 19-22, the others one particle each,
        so that h varies from particle to particle): the internal forces of
        sphFluid's passes sum to zero, its FPM continuity and the corrected
        gradient are exact for linear fields, and its stable step is the
        one of the finest particle.

\*---------------------------------------------------------------------------*/

#include "sphFluid.H"
#include "gradientCorrection.H"
#include "kernelFunctions.H"
#include "elementToParticle.H"
#include "wallParticles.H"
#include "dictionary.H"
#include "parallelLoop.H"
#include "IStringStream.H"
#include "testMeshes.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include <omp.h>

using namespace Foam;

namespace
{

//- Irregular particles: a lattice of spacing dx jittered by +-jitter dx,
//  in [0, n dx]^2, density 1000
particleSet irregularParticles
(
    const label n,
    const scalar dx,
    const scalar jitter,
    const unsigned seed
)
{
    std::mt19937 gen(seed);
    std::uniform_real_distribution<scalar> u(-jitter*dx, jitter*dx);
    particleSet ps;
    for (label j = 0; j < n; ++j)
    {
        for (label i = 0; i < n; ++i)
        {
            ps.append
            (
                (i + 0.5)*dx + u(gen), (j + 0.5)*dx + u(gen), 0, 0,
                1000, 0, 1000*dx*dx, 1.3*dx
            );
        }
    }
    return ps;
}


//- 3 layers of dummy wall particles (density 1000, smoothing length h)
//  at spacing ws round a tank open at the top whose bottom is y = 0 and
//  whose sides are x = 0 (leftWall) and x = width: nw + 6 per layer below,
//  nw up each side
void appendTankWalls
(
    particleSet& ps,
    const label nw,
    const scalar ws,
    const scalar width,
    const scalar h,
    const particleSet::kind leftWall = particleSet::kind::wall
)
{
    for (label layer = 0; layer < 3; ++layer)
    {
        const scalar off = (layer + 0.5)*ws;
        for (label k = -3; k < nw + 3; ++k)
        {
            const scalar s = (k + 0.5)*ws;
            ps.append(s, -off, 0, 0, 1000, 0, 1000*ws*ws, h,
                particleSet::kind::wall);
            if (k >= 0)
            {
                ps.append(-off, s, 0, 0, 1000, 0, 1000*ws*ws, h, leftWall);
                ps.append(width + off, s, 0, 0, 1000, 0, 1000*ws*ws, h,
                    particleSet::kind::wall);
            }
        }
    }
}

//- irregularParticles(n, dx, 0.1, positionSeed) with random velocities of
//  up to 0.5 m/s per component (velocitySeed), on 3 layers of dummy wall
//  particles at spacing dx: no-slip below and right, leftWall on the left
particleSet waterBlockInWalls
(
    const label n,
    const scalar dx,
    const unsigned positionSeed,
    const unsigned velocitySeed,
    const particleSet::kind leftWall
)
{
    particleSet ps = irregularParticles(n, dx, 0.1, positionSeed);
    std::mt19937 gen(velocitySeed);
    std::uniform_real_distribution<scalar> u(-0.5, 0.5);
    for (scalar& v : ps.velocities()) v = u(gen);
    appendTankWalls(ps, n, dx, n*dx, 1.3*dx, leftWall);
    return ps;
}

//- Corrected SPH gradient of f at particle i (brute force neighbours):
//  sum_j (f_j - f_i) C_i grad_i W_ij V_j
template<class Field>
void correctedGradient
(
    const particleSet& ps,
    const label i,
    const gradientCorrectionType type,
    Field&& f,
    scalar grad[2]
)
{
    using K = sphKernels::WendlandC2;
    const scalar* x = ps.positions().data();
    scalar M[3] = {0, 0, 0}, G[2] = {0, 0};
    for (label j = 0; j < ps.size(); ++j)
    {
        const scalar dx = x[2*i] - x[2*j], dy = x[2*i + 1] - x[2*j + 1];
        const scalar r = std::hypot(dx, dy);
        const scalar h = 0.5*(ps.smoothingLength()[i] + ps.smoothingLength()[j]);
        if (j == i || r >= K::support*h) continue;
        const scalar F = K::F(r, h);
        const scalar V = ps.mass()[j]/ps.density()[j];
        M[0] -= dx*dx*F*V;
        M[1] -= dx*dy*F*V;
        M[2] -= dy*dy*F*V;
        const scalar df = f(x[2*j], x[2*j + 1]) - f(x[2*i], x[2*i + 1]);
        G[0] += df*dx*F*V;
        G[1] += df*dy*F*V;
    }
    scalar C[3];
    gradientCorrectionMatrix(type, false, M[0], M[1], M[2], C);
    grad[0] = C[0]*G[0] + C[1]*G[1];
    grad[1] = C[1]*G[0] + C[2]*G[1];
}


//- Particles of two resolutions on [0, 1]^2: the elements of a perturbed
//  n x n mesh (density 1000) become one particle each, or, with
//  probability refinedShare, three refined particles of radius 1/sqrt(3)
//  R_M (eqs. 19-22). The smoothing length (1.3 times the spacing) thus
//  differs from particle to particle, by the element's area and by 1.7
//  between the levels.
particleSet mixedResolutionParticles
(
    const label n,
    const scalar refinedShare,
    const unsigned seed
)
{
    const triMesh mesh = testMeshes::perturbed
    (
        testMeshes::build({{0, 1, 0, 1, n, n, "water"}}), 0.2, 1.0/n, seed
    );
    const std::vector<scalar>& x = mesh.points();
    const std::vector<scalar> v(x.size(), 0);
    const label nT = mesh.nTriangles();
    std::vector<scalar> m(nT);
    std::vector<label> coarse, refined;
    std::mt19937 gen(seed);
    std::uniform_real_distribution<scalar> u(0, 1);
    for (label t = 0; t < nT; ++t)
    {
        m[t] = 1000*mesh.triangleArea(t);
        (u(gen) < refinedShare ? refined : coarse).push_back(t);
    }
    particleSet ps;
    appendParticlesFromElements(x, v, mesh.triangles(), m, coarse, 1.3, ps);
    appendParticlesFromElements
    (
        x, v, mesh.triangles(), m, refined, 1.3, ps, 1/std::sqrt(3.0)
    );
    return ps;
}


//- Smallest and largest smoothing length
void smoothingLengthRange(const particleSet& ps, scalar& hMin, scalar& hMax)
{
    const std::vector<scalar>& h = ps.smoothingLength();
    hMin = *std::min_element(h.begin(), h.end());
    hMax = *std::max_element(h.begin(), h.end());
}


//- Empty system/spemSchemes plus an sph sub-dictionary
dictionary schemes(const std::string& sphEntries)
{
    IStringStream is("sph { " + sphEntries + " }");
    return dictionary(is);
}

//- The linear velocity v = (a x + b y, c x + d y) of the continuity tests
//  (div v = a + d)
const scalar linearA = 0.3, linearB = 0.2, linearC = -0.1, linearD = 0.5;

void setLinearVelocity(particleSet& ps)
{
    for (label i = 0; i < ps.size(); ++i)
    {
        const scalar* p = &ps.positions()[2*i];
        ps.velocities()[2*i] = linearA*p[0] + linearB*p[1];
        ps.velocities()[2*i + 1] = linearC*p[0] + linearD*p[1];
    }
}

//- sphFluid's density rate against drho/dt = -rho0 div v for the linear
//  velocity, with gradientCorrection corr and no diffusion, shifting,
//  viscosity or gravity (the continuity equation alone), after one step
//  of 1e-9 s: the worst relative error over the particles at least margin
//  inside [0, side]^2, and their number. lo, hi: the lost-particle box
scalar worstContinuityError
(
    const particleSet& ps,
    const word& corr,
    const scalar side,
    const scalar margin,
    const scalar lo[2],
    const scalar hi[2],
    label& nChecked
)
{
    sphFluid fluid
    (
        schemes
        (
            "gradientCorrection " + corr + "; densityDiffusion 0;"
            " shifting 0;"
        ),
        particleSet(ps), 1000, 10, 0, 0, 0, lo, hi
    );
    EXPECT_TRUE(fluid.evaluate());
    const scalar dt = 1e-9;
    fluid.advance(dt);
    EXPECT_TRUE(fluid.evaluate());

    scalar worst = 0;
    nChecked = 0;
    const particleSet& q = fluid.particles();
    for (label i = 0; i < q.size(); ++i)
    {
        const scalar* p = &q.positions()[2*i];
        if (std::min({p[0], p[1], side - p[0], side - p[1]}) < margin) continue;
        ++nChecked;
        const scalar rate = (q.density()[i] - 1000)/dt;
        worst = std::max
        (
            worst, std::abs(rate/(-1000*(linearA + linearD)) - 1)
        );
    }
    return worst;
}

} // End anonymous namespace


// * * * * * * * * * * * * * * Gradient correction * * * * * * * * * * * * * //

TEST(GradientCorrection, decoupledFPMExactAlongEachAxisFPMForAnyLinearField)
{
    const scalar dx = 0.01;
    const particleSet ps = irregularParticles(12, dx, 0.25, 7);

    const scalar a = 3, b = -2;
    auto fx = [&](scalar x, scalar) { return a*x; };
    auto fy = [&](scalar, scalar y) { return b*y; };
    auto fxy = [&](scalar x, scalar y) { return a*x + b*y; };

    // Interior particles: full support
    scalar worstNone = 0, worstDecoupledOblique = 0;
    label nChecked = 0;
    for (label i = 0; i < ps.size(); ++i)
    {
        const scalar* p = &ps.positions()[2*i];
        if (std::min({p[0], p[1], 12*dx - p[0], 12*dx - p[1]}) < 3*dx) continue;
        ++nChecked;

        scalar g[2];
        correctedGradient(ps, i, gradientCorrectionType::decoupledFPM, fx, g);
        EXPECT_NEAR(g[0], a, 1e-10);
        correctedGradient(ps, i, gradientCorrectionType::decoupledFPM, fy, g);
        EXPECT_NEAR(g[1], b, 1e-10);

        correctedGradient(ps, i, gradientCorrectionType::FPM, fxy, g);
        EXPECT_NEAR(g[0], a, 1e-10);
        EXPECT_NEAR(g[1], b, 1e-10);

        // Oblique field: decoupled FPM keeps the off-diagonal moment error
        correctedGradient(ps, i, gradientCorrectionType::decoupledFPM, fxy, g);
        worstDecoupledOblique =
            std::max(worstDecoupledOblique, std::abs(g[0] - a) + std::abs(g[1] - b));

        correctedGradient(ps, i, gradientCorrectionType::none, fx, g);
        worstNone = std::max(worstNone, std::abs(g[0] - a));
    }
    ASSERT_GT(nChecked, 20);

    // The uncorrected gradient is not exact on irregular particles (and
    // the decoupled one not for an oblique field): the tests above would
    // catch a correction that does nothing
    std::cout << "worst error |grad f - a|/|a|: uncorrected "
              << worstNone/a << ", decoupled FPM on a x + b y "
              << worstDecoupledOblique/a << std::endl;
    EXPECT_GT(worstNone/a, 1e-3);
    EXPECT_GT(worstDecoupledOblique/a, 1e-4);
}


TEST(GradientCorrection, truncatedSupportKeepsTheUncorrectedGradient)
{
    scalar C[3];
    gradientCorrectionMatrix(gradientCorrectionType::FPM, true, 0.5, 0.1, 0.7, C);
    EXPECT_EQ(C[0], 1);
    EXPECT_EQ(C[1], 0);
    EXPECT_EQ(C[2], 1);
    gradientCorrectionMatrix(gradientCorrectionType::decoupledFPM, false, 0.5, 0.1, 0.8, C);
    EXPECT_DOUBLE_EQ(C[0], 2);
    EXPECT_EQ(C[1], 0);
    EXPECT_DOUBLE_EQ(C[2], 1.25);
}


// * * * * * * * * * * * * * * * * sphFluid * * * * * * * * * * * * * * * * //

TEST(SphFluid, continuityWithFPMIsExactForLinearVelocityOnIrregularParticles)
{
    const scalar dx = 0.01;
    const label n = 16;
    particleSet ps = irregularParticles(n, dx, 0.25, 3);
    setLinearVelocity(ps);
    const scalar lo[2] = {-1, -1}, hi[2] = {1, 1};

    for (const word corr : {"FPM", "none"})
    {
        label nChecked = 0;
        const scalar worst =
            worstContinuityError(ps, corr, n*dx, 3*dx, lo, hi, nChecked);
        if (::testing::Test::HasFailure()) return;
        ASSERT_GT(nChecked, 50);
        std::cout << corr << ": worst relative error of drho/dt "
                  << worst << std::endl;
        if (corr == "FPM")
        {
            // O(dt) from the positions moved by the step
            EXPECT_LT(worst, 1e-5);
        }
        else
        {
            EXPECT_GT(worst, 1e-3);
        }
    }
}


TEST(SphFluid, momentumChangesOnlyByGravityAndWallImpulse)
{
    // A water block with random velocities in a box of no-slip and
    // free-slip dummy walls, decoupled FPM on (non-symmetric corrections)
    const scalar dx = 0.01;
    const label n = 20;
    particleSet ps =
        waterBlockInWalls(n, dx, 11, 5, particleSet::kind::slipWall);
    const scalar lo[2] = {-1, -1}, hi[2] = {2, 2};
    const scalar g = -9.81;
    sphFluid fluid(schemes(""), std::move(ps), 1000, 20, 1e-3, 0, g, lo, hi);
    ASSERT_TRUE(fluid.evaluate());
    scalar mass = 0;
    for (label i = 0; i < fluid.particles().size(); ++i)
    {
        if (fluid.particles().kinds()[i] == particleSet::kind::fluid)
        {
            mass += fluid.particles().mass()[i];
        }
    }

    scalar worst = 0, impulse = 0;
    for (int step = 0; step < 200; ++step)
    {
        const scalar dt = 0.9*fluid.stableDeltaT();
        // The velocity update spans half the last step and half this one
        const scalar span = 0.5*(fluid.previousDeltaT() + dt);
        const scalar fx = fluid.wallForce()[0], fy = fluid.wallForce()[1];
        scalar p0x, p0y, p1x, p1y;
        fluid.momentum(p0x, p0y);
        fluid.advance(dt);
        fluid.momentum(p1x, p1y);
        ASSERT_TRUE(fluid.evaluate()) << fluid.failure();

        // dP = span (M g - force on the walls)
        const scalar ex = p1x - p0x - span*(-fx);
        const scalar ey = p1y - p0y - span*(mass*g - fy);
        worst = std::max(worst, std::hypot(ex, ey));
        impulse = std::max(impulse, span*std::hypot(fx, fy));
    }
    std::cout << "worst momentum imbalance per step " << worst
              << " kg m/s; largest wall impulse per step " << impulse
              << std::endl;
    ASSERT_GT(impulse, 0);
    EXPECT_LT(worst, 1e-12*mass + 1e-9*impulse);
}


namespace
{

//- The state (positions, velocities, densities) of a water block of 80 x
//  80 particles, spacing 0.01 m (above minParallelParticles: the passes
//  split among threads), with random velocities on three layers of
//  no-slip wall particles after 40 steps (two sorts by cell) on the
//  threads set; sph entries as given; the fluid's memoryBytes() in bytes
std::vector<scalar> steppedWaterBlock
(
    const std::string& sphEntries,
    std::size_t& bytes
)
{
    particleSet ps =
        waterBlockInWalls(80, 0.01, 3, 7, particleSet::kind::wall);
    const scalar lo[2] = {-1, -1}, hi[2] = {2, 2};
    sphFluid fluid
    (
        schemes(sphEntries), std::move(ps), 1000, 20, 1e-3, 0, -9.81, lo, hi
    );
    EXPECT_TRUE(fluid.evaluate()) << fluid.failure();
    for (int step = 0; step < 2*sphFluid::reorderInterval; ++step)
    {
        fluid.advance(0.9*fluid.stableDeltaT());
        EXPECT_TRUE(fluid.evaluate()) << fluid.failure();
    }
    bytes = fluid.memoryBytes();
    std::vector<scalar> state = fluid.particles().positions();
    const std::vector<scalar>& v = fluid.particles().velocities();
    const std::vector<scalar>& rho = fluid.particles().density();
    state.insert(state.end(), v.begin(), v.end());
    state.insert(state.end(), rho.begin(), rho.end());
    return state;
}


//- How many values of two states differ at all
label differences(const std::vector<scalar>& a, const std::vector<scalar>& b)
{
    label differ = 0;
    for (size_t k = 0; k < a.size(); ++k) differ += a[k] != b[k];
    return differ;
}

} // End anonymous namespace


TEST(SphFluid, stateDoesNotDependOnTheNumberOfThreads)
{
    // The water block of steppedWaterBlock, 40 steps on one thread and on
    // two: the same state, bit for bit
    ASSERT_GT(80*80, minParallelParticles);
    const int threadsBefore = omp_get_max_threads();
    std::size_t bytes = 0;
    omp_set_num_threads(1);
    const std::vector<scalar> one = steppedWaterBlock("", bytes);
    omp_set_num_threads(2);
    const std::vector<scalar> two = steppedWaterBlock("", bytes);
    omp_set_num_threads(threadsBefore);
    ASSERT_EQ(one.size(), two.size());
    EXPECT_EQ(differences(one, two), 0) << "of " << one.size() << " values";
}


TEST(SphFluid, stateDoesNotDependOnThePairCache)
{
    // The momentum pass reads the pairs the density pass kept (pairCache
    // yes, the default) or walks the cells again (no): the same pairs in
    // the same order, the same F, so the same state, bit for bit, after
    // the 40 steps of steppedWaterBlock on two threads. The first
    // evaluation has no slots yet (every particle walks the cells), the
    // later ones read them. The cache's memory is reported
    const int threadsBefore = omp_get_max_threads();
    omp_set_num_threads(2);
    std::size_t withCache = 0, without = 0;
    const std::vector<scalar> cached =
        steppedWaterBlock("pairCache yes;", withCache);
    const std::vector<scalar> walked =
        steppedWaterBlock("pairCache no;", without);
    omp_set_num_threads(threadsBefore);
    ASSERT_EQ(cached.size(), walked.size());
    EXPECT_EQ(differences(cached, walked), 0)
        << "of " << cached.size() << " values";
    std::printf
    (
        "pairCache: %.1f B per fluid particle with it, %.1f without\n",
        double(withCache)/(80*80), double(without)/(80*80)
    );
    EXPECT_GT(withCache, without);
}


TEST(SphFluid, revertTakesOutTheParticlesAppendedSinceTheAdvance)
{
    // A step that appends fluid particles (a conversion) and fails: the
    // reverted half is the one before the step, whatever order the sort by
    // cell has given its particles, and the next particles appended get
    // the ids the reverted ones had
    const scalar dx = 0.01;
    particleSet ps = irregularParticles(12, dx, 0.1, 3);
    std::mt19937 gen(7);
    std::uniform_real_distribution<scalar> u(-0.2, 0.2);
    for (scalar& v : ps.velocities()) v = u(gen);
    const scalar lo[2] = {-1, -1}, hi[2] = {2, 2};
    sphFluid fluid
    (
        schemes(""), std::move(ps), 1000, 20, 1e-3, 0, -9.81, lo, hi
    );
    ASSERT_TRUE(fluid.evaluate());
    fluid.advance(1e-4);
    ASSERT_TRUE(fluid.evaluate()) << fluid.failure();

    // The state before the failing step, by particle id
    struct state { scalar x, y, u, v, rho; };
    const auto byId = [](const sphFluid& f)
    {
        std::map<label, state> s;
        const particleSet& p = f.particles();
        for (label i = 0; i < p.size(); ++i)
        {
            if (p.kinds()[i] != particleSet::kind::fluid) continue;
            s[p.id()[i]] =
            {
                p.positions()[2*i], p.positions()[2*i + 1],
                p.velocities()[2*i], p.velocities()[2*i + 1], p.density()[i]
            };
        }
        return s;
    };
    const std::map<label, state> before = byId(fluid);
    const label nBefore = fluid.nFluid();

    // The failing step: advance, append, evaluate (until a sort by cell,
    // every reorderInterval evaluations, has put the appended particles
    // among the others), revert
    fluid.advance(1e-4);
    particleSet converted;
    for (label k = 0; k < 5; ++k)
    {
        converted.append
        (
            (2 + 2*k + 0.5)*dx, 6.3*dx, 0.1, 0, 1000, 0, 1000*dx*dx, 1.3*dx
        );
    }
    fluid.appendFluid(converted);
    ASSERT_EQ(fluid.nFluid(), nBefore + 5);
    for (int step = 0; step < sphFluid::reorderInterval; ++step)
    {
        ASSERT_TRUE(fluid.evaluate()) << fluid.failure();
    }
    fluid.revert();

    EXPECT_EQ(fluid.nFluid(), nBefore);
    EXPECT_EQ(fluid.particles().size(), nBefore);
    const std::map<label, state> after = byId(fluid);
    ASSERT_EQ(after.size(), before.size());
    label nDiffer = 0;
    for (const auto& kv : before)
    {
        const auto it = after.find(kv.first);
        if (it == after.end()) { ++nDiffer; continue; }
        const state& a = kv.second;
        const state& b = it->second;
        nDiffer +=
            a.x != b.x || a.y != b.y || a.u != b.u || a.v != b.v
         || a.rho != b.rho;
    }
    EXPECT_EQ(nDiffer, 0) << "particles not as before the step";

    // The next conversion numbers its particles as the undone one did
    const label firstId = before.rbegin()->first + 1;
    fluid.appendFluid(converted);
    std::vector<label> ids;
    for (label i = 0; i < fluid.particles().size(); ++i)
    {
        const label id = fluid.particles().id()[i];
        if (id >= firstId) ids.push_back(id);
    }
    std::sort(ids.begin(), ids.end());
    std::vector<label> expected(5);
    for (label k = 0; k < 5; ++k) expected[k] = firstId + k;
    EXPECT_EQ(ids, expected);
}


TEST(SphFluid, symmetrisedCorrectionCarriesALinearPressureExactly)
{
    // p = G y on a regular lattice: the pressure term must give -G/rho.
    // The kernel gradient gives -M_yy G/rho (M_yy the first moment), the
    // symmetrised corrected one (C_i + C_j)/2 grad W exactly -G/rho
    const scalar dx = 0.01, rho0 = 1000, c = 1000, G = 1e4;
    const label n = 24;
    particleSet ps = irregularParticles(n, dx, 0, 1);
    for (label i = 0; i < ps.size(); ++i)
    {
        ps.density()[i] = rho0 + G*ps.positions()[2*i + 1]/(c*c);
    }
    const scalar lo[2] = {-1, -1}, hi[2] = {1, 1};
    scalar error[2];
    int k = 0;
    for (const word form : {"kernel", "symmetrisedCorrection"})
    {
        sphFluid fluid
        (
            schemes("momentumGradient " + form + ";"),
            particleSet(ps), rho0, c, 0, 0, 0, lo, hi
        );
        ASSERT_TRUE(fluid.evaluate());
        scalar worst = 0;
        label nChecked = 0;
        const particleSet& q = fluid.particles();
        for (label i = 0; i < q.size(); ++i)
        {
            const scalar* x = &q.positions()[2*i];
            // Every neighbour in the bulk: the edge particles' C is I
            if (std::min({x[0], x[1], n*dx - x[0], n*dx - x[1]}) < 6*dx) continue;
            ++nChecked;
            const scalar exact = -G/q.density()[i];
            worst = std::max
            (
                worst, std::abs(fluid.accelerations()[2*i + 1]/exact - 1)
            );
            EXPECT_LT(std::abs(fluid.accelerations()[2*i]), 1e-9*G/rho0);
        }
        ASSERT_GT(nChecked, 100);
        std::cout << form << ": worst relative error of the pressure"
                  << " acceleration " << worst << std::endl;
        error[k++] = worst;
    }
    EXPECT_GT(error[0], 5e-3);
    EXPECT_LT(error[1], 1e-5);
}


TEST(SphFluid, relaxationOpensBarycentrePairsAndKeepsMassDensityVelocity)
{
    // The barycentres of a split right mesh, (2/3, 1/3) and (1/3, 2/3) of
    // each cell: a close pair (0.47 dx apart) per cell, in a tank of walls
    // open at the top
    const scalar dx = 0.01;
    const label n = 16;
    std::mt19937 gen(7);
    std::uniform_real_distribution<scalar> u(-0.1, 0.1);
    particleSet ps;
    const scalar h = 1.3*dx/std::sqrt(2.0);
    for (label j = 0; j < n; ++j)
    {
        for (label i = 0; i < n; ++i)
        {
            for (const scalar f : {1.0/3, 2.0/3})
            {
                ps.append
                (
                    (i + 1 - f)*dx, (j + f)*dx, u(gen), u(gen),
                    1000 + u(gen), 0, 500*dx*dx, h
                );
            }
        }
    }
    const label nFluid = ps.size();
    const scalar ws = dx/std::sqrt(2.0);
    appendTankWalls(ps, label(n*dx/ws), ws, n*dx, h);
    const particleSet initial = ps;

    // Smallest distance between two fluid particles away from the walls
    // and the surface
    auto closest = [&](const particleSet& q)
    {
        const scalar* x = q.positions().data();
        scalar d = GREAT;
        for (label i = 0; i < nFluid; ++i)
        {
            if (std::min({x[2*i], x[2*i + 1], n*dx - x[2*i], n*dx - x[2*i + 1]}) < 3*dx)
            {
                continue;
            }
            for (label j = 0; j < nFluid; ++j)
            {
                if (j == i) continue;
                d = std::min(d, std::hypot(x[2*i] - x[2*j], x[2*i + 1] - x[2*j + 1]));
            }
        }
        return d;
    };

    const scalar lo[2] = {-1, -1}, hi[2] = {1, 1};
    sphFluid fluid(schemes(""), particleSet(initial), 1000, 20, 1e-3, 0, -9.81, lo, hi);
    const scalar lastShift = fluid.relax(200);
    const particleSet& q = fluid.particles();
    const scalar before = closest(initial), after = closest(q);
    std::cout << "closest interior pair " << before/dx << " dx before, "
              << after/dx << " dx after; last shift " << lastShift
              << " h" << std::endl;
    EXPECT_NEAR(before/dx, std::sqrt(2.0)/3, 1e-9);
    // Opened towards the staggered lattice (nearest distance dx/sqrt 2)
    EXPECT_GT(after/dx, 0.65);
    EXPECT_LT(lastShift, 5e-3);

    ASSERT_EQ(q.size(), initial.size());
    for (label i = 0; i < q.size(); ++i)
    {
        EXPECT_EQ(q.mass()[i], initial.mass()[i]);
        EXPECT_EQ(q.density()[i], initial.density()[i]);
        EXPECT_EQ(q.velocities()[2*i], initial.velocities()[2*i]);
        EXPECT_EQ(q.velocities()[2*i + 1], initial.velocities()[2*i + 1]);
        if (i >= nFluid)
        {
            // The walls stay
            EXPECT_EQ(q.positions()[2*i], initial.positions()[2*i]);
            EXPECT_EQ(q.positions()[2*i + 1], initial.positions()[2*i + 1]);
        }
        else
        {
            const scalar* x = &q.positions()[2*i];
            EXPECT_TRUE(x[0] > 0 && x[0] < n*dx && x[1] > 0) << i;
        }
    }
}


TEST(SphFluid, conversionRelaxationOpensNewPairsOnlyAndQuietsThem)
{
    // Water at rest under gravity in a tank of walls open at the top: the
    // lower half an even lattice (relaxed barycentres), the upper half
    // appended during the run as a conversion makes it, at the barycentres
    // of a split right mesh (a close pair, 0.47 dx apart, per cell), with
    // hydrostatic densities. Left to the pressure forces the pairs open
    // with a jolt that sets the new water moving; relaxed before their
    // first density pass (sph/conversionRelaxation) they open by pure
    // shifts, and the particles that were there stay where they are
    const scalar dx = 0.01, rho0 = 1000, c = 20, g = 9.81;
    const label n = 16;
    const scalar h = 1.3*dx/std::sqrt(2.0), H = n*dx;
    const auto barycentres = [&](particleSet& ps, const label j0, const label j1)
    {
        for (label j = j0; j < j1; ++j)
        {
            for (label i = 0; i < n; ++i)
            {
                for (const scalar f : {1.0/3, 2.0/3})
                {
                    // Hydrostatic (eq. 7)
                    const scalar y = (j + f)*dx;
                    ps.append
                    (
                        (i + 1 - f)*dx, y, 0, 0, rho0*(1 + g*(H - y)/(c*c)),
                        0, 0.5*rho0*dx*dx, h
                    );
                }
            }
        }
    };
    particleSet lower;
    barycentres(lower, 0, n/2);
    const scalar ws = dx/std::sqrt(2.0);
    appendTankWalls(lower, label(n*dx/ws), ws, n*dx, h);
    particleSet upper;
    barycentres(upper, n/2, n);

    struct outcome
    {
        scalar closestMade, closest, speed;
        label nOldMoved, nNewChanged;
    };
    const auto run = [&](const std::string& entries)
    {
        const scalar lo[2] = {-1, -1}, hi[2] = {1, 1};
        sphFluid fluid
        (
            schemes(entries), particleSet(lower), rho0, c, 1e-3, 0, -g, lo, hi
        );
        fluid.relax(200);
        const scalar dt = 0.5*h/c;
        for (int step = 0; step < 5; ++step)
        {
            EXPECT_TRUE(fluid.evaluate()) << fluid.failure();
            fluid.advance(dt);
        }
        // The state of each particle, by id
        struct state { scalar x, y, u, v, rho, m; };
        const auto states = [](const sphFluid& f)
        {
            std::map<label, state> s;
            const particleSet& p = f.particles();
            for (label i = 0; i < p.size(); ++i)
            {
                const scalar* x = &p.positions()[2*i];
                const scalar* v = &p.velocities()[2*i];
                s[p.id()[i]] = {x[0], x[1], v[0], v[1], p.density()[i], p.mass()[i]};
            }
            return s;
        };
        const label firstNew = states(fluid).rbegin()->first + 1;
        fluid.appendFluid(upper);
        // Closest pair of new particles away from the walls and the
        // surface by 3 dx, and above the lower half by 1 dx
        const auto closestNew = [&](const sphFluid& f)
        {
            const particleSet& p = f.particles();
            const scalar* x = p.positions().data();
            scalar d = GREAT;
            for (label i = 0; i < p.size(); ++i)
            {
                if
                (
                    p.id()[i] < firstNew || x[2*i] < 3*dx
                 || x[2*i] > (n - 3)*dx || x[2*i + 1] < (n/2 + 1)*dx
                 || x[2*i + 1] > (n - 3)*dx
                )
                {
                    continue;
                }
                for (label j = 0; j < p.size(); ++j)
                {
                    if (j == i || p.id()[j] < firstNew) continue;
                    d = std::min
                    (
                        d, std::hypot(x[2*i] - x[2*j], x[2*i + 1] - x[2*j + 1])
                    );
                }
            }
            return d;
        };
        outcome o{};
        o.closestMade = closestNew(fluid);
        const std::map<label, state> before = states(fluid);
        EXPECT_TRUE(fluid.evaluate()) << fluid.failure();
        o.closest = closestNew(fluid);
        for (const auto& [id, a] : states(fluid))
        {
            const state& b = before.at(id);
            if (id < firstNew)
            {
                o.nOldMoved += a.x != b.x || a.y != b.y;
            }
            else
            {
                o.nNewChanged +=
                    a.u != b.u || a.v != b.v || a.rho != b.rho || a.m != b.m;
            }
        }
        // The new particles' RMS speed over the next 300 steps of 0.5 h/c
        // (some 20 acoustic crossings of a pair)
        scalar sum = 0;
        label count = 0;
        for (int step = 0; step < 300; ++step)
        {
            fluid.advance(dt);
            EXPECT_TRUE(fluid.evaluate()) << fluid.failure();
            const particleSet& p = fluid.particles();
            for (label i = 0; i < p.size(); ++i)
            {
                if (p.id()[i] < firstNew) continue;
                sum += sqr(p.velocities()[2*i]) + sqr(p.velocities()[2*i + 1]);
                ++count;
            }
        }
        o.speed = std::sqrt(sum/count);
        return o;
    };
    const outcome plain = run("conversionRelaxation 0;");
    const outcome relaxed = run("");
    std::printf
    (
        "new particles: closest interior pair %.3f dx as made; after their"
        " first evaluation %.3f dx with conversionRelaxation 0, %.3f dx with"
        " the default (50); RMS speed over 300 steps %.4f and %.4f m/s"
        " (sqrt(g H) %.3f m/s)\n",
        plain.closestMade/dx, plain.closest/dx, relaxed.closest/dx,
        plain.speed, relaxed.speed, std::sqrt(g*H)
    );
    EXPECT_NEAR(plain.closestMade/dx, std::sqrt(2.0)/3, 1e-9);
    EXPECT_NEAR(plain.closest/dx, std::sqrt(2.0)/3, 1e-9);
    // Towards the staggered lattice (nearest distance dx/sqrt 2)
    EXPECT_GT(relaxed.closest/dx, 0.6);
    EXPECT_EQ(plain.nOldMoved, 0);
    EXPECT_EQ(relaxed.nOldMoved, 0);
    EXPECT_EQ(plain.nNewChanged, 0);
    EXPECT_EQ(relaxed.nNewChanged, 0);
    EXPECT_LT(relaxed.speed, 0.7*plain.speed);
}


// * * * * * * * * * * * * * * * Wall particles  * * * * * * * * * * * * * * //

TEST(WallParticles, layersAndCornersOutsideTheMeshAtTheirSpacing)
{
    // A 1 x 0.5 tank: left, right, bottom walls, open top
    const triMesh mesh =
        testMeshes::build({{0, 1, 0, 0.5, 10, 5, "water"}});
    List<patchType> types(mesh.nPatches());
    forAll(mesh.patchNames(), p)
    {
        const word& name = mesh.patchNames()[p];
        types[p] =
            name == "top" ? patchType::freeSurface
          : name == "left" ? patchType::slipWall
          : patchType::noSlipWall;
    }

    const scalar s = 0.05;
    const label layers = 3;
    particleSet ps;
    const label n = appendWallParticles(mesh, types, s, layers, 1000, 1.3*s, ps);

    // Bottom 20 per layer, sides 10 per layer, two 3 x 3 corner blocks
    EXPECT_EQ(n, layers*(20 + 10 + 10) + 2*layers*layers);
    ASSERT_EQ(ps.size(), n);

    label nSlip = 0;
    for (label i = 0; i < n; ++i)
    {
        const scalar x = ps.positions()[2*i], y = ps.positions()[2*i + 1];
        // Outside the tank, within the layers
        EXPECT_TRUE(x < 0 || x > 1 || y < 0) << x << ' ' << y;
        EXPECT_TRUE(x > -layers*s && x < 1 + layers*s && y > -layers*s && y < 0.5);
        EXPECT_DOUBLE_EQ(ps.mass()[i], 1000*s*s);
        if (ps.kinds()[i] == particleSet::kind::slipWall)
        {
            ++nSlip;
            EXPECT_LT(x, 0);
        }
        // No two closer than the spacing
        for (label j = 0; j < i; ++j)
        {
            const scalar d = std::hypot
            (
                x - ps.positions()[2*j], y - ps.positions()[2*j + 1]
            );
            ASSERT_GT(d, 0.99*s);
        }
    }
    // The left wall's particles (its corner belongs to the no-slip bottom)
    EXPECT_EQ(nSlip, layers*10);
}


// * * * * * * * * * * * * * * * * Conversion  * * * * * * * * * * * * * * * //

TEST(ElementToParticle, conservesMassAndMomentumAtTheBarycentre)
{
    const triMesh mesh =
        testMeshes::perturbed(testMeshes::build({{0, 1, 0, 1, 4, 4, "water"}}), 0.2, 0.25, 3);
    const std::vector<scalar>& x = mesh.points();
    std::vector<scalar> v(x.size());
    for (size_t i = 0; i < v.size(); ++i) v[i] = std::sin(3.0*i);

    const label nT = mesh.nTriangles();
    std::vector<scalar> m(nT);
    std::vector<label> all(nT);
    for (label t = 0; t < nT; ++t) { m[t] = 1 + 0.1*t; all[t] = t; }

    particleSet ps;
    EXPECT_EQ(appendParticlesFromElements(x, v, mesh.triangles(), m, all, 1.3, ps), 0);
    ASSERT_EQ(ps.size(), nT);

    // Element momentum: each node carries m_e/3 of the element's mass
    scalar mass = 0, px = 0, py = 0, qx = 0, qy = 0;
    for (label t = 0; t < nT; ++t)
    {
        const label* nd = &mesh.triangles()[3*t];
        scalar cx = 0, cy = 0, area;
        for (int k = 0; k < 3; ++k)
        {
            cx += x[2*nd[k]]/3;
            cy += x[2*nd[k] + 1]/3;
            px += m[t]/3*v[2*nd[k]];
            py += m[t]/3*v[2*nd[k] + 1];
        }
        const scalar* a = &x[2*nd[0]];
        const scalar* b = &x[2*nd[1]];
        const scalar* c = &x[2*nd[2]];
        area = 0.5*std::abs((b[0]-a[0])*(c[1]-a[1]) - (b[1]-a[1])*(c[0]-a[0]));

        EXPECT_NEAR(ps.positions()[2*t], cx, 1e-14);
        EXPECT_NEAR(ps.positions()[2*t + 1], cy, 1e-14);
        EXPECT_DOUBLE_EQ(ps.mass()[t], m[t]);
        EXPECT_NEAR(ps.density()[t], m[t]/area, 1e-12*m[t]/area);
        EXPECT_NEAR(ps.smoothingLength()[t], 1.3*std::sqrt(area), 1e-14);
        mass += ps.mass()[t];
        qx += ps.mass()[t]*ps.velocities()[2*t];
        qy += ps.mass()[t]*ps.velocities()[2*t + 1];
    }
    scalar mTotal = 0;
    for (const scalar mt : m) mTotal += mt;
    EXPECT_NEAR(mass, mTotal, 1e-13*mTotal);
    EXPECT_NEAR(qx, px, 1e-12);
    EXPECT_NEAR(qy, py, 1e-12);
}


// * * * * * * * * * * * Mixed resolution (eqs. 19-22) * * * * * * * * * * //

TEST(MixedResolution, internalForcesSumToZeroOverARandomMixedSet)
{
    // Random velocities and densities, viscous, no walls and no gravity:
    // sum m_i a_i is the sum of the pair forces, zero if each pair's is
    // antisymmetric, which with h_i != h_j needs the same h_ij both ways
    particleSet ps = mixedResolutionParticles(14, 0.5, 21);
    std::mt19937 gen(8);
    std::uniform_real_distribution<scalar> u(-1, 1);
    for (scalar& v : ps.velocities()) v = 0.5*u(gen);
    for (scalar& rho : ps.density()) rho *= 1 + 0.01*u(gen);
    scalar hMin, hMax;
    smoothingLengthRange(ps, hMin, hMax);
    std::cout << ps.size() << " particles, h from " << hMin << " to " << hMax
              << std::endl;
    ASSERT_GT(hMax/hMin, 1.7);

    const scalar lo[2] = {-1, -1}, hi[2] = {2, 2};
    for (const word form : {"kernel", "symmetrisedCorrection"})
    {
        SCOPED_TRACE(form);
        sphFluid fluid
        (
            schemes("momentumGradient " + form + ";"), particleSet(ps),
            1000, 20, 1e-3, 0, 0, lo, hi
        );
        ASSERT_TRUE(fluid.evaluate()) << fluid.failure();
        const particleSet& q = fluid.particles();
        const std::vector<scalar>& a = fluid.accelerations();
        long double fx = 0, fy = 0, scale = 0;
        for (label i = 0; i < q.size(); ++i)
        {
            fx += q.mass()[i]*a[2*i];
            fy += q.mass()[i]*a[2*i + 1];
            scale += q.mass()[i]*std::hypot(a[2*i], a[2*i + 1]);
        }
        std::cout << form << ": |sum m a| " << double(std::hypot(fx, fy))
                  << " N of sum m |a| " << double(scale) << " N" << std::endl;
        ASSERT_GT(scale, 0);
        EXPECT_LT(double(std::hypot(fx, fy)), 1e-13*double(scale));
    }
}


TEST(MixedResolution, correctedGradientIsExactForLinearFieldsOnAMixedSet)
{
    // The test's own sums with h_ij (correctedGradient above) and
    // src/SPEM/sph/gradientCorrection's matrix, at the particles whose
    // support lies inside the set
    const particleSet ps = mixedResolutionParticles(14, 0.5, 5);
    scalar hMin, hMax;
    smoothingLengthRange(ps, hMin, hMax);
    const scalar a = 3, b = -2, reach = 2*hMax;
    auto fx = [&](scalar x, scalar) { return a*x; };
    auto fy = [&](scalar, scalar y) { return b*y; };
    auto fxy = [&](scalar x, scalar y) { return a*x + b*y; };
    scalar worstNone = 0;
    label nChecked = 0, nRefined = 0;
    for (label i = 0; i < ps.size(); ++i)
    {
        const scalar* p = &ps.positions()[2*i];
        if (std::min({p[0], p[1], 1 - p[0], 1 - p[1]}) < reach) continue;
        ++nChecked;
        nRefined += ps.level()[i];
        scalar g[2];
        correctedGradient(ps, i, gradientCorrectionType::decoupledFPM, fx, g);
        EXPECT_NEAR(g[0], a, 1e-10);
        correctedGradient(ps, i, gradientCorrectionType::decoupledFPM, fy, g);
        EXPECT_NEAR(g[1], b, 1e-10);
        correctedGradient(ps, i, gradientCorrectionType::FPM, fxy, g);
        EXPECT_NEAR(g[0], a, 1e-10);
        EXPECT_NEAR(g[1], b, 1e-10);
        correctedGradient(ps, i, gradientCorrectionType::none, fx, g);
        worstNone = std::max(worstNone, std::abs(g[0] - a)/a);
    }
    ASSERT_GT(nChecked, 100);
    ASSERT_GT(nRefined, 50);
    std::cout << nChecked << " particles (" << nRefined << " refined):"
              << " worst uncorrected error " << worstNone << std::endl;
    EXPECT_GT(worstNone, 1e-2);
}


TEST(MixedResolution, fpmContinuityIsExactForLinearVelocityOnAMixedSet)
{
    // sphFluid's own density pass (moments and continuity with h_ij):
    // drho/dt = -rho div v for v = (a x + b y, c x + d y)
    particleSet ps = mixedResolutionParticles(14, 0.5, 9);
    scalar hMin, hMax;
    smoothingLengthRange(ps, hMin, hMax);
    setLinearVelocity(ps);
    const scalar lo[2] = {-1, -1}, hi[2] = {2, 2};
    for (const word corr : {"FPM", "none"})
    {
        SCOPED_TRACE(corr);
        label nChecked = 0;
        const scalar worst =
            worstContinuityError(ps, corr, 1, 2*hMax, lo, hi, nChecked);
        if (::testing::Test::HasFailure()) return;
        ASSERT_GT(nChecked, 100);
        std::cout << corr << ": worst relative error of drho/dt " << worst
                  << std::endl;
        if (corr == "FPM")
        {
            // O(dt) from the positions moved by the step
            EXPECT_LT(worst, 1e-5);
        }
        else
        {
            EXPECT_GT(worst, 1e-3);
        }
    }
}


TEST(MixedResolution, stableStepIsTheFinestParticles)
{
    // At rest at rho0 without gravity or viscosity: no force, and the
    // step is the acoustic one, acousticFactor h/c, of the smallest h
    particleSet ps = mixedResolutionParticles(10, 0.5, 3);
    for (scalar& rho : ps.density()) rho = 1000;
    scalar hMin, hMax;
    smoothingLengthRange(ps, hMin, hMax);
    const scalar c = 20, lo[2] = {-1, -1}, hi[2] = {2, 2};
    sphFluid fluid(schemes(""), particleSet(ps), 1000, c, 0, 0, 0, lo, hi);
    ASSERT_TRUE(fluid.evaluate());
    std::cout << "h from " << hMin << " to " << hMax << ": stable step "
              << fluid.stableDeltaT() << " s" << std::endl;
    EXPECT_NEAR
    (
        fluid.stableDeltaT(), sphFluid::acousticFactor*hMin/c, 1e-12*hMin/c
    );
}


// ************************************************************************* //
