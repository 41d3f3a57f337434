#!/usr/bin/env bash
# The Python package's tests: a virtual environment from the Python registry,
# the package installed by pip (built by maturin with cargo's `test` profile,
# the one `cargo test` builds the dependencies with, sharing the workspace's
# target/), then pytest against the `lpm` binary.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=target/python-venv
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
# pandas for DataFrames, dask.distributed for the Dask template's test, FMPy
# to validate and run exported FMUs.
"$venv/bin/pip" install -q --disable-pip-version-check pytest numpy pandas "dask[distributed]" fmpy
MATURIN_PEP517_ARGS="--profile test" "$venv/bin/pip" install -q --disable-pip-version-check ./python
# lpm, and the FMU runtime that `lpm export-fmu` packs (python/tests/test_fmu.py),
# with the same profile (its output lies in target/debug as the dev profile's).
cargo build -q --profile test -p lpm -p lagrangian-fmu
# Exit status 5 (no tests collected) is a failure here too.
"$venv/bin/python" -m pytest -q -p no:cacheprovider python/tests
