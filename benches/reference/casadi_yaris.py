#!/usr/bin/env python3
"""CasADi peer of the q̈ bench (benches/evaluation.rs): the paper's model
(specs/yaris_double_pendulum.lpm) built in CasADi from its positions and
energies, differentiated by CasADi, and written out as C by CasADi's code
generator.

Two functions are generated, both taking ``(t, q[3], v[3], p[17])`` with the
parameters in spec order:

* ``yaris_mass_forcing`` -> ``(M[3x3] column-major, f[3])``;
* ``yaris_accelerations`` -> ``q̈[3] = solve(M, f)`` (CasADi's symbolic
  solve of the SX expressions, written out in full).

The inputs of the spec are the bench's cheap stand-ins, written into the
expressions here exactly as ``inputs`` in benches/evaluation.rs computes them
(crush = 8e5 x + 3e3 v, weld = 1e5 x + 1e3 v, each barrier force 1e3), so
every peer evaluates the same function.

Run from the repository root (Python >= 3.9, ``pip install casadi``)::

    python3 benches/reference/casadi_yaris.py

It writes ``benches/casadi/yaris_casadi.c``, which is committed: the bench
compiles it with a C compiler and does not need Python.
"""

import sys
from pathlib import Path

import casadi as ca

ROOT = Path(__file__).resolve().parent.parent.parent
OUT = ROOT / "benches" / "casadi"

PARAMETERS = [
    "m1", "m2", "l0", "l1", "l2", "l3", "I1", "I2", "k1", "k2", "c1", "c2",
    "k_comp", "c_comp", "k_tor", "c_tor", "g",
]


def model():
    """(t, q, v, p) symbols and the expressions M, f of M q̈ = f."""
    t = ca.SX.sym("t")
    q = ca.SX.sym("q", 3)
    v = ca.SX.sym("v", 3)
    p = ca.SX.sym("p", len(PARAMETERS))
    P = {name: p[k] for k, name in enumerate(PARAMETERS)}
    r, th1, th2 = q[0], q[1], q[2]
    rd, w2 = v[0], v[2]
    a = P["l0"] + r
    x1, z1 = a * ca.cos(th1), a * ca.sin(th1)
    x2 = (a + P["l1"]) * ca.cos(th1) + P["l2"] * ca.cos(th2)
    z2 = (a + P["l1"]) * ca.sin(th1) + P["l2"] * ca.sin(th2)
    r1 = (a - P["l3"]) * th1
    r2 = (a + P["l1"]) * th1 + P["l2"] * th2

    def dot(e):
        return ca.jtimes(e, q, v)

    kinetic = (0.5 * P["m1"] * (dot(x1) ** 2 + dot(z1) ** 2)
               + 0.5 * P["m2"] * (dot(x2) ** 2 + dot(z2) ** 2)
               + 0.5 * P["I1"] * v[1] ** 2 + 0.5 * P["I2"] * v[2] ** 2)
    potential = (P["m1"] * P["g"] * z1 + P["m2"] * P["g"] * z2
                 + 0.5 * P["k_comp"] * r ** 2
                 + 0.5 * P["k1"] * r1 ** 2 + 0.5 * P["k2"] * r2 ** 2
                 + 0.5 * P["k_tor"] * th2 ** 2)
    dissipation = (0.5 * P["c_comp"] * rd ** 2
                   + 0.5 * P["c1"] * dot(r1) ** 2 + 0.5 * P["c2"] * dot(r2) ** 2
                   + 0.5 * P["c_tor"] * w2 ** 2)
    # The bench's input functions.
    crush = 8.0e5 * r + 3.0e3 * rd
    weld = 1.0e5 * th2 + 1.0e3 * w2
    barrier = 1.0e3
    forces = ca.vertcat(-crush, 0, -weld)
    for x, z in ((x1, z1), (x2, z2)):
        forces += barrier * ca.jacobian(x, q).T + barrier * ca.jacobian(z, q).T

    momentum = ca.gradient(kinetic, v)
    mass = ca.jacobian(momentum, v)
    forcing = (ca.gradient(kinetic - potential, q)
               - ca.jtimes(momentum, q, v)
               - ca.gradient(dissipation, v)
               + forces)
    return t, q, v, p, mass, forcing


def main():
    t, q, v, p, mass, forcing = model()
    mass_forcing = ca.Function(
        "yaris_mass_forcing", [t, q, v, p], [ca.densify(mass), forcing],
        ["t", "q", "v", "p"], ["M", "f"])
    accelerations = ca.Function(
        "yaris_accelerations", [t, q, v, p], [ca.solve(mass, forcing)],
        ["t", "q", "v", "p"], ["qdd"])
    generator = ca.CodeGenerator("yaris_casadi.c", {"with_header": False})
    generator.add(mass_forcing)
    generator.add(accelerations)
    OUT.mkdir(parents=True, exist_ok=True)
    generator.generate(str(OUT) + "/")
    print(f"CasADi {ca.__version__}: wrote {OUT / 'yaris_casadi.c'}", file=sys.stderr)


if __name__ == "__main__":
    main()
