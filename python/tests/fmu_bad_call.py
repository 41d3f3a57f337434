"""One bad FMI call on an FMU, in a process of its own (run by
test_fmu_bad_calls.py): `python fmu_bad_call.py UNZIPPED_FMU CASE` brings an
instance to the state the case names with FMPy's low-level API
(fmpy.fmi2.FMU2Slave / FMU2Model), makes the bad call through the
instance's C function itself (so that the raw status comes back, not an
exception), and prints one JSON line: the status returned and the messages
the FMU sent to the logger callback. A crash kills only this process."""

import ctypes
import json
import math
import pathlib
import sys

from fmpy import read_model_description
from fmpy.fmi2 import (FMU2Model, FMU2Slave, fmi2CallbackFunctions, fmi2CallbackLoggerTYPE,
                       fmi2EventInfo, fmi2FMUstate, fmi2Real, fmi2String, fmi2ValueReference)

STATUS = {0: "fmi2OK", 1: "fmi2Warning", 2: "fmi2Discard", 3: "fmi2Error", 4: "fmi2Fatal"}


class Run:
    """An instance of the FMU in `directory` whose logged messages are kept."""

    def __init__(self, directory, model_exchange):
        self.description = read_model_description(directory)
        self.vr = {v.name: v.valueReference for v in self.description.modelVariables}
        kind = FMU2Model if model_exchange else FMU2Slave
        identifier = (self.description.modelExchange if model_exchange
                      else self.description.coSimulation).modelIdentifier
        self.fmu = kind(guid=self.description.guid, unzipDirectory=directory,
                        modelIdentifier=identifier, instanceName="bad")
        self.messages = []

        def log(environment, name, status, category, message):
            self.messages.append(message.decode().replace("%%", "%"))

        self.callbacks = fmi2CallbackFunctions()
        self.callbacks.logger = fmi2CallbackLoggerTYPE(log)
        self.fmu.instantiate(callbacks=self.callbacks)

    def c(self, name, *args):
        """The status of the C function `name` called with `args`."""
        return self.fmu._functions[name](*args)

    def set_real(self, names_or_vrs, values):
        vrs = [self.vr.get(n, n) for n in names_or_vrs]
        vr = (fmi2ValueReference * len(vrs))(*vrs)
        value = (fmi2Real * len(vrs))(*values)
        return self.c("fmi2SetReal", self.fmu.component, vr, len(vrs), value)

    def get_real(self, names_or_vrs):
        vrs = [self.vr.get(n, n) for n in names_or_vrs]
        vr = (fmi2ValueReference * len(vrs))(*vrs)
        value = (fmi2Real * len(vrs))()
        return self.c("fmi2GetReal", self.fmu.component, vr, len(vrs), value)

    def initialized(self, **setup):
        self.fmu.setupExperiment(**setup)
        self.fmu.enterInitializationMode()
        self.fmu.exitInitializationMode()
        return self

    def continuous_time(self):
        self.initialized()
        self.fmu.newDiscreteStates()
        self.fmu.enterContinuousTimeMode()
        return self

    def states(self):
        return self.description.numberOfContinuousStates


def me(directory):
    return Run(directory, model_exchange=True)


def cs(directory):
    return Run(directory, model_exchange=False)


def n_reals(n, value=0.0):
    return (fmi2Real * n)(*([value] * n))


def derivatives_before_initialization(d):
    r = me(d)
    n = r.states()
    return r, r.c("fmi2GetDerivatives", r.fmu.component, n_reals(n), n)


def derivatives_of_a_wrong_count(d):
    r = me(d).continuous_time()
    return r, r.c("fmi2GetDerivatives", r.fmu.component, n_reals(2), 2)


def set_real_nan(d):
    r = cs(d)
    return r, r.set_real(["m1"], [math.nan])


def set_real_infinite_in_initialization(d):
    r = cs(d)
    r.fmu.setupExperiment()
    r.fmu.enterInitializationMode()
    return r, r.set_real(["m1"], [math.inf])


def set_real_of_an_output(d):
    r = cs(d)
    return r, r.set_real(["metrics.crush"], [1.0])


def set_real_unknown_reference(d):
    r = cs(d)
    return r, r.set_real([99999], [1.0])


def set_real_of_a_parameter_while_integrating(d):
    r = me(d).continuous_time()
    return r, r.set_real(["m1"], [700.0])


def set_real_after_terminate(d):
    r = cs(d).initialized()
    r.fmu.terminate()
    return r, r.set_real(["m1"], [700.0])


def get_real_unknown_reference(d):
    r = cs(d).initialized()
    return r, r.get_real([99999])


def get_real_before_initialization(d):
    r = cs(d)
    return r, r.get_real(["m1"])


def do_step_at_nan(d):
    r = cs(d).initialized()
    return r, r.c("fmi2DoStep", r.fmu.component, math.nan, 1e-3, 1)


def do_step_back_in_time(d):
    r = cs(d).initialized()
    r.fmu.doStep(0.0, 1e-3)
    return r, r.c("fmi2DoStep", r.fmu.component, 0.0, 1e-3, 1)


def do_step_negative(d):
    r = cs(d).initialized()
    return r, r.c("fmi2DoStep", r.fmu.component, 0.0, -1e-3, 1)


def do_step_nan_size(d):
    r = cs(d).initialized()
    return r, r.c("fmi2DoStep", r.fmu.component, 0.0, math.nan, 1)


def do_step_past_the_stop_time(d):
    r = cs(d).initialized(stopTime=0.01)
    return r, r.c("fmi2DoStep", r.fmu.component, 0.0, 0.02, 1)


def do_step_before_initialization(d):
    r = cs(d)
    return r, r.c("fmi2DoStep", r.fmu.component, 0.0, 1e-3, 1)


def do_step_after_an_error(d):
    r = cs(d).initialized()
    r.set_real(["m1"], [math.nan])
    return r, r.c("fmi2DoStep", r.fmu.component, 0.0, 1e-3, 1)


def do_step_on_model_exchange(d):
    r = me(d).initialized()
    # FMU2Model loads no Co-Simulation function: the library's own.
    f = r.fmu.dll.fmi2DoStep
    f.argtypes, f.restype = [ctypes.c_void_p, fmi2Real, fmi2Real, ctypes.c_int], ctypes.c_int
    return r, f(r.fmu.component, 0.0, 1e-3, 1)


def derivatives_on_co_simulation(d):
    r = cs(d).initialized()
    n = r.states()
    # FMU2Slave loads no Model Exchange function: the library's own.
    f = r.fmu.dll.fmi2GetDerivatives
    f.argtypes, f.restype = [ctypes.c_void_p, ctypes.POINTER(fmi2Real), ctypes.c_size_t], ctypes.c_int
    return r, f(r.fmu.component, n_reals(n), n)


def setup_experiment_nan_start(d):
    r = cs(d)
    return r, r.c("fmi2SetupExperiment", r.fmu.component, 0, 0.0, math.nan, 0, 0.0)


def setup_experiment_stop_before_start(d):
    r = cs(d)
    return r, r.c("fmi2SetupExperiment", r.fmu.component, 0, 0.0, 1.0, 1, 0.5)


def setup_experiment_negative_tolerance(d):
    r = cs(d)
    return r, r.c("fmi2SetupExperiment", r.fmu.component, 1, -1e-6, 0.0, 0, 0.0)


def exit_initialization_without_entering(d):
    r = cs(d)
    return r, r.c("fmi2ExitInitializationMode", r.fmu.component)


def terminate_twice(d):
    r = cs(d).initialized()
    r.fmu.terminate()
    return r, r.c("fmi2Terminate", r.fmu.component)


def set_time_nan(d):
    r = me(d).initialized()
    return r, r.c("fmi2SetTime", r.fmu.component, math.nan)


def set_time_before_the_start(d):
    r = me(d).continuous_time()
    return r, r.c("fmi2SetTime", r.fmu.component, -1.0)


def set_states_nan(d):
    r = me(d).continuous_time()
    n = r.states()
    x = n_reals(n)
    r.c("fmi2GetContinuousStates", r.fmu.component, x, n)
    x[1] = math.nan
    return r, r.c("fmi2SetContinuousStates", r.fmu.component, x, n)


def new_discrete_states_while_integrating(d):
    r = me(d).continuous_time()
    info = fmi2EventInfo()
    return r, r.c("fmi2NewDiscreteStates", r.fmu.component, ctypes.byref(info))


def debug_logging_unknown_category(d):
    r = cs(d)
    categories = (fmi2String * 1)(b"logEverything")
    return r, r.c("fmi2SetDebugLogging", r.fmu.component, 1, 1, categories)


def integer_variable(d):
    r = cs(d).initialized()
    vr = (fmi2ValueReference * 1)(3)
    value = (ctypes.c_int * 1)()
    return r, r.c("fmi2GetInteger", r.fmu.component, vr, 1, value)


def fmu_state_freed_twice(d):
    r = cs(d).initialized()
    state = fmi2FMUstate()
    r.c("fmi2GetFMUstate", r.fmu.component, ctypes.byref(state))
    copy = fmi2FMUstate(state.value)
    r.c("fmi2FreeFMUstate", r.fmu.component, ctypes.byref(state))
    return r, r.c("fmi2FreeFMUstate", r.fmu.component, ctypes.byref(copy))


def fmu_state_set_after_free(d):
    r = cs(d).initialized()
    state = fmi2FMUstate()
    r.c("fmi2GetFMUstate", r.fmu.component, ctypes.byref(state))
    copy = fmi2FMUstate(state.value)
    r.c("fmi2FreeFMUstate", r.fmu.component, ctypes.byref(state))
    return r, r.c("fmi2SetFMUstate", r.fmu.component, copy)


def free_instance_twice(d):
    r = cs(d).initialized()
    r.c("fmi2FreeInstance", r.fmu.component)
    r.c("fmi2FreeInstance", r.fmu.component)
    return r, None


def do_step_after_free(d):
    r = cs(d).initialized()
    r.c("fmi2FreeInstance", r.fmu.component)
    return r, r.c("fmi2DoStep", r.fmu.component, 0.0, 1e-3, 1)


def do_step_on_a_garbage_handle(d):
    r = cs(d).initialized()
    return r, r.c("fmi2DoStep", ctypes.c_void_p(0xDEADBEEF), 0.0, 1e-3, 1)


def instantiate_with_another_guid(d):
    r = cs(d)
    resources = pathlib.Path(d, "resources").as_uri().encode()
    component = r.c("fmi2Instantiate", b"other", 1, b"{not-its-guid}", resources,
                    ctypes.byref(r.callbacks), 0, 0)
    return r, "null" if component is None else "instance"


#: The cases: name -> the function that makes the bad call.
CASES = {f.__name__: f for f in [
    set_real_nan, set_real_infinite_in_initialization, set_real_of_an_output,
    set_real_unknown_reference, set_real_of_a_parameter_while_integrating,
    set_real_after_terminate, get_real_unknown_reference, get_real_before_initialization,
    do_step_at_nan, do_step_back_in_time, do_step_negative, do_step_nan_size,
    do_step_past_the_stop_time, do_step_before_initialization, do_step_after_an_error,
    do_step_on_model_exchange, derivatives_before_initialization, derivatives_of_a_wrong_count,
    derivatives_on_co_simulation, setup_experiment_nan_start, setup_experiment_stop_before_start,
    setup_experiment_negative_tolerance, exit_initialization_without_entering, terminate_twice,
    set_time_nan, set_time_before_the_start, set_states_nan,
    new_discrete_states_while_integrating, debug_logging_unknown_category, integer_variable,
    fmu_state_freed_twice, fmu_state_set_after_free, free_instance_twice, do_step_after_free,
    do_step_on_a_garbage_handle, instantiate_with_another_guid,
]}


def main(directory, case):
    run, status = CASES[case](directory)
    status = STATUS.get(status, status) if isinstance(status, int) else status
    print(json.dumps({"status": status, "messages": run.messages}), flush=True)


if __name__ == "__main__":
    main(*sys.argv[1:])
