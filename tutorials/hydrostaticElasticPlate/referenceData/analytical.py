#!/usr/bin/env python3
"""Static mid-span deflection of the clamped plate under the water column.

Plane strain (cylindrical bending), per unit depth, see analytical.md:

    q    = rho g H + rho_s g t                    load: water + self-weight
    D    = E t^3 / (12 (1 - nu^2))                plate bending rigidity
    w_EB = q L^4 / (384 D)                        Euler-Bernoulli, clamped-clamped
    w_T  = w_EB + q L^2 / (8 kappa G t)           + Timoshenko shear deflection
    G    = E / (2 (1 + nu)),  kappa = 5/6

Deflection is downward, i.e. a negative y-displacement: Dy = -w.

Writes midSpanDeflection.dat next to this script and prints the values.
Inputs repeat constant/spemProperties, constant/g and system/blockMeshDict.
"""

import os

# Water column (constant/spemProperties: regions.water; blockMeshDict: H, L)
rho = 1000.0        # density [kg/m3]
H = 2.0             # height [m]
# Plate (constant/spemProperties: regions.plate; blockMeshDict: t, L)
rho_s = 2700.0      # density [kg/m3]
E = 67.5e9          # Young's modulus [Pa]
nu = 0.34           # Poisson's ratio [-]
t = 0.05            # thickness [m]
L = 1.0             # span between the clamped ends [m]
# Gravity (constant/g)
g = 9.81            # [m/s2]
# Shear correction factor of a rectangular section
kappa = 5.0/6.0


def deflections():
    """Return (q, D, w_EB, w_T): load [Pa], rigidity [N m], deflections [m]."""
    q = rho*g*H + rho_s*g*t
    D = E*t**3/(12.0*(1.0 - nu**2))
    G = E/(2.0*(1.0 + nu))
    w_EB = q*L**4/(384.0*D)
    w_T = w_EB + q*L**2/(8.0*kappa*G*t)
    return q, D, w_EB, w_T


def main():
    q, D, w_EB, w_T = deflections()

    out = os.path.join(os.path.dirname(os.path.abspath(__file__)),
                       "midSpanDeflection.dat")
    with open(out, "w") as f:
        f.write("# Static mid-span deflection of the clamped plate, written by"
                " analytical.py (see analytical.md)\n")
        f.write("# q = %.6g Pa, D = %.6g N m; values are Dy [m] of the"
                " plate mid-plane at x = L/2 (downward = negative)\n"
                % (q, D))
        f.write("# quantity\tvalue\n")
        f.write("Dy_EulerBernoulli\t%.6e\n" % -w_EB)
        f.write("Dy_Timoshenko\t%.6e\n" % -w_T)

    print("load q               = %.6g Pa (water %.6g + plate %.6g)"
          % (q, rho*g*H, rho_s*g*t))
    print("bending rigidity D   = %.6g N m" % D)
    print("w_EB (Euler-Bernoulli) = %.3e m  ->  Dy = %.3e m" % (w_EB, -w_EB))
    print("w_T  (Timoshenko)      = %.3e m  ->  Dy = %.3e m" % (w_T, -w_T))
    print("shear part w_T - w_EB  = %.3e m (%.2f %% of w_EB)"
          % (w_T - w_EB, 100.0*(w_T - w_EB)/w_EB))
    print("written %s" % out)


if __name__ == "__main__":
    main()
