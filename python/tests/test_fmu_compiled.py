"""`lpm export-fmu --compiled`: an FMU whose binary is the macro-compiled
paper model (built by cargo with the debug profile in the workspace's
target/) validates and runs the paper scenario bit for bit as the
interpreting FMU; and only FMU binaries export the FMI entry points, not the
Python extension.

Slow on a fresh target/: the compiled FMU's first build compiles the crates
it depends on again for the generated crate (cargo does not reuse the
workspace's builds of them), about 3 minutes on the 2-core build machine;
later runs reuse them and take seconds."""

import ctypes
import shlex
import zipfile

import numpy as np
import pytest
from fmpy import simulate_fmu
from fmpy.validation import validate_fmu

import lagrangian
from conftest import ROOT, SPECS, run_lpm

YARIS = SPECS / "yaris_double_pendulum.lpm"
RUNTIME = ROOT / "target" / "debug" / "liblagrangian_fmu.so"
BINARY = "binaries/linux64/lagrangian_fmu.so"
#: The book's command line (docs/book/fmu.md, in a block the Rust README
#: test skips: a release build), run here with the debug profile.
README_COMMAND = "lpm export-fmu specs/yaris_double_pendulum.lpm --compiled --out yaris.fmu"
OUTPUTS = ["metrics.crush", "metrics.deceleration", "front_end.force", "r", "theta2", "der(theta1)"]

#: The 44 functions of the FMI 2.0 standard (fmi2Functions.h): the common
#: ones, then Model Exchange's, then Co-Simulation's.
FMI2_FUNCTIONS = """
fmi2GetTypesPlatform fmi2GetVersion fmi2SetDebugLogging fmi2Instantiate fmi2FreeInstance
fmi2SetupExperiment fmi2EnterInitializationMode fmi2ExitInitializationMode fmi2Terminate
fmi2Reset fmi2GetReal fmi2GetInteger fmi2GetBoolean fmi2GetString fmi2SetReal fmi2SetInteger
fmi2SetBoolean fmi2SetString fmi2GetFMUstate fmi2SetFMUstate fmi2FreeFMUstate
fmi2SerializedFMUstateSize fmi2SerializeFMUstate fmi2DeSerializeFMUstate
fmi2GetDirectionalDerivative
fmi2EnterEventMode fmi2NewDiscreteStates fmi2EnterContinuousTimeMode
fmi2CompletedIntegratorStep fmi2SetTime fmi2SetContinuousStates fmi2GetDerivatives
fmi2GetEventIndicators fmi2GetContinuousStates fmi2GetNominalsOfContinuousStates
fmi2SetRealInputDerivatives fmi2GetRealOutputDerivatives fmi2DoStep fmi2CancelStep
fmi2GetStatus fmi2GetRealStatus fmi2GetIntegerStatus fmi2GetBooleanStatus fmi2GetStringStatus
""".split()


def exported(library):
    """The FMI 2.0 functions the shared library `library` exports."""
    loaded = ctypes.CDLL(str(library))
    return [name for name in FMI2_FUNCTIONS if hasattr(loaded, name)]


@pytest.fixture(scope="module")
def fmus(tmp_path_factory):
    """The paper scenario's FMU, interpreted and compiled."""
    dir = tmp_path_factory.mktemp("fmu-compiled")
    interpreted, compiled = dir / "interpreted.fmu", dir / "compiled.fmu"
    run_lpm("export-fmu", YARIS, "--out", interpreted)
    args = shlex.split(README_COMMAND)[1:]
    args[args.index("--out") + 1] = str(compiled)
    run_lpm(*args, "--profile", "dev")
    return interpreted, compiled


def test_the_book_shows_the_command_tested_here():
    assert README_COMMAND in (ROOT / "docs" / "book" / "fmu.md").read_text()


def test_the_standard_lists_44_functions():
    assert len(set(FMI2_FUNCTIONS)) == 44


def test_the_python_extension_exports_no_fmi_function():
    assert exported(lagrangian._lagrangian.__file__) == []


def test_the_generic_runtime_exports_every_fmi_function():
    assert exported(RUNTIME) == FMI2_FUNCTIONS


def test_the_compiled_binary_exports_every_fmi_function(fmus, tmp_path):
    with zipfile.ZipFile(fmus[1]) as archive:
        binary = tmp_path / "compiled.so"
        binary.write_bytes(archive.read(BINARY))
        interpreted = zipfile.ZipFile(fmus[0]).read(BINARY)
    assert binary.read_bytes() != interpreted
    assert exported(binary) == FMI2_FUNCTIONS


def test_fmpy_finds_no_problem_in_the_compiled_fmu(fmus):
    assert validate_fmu(str(fmus[1])) == []


@pytest.mark.parametrize("fmi_type", ["CoSimulation", "ModelExchange"])
def test_the_compiled_fmu_runs_bit_for_bit_as_the_interpreted_one(fmus, fmi_type):
    settings = dict(fmi_type=fmi_type, start_values={"m1": 600.0}, output=OUTPUTS)
    interpreted, compiled = (simulate_fmu(str(fmu), **settings) for fmu in fmus)
    assert len(compiled) == len(interpreted) > 100
    for name in ["time", *OUTPUTS]:
        np.testing.assert_array_equal(compiled[name], interpreted[name], err_msg=name)
    assert compiled["metrics.crush"].max() > 0.3  # the crash happened
