"""Error measures of spemStudy: one function per tutorial, against the
published or analytical data of its referenceData/, and a generic one
against the finest run of the study.

Each measure takes the run's case folder (and, for 'finest', the finest
run's) and returns (error, unit, what): error is a non-negative number,
None if the run has no data to measure it.

    surgeFront      damBreak: largest |relative error| of the surge front
                    against Martin & Moyce (1952), Z < L/a, nondimensional
                    as in the tutorial's plot.py
    plateTip        damBreakElasticPlate: RMS of the horizontal tip
                    displacement minus Ryzhakov et al. (2010) at its times
    midSpan         hydrostaticElasticPlate: |relative error| of the
                    mid-span deflection (mean of the last 10 % of the run)
                    against the shear-corrected (Timoshenko) plate theory,
                    which the 2D plate in plane strain converges to (its
                    README; Euler-Bernoulli is 3.5 % stiffer)
    hydrostaticPressure
                    hydrostaticTank: largest |p - rho0 g (H - y)| of its
                    pressure probes (mean of the last 10 % of the run),
                    relative to rho0 g H
    bodyForce       wedgeWaterEntry, cylinderWaterExit, cylinderSinking:
                    RMS difference of the body's vertical force (the
                    rigidBodyState table's Fy) from the reference run's,
                    over the times both cover, relative to the RMS of the
                    reference run's
    surfaceHeight   cylinderWaterExit, cylinderSinking: RMS difference of
                    the free surface's height (the topmost surface of the
                    surfaceProfile function object, y against x, at each
                    of its write times) from the reference run's, over the
                    times both have and the x both cover [m]
    finest          any case: RMS difference of the first column of the
                    first function object in postProcessing/ from the
                    reference run's, over the times both cover, relative
                    to the RMS of the reference run's (0 for itself)

The reference run of bodyForce, surfaceHeight and finest is spemStudy's: in a study of
methods and resolutions, the first method's run at the largest
resolution, so that every method is measured against one run; in a
stability map, the finest run.
"""

import math
import os


def readTable(path):
    """Rows of floats of a '#'-commented table ('(x y z)' vectors split)."""
    rows = []
    with open(path) as f:
        for line in f:
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            words = line.replace("(", " ").replace(")", " ").split()
            try:
                rows.append([float(w) for w in words])
            except ValueError:
                continue
    return rows


def functionObjectFiles(caseDir, name):
    """(start time, path) of postProcessing/<name>/<start>/*.dat, the
    first .dat of each start folder, by start time."""
    base = os.path.join(caseDir, "postProcessing", name)
    if not os.path.isdir(base):
        return []
    files = []
    for start in sorted(os.listdir(base), key=float):
        folder = os.path.join(base, start)
        for fileName in sorted(os.listdir(folder)):
            if fileName.endswith(".dat"):
                files.append((float(start), os.path.join(folder, fileName)))
                break
    return files


def functionObjectRows(caseDir, name):
    """Rows of postProcessing/<name>/<start>/*.dat of every start time,
    sorted by time, a restart's rows replacing the earlier ones."""
    rows = []
    for t0, path in functionObjectFiles(caseDir, name):
        rows = [r for r in rows if r[0] < t0]
        rows += readTable(path)
    return sorted(rows)


def functionObjectHeader(caseDir, name):
    """The leading '#' lines of the function object's first table, or []."""
    files = functionObjectFiles(caseDir, name)
    header = []
    if files:
        with open(files[0][1]) as f:
            for line in f:
                if not line.startswith("#"):
                    break
                header.append(line)
    return header


def interpolate(x, xs, ys):
    """Linear interpolation of (xs, ys) at x, xs ascending."""
    if x <= xs[0]:
        return ys[0]
    if x >= xs[-1]:
        return ys[-1]
    lo, hi = 0, len(xs) - 1
    while hi - lo > 1:
        mid = (lo + hi)//2
        if xs[mid] <= x:
            lo = mid
        else:
            hi = mid
    w = (x - xs[lo])/(xs[hi] - xs[lo]) if xs[hi] > xs[lo] else 0.0
    return ys[lo] + w*(ys[hi] - ys[lo])


def referencePath(caseDir, fileName):
    """referenceData/<fileName> of the case (the study's copy links it)."""
    return os.path.join(caseDir, "referenceData", fileName)


def surgeFront(caseDir, finestDir=None, a=0.146, g=9.81, L=0.584):
    rows = functionObjectRows(caseDir, "surgeFront")
    data = readTable(referencePath(caseDir, "MartinMoyce1952_surgeFront.dat"))
    if not rows or not data:
        return None, "", "surge front vs Martin & Moyce (1952)"
    T = [r[0]*math.sqrt(2*g/a) for r in rows]
    Z = [r[1]/a for r in rows]
    worst = None
    for Te, Ze in ((d[0], d[1]) for d in data):
        if Ze >= L/a or Te < T[0] or Te > T[-1]:
            continue
        error = abs(interpolate(Te, T, Z) - Ze)/Ze
        worst = error if worst is None else max(worst, error)
    return worst, "", "largest relative error of the surge front vs " \
        "Martin & Moyce (1952)"


def plateTip(caseDir, finestDir=None):
    rows = functionObjectRows(caseDir, "plateTip")
    data = readTable(referencePath(caseDir, "Ryzhakov2010_tipDisplacement.dat"))
    if not rows or not data:
        return None, "m", "tip displacement vs Ryzhakov et al. (2010)"
    t = [r[0] for r in rows]
    dx = [r[1] for r in rows]
    inside = [d for d in data if t[0] <= d[0] <= t[-1]]
    if not inside:
        return None, "m", "tip displacement vs Ryzhakov et al. (2010)"
    s = sum((interpolate(d[0], t, dx) - d[1])**2 for d in inside)
    return math.sqrt(s/len(inside)), "m", \
        "RMS of the tip displacement minus Ryzhakov et al. (2010)"


def midSpan(caseDir, finestDir=None, averagedFraction=0.1):
    rows = functionObjectRows(caseDir, "midSpan")
    reference = {}
    path = referencePath(caseDir, "midSpanDeflection.dat")
    if os.path.isfile(path):
        with open(path) as f:
            for line in f:
                words = line.split()
                if len(words) >= 2 and not words[0].startswith("#"):
                    reference[words[0]] = float(words[1])
    what = "relative error of the mid-span deflection vs the " \
        "shear-corrected plate theory"
    if not rows or "Dy_Timoshenko" not in reference:
        return None, "", what
    tStart = rows[-1][0] - averagedFraction*(rows[-1][0] - rows[0][0])
    last = [r[2] for r in rows if r[0] >= tStart]
    dy = sum(last)/len(last)
    ref = reference["Dy_Timoshenko"]
    return abs(dy - ref)/abs(ref), "", what


def firstCurve(caseDir):
    """(name, times, values) of the first function object's first column."""
    base = os.path.join(caseDir, "postProcessing")
    if not os.path.isdir(base):
        return None, [], []
    for name in sorted(os.listdir(base)):
        rows = functionObjectRows(caseDir, name)
        if rows and len(rows[0]) >= 2:
            return name, [r[0] for r in rows], [r[1] for r in rows]
    return None, [], []


def hydrostaticPressure(caseDir, finestDir=None, rho0=1000, g=9.81, H=0.5,
                        averagedFraction=0.1):
    what = "largest |p - rho0 g (H - y)| of the probes, relative to rho0 g H"
    base = os.path.join(caseDir, "postProcessing")
    name = None
    if os.path.isdir(base):
        for n in sorted(os.listdir(base)):
            if functionObjectRows(caseDir, n) and probeHeights(caseDir, n):
                name = n
                break
    if name is None:
        return None, "", what
    rows = functionObjectRows(caseDir, name)
    heights = probeHeights(caseDir, name)
    tStart = rows[-1][0] - averagedFraction*(rows[-1][0] - rows[0][0])
    last = [r for r in rows if r[0] >= tStart]
    worst = 0
    for k, y in enumerate(heights):
        p = sum(r[k + 1] for r in last)/len(last)
        worst = max(worst, abs(p - rho0*g*(H - y))/(rho0*g*H))
    return worst, "", what


def probeHeights(caseDir, name):
    """y of each probe of a pressureProbe table (its '# Probe k (x y)'
    header lines), or [] if the table has none."""
    heights = []
    for line in functionObjectHeader(caseDir, name):
        words = line.replace("(", " ").replace(")", " ").split()
        if len(words) >= 5 and words[1] == "Probe":
            heights.append(float(words[4]))
    return heights


def bodyCurve(caseDir):
    """(times, Fy) of the rigidBodyState table in postProcessing/ (the one
    whose header names Fy), or ([], [])."""
    base = os.path.join(caseDir, "postProcessing")
    if not os.path.isdir(base):
        return [], []
    for name in sorted(os.listdir(base)):
        header = functionObjectHeader(caseDir, name)
        columns = header[0].split() if header else []
        if "Fy" in columns:
            column = columns.index("Fy") - 1
            rows = functionObjectRows(caseDir, name)
            return [r[0] for r in rows], [r[column] for r in rows]
    return [], []


def bodyForce(caseDir, finestDir):
    what = "RMS difference of the body's vertical force from the " \
        "reference run's, relative"
    t, y = bodyCurve(caseDir)
    tF, yF = bodyCurve(finestDir) if finestDir else ([], [])
    if not t or not tF:
        return None, "", what
    return relativeRmsDifference(t, y, tF, yF), "", what


def surfaceProfiles(caseDir, name="surfaceProfile"):
    """{time: (xs, ys)} of the tables postProcessing/<name>/<start>/<time>/
    *.dat (freeSurfaceProfile: x y sorted by x), or {}."""
    base = os.path.join(caseDir, "postProcessing", name)
    profiles = {}
    if not os.path.isdir(base):
        return profiles
    for start in os.listdir(base):
        for time in os.listdir(os.path.join(base, start)):
            folder = os.path.join(base, start, time)
            if not os.path.isdir(folder):
                continue
            for fileName in sorted(os.listdir(folder)):
                if fileName.endswith(".dat"):
                    rows = readTable(os.path.join(folder, fileName))
                    if rows:
                        profiles[float(time)] = ([r[0] for r in rows],
                                                 [r[1] for r in rows])
                    break
    return profiles


def surfaceHeight(caseDir, finestDir):
    """The height of the topmost free surface against the reference run's:
    where the force on a body is dominated by the weakly compressible
    water's pressure waves (the cylinders), the shape of the surface is
    what the method and the resolution change."""
    what = "RMS difference of the free surface's height from the " \
        "reference run's"
    run = surfaceProfiles(caseDir)
    reference = surfaceProfiles(finestDir) if finestDir else {}
    squares, count = 0.0, 0
    for time, (xF, yF) in reference.items():
        match = [t for t in run if abs(t - time) <= 1e-6*max(1.0, abs(time))]
        if not match:
            continue
        xs, ys = run[match[0]]
        if len(xs) < 2:
            continue
        for x, y in zip(xF, yF):
            if xs[0] <= x <= xs[-1]:
                squares += (interpolate(x, xs, ys) - y)**2
                count += 1
    if count == 0:
        return None, "m", what
    return math.sqrt(squares/count), "m", what


def finest(caseDir, finestDir):
    name, t, y = firstCurve(caseDir)
    nameF, tF, yF = firstCurve(finestDir)
    what = "RMS difference from the reference run (%s), relative" % nameF
    if name is None or nameF is None or name != nameF:
        return None, "", what
    return relativeRmsDifference(t, y, tF, yF), "", what


def relativeRmsDifference(t, y, tF, yF):
    """RMS of the curve (t, y), interpolated at the reference's times tF
    that it covers, minus yF, over the RMS of yF there; None if it covers
    none of them (0 if both are 0 there)."""
    common = [(ti, yi) for ti, yi in zip(tF, yF) if t[0] <= ti <= t[-1]]
    if not common:
        return None
    diff = sum((interpolate(ti, t, y) - yi)**2 for ti, yi in common)
    norm = sum(yi**2 for ti, yi in common)
    if norm == 0:
        return 0.0 if diff == 0 else None
    return math.sqrt(diff/norm)


measures = {
    "surgeFront": surgeFront,
    "plateTip": plateTip,
    "midSpan": midSpan,
    "hydrostaticPressure": hydrostaticPressure,
    "bodyForce": bodyForce,
    "surfaceHeight": surfaceHeight,
    "finest": finest,
}

#- The measures that compare a run with the study's reference run
referenceMeasures = ("bodyForce", "surfaceHeight", "finest")

#- The measure of each tutorial when spemStudyDict names none
tutorialMeasures = {
    "damBreak": "surgeFront",
    "damBreakElasticPlate": "plateTip",
    "hydrostaticElasticPlate": "midSpan",
    "hydrostaticTank": "hydrostaticPressure",
    "wedgeWaterEntry": "bodyForce",
    "cylinderWaterExit": "surfaceHeight",
    "cylinderSinking": "surfaceHeight",
}
