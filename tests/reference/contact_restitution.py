#!/usr/bin/env python3
"""Independent SciPy reference for the contact laws of
``sim/src/components/contact/``: the coefficient of restitution each law achieves
for a requested one.

What it is
----------
A mass ``m`` moving at ``v0`` onto a contact that pushes only: while in
contact the penetration ``d`` obeys ``m d'' = -F(d, d')``, with ``F`` the
law's force written out here from the papers, not from the Rust code:

* linear spring–dashpot ``F = k d + c d'``, ``c = 2 z sqrt(k m)``, the damping
  ratio ``z`` solving the closed form of the restitution of a linear
  oscillator whose contact ends where its force vanishes (Schwager and
  Pöschel 2007): ``e = exp(-z (pi - atan2(2 z s, 1 - 2 z^2)) / s)``,
  ``s = sqrt(1 - z^2)`` (``z < 1``);
* Anagnostopoulos (1988): the same force, ``z = -ln e / sqrt(pi^2 + ln^2 e)``,
  exact for a contact that lasts the oscillator's half period;
* Hunt and Crossley (1975): ``F = k d^n (1 + 3 (1 - e) / 2 * d' / v0)``;
* Lankarani and Nikravesh (1990): ``F = k d^n (1 + 3 (1 - e^2) / 4 * d' / v0)``;
* Flores et al. (2011): ``F = k d^n (1 + 8 (1 - e) / (5 e) * d' / v0)``.

It integrates from first contact (``d = 0``, ``d' = v0``) with
``scipy.integrate.solve_ivp`` (DOP853, rtol 1e-12) until the force falls to
zero on the way out (or the mass leaves ``d = 0``); the achieved coefficient
is the speed there over ``v0``.

How to run
----------
From the repository root, with scipy and numpy::

    python3 tests/reference/contact_restitution.py

It prints the table the Rust test ``sim/src/component_runs/contact.rs`` holds
(``REFERENCE``); the tests need no Python.
"""

import math

from scipy.integrate import solve_ivp
from scipy.optimize import brentq

M, K, N, V0 = 2.0, 4.0e4, 1.5, 3.0
REQUESTED = [0.2, 0.4, 0.6, 0.8, 0.95]


def linear_exact_ratio(e):
    """The damping ratio whose force-vanishing contact restitutes e."""
    def restitution(z):
        s = math.sqrt(1.0 - z * z)
        return math.exp(-z * (math.pi - math.atan2(2 * z * s, 1 - 2 * z * z)) / s)
    return brentq(lambda z: restitution(z) - e, 1e-12, 1.0 - 1e-12, xtol=1e-15)


def viscoelastic(z):
    c = 2.0 * z * math.sqrt(K * M)
    return lambda d, v: K * d + c * v


def hysteresis(factor):
    return lambda d, v: K * max(d, 0.0) ** N * (1.0 + factor * v / V0)


def laws(e):
    ln = math.log(e)
    return {
        "linear": viscoelastic(linear_exact_ratio(e)),
        "anagnostopoulos": viscoelastic(-ln / math.sqrt(math.pi**2 + ln**2)),
        "hunt_crossley": hysteresis(1.5 * (1.0 - e)),
        "lankarani_nikravesh": hysteresis(0.75 * (1.0 - e * e)),
        "flores": hysteresis(8.0 * (1.0 - e) / (5.0 * e)),
    }


def achieved(force):
    def rhs(_t, y):
        return [y[1], -force(y[0], y[1]) / M]

    def released(_t, y):
        return force(y[0], y[1])

    def left(_t, y):
        return y[0]

    for event in (released, left):
        event.terminal = True
        event.direction = -1
    sol = solve_ivp(rhs, (0.0, 1.0), [1e-300, V0], method="DOP853",
                    rtol=1e-12, atol=1e-15, events=(released, left))
    return abs(sol.y[1, -1]) / V0


def main():
    print(f"// m = {M} kg, k = {K}, n = {N} (hysteresis laws), v0 = {V0} m/s")
    for e in REQUESTED:
        row = {name: achieved(f) for name, f in laws(e).items()}
        print(f"({e}, [" + ", ".join(f"{row[n]:.10f}" for n in row) + "]),")


if __name__ == "__main__":
    main()
