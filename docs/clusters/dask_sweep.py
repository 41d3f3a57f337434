"""A sweep of the paper scenario on a Dask cluster, through the Python package:
the runs are split into shards, each shard is one Dask task
(``lagrangian.sweep(..., shard_index=k, shard_count=n)``), and the parts are
checked and merged into the table one full run gives (``merge_sweep``).

Run it from the repository root (every worker needs the package installed
and the scenario, spec and data files at the same paths)::

    python docs/clusters/dask_sweep.py --out results/sweep.parquet
    python docs/clusters/dask_sweep.py --address tcp://scheduler:8786 --shards 64 --out sweep.csv

Without ``--address`` it starts a ``LocalCluster`` on this machine.
``lagrangian.sweep_plan(**SWEEP)`` prints the number of runs and a
suggested number of shards.
"""

from __future__ import annotations

import argparse
import os
from typing import Any, Dict, Optional

import lagrangian

# The sweep every shard and the merge share: one plan (the same axes, sample
# count and seed). Edit it here only.
SWEEP: Dict[str, Any] = {
    "scenario": "specs/scenarios/yaris_full_frontal.toml",
    "samples": 1600,
    "vary": {"k1": (5e4, 1e5), "components.weld.failure_moment": (2e3, 8e3, "log")},
    "seed": 1,
}


def run_shard(sweep: Dict[str, Any], index: int, count: int, threads: int = 1):
    """The table of shard ``index`` (from 0) of ``count``: one Dask task."""
    return lagrangian.sweep(**sweep, shard_index=index, shard_count=count, threads=threads)


def dask_sweep(client, sweep: Dict[str, Any], shards: int, out: Optional[str] = None,
               threads: int = 1):
    """Runs ``sweep`` as ``shards`` tasks on the cluster of ``client`` and
    returns the merged table (also written to ``out``, CSV or Parquet by its
    extension, byte for byte what ``lpm sweep --out`` writes for one run)."""
    # Paths as the workers see them: absolute, from where this runs.
    sweep = {key: os.path.abspath(value) if key in ("scenario", "spec") else value
             for key, value in sweep.items()}
    futures = [client.submit(run_shard, sweep, k, shards, threads, pure=False)
               for k in range(shards)]
    parts = client.gather(futures)
    return lagrangian.merge_sweep(parts, **sweep, out=out)


def main(argv=None):
    from dask.distributed import Client, LocalCluster

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--address", help="the scheduler of a running Dask cluster")
    parser.add_argument("--workers", type=int, default=os.cpu_count() or 1,
                        help="workers of the LocalCluster started without --address")
    parser.add_argument("--processes", action=argparse.BooleanOptionalAction, default=True,
                        help="LocalCluster workers as processes (else threads of this one)")
    parser.add_argument("--shards", type=int, default=16, help="tasks to split the runs into")
    parser.add_argument("--threads", type=int, default=1, help="threads of each task")
    parser.add_argument("--samples", type=int, default=SWEEP["samples"])
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="a setting of every run, as lpm sweep --set")
    parser.add_argument("--out", help="the merged table: .csv or .parquet")
    args = parser.parse_args(argv)
    sweep = dict(SWEEP, samples=args.samples,
                 set=dict(entry.split("=", 1) for entry in args.set))
    cluster = None
    if args.address is None:
        cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1,
                               processes=args.processes)
    client = Client(args.address or cluster)
    try:
        table = dask_sweep(client, sweep, args.shards, args.out, args.threads)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    print(f"{len(table['run'])} runs in {args.shards} shards"
          + (f"; wrote {args.out}" if args.out else ""))
    return table


if __name__ == "__main__":
    main()
