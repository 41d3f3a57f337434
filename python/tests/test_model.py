"""lagrangian.Model: M, f, q̈ and the energies against `lpm eval` and
closed forms; one state and batches; the equations."""

import json
import math

import numpy as np
import pytest

import lagrangian
from conftest import SPECS, run_lpm

PENDULUM = SPECS / "pendulum.lpm"  # m = 1, l = 2, g = 9.81, c = 0.1, torque(t)
YARIS = SPECS / "yaris_double_pendulum.lpm"
YARIS_INPUTS = {
    "crush": 1.2e5, "crush_stiffness": 2e5, "crush_damping": 3e3, "barrier_x1": -4e4,
    "barrier_z1": 1e3, "barrier_x2": -2e4, "barrier_z2": 5e2, "weld": 800.0,
    "weld_stiffness": 4e3, "weld_damping": 20.0,
}


def test_pendulum_accelerations_are_the_closed_form():
    model = lagrangian.Model(PENDULUM)
    theta, omega, torque = 0.7, -1.3, 2.5
    a = model.accelerations(0.0, [theta], [omega], inputs={"torque": torque})
    # m l² θ̈ = −m g l sin θ − c θ̇ + T
    expected = (-1 * 9.81 * 2 * math.sin(theta) - 0.1 * omega + torque) / (1 * 2**2)
    assert a.shape == (1,)
    assert a[0] == pytest.approx(expected, rel=1e-14)
    energies = model.energies(0.0, [theta], [omega], inputs={"torque": torque})
    assert energies["kinetic"] == pytest.approx(0.5 * 4 * omega**2, rel=1e-14)
    assert energies["potential"] == pytest.approx(-9.81 * 2 * math.cos(theta), rel=1e-14)
    assert energies["external_power"] == pytest.approx(torque * omega, rel=1e-14)


def eval_cli(q, qd, t=0.0):
    state = ",".join(repr(float(v)) for v in [*q, *qd])
    sets = [arg for name, value in YARIS_INPUTS.items() for arg in ("--set", f"{name}={value!r}")]
    out = run_lpm("eval", YARIS, "--state", state, "--time", t, *sets).stdout
    data = json.loads(out)
    return np.array(data["mass_matrix"]), np.array(data["forcing"])


def test_yaris_mass_forcing_and_accelerations_equal_lpm_eval():
    model = lagrangian.Model(YARIS)
    q, qd = [0.31, 0.12, -0.4], [-12.0, 3.5, 7.25]
    mass, forcing = eval_cli(q, qd)
    assert np.array_equal(model.mass_matrix(0.0, q, qd, YARIS_INPUTS), mass)
    assert np.array_equal(model.forcing(0.0, q, qd, YARIS_INPUTS), forcing)
    a = model.accelerations(0.0, q, qd, YARIS_INPUTS)
    expected = np.linalg.solve(mass, forcing)
    assert np.max(np.abs(a - expected)) <= 1e-12 * np.max(np.abs(expected))


def test_a_batch_is_its_rows_evaluated_one_by_one():
    model = lagrangian.Model(YARIS)
    rng = np.random.default_rng(7)
    q = rng.uniform(-0.5, 0.5, (20, 3))
    qd = rng.uniform(-10, 10, (20, 3))
    t = np.linspace(0, 0.1, 20)
    a = model.accelerations(t, q, qd, YARIS_INPUTS)
    mass = model.mass_matrix(t, q, qd, YARIS_INPUTS)
    energies = model.energies(t, q, qd, YARIS_INPUTS)
    assert a.shape == (20, 3) and mass.shape == (20, 3, 3)
    for k in range(20):
        assert np.array_equal(a[k], model.accelerations(t[k], q[k], qd[k], YARIS_INPUTS))
        assert np.array_equal(mass[k], model.mass_matrix(t[k], q[k], qd[k], YARIS_INPUTS))
        assert energies["kinetic"][k] == model.energies(t[k], q[k], qd[k], YARIS_INPUTS)["kinetic"]


def test_parameters_can_be_read_and_set():
    model = lagrangian.Model(PENDULUM)
    assert model.parameters == {"m": 1.0, "l": 2.0, "g": 9.81, "c": 0.1}
    model.set_parameter("l", 1.0)
    a = model.accelerations(0.0, [0.5], [0.0], inputs={"torque": 0.0})
    assert a[0] == pytest.approx(-9.81 * math.sin(0.5), rel=1e-14)
    with pytest.raises(lagrangian.UsageError, match="length"):
        model.set_parameter("length", 1.0)


def test_a_spec_given_as_text_and_its_equations():
    text = PENDULUM.read_text()
    model = lagrangian.Model(text)
    assert model.name == "Pendulum" and model.coordinates == ["theta"]
    assert model.derive() == run_lpm("derive", PENDULUM).stdout
    latex = model._repr_latex_()
    assert latex.startswith("$$") and latex.endswith("$$") and "\\ddot" in latex
    with pytest.raises(lagrangian.UsageError, match="choose text, latex or markdown"):
        model.derive("html")


def test_failures_raise_the_exception_of_their_exit_status():
    with pytest.raises(lagrangian.SpecError) as raised:
        lagrangian.Model("model X;\ncoordinates { x }\nkinetic = 0.5 * m * pow(dot(x), 2);\n")
    assert raised.value.status == 3
    assert "<spec>:3" in str(raised.value) and "`m`" in str(raised.value)
    model = lagrangian.Model(PENDULUM)
    with pytest.raises(lagrangian.UsageError, match="torque have no value"):
        model.accelerations(0.0, [0.1], [0.0])
    with pytest.raises(lagrangian.UsageError, match="1 coordinates"):
        model.accelerations(0.0, [0.1, 0.2], [0.0, 0.0], inputs={"torque": 0.0})
    model.set_parameter("m", 0.0)
    with pytest.raises(lagrangian.SingularMassMatrixError):
        model.accelerations(0.0, [0.1], [0.0], inputs={"torque": 0.0})
    assert issubclass(lagrangian.SingularMassMatrixError, lagrangian.LagrangianError)


def test_every_failing_exit_status_of_lpm_has_its_exception():
    help_text = run_lpm("--help").stdout
    for code, cls in lagrangian._ERRORS.items():
        assert cls.status == code
        assert f"{code:>3}" in help_text or f"{code} " in help_text
    assert len(lagrangian._ERRORS) == len(lagrangian._lagrangian.exit_statuses()) - 1
