"""docs/clusters/dask_sweep.py on a local Dask cluster: the merged table of
the shards is the table of one `lpm sweep` run, byte for byte."""

import importlib.util

import pandas
import pytest
from dask.distributed import Client, LocalCluster

import lagrangian
from conftest import ROOT, run_lpm


def template():
    path = ROOT / "docs" / "clusters" / "dask_sweep.py"
    spec = importlib.util.spec_from_file_location("dask_sweep", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def client():
    # Threads of this process (the script's test below starts processes).
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                      dashboard_address=":0") as cluster, Client(cluster) as client:
        yield client


def test_the_dask_template_merges_its_shards_into_one_runs_table(tmp_path, client, monkeypatch):
    monkeypatch.chdir(ROOT)
    dask_sweep = template()
    sweep = dict(dask_sweep.SWEEP, samples=9, set={"simulation.t_end": 0.02})
    out = tmp_path / "merged.csv"
    merged = dask_sweep.dask_sweep(client, sweep, shards=4, out=str(out))
    single = lagrangian.sweep(**sweep)
    pandas.testing.assert_frame_equal(merged, single, check_exact=True)
    assert list(merged["run"]) == list(range(9))
    run_lpm("sweep", dask_sweep.SWEEP["scenario"], "--samples", "9",
            "--vary", "k1=5e4:1e5", "--vary", "components.weld.failure_moment=2e3:8e3:log",
            "--set", "simulation.t_end=0.02", "--quiet", "--out", tmp_path / "single.csv")
    assert out.read_bytes() == (tmp_path / "single.csv").read_bytes()


@pytest.mark.filterwarnings("ignore:Port 8787 is already in use")
def test_the_template_runs_as_a_script_on_a_local_cluster(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(ROOT)
    out = tmp_path / "sweep.csv"
    # Worker processes: the shards' tables travel between processes.
    table = template().main(["--workers", "2", "--shards", "3", "--samples", "5",
                             "--set", "simulation.t_end=0.02", "--out", str(out)])
    assert capsys.readouterr().out.strip() == f"5 runs in 3 shards; wrote {out}"
    pandas.testing.assert_frame_equal(pandas.read_csv(out), table, check_exact=True)
