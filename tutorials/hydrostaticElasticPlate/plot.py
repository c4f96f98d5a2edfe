#!/usr/bin/env python3
"""Plate mid-span deflection against the analytical static values.

Reads postProcessing/midSpan/<startTime>/midSpan.dat (tab-separated columns
Time, Dx, Dy; '#' starts a comment) written by the pointDisplacement function
object. After a restart there is one folder per start time: all are read,
joined and sorted by time (later folders win where times overlap). The
reference values come from referenceData/midSpanDeflection.dat.

Writes midSpanDeflection.png and prints the mean of Dy over the last 10 % of
the run, the analytical values and the relative errors.

Usage: python3 plot.py            (from any directory; uses its own folder)
"""

import os
import sys

# The shared reader of function object output (bin/tools)
sys.path.insert(0, os.path.join(
    os.environ.get("SPEM_PROJECT_DIR",
                   os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "..")),
    "bin", "tools"))
from spemPostProcessing import readFunctionObject  # noqa: E402

caseDir = os.path.dirname(os.path.abspath(__file__))
referenceFile = os.path.join(caseDir, "referenceData", "midSpanDeflection.dat")
pngFile = os.path.join(caseDir, "midSpanDeflection.png")

# Fraction of the run, at its end, over which Dy is averaged
averagedFraction = 0.1


def readMidSpan():
    """Return sorted lists (time, Dy) from all start-time folders."""
    comments, times, rows = readFunctionObject(caseDir, "midSpan", 2)
    return times, [r[1] for r in rows]


def readReference():
    """Return {quantity: value} from referenceData/midSpanDeflection.dat."""
    if not os.path.isfile(referenceFile):
        sys.exit("plot.py: %s missing; run python3 referenceData/analytical.py"
                 % referenceFile)
    reference = {}
    with open(referenceFile) as f:
        for line in f:
            words = line.split()
            if len(words) >= 2 and not words[0].startswith("#"):
                reference[words[0]] = float(words[1])
    return reference


def main():
    times, dy = readMidSpan()
    reference = readReference()
    dyEB = reference["Dy_EulerBernoulli"]
    dyT = reference["Dy_Timoshenko"]

    # Mean over the last 10 % of the run (in time, from the first sample)
    tStart = times[-1] - averagedFraction*(times[-1] - times[0])
    last = [d for t, d in zip(times, dy) if t >= tStart]
    dyFinal = sum(last)/len(last)

    print("samples                : %d, t = %g .. %g s"
          % (len(times), times[0], times[-1]))
    print("Dy mean over t >= %-5g: %.4e m  (%d samples)"
          % (tStart, dyFinal, len(last)))
    # Relative error (ours - reference)/reference: > 0 deflects more
    for name, value in (("Euler-Bernoulli", dyEB), ("Timoshenko", dyT)):
        print("Dy %-16s    : %.4e m  relative error %+.2f %%"
              % (name, value, 100.0*(dyFinal - value)/value))

    # Imported here so that a missing result is reported before a missing
    # matplotlib (Debian: apt-get install python3-matplotlib)
    try:
        import matplotlib
    except ImportError:
        sys.exit("plot.py: %s has no matplotlib; try /usr/bin/python3 plot.py"
                 % sys.executable)
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(times, [1e6*d for d in dy], "k-", lw=1, label="SPEM, mid-span")
    ax.axhline(1e6*dyEB, color="tab:blue", ls="--",
               label="Euler-Bernoulli, %.3e m" % dyEB)
    ax.axhline(1e6*dyT, color="tab:red", ls="-.",
               label="Timoshenko, %.3e m" % dyT)
    ax.axvspan(tStart, times[-1], color="0.9",
               label="averaged: %.3e m" % dyFinal)
    ax.set_xlabel("time [s]")
    ax.set_ylabel(r"$D_y$ at (L/2, -t/2) [$\mu$m]")
    ax.set_title("Hydrostatic water column on a clamped elastic plate")
    ax.legend(loc="best", fontsize="small")
    ax.grid(True, lw=0.3)
    fig.tight_layout()
    fig.savefig(pngFile, dpi=150)
    print("written %s" % pngFile)


if __name__ == "__main__":
    main()
