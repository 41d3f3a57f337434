#!/usr/bin/env bash
# The Python package's tests: a virtual environment from the Python registry,
# the package installed by pip (built by maturin with cargo's dev profile,
# sharing the workspace's target/ and its build of the dependencies with
# `cargo test`: see [profile.dev] in Cargo.toml), then pytest against the
# `lpm` binary.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=target/python-venv
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
# pandas for DataFrames, dask.distributed for the Dask template's test, FMPy
# to validate and run exported FMUs, maturin to build the wheel of
# test_wheel.py without a build environment of its own.
"$venv/bin/pip" install -q --disable-pip-version-check pytest numpy pandas "dask[distributed]" fmpy "maturin>=1.5,<2"
MATURIN_PEP517_ARGS="--profile dev" "$venv/bin/pip" install -q --disable-pip-version-check ./python
# The independent references of python/tests/reference/ in an environment of
# their own: pyisomme 1.1 pins numpy 1.26 and pandas 2.2 (and so an older
# FMPy), which must not choose the versions the package and its FMUs are
# tested against above. Pinned: the reference values are these versions'.
refs=target/reference-venv
[ -x "$refs/bin/python" ] || python3 -m venv "$refs"
"$refs/bin/pip" install -q --disable-pip-version-check pytest numpy pandas "objective-rating-metrics==1.3" "pyisomme==1.1.0"
MATURIN_PEP517_ARGS="--profile dev" "$refs/bin/pip" install -q --disable-pip-version-check ./python
# Debian's chromium for the report's browser test (test_report_browser.py).
if ! command -v chromium >/dev/null; then
    as_root=$([ "$(id -u)" = 0 ] || echo sudo)
    $as_root apt-get update -q >/dev/null
    DEBIAN_FRONTEND=noninteractive $as_root apt-get install -y -q chromium >/dev/null
fi
# lpm, and the FMU runtime that `lpm export-fmu` packs (python/tests/test_fmu.py).
cargo build -q -p lpm -p lagrangian-fmu
# Exit status 5 (no tests collected) is a failure here too.
"$venv/bin/python" -m pytest -q -p no:cacheprovider python/tests --ignore=python/tests/reference
"$refs/bin/python" -m pytest -q -p no:cacheprovider python/tests/reference
