"""Reading function object output of SPEM cases, for the tutorials' plot.py.

A function object writes postProcessing/<name>/<startTime>/<name>.dat:
'#' header lines, then rows "Time value value ...". After a restart there is
one folder per start time; readFunctionObject joins them, later start times
replacing earlier ones from their first time on.

Use from a tutorial's plot.py:

    sys.path.insert(0, os.path.join(os.environ.get("SPEM_PROJECT_DIR",
        os.path.join(scriptDir, "..", "..")), "bin", "tools"))
    from spemPostProcessing import readFunctionObject
"""

import os
import sys


def isNumber(word):
    try:
        float(word)
        return True
    except ValueError:
        return False


def readFunctionObject(caseDir, name, nValues=None):
    """Return (comments, times, rows) of function object `name`.

    comments: the '#' lines of all files (stripped), in file order;
    times: sorted times; rows[k]: the values after Time at times[k].
    Rows with a non-number, or with fewer than nValues values (a killed run
    may leave a partial last line), are skipped. Exits with a message if
    there is no file or no row.
    """
    dataDir = os.path.join(caseDir, "postProcessing", name)
    fileName = name + ".dat"
    startTimes = []
    if os.path.isdir(dataDir):
        startTimes = sorted(
            (d for d in os.listdir(dataDir)
             if isNumber(d)
             and os.path.isfile(os.path.join(dataDir, d, fileName))),
            key=float)
    if not startTimes:
        sys.exit("plot.py: no %s found; run spemFoam first (./Allrun)"
                 % os.path.join(dataDir, "<startTime>", fileName))

    comments = []
    rowsAtTime = {}
    for startTime in startTimes:
        rows = {}
        with open(os.path.join(dataDir, startTime, fileName)) as f:
            for line in f:
                words = line.split()
                if not words:
                    continue
                if words[0].startswith("#"):
                    comments.append(line.strip())
                    continue
                if not all(isNumber(w) for w in words):
                    continue
                if nValues is not None and len(words) < 1 + nValues:
                    continue
                rows[float(words[0])] = [float(w) for w in words[1:]]
        if rows:
            first = min(rows)
            rowsAtTime = {t: r for t, r in rowsAtTime.items() if t < first}
            rowsAtTime.update(rows)

    if not rowsAtTime:
        sys.exit("plot.py: %s holds no data rows" % dataDir)

    times = sorted(rowsAtTime)
    return comments, times, [rowsAtTime[t] for t in times]


def readReference(referenceDir, fileName, required=False):
    """Return the first two columns of referenceDir/fileName as an (n, 2)
    array ('#' comments skipped), or None if the file is missing and not
    required (a note says so); a missing required file exits."""
    path = os.path.join(referenceDir, fileName)
    if not os.path.isfile(path):
        if required:
            sys.exit("plot.py: %s missing" % path)
        print("note: %s not found, left out" % path)
        return None
    import numpy
    return numpy.loadtxt(path, comments="#", ndmin=2)[:, :2]
