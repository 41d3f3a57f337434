"""lagrangian.sweep, merge_sweep and sweep_plan: the tables of `lpm sweep`,
whole and in shards, compared with the command's files."""

import csv
import math
import sys

import pytest

import lagrangian
from conftest import ROOT, SPECS, run_lpm

SCENARIO = SPECS / "scenarios" / "yaris_full_frontal.toml"
# Seven short runs (20 ms of the crash) over two sampled axes.
SAMPLED = dict(samples=7, vary={"k1": (5e4, 1e5), "components.weld.failure_moment": (2e3, 8e3, "log")},
               t_end=0.02)
SAMPLED_CLI = ["--samples", "7", "--vary", "k1=5e4:1e5",
               "--vary", "components.weld.failure_moment=2e3:8e3:log",
               "--set", "simulation.t_end=0.02", "--quiet"]


def cli_table(tmp_path, *args, name="cli.csv"):
    out = tmp_path / name
    run_lpm("sweep", SCENARIO, *args, "--out", out)
    return out


def assert_table_is_csv(table, path):
    """`table` has the columns of the CSV file `path` and, cell by cell,
    its values (numbers equal as floats, empty cells NaN, text equal)."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    assert list(table.keys()) == header
    for k, name in enumerate(header):
        values = list(table[name])
        assert len(values) == len(body), name
        for value, row in zip(values, body):
            cell = row[k]
            if cell == "":
                assert isinstance(value, float) and math.isnan(value), (name, value)
                continue
            try:
                expected = float(cell)
            except ValueError:
                assert value == cell, name
                continue
            assert float(value) == expected, (name, value, cell)


def test_a_sampled_sweep_is_the_table_of_lpm_sweep(tmp_path):
    out = cli_table(tmp_path, *SAMPLED_CLI)
    table = lagrangian.sweep(scenario=SCENARIO, **SAMPLED)
    assert_table_is_csv(table, out)
    assert list(table["status"]) == ["ok"] * 7
    assert table.keys()[:5].tolist() == ["run", "k1", "components.weld.failure_moment", "status", "error"]
    # The native table is the command's file, byte for byte.
    options = lagrangian._sweep_options(SCENARIO, None, None, 7, SAMPLED["vary"], "latin-hypercube",
                                        1, None, {"t_end": 0.02})
    assert lagrangian._lagrangian.sweep_table(options) == out.read_text()


def test_without_pandas_the_table_is_a_dict_of_numpy_arrays(tmp_path, monkeypatch):
    out = cli_table(tmp_path, *SAMPLED_CLI)
    monkeypatch.setitem(sys.modules, "pandas", None)
    table = lagrangian.sweep(scenario=SCENARIO, **SAMPLED)
    assert isinstance(table, dict)
    assert table["run"].dtype.kind == "i" and table["k1"].dtype.kind == "f"
    assert_table_is_csv(table, out)


def test_a_grid_with_settings_is_the_table_of_lpm_sweep(tmp_path):
    out = cli_table(tmp_path, "--grid", "k1=5e4,7e4", "--grid", "initial.velocities.r*=0.9:1.1:3",
                    "--set", "simulation.t_end=0.02", "--set", "components.front_end.unloading=elastic",
                    "--threads", "1", "--quiet")
    table = lagrangian.sweep(SPECS / "yaris_double_pendulum.lpm",
                             grid={"k1": [5e4, 7e4], "initial.velocities.r*": "0.9:1.1:3"},
                             t_end=0.02, set={"components.front_end.unloading": "elastic"}, threads=1)
    assert_table_is_csv(table, out)
    assert len(table["run"]) == 6


def test_shards_are_the_rows_of_the_commands_shards_and_merge_to_the_full_table(tmp_path):
    full = cli_table(tmp_path, *SAMPLED_CLI, name="full.csv")
    parts = [lagrangian.sweep(scenario=SCENARIO, **SAMPLED, shard_index=k, shard_count=3)
             for k in range(3)]
    for k, part in enumerate(parts):
        assert_table_is_csv(part, cli_table(tmp_path, *SAMPLED_CLI, "--shard-index", str(k),
                                            "--shard-count", "3", name=f"part-{k}.csv"))
    assert [len(p["run"]) for p in parts] == [2, 2, 3]
    second = lagrangian.sweep(scenario=SCENARIO, **SAMPLED, shard="2/3")
    assert list(second["run"]) == list(parts[1]["run"]) == [2, 3]
    # Tables, in any order, and the command's files, CSV or Parquet.
    merged = lagrangian.merge_sweep(parts[::-1], scenario=SCENARIO, **SAMPLED)
    assert_table_is_csv(merged, full)
    run_lpm("sweep", SCENARIO, *SAMPLED_CLI, "--shard", "3/3", "--out", tmp_path / "c.parquet")
    out = tmp_path / "merged.csv"
    merged = lagrangian.merge_sweep([tmp_path / "c.parquet", parts[0], tmp_path / "part-1.csv"],
                                    scenario=SCENARIO, **SAMPLED, out=out)
    assert_table_is_csv(merged, full)
    assert out.read_bytes() == full.read_bytes()


def test_a_missing_or_foreign_part_is_a_data_file_error(tmp_path):
    parts = [lagrangian.sweep(scenario=SCENARIO, **SAMPLED, shard_index=k, shard_count=3)
             for k in range(3)]
    with pytest.raises(lagrangian.DataFileError, match=r"^parts\[1\]:2: runs 2\.\.4 are missing"):
        lagrangian.merge_sweep([parts[0], parts[2]], scenario=SCENARIO, **SAMPLED)
    with pytest.raises(lagrangian.DataFileError):
        lagrangian.merge_sweep(parts, scenario=SCENARIO, **dict(SAMPLED, samples=8))
    with pytest.raises(lagrangian.DataFileError, match="run 0"):
        lagrangian.merge_sweep(parts, scenario=SCENARIO, **SAMPLED, seed=2)


def test_the_plan_and_bad_options_read_as_the_command_line(tmp_path):
    plan = lagrangian.sweep_plan(scenario=SCENARIO, **SAMPLED)
    assert plan.startswith("7 runs over k1, components.weld.failure_moment\n"), plan
    assert "suggested split" in plan
    with pytest.raises(lagrangian.UsageError, match="--grid KEY=VALUES or --samples"):
        lagrangian.sweep(scenario=SCENARIO)
    with pytest.raises(lagrangian.UsageError, match="choose latin-hypercube or random"):
        lagrangian.sweep(scenario=SCENARIO, **SAMPLED, design="sobol")
    with pytest.raises(lagrangian.UsageError, match="not below the shard count"):
        lagrangian.sweep(scenario=SCENARIO, **SAMPLED, shard_index=3, shard_count=3)
    with pytest.raises(lagrangian.ScenarioError, match="no_such_key"):
        lagrangian.sweep(scenario=SCENARIO, grid={"no_such_key": [1.0]})
    with pytest.raises(lagrangian.UsageError, match="several scenarios|no scenario"):
        lagrangian.sweep(ROOT / "specs" / "pendulum.lpm", grid={"c": [0.1]})


def test_shard_auto_reads_the_schedulers_task(monkeypatch):
    second = lagrangian.sweep(scenario=SCENARIO, **SAMPLED, shard="2/3")
    for name, value in [("SLURM_ARRAY_TASK_ID", "2"), ("SLURM_ARRAY_TASK_MIN", "1"),
                        ("SLURM_ARRAY_TASK_COUNT", "3")]:
        monkeypatch.setenv(name, value)
    auto = lagrangian.sweep(scenario=SCENARIO, **SAMPLED, shard="auto")
    assert lagrangian._table_csv(auto) == lagrangian._table_csv(second)
    assert list(auto["run"]) == [2, 3]


def test_a_sweep_whose_every_run_fails_raises_every_run_failed(tmp_path):
    done = run_lpm("sweep", SCENARIO, "--grid", "k1=5e4,6e4", "--set", "simulation.max_steps=3",
                   "--quiet", "--out", tmp_path / "failed.csv", check=False)
    with pytest.raises(lagrangian.EveryRunFailedError, match="every run failed") as raised:
        lagrangian.sweep(scenario=SCENARIO, grid={"k1": [5e4, 6e4]}, set={"simulation.max_steps": 3})
    assert raised.value.status == done.returncode != 0
    assert "max_steps" in str(raised.value)


def test_ctrl_c_stops_a_sweep_and_raises_keyboard_interrupt():
    import os
    import signal
    import threading
    import time

    threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT)).start()
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        # Far more runs than finish in the test's time.
        lagrangian.sweep(scenario=SCENARIO, samples=100000, vary={"k1": (5e4, 1e5)}, threads=1)
    assert time.monotonic() - start < 10


def test_an_envelope_is_the_table_of_lpm_sweep_envelope_out(tmp_path):
    grid = {"initial.velocities.r": [-12, -15.5556, -18]}
    weights = {"initial.velocities.r": [0.2, 0.5, 0.3]}
    envelope_out = tmp_path / "envelope.csv"
    cli_table(tmp_path, "--grid", "initial.velocities.r=-12,-15.5556,-18",
              "--set", "simulation.t_end=0.02", "--quiet",
              "--envelope", "r,front_end.force", "--weights", "initial.velocities.r=0.2,0.5,0.3",
              "--envelope-out", envelope_out)
    table, envelope = lagrangian.sweep(scenario=SCENARIO, grid=grid, t_end=0.02,
                                       envelope=["r", "front_end.force"], weights=weights)
    assert_table_is_csv(envelope, envelope_out)
    assert len(table["run"]) == 3
    assert list(envelope.keys())[:6] == ["t", "r.min", "r.min_run", "r.max", "r.max_run", "r.mean"]
    with pytest.raises(lagrangian.UsageError, match="the weight of initial.velocities.r = -15.5556 is -0.5"):
        lagrangian.sweep(scenario=SCENARIO, grid=grid, t_end=0.02, envelope="r",
                         weights={"initial.velocities.r": [0.2, -0.5, 0.3]})


def test_shards_envelopes_merge_to_the_envelope_of_the_whole_sweep(tmp_path):
    grid = {"initial.velocities.r": [-12, -15.5556, -18]}
    weights = {"initial.velocities.r": [0.2, 0.5, 0.3]}
    plan = dict(scenario=SCENARIO, grid=grid, t_end=0.02, envelope=["r", "front_end.force"],
                weights=weights)
    whole, whole_envelope = lagrangian.sweep(**plan)
    parts = [lagrangian.sweep(**plan, shard_index=k, shard_count=2) for k in range(2)]
    assert all(partial.startswith('{"format":"lagrangian-sweep-envelope"') for _, partial in parts)
    table, envelope = lagrangian.merge_sweep(parts[::-1], **plan)
    assert table.equals(whole) if hasattr(table, "equals") else len(table["run"]) == 3
    envelope_out = tmp_path / "envelope.csv"
    cli_table(tmp_path, "--grid", "initial.velocities.r=-12,-15.5556,-18",
              "--set", "simulation.t_end=0.02", "--quiet",
              "--envelope", "r,front_end.force", "--weights", "initial.velocities.r=0.2,0.5,0.3",
              "--envelope-out", envelope_out)
    assert_table_is_csv(envelope, envelope_out)
    assert_table_is_csv(whole_envelope, envelope_out)
    other = dict(plan, weights=None)
    with pytest.raises(lagrangian.DataFileError, match="other --weights"):
        lagrangian.merge_sweep(parts, **other)
