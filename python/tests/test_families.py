"""A model written with indexed families on the Python and FMU surfaces:
the Pioneer chain of tests/specs/pioneer_families.lpm (one section binds
its six springs) runs in Python as `lpm simulate` runs it, its elements
named `x[1]` …, an element set as `m[2]`; its FMU validates, names its
variables `x[1]` …, and runs as `lpm simulate` does."""

import json

import pandas
import pytest
from fmpy import simulate_fmu
from fmpy.validation import validate_fmu

import lagrangian
from conftest import ROOT, run_lpm

SPEC = ROOT / "tests" / "specs" / "pioneer_families.lpm"
SCENARIO = ROOT / "tests" / "specs" / "pioneer_families.toml"


def lpm_run(tmp_path, *settings):
    args = [a for s in settings for a in ("--set", s)]
    run_lpm("simulate", SPEC, "--scenario", SCENARIO, *args, "--out", tmp_path)
    trajectory = pandas.read_csv(tmp_path / "trajectory.csv")
    return trajectory, json.loads((tmp_path / "summary.json").read_text())


def test_python_runs_a_family_model_as_lpm_simulate(tmp_path):
    trajectory, summary = lpm_run(tmp_path, "m[2]=9000", "simulation.t_end=0.1")
    result = lagrangian.simulate(SPEC, SCENARIO, set={"m[2]": 9000}, t_end=0.1)
    pandas.testing.assert_frame_equal(result.trajectory, trajectory, check_exact=True)
    assert result.summary == summary
    assert list(result.trajectory.columns[1:3]) == ["x[1] [m]", "x[2] [m]"]
    assert "spring[6].force [N]" in result.trajectory.columns
    heavier = lagrangian.simulate(SPEC, SCENARIO, t_end=0.1).summary["max_crush_m"]
    assert summary["max_crush_m"] != heavier  # the setting reached m[2]


def test_the_fmu_of_a_family_model_runs_as_lpm_simulate(tmp_path):
    fmu = tmp_path / "pioneer.fmu"
    run_lpm("export-fmu", SPEC, "--scenario", SCENARIO, "--out", fmu)
    assert validate_fmu(str(fmu)) == []
    _, summary = lpm_run(tmp_path / "run")
    for fmi_type in ["CoSimulation", "ModelExchange"]:
        result = simulate_fmu(str(fmu), fmi_type=fmi_type, relative_tolerance=1e-8,
                              output=["x[1]", "spring[1].force", "metrics.crush"])
        assert result["time"][-1] == pytest.approx(0.25)
        crush = result["metrics.crush"].max()
        assert abs(crush - summary["max_crush_m"]) / summary["max_crush_m"] < 0.005, fmi_type
        assert result["spring[1].force"].max() > 1e6, fmi_type
