"""The package under the older pandas that pyisomme pins (this directory's
environment, python/test.sh): its DataFrames hold exactly the doubles lpm
wrote. pandas 2.2's default CSV parser reads some numbers one ulp off
(0.00030000000000000003 as 0.0003); the package asks it for exact ones."""

import csv

import pandas

import lagrangian
from conftest import SPECS, run_lpm

YARIS = SPECS / "yaris_double_pendulum.lpm"
SCENARIO = SPECS / "scenarios" / "yaris_full_frontal.toml"


def cells(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def assert_frame_is_csv(frame, path):
    header, body = cells(path)
    assert list(frame.columns) == header
    for k, name in enumerate(header):
        for value, row in zip(frame[name], body):
            try:
                expected = float(row[k])
            except ValueError:
                continue
            assert float(value) == expected or (row[k] == "" and value != value), (name, value, row[k])


def test_this_environment_has_a_pandas_before_3():
    # If pyisomme's pin moves to pandas 3, this file no longer tests what it says.
    assert int(pandas.__version__.split(".")[0]) < 3, pandas.__version__


def test_a_trajectory_holds_lpms_doubles_exactly(tmp_path):
    result = lagrangian.simulate(YARIS, scenario=SCENARIO, t_end=0.03)
    run_lpm("simulate", YARIS, "--scenario", SCENARIO, "--t-end", "0.03", "--out", tmp_path)
    assert_frame_is_csv(result.trajectory, tmp_path / "trajectory.csv")


def test_a_sweep_table_holds_lpms_doubles_exactly(tmp_path):
    out = tmp_path / "sweep.csv"
    table = lagrangian.sweep(scenario=SCENARIO, samples=5, vary={"k1": (5e4, 1e5)}, t_end=0.02)
    run_lpm("sweep", SCENARIO, "--samples", "5", "--vary", "k1=5e4:1e5", "--set", "simulation.t_end=0.02",
            "--quiet", "--out", out)
    assert_frame_is_csv(table, out)
