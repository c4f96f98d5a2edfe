"""Free-surface profiles and force of the cylinder tutorials
(cylinderWaterExit, cylinderSinking): the plotting both plot.py scripts
share; each sets its title, direction and panel times and calls main().

Reads, in <case>/postProcessing/,
  surfaceProfile/<startTime>/<time>/surfaceProfile.dat   (x y; the highest
      surface point per particle spacing, a single-valued curve y(x))
  freeSurface/<startTime>/<time>/freeSurface.dat         (x y; every
      free-surface particle and free element node)
  cylinder/<startTime>/cylinder.dat                      (rigidBodyState:
      Time x y angle u v omega Fx Fy Mz)
and V0 and d from system/controlDict; T = V0 t/d.
"""

import argparse
import glob
import os
import re
import sys

from spemPostProcessing import readFunctionObject, isNumber

# Reference profiles: (legend, file pattern with {T} as in "T0.2", style).
# Each file would hold two columns, x [m] and y [m] (see
# referenceData/README.md); none is shipped yet.
referenceData = [
    ("Lin (1984)", "Lin1984_T{T}.dat", "-"),
    ("Greenhow & Moyo (1997)", "GreenhowMoyo1997_T{T}.dat", "--"),
    ("Tyvand & Miloh (1995)", "TyvandMiloh1995_T{T}.dat", ":"),
]


def parseArguments(description, scriptDir):
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--case", default=scriptDir,
                        help="case folder (default: the script's folder)")
    return parser.parse_args()


def controlValue(caseDir, key):
    """A plain number entry of system/controlDict."""
    with open(os.path.join(caseDir, "system", "controlDict")) as f:
        for line in f:
            m = re.match(r"\s*%s\s+([-+0-9.eE]+)\s*;" % key, line)
            if m:
                return float(m.group(1))
    sys.exit("plot.py: no '%s <number>;' in system/controlDict" % key)


def profileTimes(caseDir, name):
    """{time: file} of a freeSurfaceProfile function object."""
    files = {}
    for startDir in glob.glob(os.path.join(caseDir, "postProcessing", name,
                                           "*")):
        if not isNumber(os.path.basename(startDir)):
            continue
        for timeDir in glob.glob(os.path.join(startDir, "*")):
            path = os.path.join(timeDir, name + ".dat")
            if isNumber(os.path.basename(timeDir)) and os.path.isfile(path):
                files[float(os.path.basename(timeDir))] = path
    return files


def load(np, path):
    data = np.loadtxt(path, comments="#", ndmin=2)
    return data.reshape(-1, 2) if data.size else np.zeros((0, 2))


def nearest(files, t, tolerance):
    """The file of the time closest to t, if within tolerance."""
    if not files:
        return None
    best = min(files, key=lambda s: abs(s - t))
    return files[best] if abs(best - t) <= tolerance else None


def main(description, scriptDir, TITLE, DIRECTION, PANEL_TIMES, Y_LIMITS,
         RADIUS=1.0, RHO=1000.0, G=1.0):
    """Plot a cylinder tutorial run: TITLE for the figures, DIRECTION +1
    (pulled up) or -1 (pushed down), the profiles at PANEL_TIMES (T), each
    panel over Y_LIMITS; RADIUS, RHO and G as in the case's
    constant/rigidBodyProperties, spemProperties and g."""
    referenceDir = os.path.join(scriptDir, "referenceData")
    args = parseArguments(description, scriptDir)
    caseDir = os.path.abspath(args.case)
    V0 = controlValue(caseDir, "V0")
    d = controlValue(caseDir, "d")
    timeScale = d/V0

    profiles = profileTimes(caseDir, "surfaceProfile")
    points = profileTimes(caseDir, "freeSurface")
    if not profiles:
        sys.exit("plot.py: no postProcessing/surfaceProfile/<startTime>/"
                 "<time>/surfaceProfile.dat; run spemFoam first (./Allrun)")
    _, times, rows = readFunctionObject(caseDir, "cylinder", 9)

    try:
        import numpy as np
        import matplotlib
    except ImportError:
        sys.exit("plot.py: %s has no numpy/matplotlib; try /usr/bin/python3"
                 " plot.py" % sys.executable)
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    print("case     : %s" % caseDir)
    print("V0 = %g m/s, d = %g m, d/V0 = %.6g s; profiles at T = %s"
          % (V0, d, timeScale,
             ", ".join("%.3g" % (t/timeScale) for t in sorted(profiles))))

    # Free-surface panels
    fig, axes = plt.subplots(len(PANEL_TIMES), 1, sharex=True,
                             figsize=(7, 2.0*len(PANEL_TIMES) + 0.6))
    theta = np.linspace(0, 2*np.pi, 200)
    for ax, T in zip(axes, PANEL_TIMES):
        t = T*timeScale
        yc = -d + DIRECTION*V0*t
        ax.fill(RADIUS*np.cos(theta), yc + RADIUS*np.sin(theta),
                color="0.8", ec="0.4", lw=0.8)
        ax.axhline(0.0, color="0.75", lw=0.5, ls=":")
        tol = 0.02*timeScale
        pointFile = nearest(points, t, tol)
        profileFile = nearest(profiles, t, tol)
        label = "T = %.1f" % T
        if pointFile:
            xy = load(np, pointFile)
            ax.plot(xy[:, 0], xy[:, 1], ".", ms=1.5, color="tab:blue",
                    label="SPEM surface points")
        if profileFile:
            xy = load(np, profileFile)
            ax.plot(xy[:, 0], xy[:, 1], "-", lw=1.0, color="k",
                    label="SPEM profile (highest point per bin)")
            top = xy[np.abs(xy[:, 0]) < RADIUS/4]
            summary = []
            if len(top):
                summary.append("top of the water above the cylinder "
                               "y = %.3f m (cylinder top %.3f m)"
                               % (top[:, 1].max(), yc + RADIUS))
            for x0 in (-4*RADIUS, -2*RADIUS, 2*RADIUS, 4*RADIUS):
                near = xy[np.abs(xy[:, 0] - x0) < 0.1]
                if len(near):
                    summary.append("y(%+.0f) = %.3f" % (x0, near[0, 1]))
            print("T = %.1f: %s" % (T, "; ".join(summary)))
        else:
            label += " (not written)"
            print("T = %.1f: no profile written" % T)
        for name, pattern, style in referenceData:
            path = os.path.join(referenceDir, pattern.format(T="%.1f" % T))
            if os.path.isfile(path):
                ref = load(np, path)
                ax.plot(ref[:, 0], ref[:, 1], ls=style, color="tab:red",
                        lw=1.0, label=name)
        ax.set_aspect("equal")
        ax.set_xlim(-6, 6)
        ax.set_ylim(Y_LIMITS)
        ax.text(0.01, 0.92, label, transform=ax.transAxes, va="top",
                fontsize="small")
        ax.set_ylabel("y [m]")
    axes[0].legend(loc="upper right", fontsize="x-small")
    axes[-1].set_xlabel("x [m]")
    axes[0].set_title(TITLE + ": free surface")
    fig.tight_layout()
    pngFile = os.path.join(caseDir, "freeSurface.png")
    fig.savefig(pngFile, dpi=150)
    plt.close(fig)
    print("written %s" % pngFile)

    # Force
    times = np.array(times)
    rows = np.array(rows)
    Fx, Fy = rows[:, 6], rows[:, 7]
    buoyancy = RHO*G*np.pi*RADIUS**2
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(times/timeScale, Fy, "k-", lw=1.0, label="$F_y$")
    ax.plot(times/timeScale, Fx, color="0.55", lw=0.8, label="$F_x$")
    ax.axhline(buoyancy, color="tab:blue", ls="--", lw=0.8,
               label=r"$\rho g \pi R^2$ (buoyancy when submerged)")
    ax.axhline(0.0, color="0.7", lw=0.5)
    ax.set_xlabel("T = V0 t / d")
    ax.set_ylabel("force of the water on the cylinder [N/m]")
    ax.set_title(TITLE + ": force")
    ax.legend(loc="best", fontsize="small")
    ax.grid(True, lw=0.3)
    fig.tight_layout()
    pngFile = os.path.join(caseDir, "force.png")
    fig.savefig(pngFile, dpi=150)
    plt.close(fig)
    for T in PANEL_TIMES:
        k = np.abs(times/timeScale - T).argmin()
        if abs(times[k]/timeScale - T) < 0.05:
            print("T = %.1f: Fx = %.1f N/m, Fy = %.1f N/m (rho g pi R^2 ="
                  " %.1f)" % (T, Fx[k], Fy[k], buoyancy))
    print("Fy over the run: %.1f .. %.1f N/m" % (Fy.min(), Fy.max()))
    print("written %s" % pngFile)

