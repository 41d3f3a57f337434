"""lagrangian.fit: the report and files of `lpm fit`."""

import json

import pytest

import lagrangian
from conftest import SPECS, run_lpm

YARIS = SPECS / "yaris_double_pendulum.lpm"
TARGET = SPECS / "data" / "yaris_pulse.csv"  # the pulse of the car with a 10 % stiffer front end


def without_time(report):
    return {key: value for key, value in report.items() if key != "seconds"}


def test_a_fit_gives_the_report_and_files_of_lpm_fit(tmp_path):
    printed = run_lpm("fit", YARIS, "--target", TARGET, "--fit", "stiffness", "--starts", "1",
                      "--quiet", "--out", tmp_path / "cli").stdout
    result = lagrangian.fit(YARIS, TARGET, fit="stiffness", starts=1, out=tmp_path / "py")
    cli = json.loads((tmp_path / "cli" / "fit.json").read_text())
    assert without_time(result.report) == without_time(cli)
    assert result.report == json.loads((tmp_path / "py" / "fit.json").read_text())
    for name in ("fitted.toml", "fit.svg"):
        assert (tmp_path / "py" / name).read_text() == (tmp_path / "cli" / name).read_text(), name
    assert result.scenario == (tmp_path / "py" / "fitted.toml").read_text()
    assert result.svg.startswith("<svg")
    # The printed report, but its timing and the line naming the files.
    strip = lambda text: [line for line in text.splitlines()[1:] if "wrote" not in line]  # noqa: E731
    assert strip(result.text) == strip(printed)
    assert result.text.splitlines()[0].split(" in ")[0] == printed.splitlines()[0].split(" in ")[0]
    # k1…k6 of the stiffer front end: 1.1 times the scenario's; k7 is held.
    assert list(result.parameters) == [f"front_end.k{k}" for k in range(1, 8)]
    assert result.cost < 1e-3 * result.cost_initial
    fitted = result.report["parameters"]
    for p in fitted[:6]:
        assert p["fitted"] / p["initial"] == pytest.approx(1.1, rel=0.02), p["name"]
    assert fitted[6]["fitted"] == fitted[6]["initial"]
    # The fitted scenario, written elsewhere, still finds its spec and data.
    rerun = lagrangian.simulate(YARIS, scenario=tmp_path / "py" / "fitted.toml")
    assert rerun.summary["max_crush_m"] > 0


def test_fit_errors_raise_the_exception_of_their_exit_status(tmp_path):
    with pytest.raises(lagrangian.UsageError, match="no_such_parameter"):
        lagrangian.fit(YARIS, TARGET, fit=["no_such_parameter"])
    done = run_lpm("fit", YARIS, "--target", tmp_path / "no_such_target.csv", check=False)
    with pytest.raises(lagrangian.LagrangianError, match="no_such_target") as raised:
        lagrangian.fit(YARIS, tmp_path / "no_such_target.csv")
    assert raised.value.status == done.returncode != 0
