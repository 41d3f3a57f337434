"""Bad FMI calls on the paper scenario's FMU, each in a process of its own
(fmu_bad_call.py) so that a crash fails its case instead of the suite: the
status each returns, and that the message the FMU logs names the call and
the variable, the argument or the state at fault. The expected statuses
are the FMI 2.0 standard's (a call out of order, or with an argument
outside its domain, is fmi2Error); the states allowed per call are the
standard's tables. Calls on a handle that is no live instance have no
logger to go to: their message is on the standard error.

`pytest -s` prints the table (case, status, message)."""

import json
import subprocess
import sys

import pytest
from fmpy import extract

from conftest import ROOT, SPECS, run_lpm

sys.path.insert(0, str(ROOT / "python" / "tests"))
import fmu_bad_call  # noqa: E402

HELPER = ROOT / "python" / "tests" / "fmu_bad_call.py"
ERROR = "fmi2Error"

#: case: (status, words the message must hold: the call first, then the
#: variable, argument or state).
EXPECTED = {
    "set_real_nan": (ERROR, ["fmi2SetReal", "`m1`", "NaN"]),
    "set_real_infinite_in_initialization": (ERROR, ["fmi2SetReal", "`m1`", "inf"]),
    "set_real_of_an_output": (ERROR, ["fmi2SetReal", "`metrics.crush`", "output"]),
    "set_real_unknown_reference": (ERROR, ["fmi2SetReal", "unknown value reference 99999"]),
    "set_real_of_a_parameter_while_integrating": (ERROR, ["fmi2SetReal", "`m1`", "continuousTimeMode"]),
    "set_real_after_terminate": (ERROR, ["fmi2SetReal", "state terminated"]),
    "get_real_unknown_reference": (ERROR, ["fmi2GetReal", "unknown value reference 99999"]),
    "get_real_before_initialization": (ERROR, ["fmi2GetReal", "state instantiated"]),
    "do_step_at_nan": (ERROR, ["fmi2DoStep", "currentCommunicationPoint = NaN"]),
    "do_step_back_in_time": (ERROR, ["fmi2DoStep", "currentCommunicationPoint = 0e0", "t = 1e-3"]),
    "do_step_negative": (ERROR, ["fmi2DoStep", "communicationStepSize = -1e-3"]),
    "do_step_nan_size": (ERROR, ["fmi2DoStep", "communicationStepSize = NaN"]),
    "do_step_past_the_stop_time": (ERROR, ["fmi2DoStep", "stopTime = 1e-2"]),
    "do_step_before_initialization": (ERROR, ["fmi2DoStep", "state instantiated"]),
    "do_step_after_an_error": (ERROR, ["fmi2DoStep", "state error", "an earlier call failed"]),
    "do_step_on_model_exchange": (ERROR, ["fmi2DoStep", "Co-Simulation function", "Model Exchange"]),
    "derivatives_before_initialization": (ERROR, ["fmi2GetDerivatives", "state instantiated"]),
    # The paper model's states: 3 coordinates, 3 rates and 2 internal states.
    "derivatives_of_a_wrong_count": (ERROR, ["fmi2GetDerivatives", "2 derivatives asked for", "has 8"]),
    "derivatives_on_co_simulation": (ERROR, ["fmi2GetDerivatives", "Model Exchange function"]),
    "setup_experiment_nan_start": (ERROR, ["fmi2SetupExperiment", "startTime = NaN"]),
    "setup_experiment_stop_before_start": (ERROR, ["fmi2SetupExperiment", "stopTime = 0.5"]),
    "setup_experiment_negative_tolerance": (ERROR, ["fmi2SetupExperiment", "tolerance = -0.000001"]),
    "exit_initialization_without_entering": (ERROR, ["fmi2ExitInitializationMode", "state instantiated"]),
    "terminate_twice": (ERROR, ["fmi2Terminate", "state terminated"]),
    "set_time_nan": (ERROR, ["fmi2SetTime", "time = NaN"]),
    "set_time_before_the_start": (ERROR, ["fmi2SetTime", "time = -1e0"]),
    "set_states_nan": (ERROR, ["fmi2SetContinuousStates", "x[1] (theta1) = NaN"]),
    "new_discrete_states_while_integrating": (ERROR, ["fmi2NewDiscreteStates", "state continuousTimeMode"]),
    "debug_logging_unknown_category": (ERROR, ["fmi2SetDebugLogging", "`logEverything`"]),
    "integer_variable": (ERROR, ["fmi2GetInteger", "unknown value reference 3", "no Integer"]),
    "fmu_state_freed_twice": (ERROR, ["fmi2FreeFMUstate", "not one this instance saved"]),
    "fmu_state_set_after_free": (ERROR, ["fmi2SetFMUstate", "not one this instance saved"]),
    "instantiate_with_another_guid": ("null", ["fmi2Instantiate", "GUID {not-its-guid}"]),
    # No instance, so no logger: said on the standard error.
    "free_instance_twice": (None, ["fmi2FreeInstance", "no live instance"]),
    "do_step_after_free": (ERROR, ["fmi2DoStep", "no live instance"]),
    "do_step_on_a_garbage_handle": (ERROR, ["fmi2DoStep", "0xdeadbeef is no live instance"]),
}
ON_STDERR = {"free_instance_twice", "do_step_after_free", "do_step_on_a_garbage_handle"}
TABLE = []


@pytest.fixture(scope="module")
def unzipped(tmp_path_factory):
    """The paper scenario's FMU, exported and extracted once."""
    dir = tmp_path_factory.mktemp("bad-calls")
    fmu = dir / "yaris.fmu"
    run_lpm("export-fmu", SPECS / "yaris_double_pendulum.lpm", "--out", fmu)
    yield extract(str(fmu), str(dir / "unzipped"))
    print("\n\nBad FMI calls (case | status | message)")
    for row in TABLE:
        print(" | ".join(row))


def test_every_case_of_the_helper_has_an_expectation():
    assert set(EXPECTED) == set(fmu_bad_call.CASES)


@pytest.mark.parametrize("case", sorted(EXPECTED))
def test_a_bad_call_is_refused_with_a_message_naming_it(unzipped, case):
    done = subprocess.run([sys.executable, str(HELPER), unzipped, case],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, f"crashed ({done.returncode}): {done.stderr}"
    result = json.loads(done.stdout.strip().splitlines()[-1])
    status, words = EXPECTED[case]
    logged = result["messages"][-1] if result["messages"] else ""
    message = done.stderr.strip() if case in ON_STDERR else logged
    TABLE.append((case, str(result["status"]), message))
    assert result["status"] == status, message
    for word in words:
        assert word in message, (word, message)
    if case not in ON_STDERR:
        assert message.startswith(words[0] + ":"), message
