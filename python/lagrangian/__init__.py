"""Euler–Lagrange models from spec files: equations, evaluation, simulation.

``Model`` compiles a spec (a path or its text) and evaluates ``M(q)``,
``f(q, q̇, t)``, ``q̈`` and the energies at one state or at each row of a
batch (the loop runs in Rust). ``simulate`` runs ``lpm simulate`` and returns
its summary, trajectory and events; ``sweep`` (with ``merge_sweep`` and
``sweep_plan``) and ``fit`` run ``lpm sweep`` and ``lpm fit``;
``export_fmu`` runs ``lpm export-fmu``. Failures raise the subclass of
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

    @property
    def constraints(self) -> List[str]:
        """The names of the spec's constraints (empty without)."""
        return self._native.constraint_names

    def accelerations(self, t, q, qd, inputs: Optional[Mapping[str, float]] = None) -> np.ndarray:
        """``q̈`` (n, or k × n for a batch): ``M q̈ = f``, or for a spec with
        constraints the constrained ``q̈`` of ``M q̈ = f + Gᵀλ``, ``G q̈ = γ``
        (the solve ``lpm simulate`` and ``lpm eval`` use, asked for ``g̈ = 0``;
        see ``multipliers`` for ``λ``)."""
        single, (a, _) = self._call(self._native.accelerations, t, q, qd, inputs)
        return a[0] if single else a

    def multipliers(self, t, q, qd, inputs: Optional[Mapping[str, float]] = None) -> Dict[str, Any]:
        """The constraints' multipliers ``λ`` by name (numbers, or arrays of
        k for a batch; empty without constraints): ``Gᵀλ`` is the
        generalized force of the constraints, in the unit of each
        constraint's multiplier (a rod's tension in N for a length
        constraint written in metres)."""
        single, (_, lam) = self._call(self._native.accelerations, t, q, qd, inputs)
        names = self.constraints
        if single:
            return {name: float(v) for name, v in zip(names, lam[0])}
        return {name: lam[:, k] for k, name in enumerate(names)}

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


def _dataframe(pandas, text: str):
    """`text` (a CSV lpm wrote, every number in its shortest round-trip
    form) as a DataFrame with exactly lpm's doubles. Before pandas 3 the
    default parser may land one ulp off (0.00030000000000000003 read as
    0.0003); pandas 3 parses exactly and deprecates the option."""
    if int(pandas.__version__.split(".")[0]) < 3:
        return pandas.read_csv(io.StringIO(text), float_precision="round_trip")
    return pandas.read_csv(io.StringIO(text))


def _trajectory(text: str):
    try:
        import pandas
    except ImportError:
        pandas = None
    if pandas is not None:
        return _dataframe(pandas, text)
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
    scenario_path = None if scenario is None else os.fspath(scenario)
    entries = _entries(set, settings)
    summary, trajectory, events = _lagrangian.simulate(os.fspath(spec), scenario_path, entries)
    return Result(
        summary=json.loads(summary),
        trajectory=_trajectory(trajectory),
        events=[Event(*e) for e in events],
    )


# --- Sweeps and fits: `lpm sweep` and `lpm fit` --------------------------

__all__ += ["sweep", "merge_sweep", "sweep_plan", "fit", "FitResult"]


def _entries(set: Optional[Mapping[str, Any]], settings: Mapping[str, Any]) -> List[str]:
    """The ``--set`` entries of keyword settings (``t_end``, ``rtol``,
    ``atol``, ``method`` go under ``simulation.``) and of ``set``."""
    entries = []
    for key, value in settings.items():
        key = f"simulation.{key}" if key in _SIMULATION_KEYS else key
        entries.append(_setting(key, value))
    return entries + [_setting(key, value) for key, value in (set or {}).items()]


def _number(value: Any) -> str:
    """A number as the command line takes it (exactly: ``repr`` of a float
    reads back as the same float)."""
    return value if isinstance(value, str) else repr(float(value))


def _key_arguments(entries, join) -> List[str]:
    """``KEY=VALUES`` arguments of a dict (the values a string as the
    command line takes it, or a sequence ``join`` makes one) or of a string
    or list of such strings."""
    if entries is None:
        return []
    if isinstance(entries, str):
        return [entries]
    if not isinstance(entries, Mapping):
        return [str(e) for e in entries]
    return [f"{key}={values if isinstance(values, str) else join(values)}"
            for key, values in entries.items()]


def _grid_arguments(grid) -> List[str]:
    """``--grid KEY=VALUES`` arguments of a dict (``{"k1": [5e4, 6e4]}``,
    ``{"k1*": "0.8:1.2:5"}``) or a list of such strings."""
    return _key_arguments(grid, lambda values: ",".join(_number(v) for v in values))


def _vary_arguments(vary) -> List[str]:
    """``--vary KEY=LOW:HIGH[:log]`` arguments of a dict (``{"k1": (5e4,
    1e5)}``, ``{"c": (1, 100, "log")}``) or a list of such strings."""
    return _key_arguments(
        vary, lambda bounds: ":".join(b if b == "log" else _number(b) for b in bounds))


def _sweep_options(
    scenario, spec, grid, samples, vary, design, seed, set, settings,
    shard=None, shard_index=None, shard_count=None, threads=None, out=None, format=None,
    envelope=None, weights=None,
) -> Dict[str, Any]:
    """The options of ``lpm sweep`` as the native module takes them."""
    path = lambda p: None if p is None else os.fspath(p)  # noqa: E731
    return {
        "scenario": path(scenario),
        "spec": path(spec),
        "grid": _grid_arguments(grid),
        "samples": samples,
        "vary": _vary_arguments(vary),
        "design": design,
        "seed": seed,
        "set": _entries(set, settings),
        "shard": shard,
        "shard_index": shard_index,
        "shard_count": shard_count,
        "threads": threads or 0,
        "out": path(out),
        "format": format,
        "envelope": _channel_list(envelope),
        "weights": _weights_argument(weights),
    }


def _channel_list(channels) -> List[str]:
    """``--envelope``'s channels: a list, or one comma-separated string."""
    if channels is None:
        return []
    if isinstance(channels, str):
        return [c.strip() for c in channels.split(",")]
    return [str(c) for c in channels]


def _weights_argument(weights) -> Optional[str]:
    """``--weights``: a mapping of one grid key to its weights, a
    ``KEY=W1,…`` string, or the path of a CSV file of ``run,weight``."""
    if weights is None or isinstance(weights, str):
        return weights
    if isinstance(weights, Mapping):
        if len(weights) != 1:
            raise ValueError("weights: give the weights of one grid key, e.g. {'v0': [0.2, 0.8]}")
        [(key, values)] = weights.items()
        return f"{key}=" + ",".join(repr(float(w)) for w in values)
    return os.fspath(weights)


def _column(cells: List[str]) -> np.ndarray:
    """A table column: integers, numbers (an empty cell is NaN) or text."""
    try:
        return np.array([int(c) for c in cells], dtype=np.int64)
    except ValueError:
        pass
    try:
        return np.array([float(c) if c else np.nan for c in cells], dtype=np.float64)
    except ValueError:
        return np.array(cells, dtype=object)


def _table(text: str):
    """A sweep table's CSV text as a pandas DataFrame (when pandas is
    installed: the frame ``pandas.read_csv`` reads from ``lpm sweep``'s
    file), else a dict of numpy arrays."""
    try:
        import pandas
    except ImportError:
        pandas = None
    if pandas is not None:
        return _dataframe(pandas, text)
    rows = list(csv.reader(io.StringIO(text)))
    header, body = rows[0], rows[1:]
    return {name: _column([row[k] for row in body]) for k, name in enumerate(header)}


def sweep(
    spec: Optional[Union[str, os.PathLike]] = None,
    scenario: Optional[Union[str, os.PathLike]] = None,
    *,
    grid=None,
    samples: Optional[int] = None,
    vary=None,
    design: str = "latin-hypercube",
    seed: int = 1,
    shard: Optional[str] = None,
    shard_index: Optional[int] = None,
    shard_count: Optional[int] = None,
    threads: Optional[int] = None,
    envelope=None,
    weights=None,
    set: Optional[Mapping[str, Any]] = None,
    **settings: Any,
):
    """Runs ``lpm sweep`` on ``scenario`` (by default the scenario beside
    the spec that names it; without ``spec``, the scenario's ``spec`` key
    names the model) and returns its table, one row per run: the
    columns and values of ``lpm sweep … --out FILE.csv``, as a pandas
    DataFrame when pandas is installed, else a dict of numpy arrays.

    ``grid`` (``--grid``) maps keys to values or ``"low:high:count"``;
    ``samples`` with ``vary`` (``--vary``) maps keys to ``(low, high)`` or
    ``(low, high, "log")``, placed by ``design`` (``"latin-hypercube"`` or
    ``"random"``) from ``seed``. Either may also be a list of the command
    line's ``KEY=…`` strings. ``shard="i/n"``, ``shard="auto"`` or
    ``shard_index=k, shard_count=n`` (from 0) run one block of the runs;
    ``threads`` defaults to one per core. ``set`` and ``settings`` fix
    values for every run, as in :func:`simulate`.

    ``envelope`` (``--envelope``: a list of channels or a comma-separated
    string) returns ``(table, envelope_table)`` instead, the second with
    the columns of ``--envelope-out FILE.csv`` (per output time, each
    channel's min and max over the runs, the runs attaining them and the
    weighted mean); ``weights`` (``--weights``) is ``{key: [w, …]}`` (one
    per value of grid axis ``key``), a ``"KEY=W1,…"`` string or the path
    of a CSV file of ``run,weight``. For a shard the second is the
    shard's partial envelope instead (the JSON text ``lpm sweep`` writes
    beside a shard's table), which :func:`merge_sweep` takes with the table.
    """
    options = _sweep_options(scenario, spec, grid, samples, vary, design, seed, set, settings,
                             shard, shard_index, shard_count, threads,
                             envelope=envelope, weights=weights)
    if not options["envelope"]:
        return _table(_lagrangian.sweep_table(options))
    table, envelope_table = _lagrangian.sweep_envelope(options)
    if envelope_table.startswith("{"):
        return _table(table), envelope_table
    return _table(table), _table(envelope_table)


def _table_csv(table) -> str:
    """A table ``sweep`` returned (a DataFrame or a dict of arrays) as CSV
    that reads back to the same values."""

    def cell(value) -> str:
        if isinstance(value, str):
            return value
        if isinstance(value, (float, np.floating)):
            value = float(value)
            if value != value:
                return ""
            return str(int(value)) if value.is_integer() else repr(value)
        return str(value)

    names = list(table.keys())
    columns = [list(table[name]) for name in names]
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(names)
    writer.writerows([cell(v) for v in row] for row in zip(*columns))
    return out.getvalue()


def merge_sweep(
    parts,
    spec: Optional[Union[str, os.PathLike]] = None,
    scenario: Optional[Union[str, os.PathLike]] = None,
    *,
    grid=None,
    samples: Optional[int] = None,
    vary=None,
    design: str = "latin-hypercube",
    seed: int = 1,
    out: Optional[Union[str, os.PathLike]] = None,
    format: Optional[str] = None,
    envelope=None,
    weights=None,
    set: Optional[Mapping[str, Any]] = None,
    **settings: Any,
):
    """``lpm sweep --merge``: the shards' tables ``parts`` (tables
    :func:`sweep` returned, or files ``lpm sweep`` wrote, CSV or Parquet, in
    any order) checked against the plan of the same arguments — every run
    exactly once, with the plan's values — and merged into the table of one
    full run (a ``DataFileError`` names a missing, repeated or foreign
    part). With ``out`` the table is also written there as the command
    writes it (CSV or Parquet by the extension, or ``format``).

    With ``envelope`` (and ``weights``) as the shards had them, each part is
    a ``(table, partial_envelope)`` pair :func:`sweep` returned for a shard
    (or a file with its partial envelope beside it), and the result is
    ``(table, envelope_table)``: the envelope of the whole sweep, that of
    one full run.
    """
    import tempfile

    options = _sweep_options(scenario, spec, grid, samples, vary, design, seed, set, settings,
                             out=out, format=format, envelope=envelope, weights=weights)
    with tempfile.TemporaryDirectory(prefix="lagrangian-merge-") as directory:
        paths = []
        for k, part in enumerate(parts):
            if isinstance(part, (str, os.PathLike)):
                paths.append(os.fspath(part))
                continue
            path = os.path.join(directory, f"parts[{k}]")
            if isinstance(part, tuple):
                # A shard's table and its partial envelope, which the merge
                # reads beside the table.
                part, partial = part
                with open(path + ".envelope.json", "w", encoding="utf-8") as f:
                    f.write(partial)
            with open(path, "w", encoding="utf-8", newline="") as f:
                f.write(_table_csv(part))
            paths.append(path)
        try:
            if options["envelope"]:
                table, envelope_table = _lagrangian.sweep_merge_envelope(options, paths)
                return _table(table), _table(envelope_table)
            return _table(_lagrangian.sweep_merge(options, paths))
        except LagrangianError as e:
            # A table part is named `parts[k]`, not by its temporary file.
            message = str(e).replace(os.path.join(directory, ""), "")
            raise type(e)(message, e.status) from None


def sweep_plan(
    spec: Optional[Union[str, os.PathLike]] = None,
    scenario: Optional[Union[str, os.PathLike]] = None,
    *,
    grid=None,
    samples: Optional[int] = None,
    vary=None,
    design: str = "latin-hypercube",
    seed: int = 1,
    set: Optional[Mapping[str, Any]] = None,
    **settings: Any,
) -> str:
    """What ``lpm sweep --plan`` prints: the number of runs, the time of a
    run measured on a few, and a suggested split."""
    options = _sweep_options(scenario, spec, grid, samples, vary, design, seed, set, settings)
    return _lagrangian.sweep_plan(options)


@dataclass
class FitResult:
    """A fit: ``parameters`` (fitted value by name), ``cost`` and
    ``cost_initial``, ``report`` (the dict of fit.json: standard errors,
    residuals per channel, starts, correlations), ``text`` (the report
    ``lpm fit`` prints), ``scenario`` (the text of fitted.toml, a scenario
    :func:`simulate` runs) and ``svg`` (the overlay plot fit.svg)."""

    parameters: Dict[str, float]
    cost: float
    cost_initial: float
    report: Dict[str, Any]
    text: str
    scenario: str
    svg: str


def fit(
    spec: Union[str, os.PathLike],
    target: Union[str, os.PathLike],
    scenario: Optional[Union[str, os.PathLike]] = None,
    *,
    fit: Optional[Union[str, List[str]]] = None,
    channel: Optional[Union[str, List[str]]] = None,
    starts: int = 4,
    seed: int = 1,
    out: Optional[Union[str, os.PathLike]] = None,
    set: Optional[Mapping[str, Any]] = None,
    **settings: Any,
) -> FitResult:
    """Runs ``lpm fit``: identifies ``fit`` (``"stiffness"``,
    ``"damping"``, spec parameters or dotted scenario entries; a list or a
    comma-separated string; by default stiffness and damping) from the
    target time histories ``target``: a CSV with units in the header, or an
    ISO-MME test (a folder, an ``.mme`` or a ``.zip``) whose channels
    ``channel`` names, as ``--channel CODE[=QUANTITY]`` (a list, or one).

    ``scenario`` defaults to the one beside the spec that names it;
    ``starts`` and ``seed`` as ``--starts`` and ``--seed``; ``set`` and
    ``settings`` as in :func:`simulate`. With ``out`` the files of ``lpm
    fit`` (fitted.toml, fit.json, fit.svg) are written there; without it,
    the fitted scenario's relative paths start from the current directory.
    """
    names = fit.split(",") if isinstance(fit, str) else list(fit or [])
    path = lambda p: None if p is None else os.fspath(p)  # noqa: E731
    options = {
        "spec": os.fspath(spec),
        "target": os.fspath(target),
        "channel": [channel] if isinstance(channel, str) else list(channel or []),
        "scenario": path(scenario),
        "fit": [name.strip() for name in names],
        "set": _entries(set, settings),
        "out": path(out),
        "starts": starts,
        "seed": seed,
    }
    text, files = _lagrangian.fit(options)
    files = dict(files)
    report = json.loads(files["fit.json"])
    return FitResult(
        parameters={p["name"]: p["fitted"] for p in report["parameters"]},
        cost=report["cost"],
        cost_initial=report["cost_initial"],
        report=report,
        text=text,
        scenario=files["fitted.toml"],
        svg=files["fit.svg"],
    )
def packaged_runtime() -> Optional[pathlib.Path]:
    """The FMU runtime the installed package ships
    (``lagrangian/liblagrangian_fmu.so`` on Linux), if it is there."""
    path = pathlib.Path(__file__).parent / _lagrangian.fmu_runtime_file()
    return path if path.is_file() else None


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

    ``runtime`` is the FMU runtime library to pack; by default
    ``$LPM_FMU_RUNTIME``, else the one the package ships (the wheel carries
    it, built with the extension: no Rust toolchain is needed), else the
    one ``cargo build -p lagrangian-fmu`` writes beside ``lpm``.
    """
    if runtime is None and "LPM_FMU_RUNTIME" not in os.environ:
        runtime = packaged_runtime()
    _lagrangian.export_fmu(
        os.fspath(spec),
        None if scenario is None else os.fspath(scenario),
        os.fspath(out),
        None if runtime is None else os.fspath(runtime),
    )
    return pathlib.Path(out)
