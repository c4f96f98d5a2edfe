#!/usr/bin/env python3
"""Sinking of a circular cylinder: free-surface profiles and the force.

Reads, in <case>/postProcessing/,
  surfaceProfile/<startTime>/<time>/surfaceProfile.dat   (x y; the highest
      surface point per particle spacing, a single-valued curve y(x))
  freeSurface/<startTime>/<time>/freeSurface.dat         (x y; every
      free-surface particle and free element node)
  cylinder/<startTime>/cylinder.dat                      (rigidBodyState:
      Time x y angle u v omega Fx Fy Mz)
written by the function objects of system/controlDict. V0 and d are read
from system/controlDict; T = V0 t/d is the paper's dimensionless time.

Writes into the case folder
  freeSurface.png  one panel per T of PANEL_TIMES (the paper's Fig. 17
                   shows T = 0, 0.4, 1.0, 2.0): the profile (line), the
                   surface points (dots) and the cylinder;
  force.png        the water's force on the cylinder, Fx and Fy [N/m],
                   against T, with the buoyancy of the submerged cylinder
                   at rest, rho g pi R^2, for scale;
and prints, per panel time, the highest surface point above the cylinder
(|x| < R/4) and the surface at x = 0, +-2R, +-4R.

Reference profiles are drawn from referenceData/ if files are there (see
referenceData/README.md: none has been found in digital form yet).

Usage: python3 plot.py [--case DIR]
"""

import os
import sys

sys.path.insert(0, os.path.join(
    os.environ.get("SPEM_PROJECT_DIR",
                   os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "..")),
    "bin", "tools"))
import cylinderPlot  # noqa: E402

if __name__ == "__main__":
    cylinderPlot.main(
        description=__doc__.split("\n")[0],
        scriptDir=os.path.dirname(os.path.abspath(__file__)),
        TITLE="Sinking cylinder",
        DIRECTION=-1,           # +1: pulled up (exit), -1: pushed down
        PANEL_TIMES=[0.2, 0.4, 0.6, 1.0, 2.0],
        Y_LIMITS=(-5.0, 1.2),   # of every panel [m]
        RADIUS=1.0,             # as in constant/rigidBodyProperties
        RHO=1000.0, G=1.0)      # as in constant/spemProperties and g
