"""lagrangian.Model on specs with constraints: the constrained q̈ and the
multipliers λ against a closed form (a pendulum in Cartesian coordinates),
against `lpm eval` and against the first sample of `lagrangian.simulate`."""

import io
import json
import math

import numpy as np
import pytest

import lagrangian
from conftest import SPECS, run_lpm

# A point mass m on a massless rod of length l, in x, y (y up), the rod a
# constraint in metres: its multiplier is a force [N].
CARTESIAN_PENDULUM = """model CartesianPendulum;
coordinates { x [m], y [m] }
parameters { m [kg] = 2.0, l [m] = 1.5, g [m/s^2] = 9.81 }
kinetic = 0.5 * m * (pow(dot(x), 2) + pow(dot(y), 2));
potential = m * g * y;
constraint rod = sqrt(x * x + y * y) - l;
"""


def test_a_pendulum_at_rest_has_the_closed_form_acceleration_and_rod_tension():
    model = lagrangian.Model(CARTESIAN_PENDULUM)
    assert model.constraints == ["rod"]
    m, l, g = 2.0, 1.5, 9.81
    for theta in (0.0, 0.6, -1.1, 2.0):
        q = [l * math.sin(theta), -l * math.cos(theta)]
        a = model.accelerations(0.0, q, [0.0, 0.0])
        # At rest only the tangential part of gravity accelerates the mass:
        # g sin θ along −(cos θ, sin θ).
        expected = [-g * math.sin(theta) * math.cos(theta), -g * math.sin(theta) ** 2]
        assert a == pytest.approx(expected, abs=1e-12)
        # The rod pulls inwards with T = m g cos θ; G = (x, y)/l points
        # outwards, so its generalized force Gᵀλ is the pull for λ = −T.
        lam = model.multipliers(0.0, q, [0.0, 0.0])
        assert lam["rod"] == pytest.approx(-m * g * math.cos(theta), rel=1e-12, abs=1e-12)


def test_a_moving_pendulum_adds_the_centripetal_pull():
    model = lagrangian.Model(CARTESIAN_PENDULUM)
    m, l, g = 2.0, 1.5, 9.81
    theta, omega = 0.6, 1.7
    q = [l * math.sin(theta), -l * math.cos(theta)]
    qd = [l * omega * math.cos(theta), l * omega * math.sin(theta)]
    lam = model.multipliers(0.0, q, qd)
    # T = m g cos θ + m l ω².
    assert lam["rod"] == pytest.approx(-(m * g * math.cos(theta) + m * l * omega**2), rel=1e-12)
    a = model.accelerations(0.0, q, qd)
    # θ̈ = −(g/l) sin θ; the acceleration is l θ̈ t̂ − l ω² r̂.
    tangential, radial = -g * math.sin(theta), -l * omega**2
    expected = [tangential * math.cos(theta) + radial * math.sin(theta),
                tangential * math.sin(theta) - radial * math.cos(theta)]
    assert a == pytest.approx(expected, rel=1e-12)


def test_a_batch_gives_each_rows_multipliers():
    model = lagrangian.Model(CARTESIAN_PENDULUM)
    thetas = np.linspace(-1.0, 1.0, 5)
    q = np.column_stack([1.5 * np.sin(thetas), -1.5 * np.cos(thetas)])
    lam = model.multipliers(0.0, q, np.zeros_like(q))
    assert lam["rod"] == pytest.approx(-2.0 * 9.81 * np.cos(thetas), rel=1e-12)
    assert model.accelerations(0.0, q, np.zeros_like(q)).shape == (5, 2)


def test_an_unconstrained_spec_has_no_multipliers():
    model = lagrangian.Model(SPECS / "pendulum.lpm")
    assert model.constraints == []
    assert model.multipliers(0.0, [0.5], [0.0], inputs={"torque": 0.0}) == {}


def first_sample(spec):
    """q, q̇, q̈ and the multipliers of the first row of a run's trajectory."""
    result = lagrangian.simulate(spec, t_end=0.01)
    table = result.trajectory
    model = lagrangian.Model(spec)
    row = lambda name: float(np.asarray(table[name])[0])
    unit = lambda name: next(c for c in table.keys() if c.split(" [")[0] == name)
    q = [row(unit(c)) for c in model.coordinates]
    qd = [row(unit(f"{c}_dot")) for c in model.coordinates]
    qdd = [row(unit(f"{c}_ddot")) for c in model.coordinates]
    lam = {name: row(unit(f"{name}.lambda")) for name in model.constraints}
    return model, q, qd, qdd, lam


@pytest.mark.parametrize("name", ["four_bar_linkage", "slider_crank"])
def test_constrained_specs_give_simulates_first_sample_and_lpm_eval(name):
    spec = SPECS / f"{name}.lpm"
    model, q, qd, qdd, lam = first_sample(spec)
    scale = max(abs(v) for v in qdd)
    a = model.accelerations(0.0, q, qd)
    assert np.max(np.abs(a - qdd)) <= 1e-9 * scale, (a, qdd)
    found = model.multipliers(0.0, q, qd)
    for k, expected in lam.items():
        assert found[k] == pytest.approx(expected, rel=1e-9, abs=1e-12)
    state = ",".join(repr(v) for v in [*q, *qd])
    data = json.loads(run_lpm("eval", spec, "--state", state).stdout)
    assert np.array_equal(np.array(data["accelerations"]), a)
    assert data["constraints"]["names"] == model.constraints
    assert data["constraints"]["multipliers"] == [found[k] for k in model.constraints]
