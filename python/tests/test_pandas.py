"""With pandas installed, trajectories and sweep tables are DataFrames: the
frames pandas reads from the files of `lpm simulate` and `lpm sweep`."""

import pandas
from pandas.testing import assert_frame_equal

import lagrangian
from conftest import SPECS, run_lpm

YARIS = SPECS / "yaris_double_pendulum.lpm"


def test_a_trajectory_is_the_dataframe_of_trajectory_csv(tmp_path):
    result = lagrangian.simulate(YARIS, t_end=0.03)
    run_lpm("simulate", YARIS, "--t-end", "0.03", "--out", tmp_path)
    assert isinstance(result.trajectory, pandas.DataFrame)
    assert_frame_equal(result.trajectory, pandas.read_csv(tmp_path / "trajectory.csv"), check_exact=True)
    assert result.trajectory["t [s]"].iloc[-1] == 0.03


def test_a_sweep_is_the_dataframe_of_its_csv(tmp_path):
    scenario = SPECS / "scenarios" / "yaris_full_frontal.toml"
    table = lagrangian.sweep(scenario=scenario, grid={"k1": [5e4, 6e4, 7e4]}, t_end=0.02)
    run_lpm("sweep", scenario, "--grid", "k1=5e4,6e4,7e4", "--set", "simulation.t_end=0.02",
            "--quiet", "--out", tmp_path / "sweep.csv")
    assert isinstance(table, pandas.DataFrame)
    assert_frame_equal(table, pandas.read_csv(tmp_path / "sweep.csv"), check_exact=True)
    assert table["run"].tolist() == [0, 1, 2] and table["k1"].tolist() == [5e4, 6e4, 7e4]
    assert (table["status"] == "ok").all()
