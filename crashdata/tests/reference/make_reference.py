"""Writes the pyisomme reference test that `tests/pyisomme_reference.rs` reads.

pyisomme (MIT, PyPI `pyisomme`) is the independent ISO-MME reader and writer.
This script builds a small test with it — a vehicle CG acceleration in g at
5 kHz, a dummy head acceleration at 10 kHz and a fixed-barrier force in N,
with NOVALUE header fields, a NaN sample, repeated Comments, a non-ASCII
laboratory name and non-zero times of first sample — and writes it with
pyisomme as a folder and as a zip into `../data/pyisomme/`. It then reads the
folder back with pyisomme and dumps what pyisomme holds (every header line
with its parsed type, each channel's unit, times and values) to
`../data/pyisomme/reference.json`, after checking that the zip reads the same.

Run from anywhere, in a venv with pyisomme (`pip install pyisomme`):

    python crashdata/tests/reference/make_reference.py

The outputs are committed; `cargo test` needs no Python.
"""

from __future__ import annotations

import datetime
import importlib.metadata
import json
import math
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
from pyisomme import Channel, Isomme

HERE = Path(__file__).resolve().parent
OUT = HERE.parent / "data" / "pyisomme"
NAME = "REF001"
VERSION = importlib.metadata.version("pyisomme")


def channel(code, t0, dt, values, unit, info):
    """A pyisomme channel on the implicit time base t0 + i*dt."""
    times = t0 + dt * np.arange(len(values))
    data = pd.DataFrame({"value": values}, index=times)
    return Channel(code, data, unit=unit, info=info)


def vehicle_acceleration():
    """10VEHCCG0000ACXP: a 30 g half-sine deceleration over 80 ms [g], 5 kHz."""
    t0, dt, n = -0.010, 0.0002, 600
    t = t0 + dt * np.arange(n)
    values = np.where((t >= 0) & (t <= 0.08), -30.0 * np.sin(np.pi * t / 0.08), 0.0)
    values = values + 0.05 * np.sin(2 * np.pi * 430 * t)  # some ripple
    values[17] = np.nan  # a sample without a value
    info = [
        ("Name of the channel", "Vehicle CG acceleration X"),
        ("Laboratory channel code", None),
        ("Customer channel code", None),
        ("Reference channel", "implicit"),
        ("Location", "CG"),
        ("Direction", "X"),
        ("Channel frequency class", None),
        ("Transducer type", None),
        ("Comments", "ripple added at 430 Hz"),
    ]
    return channel("10VEHCCG0000ACXP", t0, dt, values, "g", info)


def head_acceleration():
    """11HEAD0000H3ACXA: a head pulse peaking near 60 g [g], 10 kHz."""
    t0, dt, n = -0.020, 0.0001, 1700
    t = t0 + dt * np.arange(n)
    values = -60.0 * np.exp(-(((t - 0.07) / 0.012) ** 2)) + 2.5 * np.sin(2 * np.pi * 95 * t)
    info = [
        ("Name of the channel", "Driver head acceleration X"),
        ("Laboratory channel code", "HX01"),
        ("Reference channel", "implicit"),
        ("Data source", "Transducer"),
        ("Test object number", 1),
        ("Channel frequency class", 1000),
        ("Dimension", "AC"),
    ]
    return channel("11HEAD0000H3ACXA", t0, dt, values, "g", info)


def barrier_force():
    """B0FBAR000000FOXP: a barrier load rising to 400 kN and back [N], 10 kHz."""
    t0, dt, n = -0.005, 0.0001, 1200
    t = t0 + dt * np.arange(n)
    shape = np.clip(np.sin(np.pi * t / 0.1), 0.0, None) ** 1.5
    values = 4.0e5 * np.where((t >= 0) & (t <= 0.1), shape, 0.0)
    info = [
        ("Name of the channel", "Barrier force X"),
        ("Reference channel", "implicit"),
        ("Transducer type", None),
        ("Unit", "N"),
    ]
    return channel("B0FBAR000000FOXP", t0, dt, values, "N", info)


def the_test():
    test_info = [
        ("Data format edition number", "1.6"),
        ("Laboratory name", "Prüfstand Süd"),
        ("Laboratory contact name", None),
        ("Laboratory test ref. number", NAME),
        ("Title", "Reference test written by pyisomme"),
        ("Type of the test", "Full frontal"),
        ("Reference temperature", 20.5),
        ("Number of test objects", 1),
        ("Comments", "first comment"),
        ("Comments", None),
        ("Comments", "third comment"),
        ("Name of test object 1", "Small car"),
        ("Velocity test object 1", 15.56),
        ("Mass test object 1", 1168),
    ]
    channel_info = [("Instrumentation standard", "SAEJ211, issued 1992")]
    return Isomme(
        test_number=NAME,
        test_info=test_info,
        channels=[vehicle_acceleration(), head_acceleration(), barrier_force()],
        channel_info=channel_info,
    )


def typed(value):
    """A header value as pyisomme holds it: its kind and a JSON value."""
    if value is None:
        return {"kind": "none", "value": None}
    if isinstance(value, bool):
        return {"kind": "bool", "value": value}
    if isinstance(value, int):
        return {"kind": "int", "value": value}
    if isinstance(value, float):
        if math.isnan(value):  # pyisomme's maximum of a channel with a NaN
            return {"kind": "nan", "value": None}
        return {"kind": "float", "value": value}
    if isinstance(value, datetime.datetime):
        return {"kind": "datetime", "value": value.isoformat()}
    return {"kind": "str", "value": str(value)}


def lines(info):
    return [{"name": name, **typed(value)} for name, value in info]


def number(x):
    return None if math.isnan(x) else float(x)


def dump(isomme):
    return {
        "pyisomme_version": VERSION,
        "name": isomme.test_number,
        "info": lines(isomme.test_info),
        "channel_info": lines(isomme.channel_info),
        "channels": [
            {
                "code": str(c.code),
                "unit": c.unit.to_isomme(),
                "header": lines(c.info),
                "times": [float(t) for t in c.data.index],
                "values": [number(x) for x in c.get_data()],
            }
            for c in isomme.channels
        ],
    }


def main():
    folder, archive = OUT / NAME, OUT / f"{NAME}.zip"
    shutil.rmtree(folder, ignore_errors=True)
    archive.unlink(missing_ok=True)
    OUT.mkdir(parents=True, exist_ok=True)
    test = the_test()
    test.write(folder)
    test.write(archive)
    held = dump(Isomme().read(folder))
    assert dump(Isomme().read(archive)) == held, "the zip reads differently"
    (OUT / "reference.json").write_text(json.dumps(held, allow_nan=False) + "\n")
    print(f"wrote {folder}, {archive} and reference.json (pyisomme {VERSION})")


if __name__ == "__main__":
    main()
