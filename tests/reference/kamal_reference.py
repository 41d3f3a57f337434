#!/usr/bin/env python3
"""Independent SciPy reference for specs/kamal_1970.lpm under
specs/scenarios/kamal_1970.toml.

What it is
----------
The two-mass Kamal model written out by hand (Newton's second law for the
body and the engine), with its own implementation of the scenario's crush
springs: force–deflection curves (force linear between breakpoints, the
last segment extrapolated) that push but never pull, unloading plastically
from the peak reached along a line of the given unloading stiffness.
It integrates with ``scipy.integrate.solve_ivp`` (DOP853, rtol 1e-12) with
a short maximum step, updating each spring's peak between steps, for
several impact speeds, and records the maximum body crush, its time and the
largest body deceleration of the run (to 0.15 s).

How to run
----------
From the repository root, with scipy and numpy (a virtual environment)::

    python3 tests/reference/kamal_reference.py

It writes ``tests/reference/kamal_reference.json``, which the Rust test
``tests/variants.rs`` reads; the tests need no Python.
"""

import json
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

MB, ME = 1050.0, 200.0          # body, engine [kg]
K_EB, C_EB = 1.5e6, 2.0e3       # engine mounts [N/m], [N s/m]
FRONT = ([0.0, 0.10, 0.45, 0.55], [0.0, 60.0e3, 100.0e3, 400.0e3], 5.0e6)
RAILS = ([0.0, 0.10, 0.60, 0.80], [0.0, 180.0e3, 220.0e3, 600.0e3], 2.0e7)


def loading(curve, x):
    """Force on the loading curve at deflection x >= 0 (extrapolated)."""
    xs, fs, _ = curve
    if x <= xs[-1]:
        return float(np.interp(x, xs, fs))
    slope = (fs[-1] - fs[-2]) / (xs[-1] - xs[-2])
    return fs[-1] + slope * (x - xs[-1])


class Spring:
    """A crush spring with plastic unloading, compression only."""

    def __init__(self, curve):
        self.curve = curve
        self.peak = 0.0

    def force(self, x):
        if x >= self.peak:
            return max(loading(self.curve, x), 0.0)
        k_u = self.curve[2]
        return max(loading(self.curve, self.peak) - k_u * (self.peak - x), 0.0)

    def advance(self, x):
        self.peak = max(self.peak, x)


def run(speed):
    front, rails = Spring(FRONT), Spring(RAILS)

    def rhs(_t, y):
        xb, xe, vb, ve = y
        mount = K_EB * (xe - xb) + C_EB * (ve - vb)
        ab = (mount - rails.force(xb)) / MB
        ae = (-mount - front.force(xe)) / ME
        return [vb, ve, ab, ae]

    y = np.array([0.0, 0.0, speed, speed])
    t, dt = 0.0, 2e-6
    best = (0.0, 0.0)          # (crush, time)
    peak_deceleration = 0.0
    while t < 0.15:
        sol = solve_ivp(rhs, (t, t + dt), y, method="DOP853", rtol=1e-12, atol=1e-14)
        y = sol.y[:, -1]
        t += dt
        front.advance(y[1])
        rails.advance(y[0])
        if y[0] > best[0]:
            best = (y[0], t)
        peak_deceleration = max(peak_deceleration, -rhs(t, y)[2])
    return {"speed_mps": speed, "max_crush_m": best[0], "time_of_max_crush_s": best[1],
            "peak_body_deceleration_mps2": peak_deceleration}


def main():
    runs = [run(v) for v in (12.0, 15.5556)]
    out = Path(__file__).with_name("kamal_reference.json")
    out.write_text(json.dumps({"runs": runs}, indent=2) + "\n")
    print(json.dumps(runs, indent=2))


if __name__ == "__main__":
    main()
