"""`lpm compare` against objective_rating_metrics (the ISO/TS 18571
implementation pyisomme runs), live: two CSV files at different sample
rates, start times and units, rated by both."""

import json

import numpy as np
from objective_rating_metrics.rating import ISO18571

from conftest import run_lpm

G = 9.80665
STEP = 1e-4  # the common 10 kHz time base
KEYS = ("corridor", "phase", "magnitude", "slope", "overall")


def pulse(t, peak, duration, delay):
    s = np.clip((t - delay) / duration, 0.0, 1.0)
    return peak * (np.sin(np.pi * s) ** 2 + 0.3 * np.sin(2 * np.pi * s) ** 2 * (s > 0.5))


def write_csv(path, header, t, *columns):
    rows = np.column_stack([t, *columns])
    np.savetxt(path, rows, delimiter=",", header=",".join(header), comments="", fmt="%.12g")


def objective_rating(t_ref, y_ref, t_cmp, y_cmp):
    """objective_rating_metrics on the grid lpm documents: from the later
    first time to the earlier last one (included when on the grid) every
    0.1 ms, values interpolated linearly."""
    start, end = max(t_ref[0], t_cmp[0]), min(t_ref[-1], t_cmp[-1])
    t = start + STEP * np.arange(int(np.floor((end - start) / STEP + 1e-6)) + 1)
    reference = np.c_[t, np.interp(t, t_ref, y_ref)]
    comparison = np.c_[t, np.interp(t, t_cmp, y_cmp)]
    rating = ISO18571(reference, comparison)
    return {
        "corridor": rating.corridor_rating(ndigits=-1),
        "phase": rating.phase_rating(ndigits=-1),
        "magnitude": rating.magnitude_rating(ndigits=-1),
        "slope": rating.slope_rating(ndigits=-1),
        "overall": rating.overall_rating(ndigits=-1),
    }


def test_lpm_compare_rates_as_objective_rating_metrics(tmp_path):
    # The test: 20 kHz from -10 ms, deceleration in g, barrier force in kN.
    t_test = -0.01 + 5e-5 * np.arange(2601)
    a_test = pulse(t_test, -36.0, 0.085, 0.004)
    f_test = pulse(t_test, 420.0, 0.08, 0.005)
    # The model: 4 kHz from 0 to 120 ms, in m/s² and N, later and softer.
    t_model = 2.5e-4 * np.arange(481)
    a_model = pulse(t_model, -33.0, 0.09, 0.006) * G
    f_model = pulse(t_model, 390.0, 0.083, 0.0055) * 1e3
    write_csv(tmp_path / "test.csv", ["t [s]", "a [g]", "F [kN]"], t_test, a_test, f_test)
    model_header = ["time [ms]", "accel [m/s^2]", "F [N]"]
    write_csv(tmp_path / "model.csv", model_header, t_model * 1e3, a_model, f_model)

    done = run_lpm(
        "compare", tmp_path / "test.csv", tmp_path / "model.csv",
        "--channel", "a=accel", "--channel", "F", "--format", "json",
    )
    pairs = json.loads(done.stdout)["pairs"]
    assert [(p["reference"], p["comparison"]) for p in pairs] == [("a", "accel"), ("F", "F")]

    # The files' numbers as lpm reads them: times in s, the model's values
    # in the test's units.
    test = np.loadtxt(tmp_path / "test.csv", delimiter=",", skiprows=1)
    model = np.loadtxt(tmp_path / "model.csv", delimiter=",", skiprows=1)
    t_model_s = model[:, 0] * 1e-3
    expected = [
        objective_rating(test[:, 0], test[:, 1], t_model_s, model[:, 1] / G),
        objective_rating(test[:, 0], test[:, 2], t_model_s, model[:, 2] / 1e3),
    ]
    for pair, theirs in zip(pairs, expected):
        for key in KEYS:
            assert abs(pair[key] - theirs[key]) < 1e-9, (pair["reference"], key, pair[key], theirs[key])
        print(pair["reference"], {key: f"{pair[key]:.6f} ({pair[key] - theirs[key]:+.1e})" for key in KEYS})
    # Not a pair that agrees by being trivial: the pulses differ.
    assert all(p["grade"] in ("good", "fair") for p in pairs), pairs
