"""Euler–Lagrange models from spec files: equations, evaluation, simulation.

``Model`` compiles a spec (a path or its text) and evaluates ``M(q)``,
``f(q, q̇, t)``, ``q̈`` and the energies at one state or at each row of a
batch (the loop runs in Rust). ``simulate`` runs ``lpm simulate`` and returns
its summary, trajectory and events; ``export_fmu`` runs ``lpm export-fmu``.
Failures raise the subclass of
``LagrangianError`` named after the ``lpm`` exit status they would give.
"""

from __future__ import annotations

import csv
import io
import json
import os
import pathlib
from dataclasses import dataclass, field
from typing import Any, Dict, List, Mapping, Optional, Union

import numpy as np

from . import _lagrangian

__all__ = ["Model", "Result", "Event", "simulate", "LagrangianError", "export_fmu"]


class LagrangianError(Exception):
    """A failure of the compiler or a simulation; ``status`` is the exit
    status ``lpm`` gives for it and ``status_name`` its name."""

    status: int = 0
    status_name: str = ""

    def __init__(self, message: str, status: Optional[int] = None):
        super().__init__(message)
        if status is not None:
            self.status = status


def _error_classes() -> Dict[int, type]:
    """One subclass of LagrangianError per failing exit status of ``lpm``
    (``SpecError``, ``ScenarioError``, ``SingularMassMatrixError``, …)."""
    classes = {}
    for code, name, meaning in _lagrangian.exit_statuses():
        if code == 0:
            continue
        cls = type(
            f"{name}Error",
            (LagrangianError,),
            {"status": code, "status_name": name, "__doc__": f"{meaning} (lpm exit status {code})."},
        )
        cls.__module__ = __name__
        classes[code] = cls
    return classes


_ERRORS = _error_classes()
_lagrangian.register_errors(_ERRORS)
globals().update({cls.__name__: cls for cls in _ERRORS.values()})
__all__ += [cls.__name__ for cls in _ERRORS.values()]


def _spec_source(spec: Union[str, os.PathLike]) -> tuple:
    """(text, file name) of a spec given as a path or as its text."""
    if isinstance(spec, os.PathLike) or (isinstance(spec, str) and "\n" not in spec and os.path.isfile(spec)):
        path = os.fspath(spec)
        with open(path, encoding="utf-8") as f:
            return f.read(), path
    return str(spec), "<spec>"


def _batch(n: int, t, q, qd):
    """The arguments as a batch (times k, states k × n) and whether they
    were one state."""
    q = np.ascontiguousarray(q, dtype=np.float64)
    qd = np.ascontiguousarray(qd, dtype=np.float64)
    single = q.ndim == 1
    if single:
        q, qd = q.reshape(1, -1), qd.reshape(1, -1)
    rows = q.shape[0]
    t = np.ascontiguousarray(np.broadcast_to(np.asarray(t, dtype=np.float64), (rows,)))
    return single, t, q, qd


class Model:
    """A spec compiled and run by the interpreter.

    ``spec`` is the path of a ``.lpm`` file or the spec's text. The
    evaluation methods take one state (``q`` and ``qd`` of length n) or a
    batch (k × n rows; ``t`` a number or k times) and ``inputs``, constant
    values of the spec's input functions by name.
    """

    def __init__(self, spec: Union[str, os.PathLike]):
        source, file = _spec_source(spec)
        self._native = _lagrangian.NativeModel(source, file)

    @property
    def name(self) -> str:
        return self._native.name

    @property
    def coordinates(self) -> List[str]:
        return self._native.coordinates

    @property
    def parameters(self) -> Dict[str, float]:
        return dict(zip(self._native.parameter_names, self._native.parameter_values))

    @property
    def inputs(self) -> List[str]:
        return self._native.input_names

    @property
    def outputs(self) -> List[str]:
        return self._native.output_names

    def set_parameter(self, name: str, value: float) -> None:
        self._native.set_parameter(name, float(value))

    def _call(self, method, t, q, qd, inputs):
        single, t, q, qd = _batch(len(self.coordinates), t, q, qd)
        result = method(t, q, qd, dict(inputs or {}))
        return single, result

    def mass_matrix(self, t, q, qd, inputs: Optional[Mapping[str, float]] = None) -> np.ndarray:
        """``M`` (n × n, or k × n × n for a batch)."""
        single, (mass, _) = self._call(self._native.dynamics, t, q, qd, inputs)
        return mass[0] if single else mass

    def forcing(self, t, q, qd, inputs: Optional[Mapping[str, float]] = None) -> np.ndarray:
        """``f`` (n, or k × n for a batch)."""
        single, (_, forcing) = self._call(self._native.dynamics, t, q, qd, inputs)
        return forcing[0] if single else forcing

    def accelerations(self, t, q, qd, inputs: Optional[Mapping[str, float]] = None) -> np.ndarray:
        """``q̈ = M⁻¹ f`` (n, or k × n for a batch)."""
        single, a = self._call(self._native.accelerations, t, q, qd, inputs)
        return a[0] if single else a

    def energies(self, t, q, qd, inputs: Optional[Mapping[str, float]] = None) -> Dict[str, Any]:
        """``kinetic``, ``potential``, ``dissipation``, ``damping_power`` and
        ``external_power``: numbers, or arrays of k for a batch."""
        single, values = self._call(self._native.energies, t, q, qd, inputs)
        names = self._native.energy_names
        if single:
            return {name: float(v) for name, v in zip(names, values[0])}
        return {name: values[:, k] for k, name in enumerate(names)}

    def derive(self, format: str = "text") -> str:
        """The derived equations as ``lpm derive`` prints them (``text``,
        ``latex`` or ``markdown``)."""
        return self._native.derive(format)

    def _repr_latex_(self) -> str:
        return "$$" + self.derive("latex") + "$$"

    def __repr__(self) -> str:
        return f"Model({self.name!r}, coordinates={self.coordinates!r})"


@dataclass
class Event:
    """An event of a run: when, which component, what changed."""

    t: float
    component: str
    description: str


@dataclass
class Result:
    """A simulation: ``summary`` (the dict of summary.json), ``trajectory``
    (a pandas DataFrame when pandas is installed, else a dict of numpy
    arrays, with the columns of trajectory.csv) and ``events``."""

    summary: Dict[str, Any]
    trajectory: Any
    events: List[Event] = field(default_factory=list)


def _trajectory(text: str):
    try:
        import pandas
    except ImportError:
        pandas = None
    if pandas is not None:
        return pandas.read_csv(io.StringIO(text))
    rows = list(csv.reader(io.StringIO(text)))
    header, values = rows[0], np.array(rows[1:], dtype=np.float64).reshape(-1, len(rows[0]))
    return {name: values[:, k] for k, name in enumerate(header)}


_SIMULATION_KEYS = ("t_end", "rtol", "atol", "method")


def _setting(key: str, value: Any) -> str:
    """``KEY=VALUE`` as ``lpm simulate --set`` takes it."""
    if isinstance(value, bool):
        value = "true" if value else "false"
    return f"{key}={value}"


def simulate(
    spec: Union[str, os.PathLike],
    scenario: Optional[Union[str, os.PathLike]] = None,
    set: Optional[Mapping[str, Any]] = None,
    **settings: Any,
) -> Result:
    """Runs ``lpm simulate`` on ``spec`` (a path) under ``scenario`` (by
    default the scenario beside the spec that names it, else the defaults).

    ``settings`` are ``t_end``, ``rtol``, ``atol``, ``method`` and
    parameters or input constants by name (``k1=7e4``); ``set`` takes any
    ``--set`` entry, dotted keys included
    (``{"components.front_end.unloading": "elastic"}``).
    """
    entries = []
    for key, value in settings.items():
        key = f"simulation.{key}" if key in _SIMULATION_KEYS else key
        entries.append(_setting(key, value))
    entries += [_setting(key, value) for key, value in (set or {}).items()]
    scenario_path = None if scenario is None else os.fspath(scenario)
    summary, trajectory, events = _lagrangian.simulate(os.fspath(spec), scenario_path, entries)
    return Result(
        summary=json.loads(summary),
        trajectory=_trajectory(trajectory),
        events=[Event(*e) for e in events],
    )


def export_fmu(
    spec: Union[str, os.PathLike],
    scenario: Optional[Union[str, os.PathLike]] = None,
    *,
    out: Union[str, os.PathLike],
    runtime: Optional[Union[str, os.PathLike]] = None,
) -> pathlib.Path:
    """Runs ``lpm export-fmu``: writes ``out``, an FMI 2.0 FMU
    (Co-Simulation and Model Exchange) of ``spec`` under ``scenario`` (by
    default the scenario beside the spec that names it), and returns its
    path.

    ``runtime`` is the FMU runtime library to pack
    (``target/debug/liblagrangian_fmu.so`` after ``cargo build -p
    lagrangian-fmu``); by default ``$LPM_FMU_RUNTIME``.
    """
    _lagrangian.export_fmu(
        os.fspath(spec),
        None if scenario is None else os.fspath(scenario),
        os.fspath(out),
        None if runtime is None else os.fspath(runtime),
    )
    return pathlib.Path(out)
