#!/usr/bin/env python3
"""wedgeForce.py: the accuracy figures of Table 1 (benchmarks/README.md).

    wedgeForce.py RUN... REFERENCE

Each argument is a finished wedgeWaterEntry run (a case folder with
postProcessing/wedge/0/wedge.dat, e.g. kept by `benchmarks/cases/run
-keep`). For every run it prints the largest vertical force sample, the
peak of the force's 1 ms running mean (the tutorial's plot averages over
1 ms: single samples carry the impact's acoustic ringing) and the speed
at the end; for every run but the last, the RMS difference of its 1 ms
mean curve from the last run's (after 2 ms, relative to the last run's
mean peak). Only the Python standard library.
"""
import bisect
import os
import sys

WINDOW = 1e-3


def load(case):
    """Times, vertical forces and vertical speeds of a run."""
    t, fy, v = [], [], []
    with open(os.path.join(case, "postProcessing/wedge/0/wedge.dat")) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            c = [float(x) for x in line.split()]
            t.append(c[0])
            fy.append(c[8])
            v.append(c[5])
    return t, fy, v


def interp(t, f, x):
    """f at x, linear between the samples (clamped at the ends)."""
    k = bisect.bisect_left(t, x)
    if k <= 0:
        return f[0]
    if k >= len(t):
        return f[-1]
    w = (x - t[k - 1])/(t[k] - t[k - 1])
    return (1 - w)*f[k - 1] + w*f[k]


def runningMean(t, f, step=1e-4, n=40):
    """The mean of f over [x - WINDOW/2, x + WINDOW/2] (trapezoids on n
    intervals), at x every step from t0 + WINDOW/2 to t1 - WINDOW/2."""
    xs, means = [], []
    x = t[0] + WINDOW/2
    while x <= t[-1] - WINDOW/2:
        s = [interp(t, f, x - WINDOW/2 + k*WINDOW/n) for k in range(n + 1)]
        means.append((sum(s) - 0.5*(s[0] + s[-1]))/n)
        xs.append(x)
        x += step
    return xs, means


def main(cases):
    if not cases:
        sys.exit(__doc__)
    curves = {}
    for case in cases:
        t, fy, v = load(case)
        tm, fm = runningMean(t, fy)
        i = max(range(len(fy)), key=fy.__getitem__)
        j = max(range(len(fm)), key=fm.__getitem__)
        curves[case] = (tm, fm)
        print(
            "%s: %d samples, peak Fy %.0f N/m at %.2f ms, peak of the 1 ms"
            " mean %.0f N/m at %.2f ms, V %.4f m/s at %.4f s"
            % (case, len(t), fy[i], 1e3*t[i], fm[j], 1e3*tm[j], -v[-1], t[-1])
        )
    ref = cases[-1]
    tr, fr = curves[ref]
    peak = max(fr)
    for case in cases[:-1]:
        tm, fm = curves[case]
        d = [
            interp(tm, fm, x) - y for x, y in zip(tr, fr)
            if x > 2e-3 and tm[0] <= x <= tm[-1]
        ]
        rms = (sum(e*e for e in d)/max(len(d), 1))**0.5
        print(
            "%s against %s: 1 ms mean peak %+.1f %%, RMS of the 1 ms mean"
            " curves %.1f %% of the reference's peak"
            % (case, ref, 100*(max(fm)/peak - 1), 100*rms/peak)
        )


if __name__ == "__main__":
    main(sys.argv[1:])
