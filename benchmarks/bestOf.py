#!/usr/bin/env python3
"""Best steps per second of each benchmark over several runs.

On a machine shared with other work the slow repetitions measure the other
work, not the code; the best repetition is the closest to the code's own
speed. Reads the JSON files written by

    elementStepBenchmark --benchmark_repetitions=5 \
        --benchmark_out=run1.json --benchmark_out_format=json

(or particleStepBenchmark) and prints, for each benchmark, the best and median
element- or particle-steps per second (counters elementSteps, particleSteps)
and ns per element- or particle-step over all repetitions of all files, and
the number of repetitions.

    bestOf.py run*.json
"""

import json
import statistics
import sys

# Items-per-second counters of the benchmarks
COUNTERS = ("elementSteps", "particleSteps")


def main(paths):
    rates = {}
    order = []
    for path in paths:
        try:
            with open(path) as f:
                data = json.load(f)
        except (OSError, ValueError) as err:
            print(f"skipping {path}: {err}", file=sys.stderr)
            continue
        for b in data["benchmarks"]:
            counter = next((c for c in COUNTERS if c in b), None)
            if b.get("run_type") != "iteration" or counter is None:
                continue
            name = b["run_name"]
            if name not in rates:
                rates[name] = []
                order.append(name)
            rates[name].append(b[counter])

    width = max((len(n) for n in order), default=10)
    print(f"{'benchmark':<{width}}  {'best [M/s]':>10}  {'best [ns]':>9}  "
          f"{'median [M/s]':>12}  {'median [ns]':>11}  reps")
    for name in order:
        r = rates[name]
        best, median = max(r), statistics.median(r)
        print(f"{name:<{width}}  {best/1e6:10.3f}  {1e9/best:9.1f}  "
              f"{median/1e6:12.3f}  {1e9/median:11.1f}  {len(r):4d}")

if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
