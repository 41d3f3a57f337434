"""`lpm simulate --iso-mme DIR` read by pyisomme, the independent ISO-MME
reader: the channels it holds are the run's trajectory.csv columns, with the
same times, codes and units.

Each expected channel is derived here from trajectory.csv by the scenario's
own definitions (crush = -r; ISO's x forward, so the vehicle velocity is the
crush rate and its acceleration the crush acceleration; the barrier load the
front end's compressive force), not from lpm's writer. The other direction,
a test pyisomme wrote read by lpm's reader, is the Rust test
crashdata/tests/pyisomme_reference.rs (no lpm command reads ISO-MME yet).
"""

import csv
import pathlib

import numpy as np
import pytest
import pyisomme

from conftest import SPECS, run_lpm

G0 = 9.80665


def trajectory(out: pathlib.Path) -> dict:
    """trajectory.csv as columns by name (units dropped)."""
    with open(out / "trajectory.csv", newline="") as f:
        rows = list(csv.reader(f))
    names = [name.split(" [")[0] for name in rows[0]]
    values = np.array(rows[1:], dtype=float)
    return {name: values[:, k] for k, name in enumerate(names)}


def read_test(folder: pathlib.Path):
    test = pyisomme.Isomme().read(folder)
    return test, {str(c.code): c for c in test.channels}


# Each run: the spec, its extra lpm arguments, and each channel's code with
# its unit and its values from trajectory.csv's columns (in that unit).
VEHICLE = {
    "10VEHCCG0000DSXP": ("m", lambda c: -c["r"]),
    "10VEHCCG0000VEXP": ("m/s", lambda c: -c["r_dot"]),
    "10VEHCCG0000ACXP": ("g", lambda c: -c["r_ddot"] / G0),
    "B0FBAR000000FOXP": ("N", lambda c: c["front_end.force"]),
}
RUNS = {
    "paper": ("yaris_double_pendulum.lpm", VEHICLE),
    "occupant": (
        "yaris_occupant.lpm",
        {
            **VEHICLE,
            "11CHST0000H3ACXP": ("m/s^2", lambda c: -c["occupant_deceleration"]),
            "11OCCU000000DSXP": ("m", lambda c: c["s"]),
            "11SEBE000000FO0P": ("N", lambda c: c["belt_force"]),
        },
    ),
}


@pytest.mark.parametrize("run", RUNS)
def test_pyisomme_reads_the_run_with_the_values_of_the_trajectory(run, tmp_path):
    spec, expected = RUNS[run]
    out, folder = tmp_path / "out", tmp_path / "iso"
    run_lpm("simulate", SPECS / spec, "--out", out, "--iso-mme", folder)
    columns = trajectory(out)
    test, channels = read_test(folder)
    assert test.test_number == pathlib.Path(spec).stem
    assert sorted(channels) == sorted(expected)
    for code, (unit, values) in expected.items():
        channel = channels[code]
        want = values(columns)
        n = len(channel.data)
        # Every output interval (0.1 ms) from 0: the trajectory's own times
        # (written to 7 decimals), up to its last sample on that grid.
        times = channel.data.index.to_numpy()
        assert n == len(want) == 1501, (code, n, len(want))
        assert np.max(np.abs(times - columns["t"][:n])) < 1e-9, code
        # In the channel's unit: pyisomme converts from the unit it read
        # (its `g` of an acceleration is standard gravity, astropy's g0).
        assert channel.unit.to_isomme() == unit or channel.unit.is_equivalent(unit), code
        got = channel.get_data(unit=pyisomme.unit.g0 if unit == "g" else unit)
        scale = np.max(np.abs(want))
        largest = np.max(np.abs(got - want))
        print(f"{run} {code}: largest difference {largest:.2e} {unit} (of {scale:.3g})")
        # trajectory.csv has 11 significant digits.
        assert largest <= 1e-9 * scale, (code, largest, scale)


def test_the_test_header_names_the_run_and_its_laboratory(tmp_path):
    out, folder = tmp_path / "out", tmp_path / "iso"
    run_lpm("simulate", SPECS / "yaris_occupant.lpm", "--out", out, "--iso-mme", folder)
    test, channels = read_test(folder)
    assert test.get_test_info("Laboratory name") == "lagrangian (simulation)"
    assert test.get_test_info("Title").startswith("2010 Toyota Yaris with a belted")
    assert channels["10VEHCCG0000ACXP"].unit.to_isomme() == "g"
    chest = channels["11CHST0000H3ACXP"]
    assert chest.get_info("Sampling interval") == pytest.approx(1e-4, rel=1e-12)
    assert chest.get_info("Time of first sample") == 0


def test_a_bad_code_in_a_setting_is_refused_before_anything_is_written(tmp_path):
    out, folder = tmp_path / "out", tmp_path / "iso"
    done = run_lpm(
        "simulate", SPECS / "yaris_double_pendulum.lpm", "--out", out, "--iso-mme", folder,
        "--set", 'iso_mme.channels.theta2="10VEHCCG0000ANYZ"', check=False,
    )
    assert done.returncode == 4, done.stderr
    assert "iso_mme.channels.theta2" in done.stderr and "filter class (position 16)" in done.stderr
    assert not out.exists() and not folder.exists()
