"""`lpm fit --target TEST --channel CODE`: fitting to an ISO-MME test that
pyisomme, the independent ISO-MME writer, wrote.

pyisomme writes the shipped target (specs/data/yaris_pulse.csv: the car's
deceleration in g every 0.5 ms) as the vehicle's x acceleration: forward
positive, so the negated deceleration, after 5 ms of pre-trigger zeros, in g
and in m/s**2 (which it writes `m / s2`). Fitted to it, lpm must give the fit
of the CSV: the same values and ratings. The channel's values come from the
CSV here, not from lpm's reader.
"""

import csv
import json

import numpy as np
import pandas as pd
import pytest
import pyisomme

import lagrangian
from conftest import SPECS, run_lpm

YARIS = SPECS / "yaris_double_pendulum.lpm"
TARGET = SPECS / "data" / "yaris_pulse.csv"
CODE = "10VEHCCG0000ACXD"  # vehicle CG, x acceleration, CFC 60
G0 = 9.80665
STEP = 5e-4  # the target's sampling interval [s]
PRE_TRIGGER = 10  # samples before first contact


def shipped_pulse():
    """The target's times [s] and deceleration [g]."""
    with open(TARGET, newline="") as f:
        rows = list(csv.reader(f))
    assert rows[0] == ["t [ms]", "deceleration [g]"]
    t = np.array([float(row[0]) for row in rows[1:]]) * 1e-3
    deceleration = np.array([float(row[1]) for row in rows[1:]])
    assert np.allclose(np.diff(t), STEP, rtol=1e-9)
    return t, deceleration


def write_test(folder, unit):
    """The target as pyisomme's test `PULSE` at `folder`, in `unit`."""
    t, deceleration = shipped_pulse()
    times = STEP * (np.arange(PRE_TRIGGER + len(t)) - PRE_TRIGGER)
    scale = G0 if unit == "m/s**2" else 1.0
    values = np.concatenate([np.zeros(PRE_TRIGGER), -deceleration * scale])
    info = [("Name of the channel", "Vehicle CG acceleration X"), ("Reference channel", "implicit")]
    data = pd.DataFrame({"value": values}, index=times)
    channel = pyisomme.Channel(CODE, data, unit=unit, info=info)
    pyisomme.Isomme(test_number="PULSE", channels=[channel]).write(folder)
    return folder


def fit_json(target, out, *args):
    run_lpm("fit", YARIS, "--target", target, "--fit", "stiffness", "--starts", "1", "--quiet",
            "--out", out, *args)
    return json.loads((out / "fit.json").read_text())


# pyisomme writes 6 decimals: in g those of the CSV, the same numbers; in
# m/s**2 the CSV's values times g0, rounded to 1e-6 m/s^2.
TOLERANCE = {"g": 1e-9, "m/s**2": 1e-7}


@pytest.mark.parametrize("unit", ["g", "m/s**2"])
def test_a_test_pyisomme_wrote_gives_the_fit_of_the_same_csv(unit, tmp_path):
    folder = write_test(tmp_path / "PULSE", unit)
    by_csv = fit_json(TARGET, tmp_path / "csv")
    by_test = fit_json(folder, tmp_path / "iso", "--channel", CODE)
    csv_values = np.array([p["fitted"] for p in by_csv["parameters"]])
    test_values = np.array([p["fitted"] for p in by_test["parameters"]])
    largest = np.max(np.abs(test_values / csv_values - 1))
    print(f"{unit}: fitted values, ISO-MME against CSV, largest relative difference {largest:.1e}")
    assert largest < TOLERANCE[unit]
    channel = by_test["channels"][0]
    written = pyisomme.Isomme().read(folder).get_channel(CODE).unit.to_isomme()
    assert channel["channel"] == f"{CODE} [{written}]"
    for key in ("rating_initial", "rating"):
        ours, theirs = channel[key], by_csv["channels"][0][key]
        assert ours["grade"] == theirs["grade"]
        assert ours["overall"] == pytest.approx(theirs["overall"], abs=TOLERANCE[unit]), key
    assert channel["rating"]["grade"] == "excellent"


def without_time(report):
    return {key: value for key, value in report.items() if key != "seconds"}


def test_lagrangian_fit_takes_the_channels_of_a_test(tmp_path):
    folder = write_test(tmp_path / "PULSE", "g")
    cli = fit_json(folder, tmp_path / "cli", "--channel", CODE)
    result = lagrangian.fit(YARIS, folder, channel=CODE, fit="stiffness", starts=1)
    assert without_time(result.report) == without_time(cli)
    with pytest.raises(lagrangian.UsageError, match="did you mean 10VEHCCG0000ACXD"):
        lagrangian.fit(YARIS, folder, channel=["10VEHCCG0000ACXP"])
    with pytest.raises(lagrangian.UsageError, match="is a CSV file"):
        lagrangian.fit(YARIS, TARGET, channel=CODE)
