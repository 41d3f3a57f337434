"""The wheel ships the FMU runtime: built once with `pip wheel ./python`
(cargo's dev profile, as python/test.sh builds the package, so that the
workspace's target/debug is reused), installed into a fresh virtual
environment, it exports the paper scenario's FMU with no Rust toolchain on
the PATH, no $LPM_FMU_RUNTIME and no source tree around; the FMU packs the
runtime of the wheel, validates in FMPy and runs as `lpm simulate` does.

The fresh environment gets the wheel with `--no-index --no-deps` and numpy
linked in from the test environment (no registry needed). Slow on a cold
target/: the wheel build is the package's and the runtime's cargo builds."""

import hashlib
import os
import shutil
import subprocess
import sys
import sysconfig
import zipfile

import pytest
from fmpy import simulate_fmu
from fmpy.validation import validate_fmu

import lagrangian
from conftest import ROOT, SPECS

YARIS = SPECS / "yaris_double_pendulum.lpm"
RUNTIME_IN_WHEEL = "lagrangian/" + lagrangian._lagrangian.fmu_runtime_file()


@pytest.fixture(scope="module")
def wheel(tmp_path_factory):
    out = tmp_path_factory.mktemp("wheel")
    # maturin's backend runs the `maturin` of this environment's bin/.
    path = f"{os.path.dirname(sys.executable)}:{os.environ.get('PATH', '')}"
    env = dict(os.environ, MATURIN_PEP517_ARGS="--profile dev", PATH=path)
    command = [sys.executable, "-m", "pip", "wheel", "-q", "--no-deps", "--disable-pip-version-check",
               "-w", str(out), str(ROOT / "python")]
    try:
        import maturin  # noqa: F401 (then no build environment is downloaded)
        command.insert(4, "--no-build-isolation")
    except ImportError:
        pass
    subprocess.run(command, check=True, env=env)
    (found,) = out.glob("lagrangian-*.whl")
    return found


@pytest.fixture(scope="module")
def fresh(tmp_path_factory, wheel):
    """A new virtual environment with the wheel installed and numpy."""
    venv = tmp_path_factory.mktemp("fresh") / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    python = venv / "bin" / "python"
    site = subprocess.run([str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                          check=True, capture_output=True, text=True).stdout.strip()
    here = sysconfig.get_paths()["purelib"]
    for entry in os.listdir(here):
        if entry == "numpy" or entry.startswith(("numpy-", "numpy.libs")):
            os.symlink(os.path.join(here, entry), os.path.join(site, entry))
    subprocess.run([str(python), "-m", "pip", "install", "-q", "--no-index", "--no-deps",
                    "--disable-pip-version-check", str(wheel)], check=True)
    return python


def test_the_wheel_carries_the_runtime(wheel):
    with zipfile.ZipFile(wheel) as archive:
        names = archive.namelist()
        assert RUNTIME_IN_WHEEL in names, names
        assert archive.read(RUNTIME_IN_WHEEL)[:4] == b"\x7fELF"


def test_a_fresh_environment_exports_an_fmu_without_a_toolchain(fresh, wheel, tmp_path):
    out = tmp_path / "yaris.fmu"
    bare = {"PATH": f"{fresh.parent}:/usr/bin:/bin", "HOME": str(tmp_path)}
    assert shutil.which("cargo", path=bare["PATH"]) is None
    assert shutil.which("rustc", path=bare["PATH"]) is None
    script = ("import lagrangian, sys; "
              "lagrangian.export_fmu(sys.argv[1], out=sys.argv[2]); "
              "print(lagrangian.__file__)")
    done = subprocess.run([str(fresh), "-c", script, str(YARIS), str(out)], env=bare,
                          cwd=tmp_path, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith(str(fresh.parent.parent)), done.stdout  # the wheel's package
    with zipfile.ZipFile(wheel) as archive:
        shipped = archive.read(RUNTIME_IN_WHEEL)
    with zipfile.ZipFile(out) as fmu:
        packed = fmu.read("binaries/linux64/lagrangian_fmu.so")
    assert hashlib.sha256(packed).digest() == hashlib.sha256(shipped).digest()
    assert validate_fmu(str(out)) == []
    result = simulate_fmu(str(out), fmi_type="CoSimulation", output=["metrics.crush"])
    reference = lagrangian.simulate(YARIS).summary["max_crush_m"]
    assert abs(result["metrics.crush"].max() - reference) / reference < 0.005
