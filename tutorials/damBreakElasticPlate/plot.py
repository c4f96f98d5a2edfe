#!/usr/bin/env python3
"""Breaking dam on an elastic plate: the plate's tip displacement.

Reads <case>/postProcessing/plateTip/<startTime>/plateTip.dat (columns Time,
Dx, Dy, tab-separated, '#' starts a comment), written by the
pointDisplacement function object at the plate's upper-left corner. After a
restart there is one folder per start time: all are read, joined and sorted
by time (later folders win where times overlap).

The published curves come from referenceData/ next to this script (see
referenceData/README.md); a missing file is left out with a note, so the
plot shows ours alone if there are none.

Writes plateTip.png into the case folder: Dx (and Dy) against time, with
the reference Dx curves. Prints our peak Dx and its time, each reference's
peak over the same time span, and at the reference times inside our run
the difference ours - reference (largest and RMS).

Usage: python3 plot.py [--case DIR]
"""

import argparse
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

# name in the legend, file in referenceData/, line style
referenceData = [
    ("Meduri et al. (2017)", "Meduri2017_tipDisplacement.dat", "--"),
    ("Ryzhakov et al. (2010)", "Ryzhakov2010_tipDisplacement.dat", ":"),
]


def parseArguments():
    parser = argparse.ArgumentParser(
        description="Plot the plate's upper-left corner displacement "
                    "against the published curves of referenceData/.")
    parser.add_argument("--case", default=scriptDir,
                        help="case folder (default: this script's folder)")
    return parser.parse_args()


def compare(name, data, times, dx):
    """Print the reference's peak and ours - reference at its times."""
    inside = (data[:, 0] >= times[0]) & (data[:, 0] <= times[-1])
    print("\n%s" % name)
    if not inside.any():
        print("  no reference point inside the run (t = %g .. %g s)"
              % (times[0], times[-1]))
        return
    ref = data[inside]
    peak = ref[:, 1].argmax()
    print("  peak Dx %.4f m at t = %.3f s (reference points with t <= %g s)"
          % (ref[peak, 1], ref[peak, 0], times[-1]))
    difference = np.interp(ref[:, 0], times, dx) - ref[:, 1]
    worst = abs(difference).argmax()
    print("  ours - reference at its %d points: largest %+.4f m at t = "
          "%.3f s, RMS %.4f m"
          % (len(ref), difference[worst], ref[worst, 0],
             float(np.sqrt(np.mean(difference**2)))))


def main():
    global np
    args = parseArguments()
    caseDir = os.path.abspath(args.case)

    comments, times, rows = readFunctionObject(caseDir, "plateTip", 2)

    # Imported here so that a missing result is reported before a missing
    # numpy or matplotlib (Debian: apt-get install python3-matplotlib)
    try:
        import numpy
    except ImportError:
        sys.exit("plot.py: %s has no numpy; try /usr/bin/python3 plot.py"
                 % sys.executable)
    np = numpy
    times = np.array(times)
    dx = np.array([r[0] for r in rows])
    dy = np.array([r[1] for r in rows])

    print("case     : %s" % caseDir)
    print("samples  : %d, t = %g .. %g s" % (len(times), times[0], times[-1]))
    peak = dx.argmax()
    print("ours     : peak Dx %.4g m at t = %.3f s; Dx %.4g .. %.4g m, "
          "Dy %.4g .. %.4g m"
          % (dx[peak], times[peak], dx.min(), dx.max(), dy.min(), dy.max()))

    references = []
    for name, fileName, style in referenceData:
        data = readReference(referenceDir, fileName)
        if data is not None:
            references.append((name, data, style))
            compare(name, data, times, dx)
    if not references:
        print("note: no reference data; plotting ours alone")

    try:
        import matplotlib
    except ImportError:
        sys.exit("plot.py: %s has no matplotlib; try /usr/bin/python3 plot.py"
                 % sys.executable)
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(times, dx, "k-", lw=1.4, label="SPEM, $D_x$")
    ax.plot(times, dy, color="0.55", ls="-", lw=1.0, label="SPEM, $D_y$")
    for name, data, style in references:
        ax.plot(data[:, 0], data[:, 1], ls=style, lw=1.2,
                label="%s, $D_x$" % name)
    ax.axhline(0.0, color="0.7", lw=0.6)
    # Our run, at least up to 0.4 s (past the references' first peak)
    tRight = times[-1]
    if references and tRight < 0.4:
        tRight = 0.4
    ax.set_xlim(0.0, tRight)
    # y range of what is shown (the references go on to 1 s)
    shown = [dx, dy] + [data[data[:, 0] <= tRight, 1]
                        for _, data, _ in references]
    yLow = min(float(v.min()) for v in shown if len(v))
    yHigh = max(float(v.max()) for v in shown if len(v))
    margin = 0.05*max(yHigh - yLow, 1e-6)
    ax.set_ylim(yLow - margin, yHigh + margin)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("displacement of the upper-left corner [m]")
    ax.set_title("Breaking dam on an elastic plate: plate tip")
    ax.legend(loc="best", fontsize="small")
    ax.grid(True, lw=0.3)
    fig.tight_layout()
    pngFile = os.path.join(caseDir, "plateTip.png")
    fig.savefig(pngFile, dpi=150)
    plt.close(fig)
    print("\nwritten %s" % pngFile)


if __name__ == "__main__":
    main()
