"""Writes specs/data/yaris_test/: the pulse of yaris_pulse.csv (the paper's
car with a 10 % stiffer front end, see make_yaris_pulse.py) as an ISO-MME
test, written by pyisomme (MIT, PyPI `pyisomme`), the independent ISO-MME
writer, as a lab would hand it over: the vehicle's CG x acceleration in g,
signed as ISO signs it (x forward: the deceleration is negative),
unfiltered (filter class 0), every 0.5 ms from 0, and the impact speed in
the .mme. Run:

    python3 -m venv /tmp/ref && /tmp/ref/bin/pip install pyisomme==1.1.0
    /tmp/ref/bin/python specs/data/make_yaris_test.py
"""

import csv
import pathlib
import shutil

import numpy as np
import pandas as pd
from pyisomme import Channel, Isomme

HERE = pathlib.Path(__file__).parent

with open(HERE / "yaris_pulse.csv") as f:
    rows = list(csv.DictReader(f))
t = np.array([float(r["t [ms]"]) for r in rows]) * 1e-3
acceleration = -np.array([float(r["deceleration [g]"]) for r in rows])

info = [
    ("Name of the channel", "Vehicle CG acceleration X"),
    ("Reference channel", "implicit"),
    ("Location", "CG"),
    ("Direction", "X"),
]
channel = Channel("10VEHCCG0000ACX0", pd.DataFrame(acceleration, index=t), unit="g", info=info)
test = Isomme(
    test_number="YARIS56",
    test_info=[
        ("Data format edition number", "1.6"),
        ("Laboratory name", "lagrangian (synthetic test: the paper's model, front 10 % stiffer)"),
        ("Title", "2010 Toyota Yaris, 56 km/h full frontal, rigid barrier"),
        ("Type of the test", "Full frontal"),
        ("Number of test objects", 1),
        ("Name of test object 1", "2010 Toyota Yaris"),
        ("Velocity test object 1", 15.5556),
        ("Mass test object 1", 1168),
    ],
    channels=[channel],
)
out = HERE / "yaris_test"
shutil.rmtree(out, ignore_errors=True)
test.write(out)
print(f"wrote {out}")
