#!/usr/bin/env python3
"""Independent SymPy reference for `lpm linearize`.

What it is
----------
The state-space matrices ``A = d(x')/dx`` and ``B = d(x')/dr`` of two
models, with the state ``x = (q, q')`` and the inputs ``r``, by SymPy's
``LagrangesMethod.linearize`` (``sympy.physics.mechanics.Linearizer``),
written from the model definitions in ``specs/*.lpm`` only:

* ``spring_mass_damper``: ``m x'' + c x' + k x = push`` with the input
  force ``push`` (``specs/spring_mass_damper.lpm``), about ``x = 0``;
* ``double_pendulum``: two point masses on rigid rods
  (``specs/double_pendulum.lpm``) with unequal masses and lengths, about its
  downward equilibrium and about a moving state away from it (where the
  term ``d(M q'')/dq`` of ``A`` matters).

Every ``A`` (and ``B``) is also computed directly as the Jacobian of
``x' = (q', M^-1 f)`` and the script stops if the two differ, so the
numbers do not rest on one method. Values are evaluated at 30 digits and
stored as floats.

How to run
----------
From the repository root::

    python3 tests/reference/linearize_reference.py

It writes ``tests/reference/linearize_reference.json`` (a few seconds).
``tests/linearize_reference.rs`` compares the interpreter's linearization
with it to 1e-9.
"""

import json
import os

import sympy as sp
from sympy.physics.mechanics import LagrangesMethod, Point, ReferenceFrame, dynamicsymbols, msubs

DIGITS = 30
OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "linearize_reference.json")


def direct(method, qs, inputs, values, parameters):
    """A and B as the Jacobian of x' = (q', M^-1 f) at `values`."""
    qds = [q.diff() for q in qs]
    qdd = method.mass_matrix.LUsolve(method.forcing)
    xdot = sp.Matrix(qds + list(qdd))
    # Differentiate with plain symbols in place of the functions of time
    # (velocities first, so that x' is not taken for the derivative of x).
    order = qds + qs + list(inputs)
    plain = {s: sp.Symbol(f"s{k}") for k, s in enumerate(order)}
    xdot_s = xdot.subs([(s, plain[s]) for s in order])
    x_s = [plain[s] for s in qs + qds]
    r_s = [plain[s] for s in inputs]
    at = {plain[s]: v for s, v in values.items()} | parameters
    a = xdot_s.jacobian(x_s).subs(at)
    b = xdot_s.jacobian(r_s).subs(at) if r_s else sp.zeros(len(x_s), 0)
    return a, b


def linearize(lagrangian, qs, forces, frame, inputs, parameters, q0, qd0, r0):
    """SymPy's linearization, checked against the direct Jacobian."""
    method = LagrangesMethod(lagrangian, qs, forcelist=forces, frame=frame)
    method.form_lagranges_equations()
    qds = [q.diff() for q in qs]
    values = dict(zip(qs, q0)) | dict(zip(qds, qd0)) | dict(zip(inputs, r0))
    # The Linearizer needs q'' at the operating point: M^-1 f there.
    qdd = method.mass_matrix.LUsolve(method.forcing)
    qdd_values = [sp.simplify(msubs(e, values, parameters)) for e in qdd]
    op_point = values | {q.diff(t, 2): v for q, v in zip(qs, qdd_values)}
    a, b, r = method.linearize(q_ind=qs, qd_ind=qds, A_and_B=True, op_point=op_point)
    assert list(r) == list(inputs), (r, inputs)
    a = msubs(a, parameters)
    b = msubs(b, parameters) if inputs else sp.zeros(a.shape[0], 0)
    a_direct, b_direct = direct(method, qs, inputs, values, parameters)
    for found, expected in [(a, a_direct), (b, b_direct)]:
        difference = (sp.Matrix(found) - expected).evalf(DIGITS)
        assert all(abs(d) < 1e-25 for d in difference), difference
    return {
        "parameters": {str(k): float(v) for k, v in parameters.items()},
        "q": [float(v) for v in q0],
        "qd": [float(v) for v in qd0],
        "inputs": [str(i).replace("(t)", "") for i in inputs],
        "input_values": [float(v) for v in r0],
        "A": _rows(a),
        "B": _rows(b),
    }


def _rows(m):
    return [[float(sp.N(m[i, j], DIGITS)) for j in range(m.shape[1])] for i in range(m.shape[0])]


t = dynamicsymbols._t  # noqa: SLF001


def spring_mass_damper():
    x = dynamicsymbols("x")
    push = dynamicsymbols("push")
    m, k, c = sp.symbols("m k c")
    frame = ReferenceFrame("N")
    point = Point("P")
    point.set_vel(frame, x.diff() * frame.x)
    lagrangian = m * x.diff() ** 2 / 2 - k * x**2 / 2
    # The damper and the input as the forces on the mass.
    forces = [(point, (-c * x.diff() + push) * frame.x)]
    parameters = {m: sp.Rational(2), k: sp.Rational(50), c: sp.Rational(3)}
    return linearize(lagrangian, [x], forces, frame, [push], parameters, [0], [0], [0])


def double_pendulum(q0, qd0):
    th1, th2 = dynamicsymbols("theta1 theta2")
    m1, m2, l1, l2, g = sp.symbols("m1 m2 l1 l2 g")
    x1, y1 = l1 * sp.sin(th1), -l1 * sp.cos(th1)
    x2, y2 = x1 + l2 * sp.sin(th2), y1 - l2 * sp.cos(th2)
    kinetic = m1 * (x1.diff(t) ** 2 + y1.diff(t) ** 2) / 2 + m2 * (x2.diff(t) ** 2 + y2.diff(t) ** 2) / 2
    potential = m1 * g * y1 + m2 * g * y2
    parameters = {
        m1: sp.Rational(13, 10),
        m2: sp.Rational(7, 10),
        l1: sp.Rational(11, 10),
        l2: sp.Rational(6, 10),
        g: sp.Rational(981, 100),
    }
    return linearize(kinetic - potential, [th1, th2], [], None, [], parameters, q0, qd0, [])


def main():
    reference = {
        "spring_mass_damper": spring_mass_damper(),
        "double_pendulum_equilibrium": double_pendulum([0, 0], [0, 0]),
        "double_pendulum_moving": double_pendulum(
            [sp.Rational(3, 10), sp.Rational(-2, 10)], [sp.Rational(1, 10), sp.Rational(4, 10)]
        ),
    }
    with open(OUT, "w") as f:
        json.dump(reference, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
