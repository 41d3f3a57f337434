"""The package's PEP 517 build backend: maturin's, after one step of its own.

The wheel ships the FMU runtime (the `lagrangian-fmu` cdylib that
`lagrangian.export_fmu` packs as an FMU's binary), so that exporting needs
no Rust toolchain after `pip install`. Maturin builds one cargo artifact,
the extension module; this backend first builds the runtime with cargo, in
the same profile, and copies it into the package folder
(`lagrangian/liblagrangian_fmu.so`, `.dylib`, `lagrangian_fmu.dll`), where
pyproject.toml's `[tool.maturin] include` puts it in the wheel.

Not the extension module itself as the runtime: an extension module built
for abi3 leaves the Python C API's symbols undefined (the interpreter that
imports it provides them), so an FMU host that is not a Python process
(Simulink, OpenModelica, a C program) could not load it; and it would carry
the whole package (compiler, JIT) into every FMU.
"""

import json
import os
import pathlib
import shlex
import shutil
import subprocess

import maturin
from maturin import *  # noqa: F401,F403 (the rest of the backend's hooks)

HERE = pathlib.Path(__file__).resolve().parent
PACKAGE = HERE / "lagrangian"


def _profile(config_settings):
    """The cargo profile maturin will build with: `--profile NAME` or
    `--release` in its arguments (MATURIN_PEP517_ARGS or the config
    settings), else its default for wheels, release."""
    args = maturin.get_maturin_pep517_args(config_settings)
    for i, arg in enumerate(args):
        if arg == "--profile" and i + 1 < len(args):
            return args[i + 1]
        if arg.startswith("--profile="):
            return arg.split("=", 1)[1]
    return "release"


def _build_runtime(config_settings):
    """Builds the runtime with cargo and copies it into the package."""
    cargo = os.environ.get("CARGO", "cargo")
    command = [cargo, "build", "--lib", "-p", "lagrangian-fmu", "--profile",
               _profile(config_settings), "--manifest-path", str(HERE / "Cargo.toml"),
               "--message-format=json-render-diagnostics"]
    try:
        done = subprocess.run(command, stdout=subprocess.PIPE, text=True, check=False)
    except OSError as e:
        raise RuntimeError(f"building the FMU runtime needs cargo, and `{cargo}` cannot be run ({e})")
    if done.returncode != 0:
        raise RuntimeError(f"`{shlex.join(command)}` failed ({done.returncode}); its messages are above")
    library = _cdylib(done.stdout)
    for old in PACKAGE.glob("*lagrangian_fmu.*"):
        old.unlink()
    shutil.copy2(library, PACKAGE / library.name)


def _cdylib(messages):
    """The cdylib of `lagrangian-fmu` that cargo's JSON messages name."""
    for line in messages.splitlines():
        try:
            message = json.loads(line)
        except json.JSONDecodeError:
            continue
        if message.get("reason") != "compiler-artifact":
            continue
        if message["target"]["name"] != "lagrangian_fmu" or "cdylib" not in message["target"]["crate_types"]:
            continue
        for file in message["filenames"]:
            if pathlib.Path(file).suffix in (".so", ".dylib", ".dll"):
                return pathlib.Path(file)
    raise RuntimeError("cargo built lagrangian-fmu but named no shared library of it")


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    _build_runtime(config_settings)
    return maturin.build_wheel(wheel_directory, config_settings, metadata_directory)


def build_editable(wheel_directory, config_settings=None, metadata_directory=None):
    _build_runtime(config_settings)
    return maturin.build_editable(wheel_directory, config_settings, metadata_directory)
