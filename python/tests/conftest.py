"""What the tests share: the repository's specs and the `lpm` binary the
package is compared with (built by `cargo test`, or named by $LPM)."""

import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SPECS = ROOT / "specs"


def lpm_binary() -> pathlib.Path:
    path = pathlib.Path(os.environ.get("LPM", ROOT / "target" / "debug" / "lpm"))
    if not path.is_file():
        pytest.fail(f"no lpm binary at {path}: build it (cargo build -p lpm) or set $LPM")
    return path


def run_lpm(*args, check=True) -> subprocess.CompletedProcess:
    done = subprocess.run([str(lpm_binary()), *map(str, args)], capture_output=True, text=True, cwd=ROOT)
    if check and done.returncode != 0:
        pytest.fail(f"lpm {' '.join(map(str, args))} exited {done.returncode}: {done.stderr}")
    return done
