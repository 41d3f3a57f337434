#!/usr/bin/env python3
"""Independent SymPy reference for the Euler-Lagrange compiler.

What it is
----------
This script re-derives the equations of motion ``M(q) q'' = f(q, q', t)`` of
the project's example models with ``sympy.physics.mechanics.LagrangesMethod``,
written from the model definitions in ``specs/*.lpm`` only (it deliberately
does not look at the Rust derivation code, so that it is an independent
check).  For every model it evaluates M, f and the energies T, V and the
Rayleigh dissipation function D at 50 pseudo-random states with mpmath at 30
significant digits, and it records SymPy's own operation counts after
``sympy.cse`` for the Yaris model and a 10-link pendulum chain, as a yardstick
for the size of the Rust compiler's generated code.

Conventions
-----------
* ``L = T - V``; the equations are ``M q'' = f`` with
  ``f = LagrangesMethod.forcing - dD/dq'_i + Q_i``: the forcing already holds
  the generalized forces of the point forces passed in ``forcelist``
  (``Q_i = F . dp/dq_i``); Rayleigh dissipation and direct generalized forces
  (``force q = Q;`` in a spec) are added here.
* Input functions (``push(t)``, ``crush(r, r')``, ``barrier_x1(t)``, ...) are
  plain symbols; their value at each state is stored with the state.  Inputs
  that do not enter M or f (``crush_stiffness``, ``weld_damping``, ...) are
  stored as 0.0 (their random value is still drawn, then discarded).
* States are drawn with one ``random.Random(20261122)`` per model, in this
  order per state: t, q (spec order), q', parameters (spec order), inputs
  (spec order).  Coordinates are uniform in [-1, 1] (Yaris r: [-0.6, 0.2]),
  velocities in [-2, 2] (Yaris r': [-16, 2]), t in [0, 0.2], parameters are
  default * U(0.8, 1.2) (a zero default, i.e. an inertia, is U(0, 50)),
  inputs U(-1e5, 1e5) for the Yaris model and U(-10, 10) otherwise.

How to run
----------
From the repository root::

    python3 tests/reference/sympy_reference.py

(Python >= 3.9 with sympy and mpmath; about a minute on two cores.)  It
writes ``tests/reference/sympy_reference.json``; the state values are
deterministic, only the recorded timings change from run to run.  The
script asserts its sanity checks (symmetric M, a second hand-written
Euler-Lagrange derivation, textbook closed forms, the paper's eqs 23 and
37-40 for the Yaris model) before writing anything.

The JSON file is committed to the repository and read by the Rust tests, so
the tests need neither Python nor SymPy; re-run this script only when a spec
or the reference itself changes, and commit the regenerated JSON.
"""

import json
import multiprocessing
import random
import re
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import mpmath
import sympy as sp
from sympy.physics.mechanics import (LagrangesMethod, Point, ReferenceFrame,
                                     dynamicsymbols, msubs)

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
OUTPUT = HERE / "sympy_reference.json"

SEED = 20261122
N_STATES = 50
DIGITS = 30
TRIGSIMP_LIMIT_S = 60.0

T_SYM = dynamicsymbols._t
HALF = sp.Rational(1, 2)


def dot(expr):
    """Total time derivative, like ``dot(e)`` in the spec language."""
    return sp.diff(expr, T_SYM)


# ---------------------------------------------------------------------------
# Reading the declarations (names and default values) of a spec file.  Only
# used to take the parameter defaults and to check that the hand-written
# models below use the spec's names in the spec's order.
# ---------------------------------------------------------------------------

def _block(text, keyword):
    """Body of the top-level ``keyword { ... }`` block, or '' if absent."""
    match = re.search(r"^\s*" + keyword + r"\s*\{", text, re.M)
    if not match:
        return ""
    depth, start = 1, match.end()
    for pos in range(start, len(text)):
        if text[pos] == "{":
            depth += 1
        elif text[pos] == "}":
            depth -= 1
            if depth == 0:
                return text[start:pos]
    raise ValueError(f"unbalanced braces in block {keyword!r}")


def _strip_comments(text):
    return re.sub(r"//[^\n]*", "", text)


def _eval_default(expr):
    expr = expr.strip()
    if not re.fullmatch(r"[0-9eE.+\-*/ ()]+", expr):
        raise ValueError(f"unsupported default value {expr!r}")
    return float(eval(expr, {"__builtins__": {}}))  # digits and + - * / only


def read_spec_declarations(relpath):
    """Return (coordinates, [(parameter, default)], inputs) of a spec."""
    text = _strip_comments((ROOT / relpath).read_text(encoding="utf-8"))
    coords = re.findall(r"^\s*(\w+)\s*\[", _block(text, "coordinates"), re.M)
    params = [(name, _eval_default(value)) for name, value in re.findall(
        r"^\s*(\w+)\s*\[[^\]]*\]\s*=\s*([^,\n]+)",
        _block(text, "parameters"), re.M)]
    inputs_body = _block(text, "inputs")
    while re.search(r"\{[^{}]*\}", inputs_body):  # drop d(x) = ... blocks
        inputs_body = re.sub(r"\{[^{}]*\}", "", inputs_body)
    inputs = re.findall(r"^\s*(\w+)\s*\(", inputs_body, re.M)
    return coords, params, inputs


# ---------------------------------------------------------------------------
# Model definitions.
# ---------------------------------------------------------------------------

@dataclass
class Model:
    """A mechanical model as SymPy expressions in dynamicsymbols."""

    name: str
    spec: str
    q: list                      # coordinates, dynamicsymbols, spec order
    params: list                 # parameter symbols, spec order
    defaults: list               # parameter default values
    inputs: list                 # input symbols, spec order (all declared)
    kinetic: sp.Expr
    potential: sp.Expr
    dissipation: sp.Expr = sp.S.Zero
    frame: ReferenceFrame = None
    origin: Point = None         # fixed point the force points hang off
    forcelist: list = field(default_factory=list)  # (Point, Vector) pairs
    direct_forces: dict = field(default_factory=dict)  # coordinate -> Q
    q_ranges: list = None        # per coordinate (lo, hi); default (-1, 1)
    qd_ranges: list = None       # per velocity (lo, hi); default (-2, 2)
    input_range: float = 10.0


def _spec_model(name, relpath, q_names, p_names, in_names):
    """Symbols for a spec model, after checking the names against the spec."""
    coords, params, inputs = read_spec_declarations(relpath)
    assert coords == q_names, (relpath, coords)
    assert [p for p, _ in params] == p_names, (relpath, params)
    assert inputs == in_names, (relpath, inputs)
    q = list(dynamicsymbols(" ".join(q_names), seq=True))
    p = list(sp.symbols(" ".join(p_names), real=True, seq=True))
    u = list(sp.symbols(" ".join(in_names), real=True, seq=True)) \
        if in_names else []
    return q, p, [d for _, d in params], u


def simple_pendulum():
    relpath = "specs/simple_pendulum.lpm"
    (theta,), (m, l, inertia, g), defaults, _ = _spec_model(
        "simple_pendulum", relpath, ["theta"], ["m", "l", "I", "g"], [])
    x = l * sp.sin(theta)
    y = -l * sp.cos(theta)
    kinetic = (HALF * m * (dot(x)**2 + dot(y)**2)
               + HALF * inertia * dot(theta)**2)
    return Model("simple_pendulum", relpath, [theta], [m, l, inertia, g],
                 defaults, [], kinetic, m * g * y)


def double_pendulum():
    relpath = "specs/double_pendulum.lpm"
    q, p, defaults, _ = _spec_model(
        "double_pendulum", relpath, ["theta1", "theta2"],
        ["m1", "m2", "l1", "l2", "g"], [])
    theta1, theta2 = q
    m1, m2, l1, l2, g = p
    x1 = l1 * sp.sin(theta1)
    y1 = -l1 * sp.cos(theta1)
    x2 = x1 + l2 * sp.sin(theta2)
    y2 = y1 - l2 * sp.cos(theta2)
    kinetic = (HALF * m1 * (dot(x1)**2 + dot(y1)**2)
               + HALF * m2 * (dot(x2)**2 + dot(y2)**2))
    potential = m1 * g * y1 + m2 * g * y2
    return Model("double_pendulum", relpath, q, p, defaults, [],
                 kinetic, potential)


def spring_mass_damper():
    relpath = "specs/spring_mass_damper.lpm"
    (x,), (m, k, c), defaults, (push,) = _spec_model(
        "spring_mass_damper", relpath, ["x"], ["m", "k", "c"], ["push"])
    return Model("spring_mass_damper", relpath, [x], [m, k, c], defaults,
                 [push],
                 kinetic=HALF * m * dot(x)**2,
                 potential=HALF * k * x**2,
                 dissipation=HALF * c * dot(x)**2,
                 direct_forces={x: push})          # force x = push(t);


def elastic_pendulum():
    relpath = "specs/elastic_pendulum.lpm"
    q, p, defaults, _ = _spec_model(
        "elastic_pendulum", relpath, ["r", "theta"],
        ["m", "I", "l0", "ls", "k", "c", "ks", "cs", "g"], [])
    r, theta = q
    m, inertia, l0, ls, k, c, ks, cs, g = p
    x = (l0 + r) * sp.cos(theta)
    z = (l0 + r) * sp.sin(theta)
    s = (l0 + r - ls) * theta          # suspension deflection
    kinetic = (HALF * m * (dot(x)**2 + dot(z)**2)
               + HALF * inertia * dot(theta)**2)
    potential = m * g * z + HALF * k * r**2 + HALF * ks * s**2
    dissipation = HALF * c * dot(r)**2 + HALF * cs * dot(s)**2
    return Model("elastic_pendulum", relpath, q, p, defaults, [],
                 kinetic, potential, dissipation)


def yaris_double_pendulum():
    """Noorsumar et al. section 2.2, as corrected in the spec file."""
    relpath = "specs/yaris_double_pendulum.lpm"
    p_names = ["m1", "m2", "l0", "l1", "l2", "l3", "I1", "I2", "k1", "k2",
               "c1", "c2", "k_comp", "c_comp", "k_tor", "c_tor", "g"]
    in_names = ["crush", "crush_stiffness", "crush_damping", "barrier_x1",
                "barrier_z1", "barrier_x2", "barrier_z2", "weld",
                "weld_stiffness", "weld_damping"]
    q, p, defaults, u = _spec_model(
        "yaris_double_pendulum", relpath, ["r", "theta1", "theta2"],
        p_names, in_names)
    r, theta1, theta2 = q
    (m1, m2, l0, l1, l2, l3, i1, i2, k1, k2, c1, c2, k_comp, c_comp, k_tor,
     c_tor, g) = p
    crush, _, _, bx1, bz1, bx2, bz2, weld, _, _ = u

    # Positions of the two lumped masses (eqs 4-7); x into the car, z up.
    x1 = (l0 + r) * sp.cos(theta1)
    z1 = (l0 + r) * sp.sin(theta1)
    x2 = (l0 + r) * sp.cos(theta1) + l1 * sp.cos(theta1) + l2 * sp.cos(theta2)
    z2 = (l0 + r) * sp.sin(theta1) + l1 * sp.sin(theta1) + l2 * sp.sin(theta2)
    # Suspension deflections (eqs 21-22).
    r1 = (l0 + r - l3) * theta1
    r2 = (l0 + r + l1) * theta1 + l2 * theta2

    kinetic = (HALF * m1 * (dot(x1)**2 + dot(z1)**2)
               + HALF * m2 * (dot(x2)**2 + dot(z2)**2)
               + HALF * i1 * dot(theta1)**2 + HALF * i2 * dot(theta2)**2)
    potential = (m1 * g * z1 + m2 * g * z2 + HALF * k_comp * r**2
                 + HALF * k1 * r1**2 + HALF * k2 * r2**2
                 + HALF * k_tor * theta2**2)
    dissipation = (HALF * c_comp * dot(r)**2 + HALF * c1 * dot(r1)**2
                   + HALF * c2 * dot(r2)**2 + HALF * c_tor * dot(theta2)**2)

    # Barrier forces act at the two mass points (virtual work, eqs 31-39).
    frame = ReferenceFrame("N")
    origin = Point("O")                 # the impact point on the barrier
    origin.set_vel(frame, 0)
    forcelist = []
    for label, (px, pz), (fx, fz) in (("P1", (x1, z1), (bx1, bz1)),
                                      ("P2", (x2, z2), (bx2, bz2))):
        point = origin.locatenew(label, px * frame.x + pz * frame.z)
        point.set_vel(frame, point.pos_from(origin).dt(frame))
        forcelist.append((point, fx * frame.x + fz * frame.z))

    return Model("yaris_double_pendulum", relpath, q, p, defaults, u,
                 kinetic, potential, dissipation, frame=frame,
                 origin=origin, forcelist=forcelist,
                 # force r = -crush(r, dot(r)); force theta2 = -weld(...);
                 direct_forces={r: -crush, theta2: -weld},
                 q_ranges=[(-0.6, 0.2), (-1.0, 1.0), (-1.0, 1.0)],
                 qd_ranges=[(-16.0, 2.0), (-2.0, 2.0), (-2.0, 2.0)],
                 input_range=1.0e5)


def pendulum_chain(n):
    """Planar chain of n point masses on massless rods (absolute angles)."""
    q = list(dynamicsymbols(" ".join(f"theta{k}" for k in range(1, n + 1)),
                            seq=True))
    m = sp.symbols(" ".join(f"m{k}" for k in range(1, n + 1)), real=True,
                   seq=True)
    l = sp.symbols(" ".join(f"l{k}" for k in range(1, n + 1)), real=True,
                   seq=True)
    g = sp.Symbol("g", real=True)
    x = y = kinetic = potential = sp.S.Zero
    for k in range(n):
        x += l[k] * sp.sin(q[k])
        y -= l[k] * sp.cos(q[k])
        kinetic += HALF * m[k] * (dot(x)**2 + dot(y)**2)
        potential += g * m[k] * y
    params = [s for k in range(n) for s in (m[k], l[k])] + [g]
    defaults = [1.0] * (2 * n) + [9.81]
    return Model(f"pendulum_chain_{n}", f"generated:pendulum_chain({n})",
                 q, params, defaults, [], kinetic, potential)


# ---------------------------------------------------------------------------
# Derivation.
# ---------------------------------------------------------------------------

@dataclass
class Derived:
    model: Model
    mass_matrix: sp.Matrix        # in dynamicsymbols, as SymPy gives it
    forcing: sp.Matrix            # LagrangesMethod forcing + extra forces
    seconds: float                # LagrangesMethod time only
    # Plain-symbol versions (q -> q_sym, q' -> qd_sym).
    q_syms: list = None
    qd_syms: list = None
    plain: dict = None


def derive(model):
    lagrangian = model.kinetic - model.potential
    start = time.perf_counter()
    lm = LagrangesMethod(lagrangian, model.q,
                         forcelist=model.forcelist or None,
                         frame=model.frame)
    lm.form_lagranges_equations()
    mass_matrix = lm.mass_matrix
    forcing = lm.forcing
    seconds = time.perf_counter() - start

    # Generalized forces LagrangesMethod does not know about: Rayleigh
    # dissipation and the direct `force q = Q;` terms of the spec.
    extra = sp.Matrix([
        -sp.diff(model.dissipation, dot(qi)) + model.direct_forces.get(qi, 0)
        for qi in model.q])
    forcing = forcing + extra

    q_syms = [sp.Symbol(f"q_{qi.func.__name__}", real=True) for qi in model.q]
    qd_syms = [sp.Symbol(f"qd_{qi.func.__name__}", real=True)
               for qi in model.q]
    to_plain = {**{dot(qi): s for qi, s in zip(model.q, qd_syms)},
                **dict(zip(model.q, q_syms))}
    plain = {
        "mass_matrix": msubs(mass_matrix, to_plain),
        "forcing": msubs(forcing, to_plain),
        "kinetic": msubs(model.kinetic, to_plain),
        "potential": msubs(model.potential, to_plain),
        "dissipation": msubs(model.dissipation, to_plain),
    }
    for key, value in plain.items():
        leftover = sp.Matrix([value]).atoms(sp.Function, sp.Derivative)
        leftover = {a for a in leftover if a.has(T_SYM)}
        assert not leftover, (model.name, key, leftover)
    return Derived(model, mass_matrix, forcing, seconds, q_syms, qd_syms,
                   plain)


def hand_euler_lagrange(derived):
    """Second derivation, by hand with plain symbols, to check SymPy's.

    M = d2T/dq'dq', f_i = dL/dq_i - sum_j d2L/dq'_i dq_j q'_j - dD/dq'_i + Q_i
    (no explicit time dependence: inputs are plain symbols).  The point
    forces enter through Q_i = F . dp/dq_i, computed from the positions.
    """
    model = derived.model
    q, qd = derived.q_syms, derived.qd_syms
    kin = derived.plain["kinetic"]
    lag = kin - derived.plain["potential"]
    dis = derived.plain["dissipation"]
    n = len(q)
    mass = sp.Matrix(n, n, lambda i, j: sp.diff(kin, qd[i], qd[j]))
    to_plain = {**{dot(qi): s for qi, s in zip(model.q, qd)},
                **dict(zip(model.q, q))}
    forcing = []
    for i in range(n):
        dl_dqd = sp.diff(lag, qd[i])
        fi = sp.diff(lag, q[i]) - sum(sp.diff(dl_dqd, q[j]) * qd[j]
                                      for j in range(n))
        fi -= sp.diff(dis, qd[i])
        direct = sp.sympify(model.direct_forces.get(model.q[i], 0))
        fi += msubs(direct, to_plain)
        for point, force in model.forcelist:
            pos = msubs(point.pos_from(model.origin), to_plain)
            fi += force.dot(pos.diff(q[i], model.frame))
        forcing.append(fi)
    return mass, sp.Matrix(forcing)


# ---------------------------------------------------------------------------
# Random states and numerical evaluation with mpmath.
# ---------------------------------------------------------------------------

def draw_states(model, rng):
    n = len(model.q)
    q_ranges = model.q_ranges or [(-1.0, 1.0)] * n
    qd_ranges = model.qd_ranges or [(-2.0, 2.0)] * n
    states = []
    for _ in range(N_STATES):
        t = rng.uniform(0.0, 0.2)
        q = [rng.uniform(lo, hi) for lo, hi in q_ranges]
        qd = [rng.uniform(lo, hi) for lo, hi in qd_ranges]
        params = [rng.uniform(0.0, 50.0) if d == 0.0
                  else d * rng.uniform(0.8, 1.2) for d in model.defaults]
        inputs = [rng.uniform(-model.input_range, model.input_range)
                  for _ in model.inputs]
        states.append({"t": t, "q": q, "qd": qd, "parameters": params,
                       "inputs": inputs})
    return states


def used_inputs(derived):
    """Mask of the inputs that occur in M or f."""
    occurring = (derived.plain["mass_matrix"].free_symbols
                 | derived.plain["forcing"].free_symbols)
    return [u in occurring for u in derived.model.inputs]


def evaluate(derived, states):
    """Fill in M, f, T, V, D (30 digits, stored as floats) for every state."""
    model = derived.model
    args = derived.q_syms + derived.qd_syms + model.params + model.inputs
    funcs = {key: sp.lambdify(args, value, modules="mpmath")
             for key, value in derived.plain.items()}
    mask = used_inputs(derived)
    results = []
    with mpmath.workdps(DIGITS):
        for state in states:
            state = dict(state)
            state["inputs"] = [v if used else 0.0
                               for v, used in zip(state["inputs"], mask)]
            values = [mpmath.mpf(v) for v in state["q"] + state["qd"]
                      + state["parameters"] + state["inputs"]]
            mass = funcs["mass_matrix"](*values)
            forcing = funcs["forcing"](*values)
            n = len(model.q)
            exact = {
                "mass_matrix": [[mpmath.mpf(mass[i, j]) for j in range(n)]
                                for i in range(n)],
                "forcing": [mpmath.mpf(forcing[i, 0]) for i in range(n)],
                "kinetic": mpmath.mpf(funcs["kinetic"](*values)),
                "potential": mpmath.mpf(funcs["potential"](*values)),
                "dissipation": mpmath.mpf(funcs["dissipation"](*values)),
            }
            results.append((state, exact, values))
    return results


def close(a, b, scale, rel=mpmath.mpf("1e-25")):
    return abs(a - b) <= rel * (1 + abs(scale))


# ---------------------------------------------------------------------------
# Sanity checks.
# ---------------------------------------------------------------------------

def check_symmetry(model, results):
    n = len(model.q)
    for _, exact, _ in results:
        mass = exact["mass_matrix"]
        scale = max(abs(v) for row in mass for v in row)
        for i in range(n):
            for j in range(i + 1, n):
                assert close(mass[i][j], mass[j][i], scale), \
                    (model.name, i, j, mass[i][j], mass[j][i])


def check_against_hand_derivation(derived, results):
    """Compare SymPy's M and f with hand_euler_lagrange at every state."""
    model = derived.model
    mass, forcing = hand_euler_lagrange(derived)
    args = derived.q_syms + derived.qd_syms + model.params + model.inputs
    f_mass = sp.lambdify(args, mass, modules="mpmath")
    f_forcing = sp.lambdify(args, forcing, modules="mpmath")
    n = len(model.q)
    with mpmath.workdps(DIGITS):
        for _, exact, values in results:
            mass_h, forcing_h = f_mass(*values), f_forcing(*values)
            m_scale = max(abs(v) for row in exact["mass_matrix"] for v in row)
            f_scale = max(abs(v) for v in exact["forcing"]) + m_scale
            for i in range(n):
                assert close(exact["forcing"][i], forcing_h[i, 0], f_scale), \
                    (model.name, "forcing", i)
                for j in range(n):
                    assert close(exact["mass_matrix"][i][j], mass_h[i, j],
                                 m_scale), (model.name, "mass", i, j)


def check_chain_closed_form(model, results):
    """M_ij = (sum_{k >= max(i,j)} m_k) l_i l_j cos(theta_i - theta_j)."""
    n = len(model.q)
    names = [str(p) for p in model.params]
    state, exact, _ = results[0]
    with mpmath.workdps(DIGITS):
        p = dict(zip(names, map(mpmath.mpf, state["parameters"])))
        theta = list(map(mpmath.mpf, state["q"]))
        for i in range(n):
            for j in range(n):
                mass = sum(p[f"m{k + 1}"] for k in range(max(i, j), n))
                want = (mass * p[f"l{i + 1}"] * p[f"l{j + 1}"]
                        * mpmath.cos(theta[i] - theta[j]))
                assert close(exact["mass_matrix"][i][j], want, want), \
                    (model.name, i, j)


def check_simple_closed_forms(model, results):
    """Textbook M and f of the two 1-DOF models, at every state."""
    with mpmath.workdps(DIGITS):
        for state, exact, _ in results:
            p = dict(zip(map(str, model.params),
                         map(mpmath.mpf, state["parameters"])))
            q, qd = map(mpmath.mpf, state["q"]), map(mpmath.mpf, state["qd"])
            (q,), (qd,) = list(q), list(qd)
            if model.name == "simple_pendulum":
                mass = p["m"] * p["l"]**2 + p["I"]
                forcing = -p["m"] * p["g"] * p["l"] * mpmath.sin(q)
            else:  # spring_mass_damper: m x'' = -k x - c x' + push
                mass = p["m"]
                forcing = (-p["k"] * q - p["c"] * qd
                           + mpmath.mpf(state["inputs"][0]))
            assert close(exact["mass_matrix"][0][0], mass, mass), model.name
            assert close(exact["forcing"][0], forcing, forcing), model.name


def check_yaris_against_paper(derived):
    """Symbolic checks of the Yaris model against the paper's equations.

    Barrier generalized forces: eqs 37-39.  Potential: eq 23 with ½k_comp·r²
    (eq 23 prints ½k_comp·r1²; eq 25 has k_comp·r).  Dissipation: eq 40 with
    ½c_tor·θ̇2² (eq 40 prints ½c_tor·θ̇2).  The piecewise-linear crush force
    and the weld moment are the `crush` and `weld` inputs on top.
    """
    model = derived.model
    r, th1, th2 = derived.q_syms
    rd, th1d, th2d = derived.qd_syms
    p = dict(zip(map(str, model.params), model.params))
    u = dict(zip(map(str, model.inputs), model.inputs))
    m1, m2, l0, l1, l2, l3 = (p[k] for k in ("m1", "m2", "l0", "l1", "l2",
                                             "l3"))
    k1, k2, c1, c2 = p["k1"], p["k2"], p["c1"], p["c2"]
    bx1, bz1, bx2, bz2 = (u[k] for k in ("barrier_x1", "barrier_z1",
                                         "barrier_x2", "barrier_z2"))
    s1, c1_, s2, c2_ = sp.sin(th1), sp.cos(th1), sp.sin(th2), sp.cos(th2)
    q_bar = sp.Matrix([
        bx1 * c1_ + bz1 * s1 + bx2 * c1_ + bz2 * s1,                    # (37)
        -bx1 * (l0 + r) * s1 + bz1 * (l0 + r) * c1_                      # (38)
        - bx2 * ((l0 + r) * s1 + l1 * s1) + bz2 * ((l0 + r) * c1_ + l1 * c1_),
        -bx2 * l2 * s2 + bz2 * l2 * c2_,                                 # (39)
    ])
    forcing = derived.plain["forcing"]
    no_barrier = forcing.subs({bx1: 0, bz1: 0, bx2: 0, bz2: 0})
    assert sp.expand(forcing - no_barrier - q_bar) == sp.zeros(3, 1)

    potential = (m1 * p["g"] * (l0 + r) * s1                             # (23)
                 + m2 * p["g"] * ((l0 + r) * s1 + l1 * s1 + l2 * s2)
                 + HALF * k1 * (l0 + r - l3)**2 * th1**2
                 + HALF * k2 * ((l0 + r + l1) * th1 + l2 * th2)**2
                 + HALF * p["k_comp"] * r**2
                 + HALF * p["k_tor"] * th2**2)
    assert sp.expand(derived.plain["potential"] - potential) == 0
    dissipation = (HALF * c1 * ((l0 + r - l3) * th1d + rd * th1)**2     # (40)
                   + HALF * c2 * ((l0 + r + l1) * th1d + rd * th1
                                  + l2 * th2d)**2
                   + HALF * p["c_comp"] * rd**2
                   + HALF * p["c_tor"] * th2d**2)
    assert sp.expand(derived.plain["dissipation"] - dissipation) == 0


# ---------------------------------------------------------------------------
# Operation counts after common-subexpression elimination.
# ---------------------------------------------------------------------------

def cse_op_counts(derived, transform=None):
    """Ops of cse([upper triangle of M] + [f]) as count_ops(visual=True)."""
    mass, forcing = derived.plain["mass_matrix"], derived.plain["forcing"]
    n = mass.shape[0]
    exprs = [mass[i, j] for i in range(n) for j in range(i, n)] + list(forcing)
    transform_seconds = 0.0
    if transform is not None:
        start = time.perf_counter()
        exprs = [transform(e) for e in exprs]
        transform_seconds = time.perf_counter() - start
    start = time.perf_counter()
    replacements, reduced = sp.cse(exprs)
    cse_seconds = time.perf_counter() - start
    visual = sp.S.Zero
    for _, rhs in replacements:
        visual += sp.count_ops(rhs, visual=True)
    for expr in reduced:
        visual += sp.count_ops(expr, visual=True)
    by_kind = {str(k): int(v) for k, v in
               sorted(visual.as_coefficients_dict().items(), key=str)
               if v != 0}
    by_kind.pop("1", None)
    record = {
        "total": sum(by_kind.values()),
        "by_kind": by_kind,
        "derivation_seconds": round(derived.seconds, 3),
        "cse_seconds": round(cse_seconds, 3),
        "expressions": len(exprs),
        "cse_replacements": len(replacements),
    }
    if transform is not None:
        record["trigsimp_seconds"] = round(transform_seconds, 3)
    return record


def _trigsimp_worker(derived_plain, n_seconds, queue):
    derived = Derived(None, None, None, n_seconds, plain=derived_plain)
    queue.put(cse_op_counts(derived, transform=sp.trigsimp))


def trigsimp_op_counts(derived, limit):
    """cse_op_counts with trigsimp, in a child process killed after limit s."""
    ctx = multiprocessing.get_context("fork")
    queue = ctx.Queue()
    plain = {k: derived.plain[k] for k in ("mass_matrix", "forcing")}
    proc = ctx.Process(target=_trigsimp_worker,
                       args=(plain, derived.seconds, queue))
    start = time.perf_counter()
    proc.start()
    proc.join(limit)
    if proc.is_alive():
        proc.terminate()
        proc.join()
        return {"skipped": f"trigsimp of the {len(plain['forcing'])} forcing "
                           f"and mass-matrix entries did not finish within "
                           f"{limit:.0f} s"}
    if proc.exitcode != 0 or queue.empty():
        return {"skipped": f"trigsimp worker failed (exit {proc.exitcode})"}
    record = queue.get()
    record["wall_seconds"] = round(time.perf_counter() - start, 3)
    return record


# ---------------------------------------------------------------------------
# Main.
# ---------------------------------------------------------------------------

def as_float(x):
    return float(x)


def build_model_entry(derived, results):
    model = derived.model
    states = []
    for state, exact, _ in results:
        entry = dict(state)
        entry["mass_matrix"] = [[as_float(v) for v in row]
                                for row in exact["mass_matrix"]]
        entry["forcing"] = [as_float(v) for v in exact["forcing"]]
        for key in ("kinetic", "potential", "dissipation"):
            entry[key] = as_float(exact[key])
        states.append(entry)
    return {
        "spec": model.spec,
        "coordinates": [qi.func.__name__ for qi in model.q],
        "parameters": [str(p) for p in model.params],
        "inputs": [str(u) for u in model.inputs],
        "states": states,
    }


def main():
    wall_start = time.perf_counter()
    models = [simple_pendulum(), double_pendulum(), spring_mass_damper(),
              elastic_pendulum(), yaris_double_pendulum(), pendulum_chain(5)]
    out = {
        "generator": "tests/reference/sympy_reference.py",
        "sympy_version": sp.__version__,
        "mpmath_version": mpmath.__version__,
        "seed": SEED,
        "digits": DIGITS,
        "models": {},
        "cse_op_counts": {},
    }
    derived_by_name = {}
    for model in models:
        derived = derive(model)
        derived_by_name[model.name] = derived
        results = evaluate(derived, draw_states(model, random.Random(SEED)))
        check_symmetry(model, results)
        check_against_hand_derivation(derived, results)
        if model.name in ("double_pendulum", "pendulum_chain_5"):
            check_chain_closed_form(model, results)
        if model.name in ("simple_pendulum", "spring_mass_damper"):
            check_simple_closed_forms(model, results)
        if model.name == "yaris_double_pendulum":
            check_yaris_against_paper(derived)
        out["models"][model.name] = build_model_entry(derived, results)
        print(f"{model.name}: derived in {derived.seconds:.2f} s, "
              f"{len(results)} states", file=sys.stderr)

    yaris = derived_by_name["yaris_double_pendulum"]
    out["cse_op_counts"]["yaris_double_pendulum"] = cse_op_counts(yaris)
    chain10 = derive(pendulum_chain(10))
    out["cse_op_counts"]["pendulum_chain_10"] = cse_op_counts(chain10)
    out["cse_op_counts"]["yaris_double_pendulum_trigsimp"] = \
        trigsimp_op_counts(yaris, TRIGSIMP_LIMIT_S)
    for name, record in out["cse_op_counts"].items():
        print(f"{name}: {record}", file=sys.stderr)

    out["generation_seconds"] = round(time.perf_counter() - wall_start, 1)
    OUTPUT.write_text(json.dumps(out, indent=1) + "\n", encoding="utf-8")
    print(f"wrote {OUTPUT.relative_to(ROOT)} in "
          f"{out['generation_seconds']} s", file=sys.stderr)


if __name__ == "__main__":
    main()
