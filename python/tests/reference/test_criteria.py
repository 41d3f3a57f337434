"""`lpm metrics TEST` on an ISO-MME test pyisomme writes, against pyisomme's
own criteria on the same channels: a Hybrid III 50th driver's head, chest
and upper neck at 10 kHz, already filtered at their classes (pyisomme's
criterion functions do not filter; the codes' filter classes tell lpm not
to either), in the units a lab writes (g, mm, kN, N·m) and a second
occupant whose femur only is instrumented."""

import json

import numpy as np
import pandas as pd
import pytest
import pyisomme
from pyisomme import Channel, Isomme
from pyisomme.calculate import calculate_hic, calculate_neck_MOCy, calculate_neck_nij, calculate_vc, calculate_xms

from conftest import run_lpm

DT = 1e-4
T = np.round(np.arange(-100, 1501) * DT, 10)


def bump(amplitude, start, duration):
    inside = (T >= start) & (T <= start + duration)
    return np.where(inside, amplitude * np.sin(np.pi * (T - start) / duration), 0.0)


def ripple(amplitude, frequency):
    return amplitude * np.sin(2 * np.pi * frequency * T) * bump(1.0, 0.0, 0.12)


CHANNELS = {
    "11HEAD0000H3ACRA": ("g", (bump(70.0, 0.02, 0.045) + ripple(6.0, 210.0)).clip(min=0.0)),
    "11CHST0000H3ACRC": ("g", (bump(42.0, 0.015, 0.07) + ripple(4.0, 90.0)).clip(min=0.0)),
    "11CHST0000H3DSXC": ("mm", -bump(38.0, 0.02, 0.06) - bump(6.0, 0.05, 0.02)),
    "11NECKUP00H3FOZB": ("kN", bump(1.8, 0.03, 0.06) - bump(0.7, 0.01, 0.02)),
    "11NECKUP00H3FOXB": ("kN", bump(0.9, 0.035, 0.05) + ripple(0.08, 140.0)),
    "11NECKUP00H3MOYB": ("N*m", -bump(28.0, 0.04, 0.05) + bump(45.0, 0.005, 0.025)),
    "13FEMRLE00H3FOZB": ("kN", -bump(4.2, 0.02, 0.05)),
}


def channel(code):
    unit, values = CHANNELS[code]
    # An implicit time base: the files give t0 and the sampling interval.
    info = [("Reference channel", "implicit")]
    return Channel(code, pd.DataFrame(values, index=T), unit=unit, info=info)


def test_lpm_metrics_of_an_iso_mme_test_gives_pyisommes_criteria(tmp_path):
    written = Isomme(test_number="CRIT01", test_info=[("Title", "criteria")], channels=[channel(c) for c in CHANNELS])
    folder = tmp_path / "CRIT01"
    written.write(folder)
    done = run_lpm("metrics", folder, "--format", "json")
    ours = json.loads(done.stdout)
    # pyisomme rates the channels as it reads them back (the files hold
    # the samples to the digits it writes), as lpm does.
    channels = Isomme().read(folder).channels

    by_code = {str(c.code): c for c in channels}
    head, chest, deflection = (by_code[c] for c in ("11HEAD0000H3ACRA", "11CHST0000H3ACRC", "11CHST0000H3DSXC"))
    fz, fx, my = (by_code[c] for c in ("11NECKUP00H3FOZB", "11NECKUP00H3FOXB", "11NECKUP00H3MOYB"))
    moc, _ = calculate_neck_MOCy(my, fx)
    nij = [c for c in calculate_neck_nij(fz, moc, oop=False)
           if c.code.main_location == "NIJC" and c.code.filter_class == "X" and c.code.fine_location_2 == "00"][0]
    theirs = {
        "head_3ms_g": calculate_xms(head, 3, method="C").get_data()[0],
        "chest_3ms_g": calculate_xms(chest, 3, method="C").get_data()[0],
        "chest_deflection_mm": -np.min(deflection.get_data(unit="mm")),
        "vc_mps": calculate_vc(deflection)[1].get_data()[0],
        "nij": nij.get_data()[0],
        "neck_tension_kn": np.max(fz.get_data(unit="kN")),
        "neck_compression_kn": -np.min(fz.get_data(unit="kN")),
        "neck_shear_kn": np.max(np.abs(fx.get_data(unit="kN"))),
        "neck_flexion_nm": np.max(moc.get_data(unit="N*m")),
        "neck_extension_nm": -np.min(moc.get_data(unit="N*m")),
    }
    driver = ours["occupants"][0]
    assert (driver["test_object"], driver["position"], driver["dummy"]) == ("1", "1", "hybrid3_50m")
    for key, value in theirs.items():
        assert driver["criteria"][key] == pytest.approx(value, rel=1e-9), key
    # HIC: pyisomme's windows are one sample short of the standard's and
    # only the widest; ours searches every window the standard allows.
    hic15 = calculate_hic(head, 15).get_data()[0]
    assert hic15 <= driver["criteria"]["hic15"] <= hic15 * 1.01
    assert calculate_hic(head, 36).get_data()[0] <= driver["criteria"]["hic36"]
    # The driver's criteria are the test's; the passenger has a femur.
    assert ours["criteria"] == driver["criteria"]
    passenger = ours["occupants"][1]
    assert passenger["position"] == "3"
    assert passenger["criteria"] == {"femur_max_kn": pytest.approx(4.2, rel=1e-6)}
    assert ours["warnings"] == []
