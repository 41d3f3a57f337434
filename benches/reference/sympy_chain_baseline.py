#!/usr/bin/env python3
"""SymPy baseline for BENCHMARKS.md: derivation time, cse() time and operation
counts of n-link pendulum chains and of the paper's model.

For each model it runs, in a fresh child process (so that the peak memory is
the model's own):

* ``LagrangesMethod(...).form_lagranges_equations()`` -- the derivation,
  timed;
* ``sympy.cse`` of the upper triangle of M and of f, timed, and the
  operations of the result counted with ``count_ops(visual=True)`` (the
  same counting as ``tests/reference/sympy_reference.py``);
* the peak resident memory of the child (``ru_maxrss``).

The models come from ``tests/reference/sympy_reference.py`` (written from
the specs, independently of the Rust code).  A model that does not finish
within the time limit is recorded as skipped.

Run from the repository root (Python >= 3.9, sympy, mpmath)::

    python3 benches/reference/sympy_chain_baseline.py [--limit SECONDS] [--models NAME ...]

It writes ``benches/reference/sympy_chain_baseline.json``; with
``--models`` it measures only the named models and updates their entries
in an existing file (a full run takes about 20 minutes up to n = 20).  Timings depend
on the machine and its load; the operation counts do not.
"""

import argparse
import json
import multiprocessing
import platform
import resource
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
sys.path.insert(0, str(ROOT / "tests" / "reference"))

import sympy as sp  # noqa: E402
import sympy_reference as ref  # noqa: E402

OUTPUT = HERE / "sympy_chain_baseline.json"
CHAINS = [1, 2, 3, 5, 8, 10, 15, 20, 40]


def measure(name, queue):
    model = ref.yaris_double_pendulum() if name == "yaris_double_pendulum" \
        else ref.pendulum_chain(int(name.rsplit("_", 1)[1]))
    derived = ref.derive(model)
    counts = ref.cse_op_counts(derived)
    peak_kib = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    queue.put({
        "derivation_seconds": counts["derivation_seconds"],
        "cse_seconds": counts["cse_seconds"],
        "cse_ops_total": counts["total"],
        "cse_ops_by_kind": counts["by_kind"],
        "peak_rss_mib": round(peak_kib / 1024, 1),
    })


def run(name, limit):
    ctx = multiprocessing.get_context("fork")
    queue = ctx.Queue()
    proc = ctx.Process(target=measure, args=(name, queue))
    start = time.perf_counter()
    proc.start()
    proc.join(limit)
    if proc.is_alive():
        proc.terminate()
        proc.join()
        return {"skipped": f"did not finish within {limit:.0f} s"}
    if proc.exitcode != 0 or queue.empty():
        return {"skipped": f"failed (exit {proc.exitcode})"}
    record = queue.get()
    record["wall_seconds"] = round(time.perf_counter() - start, 3)
    return record


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--limit", type=float, default=600.0,
                        help="seconds allowed per model (default 600)")
    parser.add_argument("--models", nargs="+", metavar="NAME",
                        help="measure only these models (e.g. pendulum_chain_40)")
    args = parser.parse_args()
    names = args.models or (
        ["yaris_double_pendulum"] + [f"pendulum_chain_{n}" for n in CHAINS])
    results = {}
    if args.models and OUTPUT.exists():
        results = json.loads(OUTPUT.read_text())["models"]
    for name in names:
        results[name] = run(name, args.limit)
        print(name, results[name], flush=True)
    document = {
        "generator": "benches/reference/sympy_chain_baseline.py",
        "sympy_version": sp.__version__,
        "python": platform.python_version(),
        "machine": f"{platform.machine()}, {multiprocessing.cpu_count()} cores",
        "limit_seconds": args.limit,
        "models": results,
    }
    OUTPUT.write_text(json.dumps(document, indent=1) + "\n")


if __name__ == "__main__":
    main()
