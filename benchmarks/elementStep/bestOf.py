#!/usr/bin/env python3
"""Best element-steps per second of each benchmark over several runs.

On a machine shared with other work the slow repetitions measure the other
work, not the code; the best repetition is the closest to the code's own
speed. Reads the JSON files written by

    elementStepBenchmark --benchmark_repetitions=5 \
        --benchmark_out=run1.json --benchmark_out_format=json

and prints, for each benchmark, the best and median element-steps per second
over all repetitions of all files, and the number of repetitions.

    bestOf.py run*.json
"""

import json
import statistics
import sys


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
            if b.get("run_type") != "iteration" or "elementSteps" not in b:
                continue
            name = b["run_name"]
            if name not in rates:
                rates[name] = []
                order.append(name)
            rates[name].append(b["elementSteps"])

    width = max((len(n) for n in order), default=10)
    print(f"{'benchmark':<{width}}  {'best [M/s]':>10}  {'median [M/s]':>12}  reps")
    for name in order:
        r = rates[name]
        print(f"{name:<{width}}  {max(r)/1e6:10.2f}  "
              f"{statistics.median(r)/1e6:12.2f}  {len(r):4d}")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
