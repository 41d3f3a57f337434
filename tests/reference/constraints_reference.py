#!/usr/bin/env python3
"""Independent reference values for holonomic constraints with Lagrange
multipliers (``constraint NAME = expr;``).

What it is
----------
1. SymPy's nonminimal pendulum: a point mass in ``x, y`` held on the circle
   ``x**2 + y**2 = l**2`` by a Lagrange multiplier, with
   ``sympy.physics.mechanics.LagrangesMethod(hol_coneqs=...)``. At one state
   it records the accelerations and the multiplier SymPy's augmented system
   gives (the multiplier converted to this project's convention: ``G^T lam``
   is the generalized constraint force added to ``f``, so
   ``lam = (G G^T)^-1 G (M qdd - f)``).  Then the pendulum's motion from
   rest at ``theta0``, integrated by SciPy in the angle (the hand-eliminated
   one-coordinate model ``theta'' = -(g/l) sin theta``), as ``x, y`` at a
   few times.
2. The four-bar linkage of ``specs/four_bar_linkage.lpm``, eliminated by
   hand to one coordinate: the crank angle ``theta1``, with the coupler's
   and rocker's angles from the loop's closed form (circle intersection,
   ``atan2``/``acos``), ``T = J(theta1) theta1'**2 / 2`` and ``V(theta1)``
   built by SymPy from those, and ``J theta1'' + J'/2 theta1'**2 + V' = 0``
   integrated by SciPy from rest at ``theta1 = 1``. It records the exact
   initial angles and ``theta1, theta2, theta3`` at a few times.

How to run
----------
From the repository root (needs ``sympy``, ``scipy`` and ``numpy``)::

    python3 tests/reference/constraints_reference.py

It writes ``tests/reference/constraints_reference.json``, which is committed
and read by the Rust tests (no Python needed to run them).
"""

import json
from pathlib import Path

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp
from sympy.physics.mechanics import LagrangesMethod, dynamicsymbols, msubs

OUT = Path(__file__).with_suffix(".json")
TIMES = [0.5, 1.0, 1.5, 2.0]


def nonminimal_pendulum():
    m, l, g = 2.0, 1.5, 9.81
    x, y = dynamicsymbols("x y")
    xd, yd = dynamicsymbols("x y", 1)
    lagrangian = sp.Rational(1, 2) * m * (xd**2 + yd**2) - m * g * y
    constraint = x**2 + y**2 - l**2
    lm = LagrangesMethod(lagrangian, [x, y], hol_coneqs=[constraint])
    lm.form_lagranges_equations()
    # A state on the circle, moving along it.
    theta, omega = 0.7, -1.3
    state = {
        x: l * np.sin(theta),
        y: -l * np.cos(theta),
        xd: l * omega * np.cos(theta),
        yd: l * omega * np.sin(theta),
    }
    solved = lm.rhs()  # [xd, yd, xdd, ydd, lam]
    values = [float(msubs(v, state)) for v in solved]
    qdd = np.array(values[2:4])
    mass = np.diag([m, m])
    forcing = np.array([0.0, -m * g])
    jacobian = np.array([[2 * state[x], 2 * state[y]]], dtype=float)
    force = mass @ qdd - forcing
    lam = np.linalg.solve(jacobian @ jacobian.T, jacobian @ force)

    theta0 = 0.6
    sol = solve_ivp(
        lambda t, s: [s[1], -(g / l) * np.sin(s[0])],
        (0.0, TIMES[-1]),
        [theta0, 0.0],
        method="DOP853",
        rtol=1e-12,
        atol=1e-12,
        t_eval=TIMES,
    )
    return {
        "parameters": {"m": m, "l": l, "g": g},
        "state": {
            "q": [state[x], state[y]],
            "qd": [state[xd], state[yd]],
            "qdd": qdd.tolist(),
            "lambda": lam.tolist(),
        },
        "motion": {
            "theta0": theta0,
            "t": TIMES,
            "x": (l * np.sin(sol.y[0])).tolist(),
            "y": (-l * np.cos(sol.y[0])).tolist(),
        },
    }


def four_bar():
    l0, l1, l2, l3 = 0.7, 0.3, 0.8, 0.6
    m1, m2, m3, g = 1.0, 2.0, 1.5, 9.81
    t1 = sp.symbols("theta1")
    bx, by = l1 * sp.cos(t1), l1 * sp.sin(t1)
    ex, ey = l0 - bx, -by  # from the crank pin B to the pivot D
    dist = sp.sqrt(ex**2 + ey**2)
    base = sp.atan2(ey, ex)
    # The angle at B between BD and BC, and at D between DB and DC (law of
    # cosines), for the assembly with C above the line BD.
    at_b = sp.acos((l2**2 + dist**2 - l3**2) / (2 * l2 * dist))
    at_d = sp.acos((l3**2 + dist**2 - l2**2) / (2 * l3 * dist))
    t2 = base + at_b
    t3 = base + sp.pi - at_d
    # Velocities per unit crank rate.
    k2, k3 = sp.diff(t2, t1), sp.diff(t3, t1)
    x2d = -l1 * sp.sin(t1) - sp.Rational(1, 2) * l2 * sp.sin(t2) * k2
    y2d = l1 * sp.cos(t1) + sp.Rational(1, 2) * l2 * sp.cos(t2) * k2
    inertia = (
        m1 * l1**2 / 3
        + m2 * (x2d**2 + y2d**2)
        + m2 * l2**2 / 12 * k2**2
        + m3 * l3**2 / 3 * k3**2
    )
    potential = g * (
        m1 * sp.Rational(1, 2) * by
        + m2 * (by + sp.Rational(1, 2) * l2 * sp.sin(t2))
        + m3 * sp.Rational(1, 2) * l3 * sp.sin(t3)
    )
    f_inertia = sp.lambdify(t1, inertia, "numpy")
    f_dinertia = sp.lambdify(t1, sp.diff(inertia, t1), "numpy")
    f_dpotential = sp.lambdify(t1, sp.diff(potential, t1), "numpy")
    f_angles = sp.lambdify(t1, [t2, t3], "numpy")

    def rhs(_t, s):
        th, w = s
        return [w, -(0.5 * f_dinertia(th) * w**2 + f_dpotential(th)) / f_inertia(th)]

    theta0 = 1.0
    sol = solve_ivp(
        rhs,
        (0.0, TIMES[-1]),
        [theta0, 0.0],
        method="DOP853",
        rtol=1e-12,
        atol=1e-12,
        t_eval=TIMES,
    )
    angles = [f_angles(th) for th in sol.y[0]]
    return {
        "initial": [theta0] + [float(a) for a in f_angles(theta0)],
        "t": TIMES,
        "theta1": sol.y[0].tolist(),
        "theta2": [float(a[0]) for a in angles],
        "theta3": [float(a[1]) for a in angles],
    }


def main():
    data = {
        "versions": {"sympy": sp.__version__, "numpy": np.__version__},
        "nonminimal_pendulum": nonminimal_pendulum(),
        "four_bar": four_bar(),
    }
    OUT.write_text(json.dumps(data, indent=2) + "\n")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
