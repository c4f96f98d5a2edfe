#!/usr/bin/env python3
"""Water entry of a wedge: vertical force, velocity and wall pressures.

Reads, in the case folder, postProcessing/wedge/<startTime>/wedge.dat
(rigidBodyState: Time x y angle u v omega Fx Fy Mz) and
postProcessing/wedgePressure/<startTime>/wedgePressure.dat (pressureProbe
moving with the wedge: Time p0 .. p4). After a restart all start times are
read and joined.

References (referenceData/README.md): no digitised curves of the
experiment of Zhao, Faltinsen & Aarsnes (1996) were found in a public
source, so the force is compared with the two constant-speed similarity
solutions of a wedge before its chines wet,
    F = C rho V^3 t,  C = pi/tan^2(beta) (von Karman),
                      C = pi^3/(4 tan^2(beta)) (Wagner),
drawn with the entry speed V0 = 6.15 m/s (thin lines) and with our own
speed V(t) (dashed), t measured from the time t0 the keel reaches the
still water level. Any file referenceData/*.dat (two columns, '#'
comments; see referenceData/README.md for the names it looks for) is
added to the plots.

Writes wedgeForce.png (force and velocity against time) and
wedgePressure.png (P1-P5 against time) into the case folder, and prints
F/(rho V^3 (t - t0)) at a few times against the two coefficients.

Usage: python3 plot.py [--case DIR]
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
from spemPostProcessing import readFunctionObject  # noqa: E402

scriptDir = os.path.dirname(os.path.abspath(__file__))
referenceDir = os.path.join(scriptDir, "referenceData")

# Case constants (constant/rigidBodyProperties, constant/spemProperties)
rho = 1000.0                    # [kg/m3]
beta = math.radians(30.0)       # deadrise angle
halfWidth = 0.25                # [m]
gap = 0.001                     # keel above the water at t = 0 [m]
V0 = 6.15                       # entry speed [m/s]
cVonKarman = math.pi/math.tan(beta)**2
cWagner = math.pi**3/(4*math.tan(beta)**2)

# Digitised curves a maintainer may add (referenceData/README.md):
# (legend, file, quantity: 'force' [N/m, time s] or 'velocity' [m/s])
digitised = [
    ("Zhao et al. 1996, experiment", "Zhao1996_force_experiment.dat", "force"),
    ("Zhao et al. 1996, nonlinear BEM", "Zhao1996_force_BEM.dat", "force"),
    ("Zhao et al. 1996, experiment", "Zhao1996_velocity_experiment.dat",
     "velocity"),
]


def parseArguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--case", default=scriptDir,
                        help="case folder (default: this script's folder)")
    return parser.parse_args()


def readReference(np, fileName):
    path = os.path.join(referenceDir, fileName)
    if not os.path.isfile(path):
        return None
    data = np.loadtxt(path, comments="#", ndmin=2)
    return data[:, 0], data[:, 1]


def main():
    args = parseArguments()
    caseDir = os.path.abspath(args.case)
    _, times, rows = readFunctionObject(caseDir, "wedge", 9)

    try:
        import numpy as np
    except ImportError:
        sys.exit("plot.py: %s has no numpy; try /usr/bin/python3 plot.py"
                 % sys.executable)
    t = np.array(times)
    y = np.array([r[1] for r in rows])
    V = -np.array([r[4] for r in rows])
    Fy = np.array([r[7] for r in rows])

    # The keel reaches y = 0 when the wedge has fallen by gap
    # (the first sample may come after it: t = 0, fallen 0 goes first)
    y0 = y[0] + V0*t[0]
    tt = np.concatenate(([0.0], t))
    fallen = np.concatenate(([0.0], y0 - y))
    k = np.searchsorted(fallen, gap)
    if k >= len(tt):
        sys.exit("plot.py: the wedge has not reached the water yet")
    w = (gap - fallen[k - 1])/(fallen[k] - fallen[k - 1])
    t0 = tt[k - 1] + w*(tt[k] - tt[k - 1])
    tau = t - t0
    tChineWagner = halfWidth*math.tan(beta)/(0.5*math.pi*V0)
    tChineGeometric = halfWidth*math.tan(beta)/V0

    print("case     : %s" % caseDir)
    print("samples  : %d, t = %g .. %g s" % (len(t), t[0], t[-1]))
    print("contact  : keel at the water at t0 = %.3e s, V = %.4f m/s"
          % (t0, np.interp(t0, t, V)))
    print("chines   : wet at t - t0 = %.4f s (Wagner) .. %.4f s (geometric)"
          % (tChineWagner, tChineGeometric))
    peak = Fy.argmax()
    print("force    : peak %.4g N/m at t - t0 = %.4f s" % (Fy[peak], tau[peak]))
    print("speed    : %.4f m/s at the end, t - t0 = %.4f s"
          % (V[-1], tau[-1]))
    print("F/(rho V^3 (t - t0)) [von Karman %.2f, Wagner %.2f]:"
          % (cVonKarman, cWagner))
    for ts in (0.002, 0.004, 0.006, 0.008, 0.010, 0.012, 0.014):
        if ts > tau[-1]:
            break
        sel = (tau > ts - 0.0005) & (tau <= ts + 0.0005)
        if sel.any():
            C = Fy[sel]/(rho*V[sel]**3*tau[sel])
            print("    t - t0 = %.3f s: %.2f (mean over +-0.5 ms)"
                  % (ts, C.mean()))

    try:
        import matplotlib
    except ImportError:
        sys.exit("plot.py: %s has no matplotlib; try /usr/bin/python3 plot.py"
                 % sys.executable)
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (axF, axV) = plt.subplots(2, 1, figsize=(7, 7.5), sharex=True)
    tauRef = np.linspace(0, tChineGeometric, 100)
    wet = tau > 0
    axF.plot(tau, Fy/1e3, "k-", lw=1.2, label="SPEM")
    for name, C, colour in (("von Karman", cVonKarman, "tab:blue"),
                            ("Wagner", cWagner, "tab:red")):
        axF.plot(tauRef, C*rho*V0**3*tauRef/1e3, color=colour, lw=1.0,
                 label="%s, $V_0$ (C = %.2f)" % (name, C))
        axF.plot(tau[wet], C*rho*V[wet]**3*tau[wet]/1e3, color=colour,
                 ls="--", lw=1.0, label="%s, our $V(t)$" % name)
    for name, fileName, quantity in digitised:
        data = readReference(np, fileName)
        if data is None:
            continue
        ax = axF if quantity == "force" else axV
        scale = 1e-3 if quantity == "force" else 1.0
        ax.plot(data[0], data[1]*scale, "o", ms=3, mfc="none", label=name)
    for ax in (axF, axV):
        ax.axvline(tChineWagner, color="0.6", ls=":", lw=0.8)
        ax.axvline(tChineGeometric, color="0.6", ls="-.", lw=0.8)
    axF.set_ylim(bottom=min(0, Fy.min()/1e3*1.05),
                 top=1.3*max(Fy.max()/1e3, 1e-3))
    axF.set_ylabel("vertical force on the wedge [kN/m]")
    axF.legend(fontsize=8, loc="upper left")
    axF.set_title("Wedge water entry, beta = 30 deg, V0 = 6.15 m/s, 241 kg/m"
                  "\n(dotted: chines wet, Wagner; dash-dot: geometric)",
                  fontsize=9)
    axV.plot(tau, V, "k-", lw=1.2, label="SPEM")
    axV.set_xlabel("time since the keel reached the water, t - t0 [s]")
    axV.set_ylabel("downward velocity [m/s]")
    axV.legend(fontsize=8)
    axV.set_xlim(min(tau[0], 0), tau[-1])
    fig.tight_layout()
    pngFile = os.path.join(caseDir, "wedgeForce.png")
    fig.savefig(pngFile, dpi=150)
    print("wrote    : %s" % pngFile)

    pressureDir = os.path.join(caseDir, "postProcessing", "wedgePressure")
    if os.path.isdir(pressureDir):
        _, pt, prows = readFunctionObject(caseDir, "wedgePressure")
        pt = np.array(pt) - t0
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for i in range(len(prows[0])):
            p = np.array([r[i] if i < len(r) else np.nan for r in prows])
            ax.plot(pt, p/1e3, lw=1.0, label="P%d" % (i + 1))
        ax.axvline(tChineWagner, color="0.6", ls=":", lw=0.8)
        ax.set_xlabel("t - t0 [s]")
        ax.set_ylabel("pressure [kPa]")
        ax.set_title("Pressure on the wedge's right face (probes moving with "
                     "it;\nP1-P5 at 10-90 % of keel-to-chine, not Zhao's "
                     "positions)", fontsize=9)
        ax.legend(fontsize=8)
        fig.tight_layout()
        pngFile = os.path.join(caseDir, "wedgePressure.png")
        fig.savefig(pngFile, dpi=150)
        print("wrote    : %s" % pngFile)


if __name__ == "__main__":
    main()
