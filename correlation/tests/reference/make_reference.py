#!/usr/bin/env python3
"""Reference ISO/TS 18571 ratings for tests/iso18571_reference.rs.

Writes iso18571.json beside this script: a handful of curve pairs (their
values rounded to 10 significant digits, the numbers rated, and their
times, an even grid as start, step and n) and
the scores of objective_rating_metrics 1.3 (ISO18571) on them, unrounded,
and of pyisomme's wrapper (Correlation_ISO18571), which resamples the
curves itself.

objective_rating_metrics takes curves already on one 10 kHz grid of equal
length; this script puts each pair on the grid lagrangian-correlation
documents (resample.rs): from the later first time, in steps of 0.1 ms, to
the earlier last time included where it falls on the grid (within 1e-6
of a step), values interpolated linearly (numpy.interp). pyisomme's
wrapper uses the shared samples when both curves are on one 10 kHz grid
(the same grid), and otherwise numpy.arange(start, end, 1e-4), which
leaves out the end: there its scores differ by that one sample.

Run from the repository root:
    python3 -m venv target/ref-venv
    target/ref-venv/bin/pip install pyisomme   # pulls objective-rating-metrics
    target/ref-venv/bin/python correlation/tests/reference/make_reference.py
"""

import json
import warnings
import logging
import pathlib
from importlib.metadata import version

import numpy as np
import pandas as pd
from objective_rating_metrics.rating import ISO18571
from pyisomme import Channel, Correlation_ISO18571

STEP = 1e-4
GRID_TOLERANCE = 1e-6
G = 9.80665


def rounded(values):
    """The values as the JSON writes them (10 significant digits)."""
    return np.array([float(f"{v:.10g}") for v in values])


class Even:
    """Times `start + step·k`, k = 0 … n−1: written as start, step and n,
    and computed from them the same way (one product, one sum) here and
    in the Rust test."""

    def __init__(self, start, step, n):
        self.start, self.step, self.n = start, step, n

    def array(self):
        return self.start + self.step * np.arange(self.n)

    def json(self):
        return {"start": self.start, "step": self.step, "n": self.n}


def grid(t_ref, t_cmp):
    start = max(t_ref[0], t_cmp[0])
    end = min(t_ref[-1], t_cmp[-1])
    n = int(np.floor((end - start) / STEP + GRID_TOLERANCE)) + 1
    return start + STEP * np.arange(n)


def scores_of(rating):
    return {
        "corridor": float(rating.corridor_rating(ndigits=-1)),
        "phase": float(rating.phase_rating(ndigits=-1)),
        "magnitude": float(rating.magnitude_rating(ndigits=-1)),
        "slope": float(rating.slope_rating(ndigits=-1)),
        "overall": float(rating.overall_rating(ndigits=-1)),
    }


def objective_rating(reference, comparison):
    t = grid(reference[0], comparison[0])
    r = np.interp(t, reference[0], reference[1])
    c = np.interp(t, comparison[0], comparison[1])
    return scores_of(ISO18571(np.c_[t, r], np.c_[t, c])), len(t)


def pyisomme_rating(reference, comparison):
    def channel(curve):
        data = pd.DataFrame({"y": curve[1]}, index=pd.Index(curve[0], name="t"))
        return Channel("10VEHCCG0000ACXP", data, unit="m/s^2")

    try:
        return scores_of(Correlation_ISO18571(channel(reference), channel(comparison)))
    except ValueError as e:
        # pyisomme 1.1.0 pairs curves by their shared time stamps, and two
        # curves on different uneven grids share one (t = 0): too few.
        return {"error": str(e)}


def times(start, end, step):
    return Even(start, step, int(round((end - start) / step)) + 1)


def crash_pulse(t, peak_g=35.0, duration=0.08, delay=0.0):
    """A frontal pulse (m/s², negative): a haversine with a second hump."""
    s = np.clip((t - delay) / duration, 0.0, 1.0)
    shape = np.sin(np.pi * s) ** 2 + 0.35 * np.sin(2.0 * np.pi * s) ** 2 * (s > 0.5)
    return -peak_g * G * shape


def half_sine(t, peak, duration):
    return np.where((t >= 0) & (t <= duration), peak * np.sin(np.pi * t / duration), 0.0)


def triangle(t, peak, duration):
    rise = np.clip(t / (duration / 2.0), 0.0, None)
    return np.where((t >= 0) & (t <= duration), peak * np.minimum(rise, 2.0 - rise), 0.0)


def cases():
    """(name, reference, comparison), each curve (times, values): times an
    Even grid or an array."""
    rng = np.random.default_rng(18571)
    grid_120 = times(0.0, 0.12, STEP)
    t = grid_120.array()
    pulse = crash_pulse(t, delay=0.01)
    on_grid = lambda values: ((grid_120, pulse), (grid_120, values))  # noqa: E731
    yield "identical", *on_grid(pulse)
    yield "scaled_0.9", *on_grid(0.9 * pulse)
    yield "shifted_2ms", *on_grid(crash_pulse(t, delay=0.012))
    yield "shifted_8ms", *on_grid(crash_pulse(t, delay=0.018))
    yield "earlier_5ms", *on_grid(crash_pulse(t, delay=0.005))
    yield "noisy", *on_grid(pulse + rng.normal(0.0, 0.004 * 35.0 * G, t.size))
    # A test's pulse (a ringing measured channel) against a smooth model's.
    ringing = crash_pulse(t, 38.0, 0.085, 0.008) * (1.0 + 0.12 * np.sin(2 * np.pi * 180.0 * t))
    yield "crash_pulse_pair", (grid_120, ringing), (grid_120, crash_pulse(t, 34.0, 0.09, 0.01))
    # A poor match: a short triangle against the long pulse.
    yield "short_triangle", *on_grid(triangle(t - 0.02, -30.0 * G, 0.03))
    grid_80 = times(0.0, 0.08, STEP)
    s = grid_80.array()
    yield "half_sine_vs_triangle", (grid_80, half_sine(s, 40.0, 0.06)), (grid_80, triangle(s, 40.0, 0.06))
    # Different sample rates and start times: a test at 20 kHz from
    # -20 ms, a model at 2.5 kHz from 0 to 130 ms.
    test, model = times(-0.02, 0.11, 5e-5), times(0.0, 0.13, 4e-4)
    yield (
        "different_rates_and_starts",
        (test, crash_pulse(test.array(), delay=0.01)),
        (model, crash_pulse(model.array(), 33.0, 0.082, 0.011)),
    )
    # Uneven steps: the comparison's times jittered by up to 40 % of 0.3 ms.
    uneven = rounded(np.cumsum(np.r_[0.0, 3e-4 * (1.0 + 0.4 * rng.uniform(-1, 1, 399))]))
    yield "uneven_times", (grid_120, pulse), (uneven, crash_pulse(uneven, 36.0, 0.08, 0.0105))


def curve(times, values):
    """The curve as rated (values rounded as written) and as written."""
    values = rounded(values)
    if isinstance(times, Even):
        return (times.array(), values), {**times.json(), "y": list(values)}
    return (times, values), {"t": list(times), "y": list(values)}


def main():
    logging.disable(logging.WARNING)  # pyisomme's note that it interpolates
    warnings.simplefilter("ignore", RuntimeWarning)  # numpy on pyisomme's failing case
    out = []
    for name, reference, comparison in cases():
        reference, reference_json = curve(*reference)
        comparison, comparison_json = curve(*comparison)
        scores, samples = objective_rating(reference, comparison)
        out.append(
            {
                "name": name,
                "reference": reference_json,
                "comparison": comparison_json,
                "samples": samples,
                "objective_rating_metrics": scores,
                "pyisomme": pyisomme_rating(reference, comparison),
            }
        )
        print(f"{name:28} {samples:5} samples  " + "  ".join(f"{k} {v:.6f}" for k, v in scores.items()))
        pyisomme = out[-1]["pyisomme"].items()
        print(f"{'  pyisomme':42}" + "  ".join(f"{k} {v:.6f}" if isinstance(v, float) else v for k, v in pyisomme))
    document = {
        "generator": "correlation/tests/reference/make_reference.py",
        "objective_rating_metrics": version("objective_rating_metrics"),
        "pyisomme": version("pyisomme"),
        "cases": out,
    }
    path = pathlib.Path(__file__).with_name("iso18571.json")
    path.write_text(json.dumps(document, separators=(",", ":")) + "\n")
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
