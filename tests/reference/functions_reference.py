#!/usr/bin/env python3
"""Independent SymPy reference for the functions of the spec language.

For every function (asin, acos, atan, atan2, sinh, cosh, tanh, hypot, abs,
sign, min, max) it records, at a few points away from any kink, the value
and the partial derivative by each argument, computed by SymPy's own
``diff`` and evaluated with mpmath at 30 significant digits.  SymPy's
``Abs``, ``sign``, ``Min`` and ``Max`` are differentiated for real
arguments (``Heaviside`` and ``sign`` away from zero).

How to run, from the repository root::

    /path/to/python tests/reference/functions_reference.py

It writes ``tests/reference/functions_reference.json`` (deterministic), which
``tests/functions.rs`` reads, so the tests need neither Python nor SymPy.
"""

import json
import pathlib

import sympy as sp

x, y = sp.symbols("x y", real=True)

FUNCTIONS = {
    "asin": (sp.asin(x), [(0.3,), (-0.8,), (0.95,)]),
    "acos": (sp.acos(x), [(0.3,), (-0.8,), (0.95,)]),
    "atan": (sp.atan(x), [(0.3,), (-2.5,), (40.0,)]),
    "atan2": (sp.atan2(x, y), [(0.3, 0.7), (1.2, -0.4), (-0.5, -2.0)]),
    "sinh": (sp.sinh(x), [(0.3,), (-2.5,), (4.0,)]),
    "cosh": (sp.cosh(x), [(0.3,), (-2.5,), (4.0,)]),
    "tanh": (sp.tanh(x), [(0.3,), (-2.5,), (4.0,)]),
    "hypot": (sp.sqrt(x**2 + y**2), [(3.0, 4.0), (-0.3, 0.7), (1e-3, -2.0)]),
    "abs": (sp.Abs(x), [(0.3,), (-2.5,)]),
    "sign": (sp.sign(x), [(0.3,), (-2.5,)]),
    "min": (sp.Min(x, y), [(0.3, 0.7), (1.2, -0.4)]),
    "max": (sp.Max(x, y), [(0.3, 0.7), (1.2, -0.4)]),
}


def evaluate(expr, args):
    """The value of expr at args (x, then y), to 30 digits, as a float."""
    values = dict(zip((x, y), (sp.Float(a, 30) for a in args)))
    value = expr.subs(values)
    value = value.rewrite(sp.Piecewise) if value.has(sp.Heaviside) else value
    return float(sp.N(value, 30))


def main():
    out = {}
    for name, (expr, points) in FUNCTIONS.items():
        arity = len(points[0])
        variables = (x, y)[:arity]
        partials = [sp.diff(expr, v) for v in variables]
        out[name] = [
            {
                "args": list(point),
                "value": evaluate(expr, point),
                "partials": [evaluate(p, point) for p in partials],
            }
            for point in points
        ]
    # Sanity: the textbook derivatives at one point.
    assert abs(out["asin"][0]["partials"][0] - 1 / (1 - 0.09) ** 0.5) < 1e-15
    assert out["abs"][1]["partials"] == [-1.0]
    assert out["min"][1]["partials"] == [0.0, 1.0]
    path = pathlib.Path(__file__).with_name("functions_reference.json")
    path.write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
