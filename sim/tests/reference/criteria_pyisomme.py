"""Reference values of the injury criteria from pyisomme (MIT, PyPI `pyisomme`),
for `sim/tests/criteria_reference.rs`.

Builds a few dummy channels sampled at 10 kHz, already filtered (pyisomme's
criterion functions do not filter), rates them with pyisomme's own
calculate_* functions and writes the samples and the values to
criteria_pyisomme.json beside this script. Run:

    python3 -m venv /tmp/ref && /tmp/ref/bin/pip install pyisomme==1.1.0
    /tmp/ref/bin/python sim/tests/reference/criteria_pyisomme.py
"""

import importlib.metadata
import json
import pathlib

import numpy as np
import pandas as pd
from pyisomme.calculate import (
    calculate_hic,
    calculate_neck_MOCy,
    calculate_neck_nij,
    calculate_vc,
    calculate_xms,
)
from pyisomme.channel import Channel

G = 9.80665
DT = 1e-4
T = np.round(np.arange(-100, 1501) * DT, 10)  # -10 ms to 150 ms


def bump(amplitude, start, duration, t=T):
    """A half-sine of `amplitude` from `start` for `duration`, 0 elsewhere."""
    inside = (t >= start) & (t <= start + duration)
    return np.where(inside, amplitude * np.sin(np.pi * (t - start) / duration), 0.0)


def ripple(amplitude, frequency, t=T):
    """A ripple that starts and ends at 0 within the record."""
    return amplitude * np.sin(2 * np.pi * frequency * t) * bump(1.0, 0.0, 0.12, t)


signals = {
    # Head: resultant of a pulse with a ripple (g). HIC15 and HIC36 of a
    # resultant, and its cumulative 3 ms clip.
    "11HEAD0000H3ACRA": (bump(70.0, 0.02, 0.045) + ripple(6.0, 210.0)).clip(min=0.0),
    # Chest acceleration resultant (g), CFC 180.
    "11CHST0000H3ACRC": (bump(42.0, 0.015, 0.07) + ripple(4.0, 90.0)).clip(min=0.0),
    # Chest deflection (m), compression negative.
    "11CHST0000H3DSXC": -bump(0.038, 0.02, 0.06) - bump(0.006, 0.05, 0.02),
    # Upper neck Fz (N), Fx (N), My (N·m), CFC 600.
    "11NECKUP00H3FOZB": bump(1800.0, 0.03, 0.06) - bump(700.0, 0.01, 0.02),
    "11NECKUP00H3FOXB": bump(900.0, 0.035, 0.05) + ripple(80.0, 140.0),
    "11NECKUP00H3MOYB": -bump(28.0, 0.04, 0.05) + bump(45.0, 0.005, 0.025),
}
# The samples as written to the JSON, so that both sides rate the same numbers.
signals = {code: np.round(v, 12) for code, v in signals.items()}
units = {"AC": "g", "DS": "m", "FO": "N", "MO": "N*m"}


def channel(code):
    return Channel(code, pd.DataFrame(signals[code], index=T), unit=units[code[12:14]])


head = channel("11HEAD0000H3ACRA")
chest = channel("11CHST0000H3ACRC")
deflection = channel("11CHST0000H3DSXC")
fz, fx, my = (channel(c) for c in ("11NECKUP00H3FOZB", "11NECKUP00H3FOXB", "11NECKUP00H3MOYB"))

moc, _ = calculate_neck_MOCy(my, fx)
nij = calculate_neck_nij(fz, moc, oop=False)
nij_peak = [c for c in nij if c.code.main_location == "NIJC" and c.code.filter_class == "X"
            and c.code.fine_location_2 == "00"][0]
_, vc_peak = calculate_vc(deflection)

values = {
    "hic15": float(calculate_hic(head, 15).get_data()[0]),
    "hic36": float(calculate_hic(head, 36).get_data()[0]),
    "head_3ms_g": float(calculate_xms(head, 3, method="C").get_data()[0]),
    "chest_3ms_g": float(calculate_xms(chest, 3, method="C").get_data()[0]),
    "chest_deflection_mm": float(-np.min(signals["11CHST0000H3DSXC"]) * 1e3),
    "vc_mps": float(vc_peak.get_data()[0]),
    "nij": float(nij_peak.get_data()[0]),
    "neck_flexion_nm": float(np.max(moc.get_data())),
    "neck_extension_nm": float(-np.min(moc.get_data())),
}
out = {
    "generator": f"pyisomme {importlib.metadata.version('pyisomme')}: sim/tests/reference/criteria_pyisomme.py",
    "t0": float(T[0]),
    "dt": DT,
    "dummy": "H3",
    "channels": {code: [float(x) for x in v] for code, v in signals.items()},
    "pyisomme": values,
}
path = pathlib.Path(__file__).with_name("criteria_pyisomme.json")
path.write_text(json.dumps(out, indent=1) + "\n")
print(json.dumps(values, indent=1))
