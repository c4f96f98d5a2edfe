#!/usr/bin/env python3
"""Hydrostatic tank: particle pressures against rho g (H - y).

Reads
  - postProcessing/pressure/<startTime>/pressure.dat, written by the
    pressureProbe function object: '# Probe i (x y)' lines, then the
    tab-separated columns Time, p0, p1, ... ('#' starts a comment). After a
    restart there is one folder per start time: all are read, joined and
    sorted by time (later folders win where times overlap);
  - the restart state of the last written time,
    <latestTime>/spem/particlePositions and particleRho (OpenFOAM lists
    of the fluid particles, binary or ascii: a count, then '(' the entries
    ')', or in ascii the uniform form count{value}), and
    0/spem/particlePositions for the
    initial height of the column;
  - rho0, c and initialPressure of the region water in
    constant/spemProperties, g from
    constant/g and the water height H (= W) from system/blockMeshDict. The
    constants below are used where a value cannot be read.

The particle pressure is p = c^2 (rho - rho0) (the equation of state of
weaklyCompressibleNewtonian). The analytical pressure is rho0 g (H - y).
The band table also lists the hydrostatic pressure of the same column made
of the weakly compressible fluid, density rho0 + p/c^2 and the same mass:
    p_wc(y) = rho0 c^2 (exp(g (H' - y)/c^2) - 1),
    H' = (c^2/g) ln(1 + g H/c^2)   (the compressed column's height),
or H' = H for a column started hydrostatic (initialPressure hydrostatic:
the mesh holds the compressed column, its mass is that much larger),
which is what the model can reach at most; the difference between the two
is the fluid's compressibility, not an error of the discretisation.

Writes probePressure.png (probe pressures against time, with the
hydrostatic values) and particlePressure.png (pressure of every fluid
particle at the last written time against y, with the analytical line and
the band means). Prints the probe values averaged over the last 20 % of the
run and the mean particle pressure in 10 horizontal bands with its relative
error (ours - analytical)/analytical.

Usage: python3 plot.py            (from any directory; uses its own folder)
"""

import math
import os
import re
import sys

# The shared reader of function object output (bin/tools)
sys.path.insert(0, os.path.join(
    os.environ.get("SPEM_PROJECT_DIR",
                   os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "..")),
    "bin", "tools"))
from spemPostProcessing import isNumber, readFunctionObject  # noqa: E402
from foamStateFiles import readFoamFile  # noqa: E402

caseDir = os.path.dirname(os.path.abspath(__file__))
probeDir = os.path.join(caseDir, "postProcessing", "pressure")
probePng = os.path.join(caseDir, "probePressure.png")
particlePng = os.path.join(caseDir, "particlePressure.png")

# Used where the case files cannot be read
defaultRho0 = 1000.0    # [kg/m3]
defaultC = 25.0         # [m/s]
defaultG = 9.81         # [m/s2]
defaultH = 0.5          # [m]

# Fraction of the run, at its end, over which the probe pressures are averaged
averagedFraction = 0.2

# Number of horizontal bands of height H/nBands for the particle pressure
nBands = 10


def stripComments(text):
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return re.sub(r"//[^\n]*", " ", text)


def readText(relPath):
    path = os.path.join(caseDir, relPath)
    if not os.path.isfile(path):
        return None
    with open(path) as f:
        return stripComments(f.read())


def readCaseConstants():
    """Return rho0, c, g, H, whether the water starts hydrostatic and a
    list of notes on what was not read."""
    notes = []
    hydrostaticStart = False
    rho0, c, g, H = defaultRho0, defaultC, defaultG, defaultH

    text = readText(os.path.join("constant", "spemProperties"))
    m = text and re.search(r"\bwater\s*\{([^{}]*)\}", text)
    if m:
        block = m.group(1)
        mr = re.search(r"\brho\s+([-+0-9.eE]+)\s*;", block)
        mc = re.search(r"\bc\s+([-+0-9.eE]+)\s*;", block)
        if mr:
            rho0 = float(mr.group(1))
        else:
            notes.append("rho of water not found, rho0 = %g" % rho0)
        hydrostaticStart = bool(
            re.search(r"\binitialPressure\s+hydrostatic\s*;", block))
        if mc:
            c = float(mc.group(1))
        else:
            notes.append("c of water not found, c = %g" % c)
    else:
        notes.append("region water not found in constant/spemProperties, "
                     "rho0 = %g, c = %g" % (rho0, c))

    text = readText(os.path.join("constant", "g"))
    m = text and re.search(r"\bvalue\s*\(\s*([-+0-9.eE]+)\s+([-+0-9.eE]+)"
                           r"\s+([-+0-9.eE]+)\s*\)", text)
    if m:
        g = sum(float(m.group(k))**2 for k in (1, 2, 3))**0.5
    else:
        notes.append("constant/g not read, g = %g" % g)

    text = readText(os.path.join("system", "blockMeshDict"))
    m = text and re.search(r"^\s*W\s+([-+0-9.eE]+)\s*;", text, flags=re.M)
    if m:
        H = float(m.group(1))
    else:
        notes.append("W not found in system/blockMeshDict, H = %g" % H)

    return rho0, c, g, H, hydrostaticStart, notes


def readProbes():
    """Return probe heights, sorted times and one pressure list per probe."""
    comments, rowTimes, rows = readFunctionObject(caseDir, "pressure")
    probeY = {}
    for line in comments:
        m = re.match(r"#\s*Probe\s+(\d+)\s*\(\s*(\S+)\s+(\S+)\s*\)", line)
        if m:
            probeY[int(m.group(1))] = float(m.group(3))

    nProbes = len(probeY)
    complete = [k for k, r in enumerate(rows) if len(r) == nProbes]
    if not complete or nProbes == 0:
        sys.exit("plot.py: %s: no complete rows or no '# Probe' lines"
                 % probeDir)
    times = [rowTimes[k] for k in complete]
    pressures = [[rows[k][i] for k in complete] for i in range(nProbes)]
    return [probeY[i] for i in range(nProbes)], times, pressures


def readFoamList(path):
    """Rows (lists of floats) of an OpenFOAM list file, ascii or binary."""
    if not os.path.isfile(path):
        sys.exit("plot.py: %s not found" % path)
    with open(path, "rb") as f:
        data = f.read()
    header = data[:data.find(b"}", data.find(b"FoamFile")) + 1]
    if re.search(rb"format\s+binary", header):
        listed = readFoamFile(path)
        if listed is None:
            sys.exit("plot.py: %s: not a list" % path)
        cls, values = listed
        nComponents = 3 if cls == "vectorField" else 1
        return [values[k:k + nComponents]
                for k in range(0, len(values), nComponents)]
    text = stripComments(data.decode("latin-1"))
    text = re.sub(r"\bFoamFile\s*\{[^{}]*\}", " ", text)

    # Uniform list: N{value} or N{(x y z)}
    uniform = re.search(r"\b(\d+)\s*\{\s*\(?([^(){}]*)\)?\s*\}", text)
    listed = re.search(r"\b(\d+)\s*\(", text)
    if uniform and (not listed or uniform.start() < listed.start()):
        value = [float(w) for w in uniform.group(2).split()]
        return [value] * int(uniform.group(1))
    if not listed:
        sys.exit("plot.py: %s: no list found" % path)

    n = int(listed.group(1))
    # Entries: numbers or (x y z), up to the list's closing bracket
    body = text[listed.end():]
    rows = []
    for m in re.finditer(r"\(([^()]*)\)|([-+0-9.eE]+)|(\))", body):
        if m.group(3):
            break
        words = (m.group(1) if m.group(1) is not None else m.group(2)).split()
        rows.append([float(w) for w in words])
    if len(rows) != n:
        sys.exit("plot.py: %s: %d entries read, %d announced"
                 % (path, len(rows), n))
    return rows


def latestTime():
    """Name of the last time folder holding spem/particleRho."""
    times = [d for d in os.listdir(caseDir)
             if isNumber(d)
             and os.path.isfile(os.path.join(caseDir, d, "spem",
                                             "particleRho"))]
    if not times:
        sys.exit("plot.py: no <time>/spem/particleRho found; run spemFoam "
                 "first (./Allrun)")
    return max(times, key=float)


def main():
    rho0, c, g, H, hydrostaticStart, notes = readCaseConstants()
    probeY, times, probeP = readProbes()
    tLast = latestTime()
    positions = readFoamList(os.path.join(caseDir, tLast, "spem",
                                          "particlePositions"))
    densities = readFoamList(os.path.join(caseDir, tLast, "spem",
                                          "particleRho"))
    if len(positions) != len(densities):
        sys.exit("plot.py: %s: %d positions but %d densities"
                 % (tLast, len(positions), len(densities)))
    y = [r[1] for r in positions]
    p = [c*c*(r[0] - rho0) for r in densities]

    def hydrostatic(yy):
        return rho0*g*(H - yy)

    # The same column, weakly compressible: rho = rho0 + p/c^2; started
    # hydrostatic, the mesh already holds the compressed column
    Hc = H if hydrostaticStart else c*c/g*math.log(1.0 + g*H/(c*c))

    def compressible(yy):
        return rho0*c*c*(math.exp(g*max(Hc - yy, 0.0)/(c*c)) - 1.0)

    print("case      : %s" % caseDir)
    print("rho0 = %g kg/m3, c = %g m/s, g = %g m/s2, H = %g m, initialPressure"
          " %s" % (rho0, c, g, H,
                   "hydrostatic" if hydrostaticStart else "zero"))
    for note in notes:
        print("note      : %s" % note)

    # Probes: mean over the last averagedFraction of the run
    tStart = times[-1] - averagedFraction*(times[-1] - times[0])
    last = [k for k, t in enumerate(times) if t >= tStart]
    print("\nProbes: %d samples, t = %g .. %g s; mean over t >= %g s"
          % (len(times), times[0], times[-1], tStart))
    print("  %7s %11s %11s %9s" % ("y [m]", "p [Pa]", "rho g(H-y)", "rel.err"))
    probeMean = []
    for yp, series in zip(probeY, probeP):
        mean = sum(series[k] for k in last)/len(last)
        probeMean.append(mean)
        exact = hydrostatic(yp)
        print("  %7.4f %11.1f %11.1f %+8.2f%%"
              % (yp, mean, exact, 100.0*(mean - exact)/exact))

    # Particles in bands of height H/nBands
    print("\nParticles at t = %s s: %d fluid particles, p = c^2 (rho - rho0)"
          % (tLast, len(y)))
    print("  %-15s %5s %8s %9s %10s %9s %9s %9s"
          % ("band y [m]", "n", "mean y", "mean p", "rho g(H-y)", "rel.err",
             "p_wc", "rel.err"))
    bands = []
    dy = H/nBands
    for b in range(nBands):
        y0, y1 = b*dy, (b + 1)*dy
        inBand = [k for k, yk in enumerate(y)
                  if yk >= y0 and (yk < y1 or (b == nBands - 1 and yk <= H))]
        if not inBand:
            print("  %6.3f - %6.3f %5d %8s %9s %10s %9s %9s %9s"
                  % (y0, y1, 0, "-", "-", "-", "-", "-", "-"))
            continue
        yMean = sum(y[k] for k in inBand)/len(inBand)
        pMean = sum(p[k] for k in inBand)/len(inBand)
        exact = hydrostatic(yMean)
        error = (pMean - exact)/exact
        # p_wc is convex in y: average it over the band's particles
        pWc = sum(compressible(y[k]) for k in inBand)/len(inBand)
        bands.append((yMean, pMean, error))
        print("  %6.3f - %6.3f %5d %8.4f %9.1f %10.1f %+8.2f%% %9.1f %+8.2f%%"
              % (y0, y1, len(inBand), yMean, pMean, exact, 100.0*error,
                 pWc, 100.0*(pMean - pWc)/pWc))
    above = sum(1 for yk in y if yk > H)
    if above:
        print("  (%d particles above y = H, not in a band)" % above)
    if bands:
        worst = max(bands, key=lambda b: abs(b[2]))
        print("  max |rel.err| against rho g(H-y): %.2f %% (band at mean y"
              " %.4f m)" % (100.0*abs(worst[2]), worst[0]))
        print("  p_wc: weakly compressible column (c = %g m/s), height"
              " H' = %.5f m" % (c, Hc))

    # Height of the column: now and at t = 0
    initial = os.path.join(caseDir, "0", "spem", "particlePositions")
    if tLast != "0" and os.path.isfile(initial):
        y0 = [r[1] for r in readFoamList(initial)]
        if len(y0) == len(y):
            print("\nColumn: mean particle height %.5f m at t = 0, %.5f m "
                  "at t = %s s (%+.2f mm);"
                  % (sum(y0)/len(y0), sum(y)/len(y), tLast,
                     1e3*(sum(y) - sum(y0))/len(y)))
            print("        highest particle %.5f m at t = 0, %.5f m "
                  "(%+.2f mm)"
                  % (max(y0), max(y), 1e3*(max(y) - max(y0))))
            # A weakly compressible column started at p = 0 settles
            # shorter: on average by about g H^2/(3 c^2), at the top by
            # H - H'; started hydrostatic it has no reason to move
            sink = 0.0 if hydrostaticStart else -1e3*g*H*H/(3*c*c)
            print("        weak compressibility alone: %+.2f mm on average,"
                  " %+.2f mm at the top" % (sink, -1e3*(H - Hc)))

    # Imported here so that a missing result is reported before a missing
    # matplotlib (Debian: apt-get install python3-matplotlib)
    try:
        import matplotlib
    except ImportError:
        sys.exit("plot.py: %s has no matplotlib; try /usr/bin/python3 plot.py"
                 % sys.executable)
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    # Probe pressures against time
    fig, ax = plt.subplots(figsize=(7, 4.5))
    colours = ["tab:blue", "tab:orange", "tab:green", "tab:red",
               "tab:purple", "tab:brown"]
    for k, (yp, series) in enumerate(zip(probeY, probeP)):
        colour = colours[k % len(colours)]
        ax.plot(times, series, "-", color=colour, lw=1,
                label="probe y = %g m" % yp)
        ax.axhline(hydrostatic(yp), color=colour, ls="--", lw=0.8)
    ax.plot([], [], "k--", lw=0.8, label=r"$\rho g (H - y)$")
    ax.axvspan(tStart, times[-1], color="0.92", label="averaged")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("pressure [Pa]")
    ax.set_title("Hydrostatic tank: probe pressures (SPH)")
    ax.set_xlim(0, times[-1])
    ax.legend(loc="lower right", fontsize="small")
    ax.grid(True, lw=0.3)
    fig.tight_layout()
    fig.savefig(probePng, dpi=150)
    plt.close(fig)

    # Particle pressures against height
    fig, ax = plt.subplots(figsize=(5.5, 6))
    ax.plot(p, y, ".", color="0.5", ms=2,
            label="fluid particles, t = %s s" % tLast)
    ax.plot([hydrostatic(0.0), 0.0], [0.0, H], "k-", lw=1,
            label=r"$\rho_0 g (H - y)$")
    yy = [H*k/100.0 for k in range(101)]
    ax.plot([compressible(v) for v in yy], yy, "k:", lw=1,
            label="weakly compressible, c = %g m/s" % c)
    if bands:
        ax.plot([b[1] for b in bands], [b[0] for b in bands], "o",
                color="tab:red", mfc="none", label="band means")
    ax.plot(probeMean, probeY, "s", color="tab:blue", mfc="none",
            label="probes (time mean)")
    ax.set_xlabel("pressure [Pa]")
    ax.set_ylabel("y [m]")
    ax.set_title("Hydrostatic tank: particle pressure (SPH)")
    ax.set_ylim(0, 1.05*H)
    ax.legend(loc="upper right", fontsize="small")
    ax.grid(True, lw=0.3)
    fig.tight_layout()
    fig.savefig(particlePng, dpi=150)
    plt.close(fig)

    print("\nwritten %s" % probePng)
    print("written %s" % particlePng)


if __name__ == "__main__":
    main()
