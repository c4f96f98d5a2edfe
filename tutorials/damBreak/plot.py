#!/usr/bin/env python3
"""Dam break: surge front and column height against the experiments.

Reads <case>/postProcessing/surgeFront/<startTime>/surgeFront.dat (columns
Time, front, height, tab-separated, '#' starts a comment): front is the x of
the leading fluid particle measured from the back wall [m], height the height
of the water at the back wall [m]. After a restart there is one folder per
start time: all are read, joined and sorted by time (later folders win where
times overlap).

The experimental data come from referenceData/ next to this script (see
referenceData/README.md). Our curves are scaled as the data are:

    surge front     T = t sqrt(2 g / a)    Z = front / a
    column height   T = t sqrt(g / a)      H = height / (n2 a)

Writes surgeFront.png and columnHeight.png into the case folder. For each
experimental surge-front point with Z < L/a (front not yet at the far wall)
prints our Z interpolated at the same T and the relative error
(ours - experiment)/experiment, then the largest one.

Usage: python3 plot.py [--case DIR] [--a 0.146] [--n2 2] [--g 9.81]
                       [--L 0.584]
"""

import argparse
import math
import os
import sys

# The shared reader of function object output (bin/tools)
sys.path.insert(0, os.path.join(
    os.environ.get("SPEM_PROJECT_DIR",
                   os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "..")),
    "bin", "tools"))
from spemPostProcessing import readFunctionObject, readReference  # noqa: E402

np = None   # numpy, imported in main() once the results have been found

scriptDir = os.path.dirname(os.path.abspath(__file__))
referenceDir = os.path.join(scriptDir, "referenceData")

# name in the legend, file in referenceData/, marker
surgeFrontData = [
    ("Martin & Moyce (1952), n$^2$ = 2",
     "MartinMoyce1952_surgeFront.dat", "o"),
    ("Koshizuka & Oka (1996)",
     "KoshizukaOka1996_surgeFront.dat", "s"),
]
columnHeightData = [
    ("Martin & Moyce (1952), n$^2$ = 2",
     "MartinMoyce1952_columnHeight.dat", "o"),
]


def parseArguments():
    parser = argparse.ArgumentParser(
        description="Plot the dam-break surge front and column height "
                    "against the experiments of Martin & Moyce (1952) "
                    "and Koshizuka & Oka (1996).")
    parser.add_argument("--case", default=".",
                        help="case folder (default: .)")
    parser.add_argument("--a", type=float, default=0.146,
                        help="initial column width a [m] (default: 0.146)")
    parser.add_argument("--n2", type=float, default=2.0,
                        help="initial column height / width (default: 2)")
    parser.add_argument("--g", type=float, default=9.81,
                        help="gravity [m/s2] (default: 9.81)")
    parser.add_argument("--L", type=float, default=0.584,
                        help="tank length, back wall to far wall [m] "
                             "(default: 0.584)")
    return parser.parse_args()


def readSurgeFront(caseDir):
    """Return lists (time, front, height) from all start-time folders."""
    comments, times, rows = readFunctionObject(caseDir, "surgeFront", 2)
    return times, [r[0] for r in rows], [r[1] for r in rows]


def compareSurgeFront(name, data, T, Z, Zwall):
    """Print our Z at the experimental T; return the largest |error|."""
    print("\n%s: surge front, points with Z < L/a = %g" % (name, Zwall))
    print("  %7s %8s %8s %9s" % ("T", "Z exp", "Z ours", "rel.err"))
    worst = None
    for Te, Ze in data:
        if Ze >= Zwall:
            continue
        if Te < T[0] or Te > T[-1]:
            print("  %7.3f %8.3f %8s %9s" % (Te, Ze, "-", "(no run)"))
            continue
        Zi = float(np.interp(Te, T, Z))
        error = (Zi - Ze)/Ze
        print("  %7.3f %8.3f %8.3f %+8.2f%%" % (Te, Ze, Zi, 100.0*error))
        if worst is None or abs(error) > abs(worst):
            worst = error
    if worst is None:
        print("  max relative error: none (no point inside the run)")
    else:
        print("  max relative error: %+.2f %%" % (100.0*worst))
    return worst


def main():
    global np
    args = parseArguments()
    caseDir = os.path.abspath(args.case)
    a, n2, g, L = args.a, args.n2, args.g, args.L

    times, front, height = readSurgeFront(caseDir)

    # Imported here so that a missing result is reported before a missing
    # numpy or matplotlib (Debian: apt-get install python3-matplotlib)
    try:
        import numpy
    except ImportError:
        sys.exit("plot.py: %s has no numpy; try /usr/bin/python3 plot.py"
                 % sys.executable)
    np = numpy
    times, front, height = np.array(times), np.array(front), np.array(height)

    # Nondimensional as the experimental data (referenceData/README.md)
    Tfront = times*math.sqrt(2.0*g/a)
    Z = front/a
    Theight = times*math.sqrt(g/a)
    H = height/(n2*a)
    Zwall = L/a

    print("case     : %s" % caseDir)
    print("samples  : %d, t = %g .. %g s" % (len(times), times[0], times[-1]))
    print("a = %g m, n2 = %g, g = %g m/s2, L = %g m (far wall at Z = %g)"
          % (a, n2, g, L, Zwall))
    if abs(n2 - 2.0) > 1e-9:
        print("note: the experiments are for n2 = 2; Martin & Moyce scale "
              "the front time as t sqrt(n2 g/a), here t sqrt(2 g/a) is kept")

    surgeFrontRefs = []
    for i, (name, fileName, marker) in enumerate(surgeFrontData):
        data = readReference(referenceDir, fileName, required=(i == 0))
        if data is not None:
            surgeFrontRefs.append((name, data, marker))
    columnHeightRefs = []
    for name, fileName, marker in columnHeightData:
        columnHeightRefs.append(
            (name, readReference(referenceDir, fileName, required=True), marker))

    worstAll = None
    for name, data, marker in surgeFrontRefs:
        worst = compareSurgeFront(name.replace("$^2$", "^2"), data,
                                  Tfront, Z, Zwall)
        if worst is not None and (worstAll is None
                                  or abs(worst) > abs(worstAll)):
            worstAll = worst
    if worstAll is not None and len(surgeFrontRefs) > 1:
        print("\nmax relative error, all surge-front data: %+.2f %%"
              % (100.0*worstAll))

    try:
        import matplotlib
    except ImportError:
        sys.exit("plot.py: %s has no matplotlib; try /usr/bin/python3 plot.py"
                 % sys.executable)
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    # Surge front
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(Tfront, Z, "k-", lw=1.2, label="simulation, leading particle")
    for name, data, marker in surgeFrontRefs:
        ax.plot(data[:, 0], data[:, 1], marker, ls="none", mfc="none",
                label=name)
    ax.axhline(Zwall, color="0.5", ls="--", lw=0.8,
               label="far wall, Z = L/a = %.3g" % Zwall)
    ax.set_xlabel(r"$T = t\,\sqrt{2g/a}$")
    ax.set_ylabel(r"$Z = z/a$")
    ax.set_title("Dam break: surge front (a = %g m, n$^2$ = %g)" % (a, n2))
    # Up to the last experimental point or, if later, our wall impact
    Tright = max(data[-1, 0] for _, data, _ in surgeFrontRefs)
    atWall = np.nonzero(Z >= Zwall)[0]
    if len(atWall):
        Tright = max(Tright, Tfront[atWall[0]])
    ax.set_xlim(0.0, 1.1*Tright)
    ax.set_ylim(0.9, 1.1*max(Zwall, max(data[:, 1].max()
                                        for _, data, _ in surgeFrontRefs)))
    ax.legend(loc="best", fontsize="small")
    ax.grid(True, lw=0.3)
    fig.tight_layout()
    pngFile = os.path.join(caseDir, "surgeFront.png")
    fig.savefig(pngFile, dpi=150)
    plt.close(fig)
    print("\nwritten %s" % pngFile)

    # Column height at the back wall
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(Theight, H, "k-", lw=1.2, label="simulation, at the back wall")
    for name, data, marker in columnHeightRefs:
        ax.plot(data[:, 0], data[:, 1], marker, ls="none", mfc="none",
                label=name)
    ax.set_xlabel(r"$T = t\,\sqrt{g/a}$")
    ax.set_ylabel(r"$H = \eta/(n^2 a)$")
    ax.set_title("Dam break: column height (a = %g m, n$^2$ = %g)"
                 % (a, n2))
    ax.set_xlim(left=0.0)
    ax.set_ylim(bottom=0.0)
    ax.legend(loc="best", fontsize="small")
    ax.grid(True, lw=0.3)
    fig.tight_layout()
    pngFile = os.path.join(caseDir, "columnHeight.png")
    fig.savefig(pngFile, dpi=150)
    plt.close(fig)
    print("written %s" % pngFile)


if __name__ == "__main__":
    main()
