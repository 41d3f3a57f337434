#!/usr/bin/env python3
"""Independent SciPy reference data for the project's adaptive ODE integrator.

What it is
----------
This script integrates two test problems with SciPy's Dormand-Prince 5(4)
solver (``scipy.integrate.solve_ivp(method="RK45")``) and records step counts,
RHS evaluation counts and final-state errors, plus the constants of SciPy's
step-size controller, as a yardstick for the Rust integrator:

1. The Arenstorf orbit (restricted three-body problem; Hairer, Norsett,
   Wanner, "Solving Ordinary Differential Equations I", Sec. II.0) over one
   period, for several tolerances.  The orbit is periodic, so
   ``||y(T) - y(0)||_inf`` is the global error.
2. The harmonic oscillator ``x'' = -x``, ``x(0) = 1``, ``x'(0) = 0`` on
   [0, 10], whose exact solution is ``x = cos t``.

How to run
----------
From the repository root (needs ``scipy`` and ``numpy``)::

    python3 tests/reference/scipy_ode_reference.py

It writes ``tests/reference/scipy_ode_reference.json``.  That JSON file is
committed and read by the Rust tests, which therefore need no Python.
"""

import json
from pathlib import Path

import numpy as np
import scipy
from scipy.integrate import RK45, solve_ivp

OUT = Path(__file__).with_suffix(".json")

MU = 0.012277471
MU_P = 1.0 - MU
ARENSTORF_Y0 = [0.994, 0.0, 0.0, -2.00158510637908252240537862224]
ARENSTORF_T = 17.0652165601579625588917206249
ARENSTORF_TOLS = [(1e-4, 1e-4), (1e-6, 1e-6), (1e-8, 1e-8), (1e-10, 1e-10),
                  (1e-6, 1e-9)]

HARMONIC_T = 10.0
HARMONIC_TOLS = [(1e-6, 1e-6), (1e-9, 1e-9)]


def arenstorf(t, y):
    y1, y2, v1, v2 = y
    d1 = ((y1 + MU) ** 2 + y2 ** 2) ** 1.5
    d2 = ((y1 - MU_P) ** 2 + y2 ** 2) ** 1.5
    return [v1, v2,
            y1 + 2 * v2 - MU_P * (y1 + MU) / d1 - MU * (y1 - MU_P) / d2,
            y2 - 2 * v1 - MU_P * y2 / d1 - MU * y2 / d2]


def harmonic(t, y):
    return [y[1], -y[0]]


class CountingRK45(RK45):
    """RK45 that counts step attempts (accepted and rejected).

    ``RungeKutta._step_impl`` loops over trial steps until one is accepted and
    calls ``_estimate_error_norm`` exactly once per trial, so counting those
    calls gives the attempts; rejected = attempts - accepted.  The numerics
    are untouched: this is SciPy's RK45 unchanged.
    """

    last = None  # the most recently created instance

    def __init__(self, *args, **kwargs):
        self.attempts = 0
        super().__init__(*args, **kwargs)
        CountingRK45.last = self

    def _estimate_error_norm(self, K, h, scale):
        self.attempts += 1
        return super()._estimate_error_norm(K, h, scale)


def run(fun, t_end, y0, rtol, atol):
    """Integrate with RK45 and return (solution, counts, y_end)."""
    rhs_calls = [0]

    def counted(t, y):
        rhs_calls[0] += 1
        return fun(t, y)

    sol = solve_ivp(counted, (0.0, t_end), y0, method=CountingRK45,
                    rtol=rtol, atol=atol)
    assert sol.success, sol.message
    accepted = len(sol.t) - 1
    rejected = CountingRK45.last.attempts - accepted
    # Our own count of RHS calls agrees with SciPy's nfev.
    assert sol.nfev == rhs_calls[0]
    # RK45 has 6 stages + FSAL: each trial step (accepted or rejected) costs
    # 6 new RHS calls (stages 2..6 and f(t + h, y_new)); K[0] reuses the
    # stored f.  Start-up costs 2: f(t0, y0) in RungeKutta.__init__ and one
    # call in select_initial_step (an explicit Euler probe).
    assert sol.nfev == 2 + 6 * (accepted + rejected)
    counts = {"rtol": rtol, "atol": atol, "accepted": accepted,
              "rejected": rejected, "nfev": int(sol.nfev)}
    return sol, counts, sol.y[:, -1]


def arenstorf_runs():
    runs = []
    for rtol, atol in ARENSTORF_TOLS:
        _, counts, y_end = run(arenstorf, ARENSTORF_T, ARENSTORF_Y0,
                               rtol, atol)
        err = np.max(np.abs(y_end - np.array(ARENSTORF_Y0)))
        runs.append(dict(counts, y_end=y_end.tolist(),
                         periodicity_error=float(err)))
    return runs


def harmonic_runs():
    runs = []
    exact = np.array([np.cos(HARMONIC_T), -np.sin(HARMONIC_T)])
    for rtol, atol in HARMONIC_TOLS:
        _, counts, y_end = run(harmonic, HARMONIC_T, [1.0, 0.0], rtol, atol)
        runs.append(dict(counts, y_end=y_end.tolist(),
                         error_x=float(abs(y_end[0] - exact[0])),
                         error_inf=float(np.max(np.abs(y_end - exact)))))
    return runs


def controller_constants():
    """SciPy RK45 controller, as read from scipy/integrate/_ivp/rk.py."""
    from scipy.integrate._ivp import rk
    return {
        "safety": rk.SAFETY,
        "min_factor": rk.MIN_FACTOR,
        "max_factor": float(rk.MAX_FACTOR),
        "error_exponent": -1.0 / (RK45.error_estimator_order + 1),
        "norm": "RMS: sqrt(mean((err_i / sc_i)^2)), "
                "sc_i = atol + rtol * max(|y_i|, |y_new_i|); "
                "accept if norm < 1",
        "step_update": "accept: h *= min(max_factor, safety * "
                       "norm^exponent) (min(1, .) if this step had a "
                       "rejection; max_factor if norm == 0); reject: "
                       "h *= max(min_factor, safety * norm^exponent)",
        "first_step": "scipy.integrate._ivp.common.select_initial_step "
                      "(HNW I, Sec. II.4): sc = atol + rtol*|y0|, "
                      "d0 = rms(y0/sc), d1 = rms(f0/sc); "
                      "h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else "
                      "0.01*d0/d1, h0 = min(h0, |t_end - t0|); "
                      "f1 = f(t0 + h0, y0 + h0*f0), "
                      "d2 = rms((f1 - f0)/sc)/h0; "
                      "h1 = max(1e-6, 1e-3*h0) if max(d1, d2) <= 1e-15 "
                      "else (0.01/max(d1, d2))^(1/5); "
                      "h = min(100*h0, h1, |t_end - t0|, max_step)",
    }


def main():
    data = {
        "generator": "tests/reference/scipy_ode_reference.py",
        "scipy_version": scipy.__version__,
        "numpy_version": np.__version__,
        "arenstorf": {"mu": MU, "y0": ARENSTORF_Y0, "period": ARENSTORF_T,
                      "runs": arenstorf_runs()},
        "harmonic": {"t_end": HARMONIC_T, "y0": [1.0, 0.0],
                     "exact_x": float(np.cos(HARMONIC_T)),
                     "runs": harmonic_runs()},
        "scipy_rk45": controller_constants(),
    }
    OUT.write_text(json.dumps(data, indent=2) + "\n")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
