"""lagrangian.simulate: the summary, trajectory and events of `lpm simulate`."""

import csv
import json

import numpy as np
import pytest

import lagrangian
from conftest import ROOT, SPECS, run_lpm

YARIS = SPECS / "yaris_double_pendulum.lpm"


def test_the_paper_scenario_gives_the_summary_of_lpm_simulate(tmp_path):
    result = lagrangian.simulate(YARIS)
    run_lpm("simulate", YARIS, "--out", tmp_path)
    assert result.summary == json.loads((tmp_path / "summary.json").read_text())
    with open(tmp_path / "trajectory.csv", newline="") as f:
        rows = list(csv.reader(f))
    columns = rows[0]
    trajectory = result.trajectory
    assert list(trajectory.keys()) == columns
    values = np.array(rows[1:], dtype=float)
    for k, name in enumerate(columns):
        assert np.array_equal(np.asarray(trajectory[name]), values[:, k]), name
    # The events the CLI lists: `58.41 ms  weld: weld fails at …`.
    printed = run_lpm("simulate", YARIS, "--out", tmp_path).stdout.split("events:\n")[1]
    listed = [line.strip().split(" ms  ", 1) for line in printed.splitlines() if " ms  " in line]
    ours = [[f"{e.t * 1e3:.2f}", f"{e.component}: {e.description}"] for e in result.events]
    assert ours == listed and len(ours) == 3
    assert result.events[0].t == result.summary["weld_failure_time_s"]
    assert result.events[-1].t == result.summary["end_of_contact_s"]


def test_settings_reach_the_scenario_as_set_does(tmp_path):
    result = lagrangian.simulate(YARIS, t_end=0.05, method="rk4", k1=7e4,
                                 set={"components.front_end.unloading": "elastic"})
    run_lpm("simulate", YARIS, "--t-end", "0.05", "--method", "rk4", "--set", "k1=70000.0",
            "--set", "components.front_end.unloading=elastic", "--out", tmp_path)
    assert result.summary == json.loads((tmp_path / "summary.json").read_text())


def test_a_scenario_that_does_not_fit_raises_scenario_error():
    with pytest.raises(lagrangian.ScenarioError, match="no_such_parameter"):
        lagrangian.simulate(YARIS, no_such_parameter=1.0)
    with pytest.raises(lagrangian.IoError):
        lagrangian.simulate(ROOT / "specs" / "no_such_spec.lpm")
