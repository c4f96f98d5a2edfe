/*---------------------------------------------------------------------------*\
Application
    particleStepBenchmark

Description
    Throughput and memory of the particle half of SPEM (Foam::sphFluid).
    One step is what spemFoam does for the particles every time step:
        advance(dt)  leapfrog update of the fluid particles with particle
                     shifting
        evaluate()   lost-particle check, neighbour search (cell-linked
                     list, particles sorted by cell every 20 steps),
                     density/continuity pass, wall pass, momentum pass
    with dt = min(0.2 dx/c, 0.9 stableDeltaT()).

    The case is a water block built in memory, no files: N fluid particles
    on a square lattice of spacing dx = 1 m/nx, at ((i + 0.5) dx,
    (j + 0.5) dx) in a box nx dx wide and ny dx tall (ny about nx), density
    1000, mass 1000 dx^2, smoothing length 1.3 dx, with a random initial
    velocity of up to 0.1 m/s per component (fixed seed) so that shifting
    and viscosity do real work; below and beside it 3 layers of no-slip
    dummy wall particles at spacing dx. sphFluid(empty schemes dictionary:
    WendlandC2, decoupledFPM, densityDiffusion 0.1, shifting 2;
    rho0 1000, c 20, mu 1e-3, g (0 -9.81), a lost-particle box 10 times
    the scene).

    Issue goal: at least 2e6 particle-steps per second on 2 cores at 100k
    fluid particles, cost linear in the particle count, at most 300 bytes
    per particle.

    Usage
        particleStepBenchmark [Google Benchmark options]
            fullStep/fluid:N/threads:T   advance(dt) + evaluate()
        for N in {100, 250, 500, 1000, 2000, 4000, 1e4, 1e5, 1e6} fluid particles
        and T OpenMP threads in {1, 2} (the small sizes place
        minParallelParticles, with a build that splits every pass:
        cmake -DSPEM_MIN_PARALLEL_PARTICLES=0). Counters: particleSteps (fluid particle-steps per second),
        secondsPerParticleStep, fluid, walls, neighbours (mean per fluid
        particle), bytesPerParticle (sphFluid::memoryBytes() / all
        particles). Each run builds a fresh fluid, calls evaluate() once
        and takes warm-up steps outside the timing, then times a fixed
        number of steps, a multiple of sphFluid::reorderInterval so that
        every run pays the same share of the sorts by cell.

        particleStepBenchmark -memory [nFluid ...]
            memory per particle for each nFluid (default 1e4 1e5 1e6); see
            memoryReport() for the method.

        particleStepBenchmark -noPairCache ...
            either of the above with sph/pairCache no (sphFluid.H)

    libOpenFOAM needs WM_PROJECT_DIR=/usr/share/openfoam in the environment
    before the program starts (. etc/bashrc sets it).

\*---------------------------------------------------------------------------*/

#include "residentMemory.H"
#include <benchmark/benchmark.h>

#include "sphFluid.H"
#include "particleSet.H"
#include "dictionary.H"
#include "IStringStream.H"

#include <malloc.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using Foam::label;
using Foam::scalar;
using Foam::particleSet;
using Foam::sphFluid;


// * * * * * * * * * * * * * * * * The case  * * * * * * * * * * * * * * * * //

namespace waterBlock
{

//- Fluid: reference density, sound speed, dynamic viscosity, gravity
const scalar rho0 = 1000, c = 20, mu = 1e-3, gx = 0, gy = -9.81;

//- Smoothing length / particle spacing
const scalar hRatio = 1.3;

//- Layers of dummy wall particles (WendlandC2 support 2 h = 2.6 dx < 3 dx)
const label wallLayers = 3;

//- Amplitude of the random initial velocity (each component) [m/s]
const scalar velocityAmplitude = 0.1;

//- Seed of the random initial velocity
const unsigned seed = 12345;

//- Width of the block [m]: dx = width/nx
const scalar width = 1;

//- Columns and rows of fluid particles
struct layout
{
    label nx, ny;
};

//- nx ny = nFluid with nx the largest divisor of nFluid in
//  (sqrt(nFluid)/2, sqrt(nFluid)] (exact for 1e4, 1e5, 1e6: 100 x 100,
//  250 x 400, 1000 x 1000), else nx about sqrt(nFluid)
layout layoutFor(const label nFluid)
{
    const label n = std::max<label>(1, nFluid);
    const label nxTarget = std::max<label>(1, std::lround(std::sqrt(double(n))));
    label nx = nxTarget;
    while (nx > nxTarget/2 && n % nx) --nx;
    if (n % nx) nx = nxTarget;
    const label ny = std::max<label>(1, std::lround(double(n)/nx));
    return {nx, ny};
}

//- The scene: particles (fluid then walls) and its size
struct scene
{
    particleSet particles;
    layout l;
    scalar dx;
    label nFluid, nWall;
    scalar boxMin[2], boxMax[2];
};

//- Build the particles of the water block and its walls
scene build(const label nFluidRequested)
{
    scene s;
    s.l = layoutFor(nFluidRequested);
    const label nx = s.l.nx, ny = s.l.ny, L = wallLayers;
    const scalar dx = width/nx;
    s.dx = dx;
    s.nFluid = nx*ny;
    s.nWall = L*(nx + 2*L) + 2*L*ny;

    const scalar m = rho0*dx*dx, h = hRatio*dx;
    particleSet& ps = s.particles;
    ps.reserve(s.nFluid + s.nWall);     // capacities = sizes

    std::mt19937 gen(seed);
    std::uniform_real_distribution<scalar> u(-velocityAmplitude, velocityAmplitude);
    for (label j = 0; j < ny; ++j)
    {
        for (label i = 0; i < nx; ++i)
        {
            const scalar vx = u(gen), vy = u(gen);
            ps.append((i + 0.5)*dx, (j + 0.5)*dx, vx, vy, rho0, 0, m, h);
        }
    }

    const particleSet::kind wall = particleSet::kind::wall;
    // Below, with the corners
    for (label k = 0; k < L; ++k)
    {
        for (label i = -L; i < nx + L; ++i)
        {
            ps.append((i + 0.5)*dx, -(k + 0.5)*dx, 0, 0, rho0, 0, m, h, wall);
        }
    }
    // Beside, up to the water height
    for (label k = 0; k < L; ++k)
    {
        for (label j = 0; j < ny; ++j)
        {
            ps.append(-(k + 0.5)*dx, (j + 0.5)*dx, 0, 0, rho0, 0, m, h, wall);
            ps.append((nx + k + 0.5)*dx, (j + 0.5)*dx, 0, 0, rho0, 0, m, h, wall);
        }
    }

    // Lost-particle box: the scene's bounding box enlarged 10 times about
    // its centre
    const scalar lo[2] = {-L*dx, -L*dx}, hi[2] = {(nx + L)*dx, ny*dx};
    for (int d = 0; d < 2; ++d)
    {
        const scalar mid = 0.5*(lo[d] + hi[d]), half = 0.5*(hi[d] - lo[d]);
        s.boxMin[d] = mid - 10*half;
        s.boxMax[d] = mid + 10*half;
    }
    return s;
}

//- sph/pairCache of the fluid (-noPairCache: no)
bool pairCache = true;

//- The fluid of a scene (the particles are moved into it), evaluated
//  once; nullptr (and why) if that evaluate() fails
std::unique_ptr<sphFluid> fluid(scene& s, std::string& failure)
{
    // Every default, but pairCache as asked
    Foam::IStringStream is(pairCache ? "" : "sph { pairCache no; }");
    const Foam::dictionary schemes(is);
    std::unique_ptr<sphFluid> f
    (
        new sphFluid
        (
            schemes, std::move(s.particles), rho0, c, mu, gx, gy,
            s.boxMin, s.boxMax
        )
    );
    if (!f->evaluate())
    {
        failure = f->failure();
        return nullptr;
    }
    return f;
}

//- Time step: 0.2 dx/c, or less if the fluid asks for it
inline scalar deltaT(const sphFluid& f, const scalar dx)
{
    return std::min(0.2*dx/c, 0.9*f.stableDeltaT());
}

//- One step as spemFoam takes it for the particles
inline bool step(sphFluid& f, const scalar dx)
{
    return f.advance(deltaT(f, dx)) && f.evaluate();
}

//- Mean number of neighbours of a fluid particle (from the cell list of
//  the last evaluate())
double meanNeighbours(const sphFluid& f)
{
    const particleSet& ps = f.particles();
    const scalar kappa = f.kernel().support();
    double pairs = 0;
    for (label i = 0; i < ps.size(); ++i)
    {
        if (ps.kinds()[i] != particleSet::kind::fluid) continue;
        f.cells().forEachNeighbour
        (
            ps, i, kappa,
            [&pairs](label, scalar, scalar, scalar) { ++pairs; }
        );
    }
    return f.nFluid() > 0 ? pairs/f.nFluid() : 0;
}

} // End namespace waterBlock


// * * * * * * * * * * * * * * * * Benchmarks  * * * * * * * * * * * * * * * //

namespace
{

//- Steps taken before timing: first touch of the pages, OpenMP thread
//  start-up, caches
const int warmUpSteps = 3;

//- Timed steps of a run: a multiple of sphFluid::reorderInterval (every
//  run then pays the same share of the sorts by cell). On one thread of the
//  reference machine (about 0.7 us per particle-step) 0.35-2.8 s at
//  500-4000, 1.5 s at 1e4, 3 s at 1e5 and 14 s at 1e6 (a single reorder
//  cycle)
int64_t timedSteps(const int64_t nFluid)
{
    const int64_t r = sphFluid::reorderInterval;
    if (nFluid <= 4000) return 50*r;
    if (nFluid <= 10000) return 10*r;
    if (nFluid <= 100000) return 2*r;
    return r;
}

//- A full particle step: advance(dt) + evaluate(), on a fresh fluid
void fullStep(benchmark::State& state)
{
    omp_set_num_threads(int(state.range(1)));
    waterBlock::scene s = waterBlock::build(state.range(0));
    const scalar dx = s.dx;
    std::string failure;
    std::unique_ptr<sphFluid> f = waterBlock::fluid(s, failure);
    if (!f)
    {
        state.SkipWithError(failure.c_str());
        return;
    }
    for (int i = 0; i < warmUpSteps; ++i)
    {
        if (!waterBlock::step(*f, dx))
        {
            state.SkipWithError(f->failure().c_str());
            return;
        }
    }

    for (auto _ : state)
    {
        if (!waterBlock::step(*f, dx))
        {
            state.SkipWithError(f->failure().c_str());
            break;
        }
    }

    using benchmark::Counter;
    const double particleSteps = double(state.iterations())*f->nFluid();
    state.SetItemsProcessed(int64_t(particleSteps));
    state.counters["particleSteps"] = Counter(particleSteps, Counter::kIsRate);
    state.counters["secondsPerParticleStep"] =
        Counter(particleSteps, Counter::kIsRate | Counter::kInvert);
    state.counters["fluid"] = f->nFluid();
    state.counters["walls"] = f->nWall();
    state.counters["neighbours"] = waterBlock::meanNeighbours(*f);
    state.counters["bytesPerParticle"] =
        double(f->memoryBytes())/f->particles().size();
    f.reset();
    malloc_trim(0);
}

//- Largest value over repetitions: for the rate counters (particleSteps)
//  the best repetition; for the time columns the slowest
double largest(const std::vector<double>& v)
{
    return v.empty() ? 0 : *std::max_element(v.begin(), v.end());
}

//- Register fullStep for every size with its fixed number of steps
int registerBenchmarks()
{
    // The small sizes place minParallelParticles: from which size two
    // threads beat one (a build with -DSPEM_MIN_PARALLEL_PARTICLES=0
    // splits every pass)
    for (const int64_t n : {100, 250, 500, 1000, 2000, 4000, 10000, 100000, 1000000})
    {
        for (const int64_t t : {1, 2})
        {
            benchmark::RegisterBenchmark("fullStep", fullStep)
                ->ArgNames({"fluid", "threads"})
                ->Args({n, t})
                ->Iterations(timedSteps(n))
                ->UseRealTime()
                ->Unit(benchmark::kMillisecond)
                ->ComputeStatistics("max", largest);
        }
    }
    return 0;
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * * Memory  * * * * * * * * * * * * * * * * //

namespace
{

using benchmarkTools::residentMemory;
using benchmarkTools::readResidentMemory;
using benchmarkTools::resetPeak;

/*
    Memory per particle, for each requested fluid particle count. Method:
      - OpenMP threads (2) are started first, so their stacks are part of
        the baseline resident set size (RSS), taken after malloc_trim with
        nothing built.
      - VmHWM is reset to the current RSS by writing 5 to
        /proc/self/clear_refs.
      - The particles are built (reserve, then append: capacities equal
        sizes), moved into a new sphFluid, evaluate() is called once (first
        sort by cell: the scratch buffers of particleSet::reorder() are
        allocated there) and 20 steps (a full reorder cycle) are taken on 2
        threads.
      - sphFluid::memoryBytes() (capacities of every array it holds) is
        divided by all particles (fluid + wall) and by the fluid particles;
        RSS - baseline and VmHWM - baseline are divided by the fluid
        particles, and so is VmHWM itself (the whole process: libOpenFOAM,
        libSPEM, ... included).
      - The fluid is destroyed and free heap returned before the next size.
    Without clear_refs (kernel < 4.0) the peaks include every earlier
    size; this is reported.
*/
int memoryReport(const std::vector<label>& sizes)
{
    const int nSteps = sphFluid::reorderInterval;
    omp_set_num_threads(2);
    #pragma omp parallel
    {
        benchmark::DoNotOptimize(omp_get_thread_num());
    }

    const double MB = 1024*1024;
    std::printf
    (
        "sphFluid memory: water block + 3 wall layers, evaluate() + %d steps"
        " on 2 threads\n", nSteps
    );
    std::printf
    (
        "%9s %7s | %9s %9s %9s %9s | %8s %8s %8s | %9s %9s\n",
        "fluid", "walls", "sph B/all", "B/fluid", "set B/all", "cells B/all",
        "RSS B/fl", "peak B/fl", "HWM B/fl", "HWM MB", "base MB"
    );

    int status = 0;
    for (const label nRequested : sizes)
    {
        malloc_trim(0);
        const residentMemory baseline = readResidentMemory();
        const bool peakReset = resetPeak();

        waterBlock::scene s = waterBlock::build(nRequested);
        const scalar dx = s.dx;
        std::string failure;
        std::unique_ptr<sphFluid> f = waterBlock::fluid(s, failure);
        if (!f)
        {
            std::fprintf(stderr, "evaluate failed: %s\n", failure.c_str());
            return 1;
        }
        for (int i = 0; i < nSteps; ++i)
        {
            if (!waterBlock::step(*f, dx))
            {
                std::fprintf(stderr, "step %d failed: %s\n", i,
                    f->failure().c_str());
                return 1;
            }
        }
        malloc_trim(0);
        const residentMemory after = readResidentMemory();

        const double nAll = f->particles().size(), nFluid = f->nFluid();
        const double bytes = f->memoryBytes();
        const double setBytes = f->particles().memoryBytes();
        const double cellBytes = f->cells().memoryBytes();
        std::printf
        (
            "%9ld %7ld | %9.1f %9.1f %9.1f %9.1f | %8.1f %8.1f %8.1f | %9.1f %9.1f\n",
            long(f->nFluid()), long(f->nWall()), bytes/nAll, bytes/nFluid,
            setBytes/nAll, cellBytes/nAll,
            (after.rss - baseline.rss)/nFluid,
            (after.peak - baseline.rss)/nFluid,
            after.peak/nFluid, after.peak/MB, baseline.rss/MB
        );
        if (!peakReset)
        {
            std::printf("warning: /proc/self/clear_refs refused: the peak "
                "includes every earlier size\n");
        }
        if (f->nFluid() != nRequested) status = 1;
        f.reset();
    }

    std::printf
    (
        "\nsph B/all   sphFluid::memoryBytes() / (fluid + wall particles)\n"
        "B/fluid     sphFluid::memoryBytes() / fluid particles\n"
        "set B/all   of which particleSet (fields + reorder scratch)\n"
        "cells B/all of which cellLinkedList\n"
        "RSS B/fl    resident set above the baseline / fluid particles\n"
        "peak B/fl   VmHWM above the baseline / fluid particles (build,"
        " construction, steps)\n"
        "HWM B/fl    process VmHWM (libraries included) / fluid particles\n"
        "base MB     baseline RSS: libraries, OpenMP threads\n"
    );
    return status;
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * * * Main  * * * * * * * * * * * * * * * * //

int main(int argc, char** argv)
{
    // -noPairCache: the momentum pass walks the cells again (sphFluid.H)
    for (int i = 1; i < argc; ++i)
    {
        if (std::string(argv[i]) == "-noPairCache")
        {
            waterBlock::pairCache = false;
            for (int k = i; k < argc - 1; ++k) argv[k] = argv[k + 1];
            --argc;
            break;
        }
    }
    for (int i = 1; i < argc; ++i)
    {
        if (std::string(argv[i]) == "-memory")
        {
            std::vector<label> sizes;
            for (int k = i + 1; k < argc; ++k)
            {
                sizes.push_back(label(std::stod(argv[k])));
            }
            if (sizes.empty()) sizes = {10000, 100000, 1000000};
            return memoryReport(sizes);
        }
    }

    registerBenchmarks();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}


// ************************************************************************* //
