"""A model built from parts on the Python and FMU surfaces: the train of
tests/specs/parts/train_parts.lpm (cars, couplers, a crush element and a
belted driver from the standard library of parts) runs in Python as
`lpm simulate` runs it, its names `car[1].m`, `driver.x` …, a part's
parameter set by that name; its FMU validates, names its variables so, and
runs as `lpm simulate` does."""

import json

import pandas
import pytest
from fmpy import simulate_fmu
from fmpy.validation import validate_fmu

import lagrangian
from conftest import ROOT, run_lpm

SPEC = ROOT / "tests" / "specs" / "parts" / "train_parts.lpm"
SCENARIO = ROOT / "tests" / "specs" / "parts" / "train_parts.toml"


def lpm_run(tmp_path, *settings):
    args = [a for s in settings for a in ("--set", s)]
    run_lpm("simulate", SPEC, "--scenario", SCENARIO, *args, "--out", tmp_path)
    trajectory = pandas.read_csv(tmp_path / "trajectory.csv")
    return trajectory, json.loads((tmp_path / "summary.json").read_text())


def test_python_runs_a_model_of_parts_as_lpm_simulate(tmp_path):
    trajectory, summary = lpm_run(tmp_path, "car[1].m=25000", "simulation.t_end=0.2")
    result = lagrangian.simulate(SPEC, SCENARIO, set={"car[1].m": 25000}, t_end=0.2)
    pandas.testing.assert_frame_equal(result.trajectory, trajectory, check_exact=True)
    assert result.summary == summary
    assert "driver.x [m]" in result.trajectory.columns
    assert "coupler[2].force [N]" in result.trajectory.columns
    lighter = lagrangian.simulate(SPEC, SCENARIO, t_end=0.2).summary["max_crush_m"]
    assert summary["max_crush_m"] != lighter  # the setting reached car[1].m


def test_the_fmu_of_a_model_of_parts_runs_as_lpm_simulate(tmp_path):
    fmu = tmp_path / "train.fmu"
    run_lpm("export-fmu", SPEC, "--scenario", SCENARIO, "--out", fmu)
    assert validate_fmu(str(fmu)) == []
    _, summary = lpm_run(tmp_path / "run")
    for fmi_type in ["CoSimulation", "ModelExchange"]:
        result = simulate_fmu(str(fmu), fmi_type=fmi_type, relative_tolerance=1e-8,
                              output=["x[1]", "driver.travel", "metrics.crush"])
        assert result["time"][-1] == pytest.approx(0.4)
        crush = result["metrics.crush"].max()
        assert abs(crush - summary["max_crush_m"]) / summary["max_crush_m"] < 0.005, fmi_type
        travel = result["driver.travel"].max()
        expected = summary["channels"]["driver.travel"]["max"]
        assert abs(travel - expected) / expected < 0.005, fmi_type
