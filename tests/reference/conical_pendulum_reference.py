#!/usr/bin/env python3
"""Independent SymPy reference for the three-link conical pendulum.

What it is
----------
``tests/specs/three_link_conical_pendulum.lpm`` is PyDy's three-link
conical pendulum written directly in the spec language (positions,
``dot()`` and squares); its canonical expansion exceeds the engine's limits,
so the compiler derives it on the derivation graph.  This script derives
the same system the way PyDy does, with ``sympy.physics.mechanics``:
reference frames oriented body-fixed relative to the previous link,
points, particles for the bobs and rigid bodies for the rods (whose
rotational energy comes from the frames' angular velocities, not from the
spec's ``|du/dt|^2``), and ``LagrangesMethod``.  It evaluates ``M``, ``f``,
``T`` and ``V`` at 12 pseudo-random states with mpmath at 30 digits and
writes ``conical_pendulum_reference.json`` next to itself, in the layout of
``sympy_reference.json`` (one model).

Conventions
-----------
* Link ``k`` is oriented relative to link ``k - 1`` (link 1 to the ground
  frame N, whose z axis points up) by ``beta_k`` about y, then ``alpha_k``
  about the new x (body-fixed 'YXZ' with a zero third angle), and points
  along its ``-z`` axis; gravity is ``-g`` along N.z.
* Bob ``k`` (mass ``m_k``) is at the end of link ``k``; rod ``k`` (mass
  ``r_k``, moment of inertia ``i_k`` about any transverse axis through its
  centre, none about its axis) has its centre at the middle of the link.
* States: ``random.Random(20261130)``; angles uniform in [-1, 1],
  velocities in [-2, 2], parameters default * U(0.8, 1.2), t = 0.

How to run
----------
From the repository root::

    python3 tests/reference/conical_pendulum_reference.py

(sympy and mpmath; about ten minutes on a busy two-core machine.)  Re-run it only when the spec or the
reference changes, and commit the JSON.
"""

import json
import random
import time
from pathlib import Path

import mpmath
import sympy as sp
import sympy.physics.mechanics as me

N_LINKS = 3
PARAMETERS = {
    "m1": 1.0, "m2": 0.8, "m3": 0.6,
    "l1": 1.0, "l2": 0.9, "l3": 0.7,
    "r1": 0.3, "r2": 0.25, "r3": 0.2,
    "i1": 0.025, "i2": 0.016875, "i3": 0.0081667,
    "g": 9.81,
}
COORDINATES = ["alpha1", "beta1", "alpha2", "beta2", "alpha3", "beta3"]


def derive():
    """M, f, T and V as SymPy expressions in q, q', the parameters."""
    alpha = me.dynamicsymbols("alpha1:4")
    beta = me.dynamicsymbols("beta1:4")
    q = [c for k in range(N_LINKS) for c in (alpha[k], beta[k])]
    p = {name: sp.Symbol(name) for name in PARAMETERS}
    frames = [me.ReferenceFrame("N")]
    origin = me.Point("O")
    origin.set_vel(frames[0], 0)
    joint = origin
    bodies = []
    potential = 0
    for k in range(N_LINKS):
        frame = me.ReferenceFrame(f"L{k + 1}")
        frame.orient_body_fixed(frames[-1], (beta[k], alpha[k], 0), "YXZ")
        frames.append(frame)
        length = p[f"l{k + 1}"]
        centre = joint.locatenew(f"C{k + 1}", -length / 2 * frame.z)
        bob = joint.locatenew(f"B{k + 1}", -length * frame.z)
        centre.v2pt_theory(joint, frames[0], frame)
        bob.v2pt_theory(joint, frames[0], frame)
        inertia = me.inertia(frame, p[f"i{k + 1}"], p[f"i{k + 1}"], 0)
        rod = me.RigidBody(f"rod{k + 1}", centre, frame, p[f"r{k + 1}"], (inertia, centre))
        ball = me.Particle(f"bob{k + 1}", bob, p[f"m{k + 1}"])
        bodies += [rod, ball]
        n_z = frames[0].z
        potential += p["g"] * (p[f"r{k + 1}"] * centre.pos_from(origin).dot(n_z)
                               + p[f"m{k + 1}"] * bob.pos_from(origin).dot(n_z))
        joint = bob
    kinetic = sum(b.kinetic_energy(frames[0]) for b in bodies)
    lagrangian = kinetic - potential
    method = me.LagrangesMethod(lagrangian, q)
    method.form_lagranges_equations()
    return q, p, method.mass_matrix, method.forcing, kinetic, potential


def main():
    start = time.time()
    q, p, mass, forcing, kinetic, potential = derive()
    qd = [sp.diff(c, me.dynamicsymbols._t) for c in q]
    plain_q = sp.symbols("q0:6")
    plain_qd = sp.symbols("qd0:6")
    rename = dict(zip(qd, plain_qd))
    rename.update(dict(zip(q, plain_q)))
    names = list(PARAMETERS)
    arguments = list(plain_q) + list(plain_qd) + [p[n] for n in names]
    exprs = [mass.xreplace(rename), forcing.xreplace(rename),
             kinetic.xreplace(rename), potential.xreplace(rename)]
    evaluate = sp.lambdify(arguments, exprs, modules="mpmath")
    mpmath.mp.dps = 30
    rng = random.Random(20261130)
    states = []
    for _ in range(12):
        qv = [rng.uniform(-1, 1) for _ in q]
        qdv = [rng.uniform(-2, 2) for _ in q]
        pv = [PARAMETERS[n] * rng.uniform(0.8, 1.2) for n in names]
        m, f, t_, v_ = evaluate(*[mpmath.mpf(x) for x in qv + qdv + pv])
        m_rows = [[float(m[i, j]) for j in range(len(q))] for i in range(len(q))]
        for i in range(len(q)):
            for j in range(len(q)):
                assert abs(m_rows[i][j] - m_rows[j][i]) <= 1e-12 * max(1.0, abs(m_rows[i][j]))
        states.append({
            "t": 0.0, "q": qv, "qd": qdv, "parameters": pv, "inputs": [],
            "mass_matrix": m_rows,
            "forcing": [float(f[i]) for i in range(len(q))],
            "kinetic": float(t_), "potential": float(v_), "dissipation": 0.0,
        })
    out = {
        "generator": "tests/reference/conical_pendulum_reference.py",
        "sympy_version": sp.__version__,
        "mpmath_version": mpmath.__version__,
        "seconds": round(time.time() - start, 1),
        "models": {"three_link_conical_pendulum": {
            "spec": "tests/specs/three_link_conical_pendulum.lpm",
            "coordinates": COORDINATES,
            "parameters": names,
            "inputs": [],
            "states": states,
        }},
    }
    path = Path(__file__).with_name("conical_pendulum_reference.json")
    path.write_text(json.dumps(out, indent=1) + "\n")
    print(f"wrote {path} in {out['seconds']} s")


if __name__ == "__main__":
    main()
