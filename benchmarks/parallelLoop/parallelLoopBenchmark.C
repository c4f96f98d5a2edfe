/*---------------------------------------------------------------------------*\
Description
    What a loop over a few items costs per call: the OpenMP form the
    libSPEM loops had (`#pragma omp parallel for if(n > minParallelLoop)`,
    which still enters a parallel region when the if-clause is false) and
    parallelFor of src/SPEM/core/parallelLoop (a plain loop below
    minParallelLoop). The loops of one item are what the solids' sub-steps
    called per smoothing domain (the material's stress of each domain next
    to the fluid, at every sub-step); see benchmarks/README.md.

    parallelLoopBenchmark                      # 1, 16 and 256 items
    parallelLoopBenchmark --benchmark_repetitions=5

\*---------------------------------------------------------------------------*/

#include "parallelLoop.H"

#include <benchmark/benchmark.h>

#include <vector>

using namespace Foam;

namespace
{

// Out of line, as the materials' stress is (a virtual call)
__attribute__((noinline)) void pragmaLoop(double* a, const label n)
{
    #pragma omp parallel for schedule(static) if(n > minParallelLoop)
    for (label k = 0; k < n; ++k) a[k] = 1.0000001*a[k] + 1;
}

__attribute__((noinline)) void helperLoop(double* a, const label n)
{
    parallelFor(0, n, [&](const label k) { a[k] = 1.0000001*a[k] + 1; });
}

template<void (*Loop)(double*, label)>
void loopCall(benchmark::State& state)
{
    const label n = state.range(0);
    std::vector<double> a(n, 1);
    for (auto _ : state)
    {
        Loop(a.data(), n);
        benchmark::DoNotOptimize(a.data());
    }
    state.counters["items"] = double(n);
}

} // End anonymous namespace

BENCHMARK_TEMPLATE(loopCall, pragmaLoop)->Arg(1)->Arg(16)->Arg(256);
BENCHMARK_TEMPLATE(loopCall, helperLoop)->Arg(1)->Arg(16)->Arg(256);

BENCHMARK_MAIN();

// ************************************************************************* //
