/*---------------------------------------------------------------------------*\
Application
    elementStepBenchmark

Description
    Throughput and memory of the element half of SPEM (Foam::elementModel).
    One step is what spemFoam does for the elements every time step:
        evaluate()   element pass, domain pass + material stress, force pass
                     (paper eqs. 2-10)
        advance(dt)  nodal gather of the element forces and the explicit
                     central-difference update, dt = 0.5 stableDeltaT()

    The case is the hydrostatic elastic plate (tutorials/hydrostaticElastic-
    Plate) made larger: a square-celled structured mesh, alternating
    diagonals, nx columns; a water block (weaklyCompressibleNewtonian
    rho 1000, c 100, mu 1e-3) on top of a plate (linearElastic, the
    tutorial's aluminium) holding 5 % of the elements, clamped plate ends,
    slip walls beside the water, free top and plate bottom, gravity on.

    Issue goal: at least 1e7 element-steps per second on 2 cores at 1M
    elements, cost linear in the element count, at most 400 bytes per
    element peak memory.

    Usage
        elementStepBenchmark [Google Benchmark options]
            fullStep/elements:N/threads:T      evaluate() + advance(dt)
            evaluateOnly/elements:N/threads:T  evaluate() alone
            advanceOnly/elements:N/threads:T   advance(dt) alone
        for N in {1e4, 1e5, 1e6} and T OpenMP threads in {1, 2}. Counters:
        elementSteps (element-steps per second), secondsPerElementStep,
        elements, nodes, domains.

        elementStepBenchmark -memory [nElements]
            memory per element of a model of nElements (default 1e6)
            elements; see memoryReport() for the method.

    libOpenFOAM needs WM_PROJECT_DIR=/usr/share/openfoam in the environment
    before the program starts (. etc/bashrc sets it).

\*---------------------------------------------------------------------------*/

#include "residentMemory.H"
#include <benchmark/benchmark.h>

#include "testMeshes.H"
#include "testModels.H"

#include <malloc.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

using Foam::label;
using Foam::scalar;
using Foam::elementModel;


// * * * * * * * * * * * * * * * * The case  * * * * * * * * * * * * * * * * //

namespace plateCase
{

//- Fraction of the element rows that are plate (solid)
const double solidFraction = 0.05;

//- Plate material: the tutorial's (aluminium)
const std::string plateSolid =
    "model linearElastic; rho 2700; E 67.5e9; nu 0.34;";

//- Columns and rows of square cells (two triangles each)
struct layout
{
    label nx, nWaterRows, nPlateRows;
};

//- Layout of a mesh of about nElements triangles: nx ny = nElements/2 with
//  ny about 2 nx (the tutorial's water column is twice as high as wide); nx
//  is the largest divisor of nElements/2 near sqrt(nElements/4), so the
//  count is exact for 1e4, 1e5 and 1e6
layout layoutFor(const label nElements)
{
    const label nCells = std::max<label>(1, nElements/2);
    const label nxTarget = std::max<label>(1, std::lround(std::sqrt(0.5*nCells)));
    label nx = nxTarget;
    while (nx > nxTarget/2 && nCells % nx) --nx;
    if (nCells % nx) nx = nxTarget;     // no divisor close by: approximate
    const label ny = std::max<label>(2, std::lround(double(nCells)/nx));
    const label nPlate = std::max<label>(1, std::lround(solidFraction*ny));
    return {nx, ny - nPlate, nPlate};
}

//- The mesh: plate [0, 1] x [-t, 0] below water [0, 1] x [0, H]
Foam::triMesh mesh(const label nElements)
{
    const layout l = layoutFor(nElements);
    const double h = 1.0/l.nx;
    return testMeshes::build
    (
        {
            {0, 1, 0, l.nWaterRows*h, int(l.nx), int(l.nWaterRows), "water"},
            {0, 1, -l.nPlateRows*h, 0, int(l.nx), int(l.nPlateRows), "plate"}
        },
        testMeshes::split::alternating,
        [](double, double my, double nx, double ny) -> std::string
        {
            if (std::abs(nx) > 0.5) return my < 0 ? "plateEnds" : "walls";
            return ny < 0 ? "plateBottom" : "top";
        }
    );
}

//- The model on a mesh: materials, boundary conditions, gravity
std::unique_ptr<elementModel> model(const Foam::triMesh& m)
{
    std::unique_ptr<elementModel> em = testModels::model
    (
        m,
        {{"water", testModels::water}, {"plate", plateSolid}},
        {
            {"plateEnds", Foam::patchType::clamped},
            {"walls", Foam::patchType::slipWall}
        }
    );
    em->setGravity(0, -9.81);
    return em;
}

//- Models by requested element count, built once per count, kept for the
//  whole run so that no benchmark times or repeats a construction
elementModel& cached(const label nElements)
{
    static std::map<label, std::unique_ptr<elementModel>> models;
    std::unique_ptr<elementModel>& em = models[nElements];
    if (!em)
    {
        em = model(mesh(nElements));
        malloc_trim(0);
    }
    return *em;
}

//- Water and plate at rest in the reference configuration
void setRest(elementModel& em)
{
    em.setState
    (
        em.referencePositions(), std::vector<scalar>(2*em.nNodes(), 0)
    );
}

//- One explicit step as spemFoam takes it
inline bool step(elementModel& em)
{
    return em.evaluate() && em.advance(0.5*em.stableDeltaT());
}


//- The plate alone, as the solid sub-steps see it (solidSubCycling): a
//  strip 1 m long of 4 rows of square cells (two triangles each), nElements
//  /8 columns, clamped ends, gravity on; its loops are those of a sub-step
//  of a plate of nElements elements
elementModel& cachedPlate(const label nElements)
{
    static std::map<label, std::unique_ptr<elementModel>> models;
    std::unique_ptr<elementModel>& em = models[nElements];
    if (!em)
    {
        const label rows = 4;
        const label nx = std::max<label>(1, nElements/(2*rows));
        const double h = 1.0/nx;
        em = testModels::model
        (
            testMeshes::build
            (
                {{0, 1, -rows*h, 0, int(nx), int(rows), "plate"}},
                testMeshes::split::alternating,
                [](double, double, double nx, double) -> std::string
                {
                    return std::abs(nx) > 0.5 ? "plateEnds" : "free";
                }
            ),
            {{"plate", plateSolid}},
            {{"plateEnds", Foam::patchType::clamped}}
        );
        em->setGravity(0, -9.81);
    }
    return *em;
}

} // End namespace plateCase


// * * * * * * * * * * * * * * * * Benchmarks  * * * * * * * * * * * * * * * //

namespace
{

//- Steps taken before timing: first touch of the pages, OpenMP thread
//  start-up, caches
const int warmUpSteps = 5;

//- Model at rest, thread count set, warmed up; nullptr after an error
elementModel* prepare(benchmark::State& state)
{
    elementModel& em = plateCase::cached(state.range(0));
    omp_set_num_threads(int(state.range(1)));
    plateCase::setRest(em);
    for (int i = 0; i < warmUpSteps; ++i)
    {
        if (!plateCase::step(em))
        {
            state.SkipWithError(em.failure().c_str());
            return nullptr;
        }
    }
    return &em;
}

void setCounters(benchmark::State& state, const elementModel& em)
{
    using benchmark::Counter;
    const double elementSteps = double(state.iterations())*em.nElements();
    state.SetItemsProcessed(int64_t(elementSteps));
    state.counters["elementSteps"] = Counter(elementSteps, Counter::kIsRate);
    state.counters["secondsPerElementStep"] =
        Counter(elementSteps, Counter::kIsRate | Counter::kInvert);
    state.counters["elements"] = em.nElements();
    state.counters["nodes"] = em.nNodes();
    state.counters["domains"] = em.nDomains();
}

//- A full element step: evaluate() + advance(dt)
void fullStep(benchmark::State& state)
{
    elementModel* em = prepare(state);
    if (!em) return;
    for (auto _ : state)
    {
        if (!plateCase::step(*em))
        {
            state.SkipWithError(em->failure().c_str());
            break;
        }
    }
    setCounters(state, *em);
}

//- The three element/domain passes alone (evaluate() is a function of the
//  state, so repeating it at a fixed state times it fairly)
void evaluateOnly(benchmark::State& state)
{
    elementModel* em = prepare(state);
    if (!em) return;
    for (auto _ : state)
    {
        if (!em->evaluate())
        {
            state.SkipWithError(em->failure().c_str());
            break;
        }
    }
    setCounters(state, *em);
}

//- The nodal gather and update alone, with the forces of one evaluate()
void advanceOnly(benchmark::State& state)
{
    elementModel* em = prepare(state);
    if (!em || !em->evaluate()) return;
    const scalar dt = 0.5*em->stableDeltaT();
    for (auto _ : state)
    {
        if (!em->advance(dt))
        {
            state.SkipWithError(em->failure().c_str());
            break;
        }
    }
    setCounters(state, *em);
}

//- A step of the plate alone: the loops of one solid sub-step, at the
//  plate sizes of the tutorials (hydrostaticElasticPlate: 320 elements at
//  nx 40, 1280 at nx 80), to measure where two threads start to pay
//  (minParallelLoop)
void plateStep(benchmark::State& state)
{
    elementModel& em = plateCase::cachedPlate(state.range(0));
    omp_set_num_threads(int(state.range(1)));
    plateCase::setRest(em);
    for (int i = 0; i < warmUpSteps; ++i) plateCase::step(em);
    for (auto _ : state)
    {
        if (!plateCase::step(em))
        {
            state.SkipWithError(em.failure().c_str());
            break;
        }
    }
    setCounters(state, em);
}

//- The solid sub-steps of a fluid step as spemFoam takes them
//  (spemMethod::advanceElements): advanceFluidPartition(dt), then
//  subStepsPerStep sub-steps of the plate alone, every thread of the
//  benchmark's count in one parallel region sharing the passes (on one
//  thread, none), to measure where a team starts to pay
//  (minParallelSolid). Time per sub-step: the time column over
//  subStepsPerStep
const int subStepsPerStep = 100;

void plateSubSteps(benchmark::State& state)
{
    elementModel& em = plateCase::cachedPlate(state.range(0));
    const int nThreads = int(state.range(1));
    omp_set_num_threads(nThreads);
    plateCase::setRest(em);
    if (!em.evaluate())
    {
        state.SkipWithError(em.failure().c_str());
        return;
    }
    const scalar dt = subStepsPerStep*0.3*em.solidStableDeltaT();
    const scalar subDt = dt/subStepsPerStep;
    bool ok = true;
    for (auto _ : state)
    {
        ok = em.advanceFluidPartition(dt);
        Foam::threadTeam team;
        #pragma omp parallel if(nThreads > 1)
        for (int j = 0; ok && j < subStepsPerStep; ++j)
        {
            const bool evaluated =
                j == 0 || em.evaluateSolids(j*subDt, team);
            const bool advanced =
                evaluated && em.advanceSolidSubStep(subDt, j*subDt, dt, team);
            if (team.rank() == 0) ok = advanced;
            team.sync();
        }
        if (!ok)
        {
            state.SkipWithError(em.failure().c_str());
            break;
        }
    }
    setCounters(state, em);
    state.counters["elementSteps"] = benchmark::Counter
    (
        double(state.iterations())*subStepsPerStep*em.nElements(),
        benchmark::Counter::kIsRate
    );
}

//- Plate elements {250 ... 16000} outer, threads {1, 2} inner
void plateElementsAndThreads(benchmark::internal::Benchmark* b)
{
    b->ArgNames({"elements", "threads"});
    for (const int64_t n : {256, 512, 1024, 2048, 4096, 8192, 16384})
    {
        for (const int64_t t : {1, 2}) b->Args({n, t});
    }
}

//- Elements {1e4, 1e5, 1e6} outer, threads {1, 2} inner: the order the
//  models are first needed in
void elementsAndThreads(benchmark::internal::Benchmark* b)
{
    b->ArgNames({"elements", "threads"});
    for (const int64_t n : {10000, 100000, 1000000})
    {
        for (const int64_t t : {1, 2}) b->Args({n, t});
    }
}

//- Largest value over repetitions: for the rate counters (elementSteps)
//  the best repetition; for the time columns the slowest
double largest(const std::vector<double>& v)
{
    return v.empty() ? 0 : *std::max_element(v.begin(), v.end());
}

} // End anonymous namespace


BENCHMARK(fullStep)->Apply(elementsAndThreads)->UseRealTime()
    ->Unit(benchmark::kMillisecond)->ComputeStatistics("max", largest);
BENCHMARK(evaluateOnly)->Apply(elementsAndThreads)->UseRealTime()
    ->Unit(benchmark::kMillisecond)->ComputeStatistics("max", largest);
BENCHMARK(advanceOnly)->Apply(elementsAndThreads)->UseRealTime()
    ->Unit(benchmark::kMillisecond)->ComputeStatistics("max", largest);
BENCHMARK(plateStep)->Apply(plateElementsAndThreads)->UseRealTime()
    ->Unit(benchmark::kMicrosecond)->ComputeStatistics("max", largest);
BENCHMARK(plateSubSteps)->Apply(plateElementsAndThreads)->UseRealTime()
    ->Unit(benchmark::kMicrosecond)->ComputeStatistics("max", largest);


// * * * * * * * * * * * * * * * * * Memory  * * * * * * * * * * * * * * * * //

namespace
{

using benchmarkTools::residentMemory;
using benchmarkTools::readResidentMemory;
using benchmarkTools::resetPeak;

//- One array of the model: name, bytes, touched every step or not
struct modelArray
{
    std::string name;
    double bytes;
    bool hot;
};

//- The arrays of an elementModel (private data of elementModel.H, in its
//  order; keep in step with that header). Arrays with an accessor are
//  measured by capacity(); the others (marked *) are computed from their
//  documented sizes. The total is checked against the measured RSS.
std::vector<modelArray> modelArrays(const elementModel& em)
{
    const double S = sizeof(scalar), L = sizeof(label);
    const double E = em.nElements(), N = em.nNodes(), D = em.nDomains();
    auto bytes = [](const auto& v)
    {
        return double(v.capacity()*sizeof(v[0]));
    };
    return
    {
        {"X_ reference positions", bytes(em.referencePositions()), false},
        {"x_ positions (2 buffers)", 2*bytes(em.positions()), true},
        {"v_ velocities (2 buffers)", 2*bytes(em.velocities()), true},
        {"nodeMass_", bytes(em.nodeMass()), true},
        {"nodeConstraint_ *", N*sizeof(elementModel::constraint), true},
        {"nodeNormal_ *", 2*N*S, true},
        {"nodeReaction_", bytes(em.constraintReactions()), false},
        {"elemNodes_", bytes(em.elementNodes()), true},
        {"elemTriangle_", bytes(em.elementTriangle()), false},
        {"elemDomains_", bytes(em.elementDomains()), true},
        {"elemArea_ *", E*S, true},
        {"elemAreaGrad_ *", 4*E*S, true},
        {"elemForce_ *", 6*E*S, true},
        {"domainElems_ *", 2*D*L, true},
        {"domainArea_", bytes(em.domainArea()), true},
        {"domainMass_", bytes(em.domainMass()), true},
        {"domainGrad_", bytes(em.domainGradient()), true},
        {"domainStress_", bytes(em.domainStress()), true},
        {"nodeElemStart_ *", (N + 1)*L, true},
        {"nodeElems_ *", 3*E*L, true}
    };
}

/*
    Memory per element. Method:
      - OpenMP threads are started first, so their stacks are part of the
        baseline resident set size (RSS) taken before anything is built.
      - The mesh is built (testMeshes::build: std::maps, test-only code,
        whose own peak is reported but is not what spemFoam pays), free heap
        is returned to the kernel (malloc_trim), and the peak (VmHWM) is
        reset to the current RSS by writing 5 to /proc/self/clear_refs.
      - The model is constructed from the mesh: VmHWM is now the
        construction peak with the mesh held by the caller (as spemFoam
        holds it).
      - The mesh is destroyed, free heap returned: RSS - baseline is the
        model alone.
      - VmHWM is reset again, 10 steps are run on 2 threads: VmHWM -
        baseline is the peak while stepping, the steady state of a run.
    All figures are divided by the element count. The model's own arrays
    are also listed by size (modelArrays) as a cross-check on the RSS.
    Without clear_refs (kernel < 4.0) the peaks include every earlier
    stage; this is reported.
*/
int memoryReport(const label nRequested)
{
    const int nSteps = 10;
    omp_set_num_threads(2);
    #pragma omp parallel
    {
        benchmark::DoNotOptimize(omp_get_thread_num());
    }

    const residentMemory baseline = readResidentMemory();
    residentMemory withMesh, constructed, modelOnly, stepping;
    std::unique_ptr<elementModel> em;
    label nTriangles = 0, nEdges = 0;
    bool peakReset = true;
    {
        const Foam::triMesh mesh = plateCase::mesh(nRequested);
        nTriangles = mesh.nTriangles();
        nEdges = mesh.nEdges();
        malloc_trim(0);
        withMesh = readResidentMemory();
        peakReset = resetPeak() && peakReset;
        em = plateCase::model(mesh);
        constructed = readResidentMemory();
    }
    malloc_trim(0);
    modelOnly = readResidentMemory();
    peakReset = resetPeak() && peakReset;
    for (int i = 0; i < nSteps; ++i)
    {
        if (!plateCase::step(*em))
        {
            std::fprintf(stderr, "step %d failed: %s\n", i, em->failure().c_str());
            return 1;
        }
    }
    stepping = readResidentMemory();

    const double E = em->nElements();
    const double MB = 1024*1024;
    std::printf
    (
        "elementModel memory: %ld elements, %ld nodes, %ld domains "
        "(%ld edges), %d steps on 2 threads\n",
        long(em->nElements()), long(em->nNodes()), long(em->nDomains()),
        long(nEdges), nSteps
    );
    if (!peakReset)
    {
        std::printf("warning: /proc/self/clear_refs refused: peaks below "
            "include all earlier stages\n");
    }
    std::printf("%-58s %10s %12s\n", "", "MB", "B/element");
    auto row = [&](const char* what, const double bytes)
    {
        std::printf("%-58s %10.1f %12.1f\n", what, bytes/MB, bytes/E);
    };
    row("baseline RSS (libraries, OpenMP threads)", baseline.rss);
    row("test mesh generator peak above baseline (test code only)",
        withMesh.peak - baseline.peak);
    row("triMesh resident", withMesh.rss - baseline.rss);
    row("construction peak above baseline (mesh held)",
        constructed.peak - baseline.rss);
    row("construction peak above the mesh", constructed.peak - withMesh.rss);
    row("model resident after the mesh is freed", modelOnly.rss - baseline.rss);
    row("peak while stepping (model only)  <- vs 400 B goal",
        stepping.peak - baseline.rss);

    std::printf("\nModel arrays (* size from elementModel.H, hot = touched "
        "every step)\n");
    double total = 0, hot = 0;
    for (const modelArray& a : modelArrays(*em))
    {
        std::printf
        (
            "  %-32s %4s %10.1f MB %8.1f B/element\n",
            a.name.c_str(), a.hot ? "hot" : "", a.bytes/MB, a.bytes/E
        );
        total += a.bytes;
        if (a.hot) hot += a.bytes;
    }
    std::printf("  %-32s %4s %10.1f MB %8.1f B/element\n", "total", "",
        total/MB, total/E);
    std::printf("  %-32s %4s %10.1f MB %8.1f B/element\n", "of which hot", "",
        hot/MB, hot/E);
    if (nTriangles != em->nElements()) return 1;
    return 0;
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * * * Main  * * * * * * * * * * * * * * * * //

int main(int argc, char** argv)
{
    for (int i = 1; i < argc; ++i)
    {
        if (std::string(argv[i]) == "-memory")
        {
            const label n = i + 1 < argc ? label(std::stol(argv[i + 1])) : 1000000;
            return memoryReport(n);
        }
    }

    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}


// ************************************************************************* //
