#!/usr/bin/env python3
"""Runs the peer simulator (railway-impact-simulator, MIT, github
sflabbe/railway-impact-simulator) on the Pioneer case of issue 19 and writes
its figures to pioneer_peer.json beside this script.

    python3 benches/peer/railway/run_peer.py PEER_CHECKOUT [--venv DIR] [--runs 5]

PEER_CHECKOUT is a source tree of the peer (its pyproject.toml at the top).
Unless --venv names one that has it already, a virtual environment is made
(default: PEER_CHECKOUT/.venv-lagrangian) and the checkout pip-installed into
it, its dependencies coming from the package registry; the script then runs
itself again under that environment's Python.

The configuration is the issue's (Fy 15 MN at uy 0.2 m, wall contact
45 MN/m, 56.3 km/h), with the Bouc–Wen shape of the peer's Pioneer
configuration; how it differs from the peer's own configs/ice1_80kmh.yml is
in DIFFERENCES below and in the JSON. The peer always adds 5 % Rayleigh
damping (C = αM + βK from the two highest modes of the linear chain; no
setting turns it off): the case runs as the peer ships it, and once more with
that damping removed, which is the model of specs/pioneer_wagon.lpm.

The figures are computed from the sampled histories (every step, 0.1 ms) by
the same definitions as lpm/tests/pioneer.rs uses on ours.
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

G = 9.80665
SPEED = 35 * 0.44704  # m/s: 35 mph (56.3 km/h)
MASSES = [4000.0, 10000.0, 4000.0, 4000.0, 4000.0, 10000.0, 4000.0]

DIFFERENCES = {
    "speed": "35 mph = 15.646 m/s = 56.3 km/h (the test's speed); configs/ice1_80kmh.yml runs 80 km/h",
    "springs": "Fy 15 MN at uy 0.2 m (the issue, and the peer's default parameter set); "
    "configs/ice1_80kmh.yml has Fy 8 MN at uy 0.1 m",
    "wall": "linear contact 45 MN/m (`hooke`: F = k·δ, pushes only, no damping); "
    "configs/ice1_80kmh.yml uses `lankarani-nikravesh` (F = k·δ^1.5·(1 + 3(1 − cr²)/4·δ̇/v0), "
    "k = 45e6 read as N/m^1.5, cr 0.8)",
    "friction": "none; configs/ice1_80kmh.yml has LuGre wheel–rail friction (μ 0.3–0.4, "
    "about 0.1 MN for 40 t, under 1 % of the wall force)",
    "geometry": "masses at 0, 3, 6.5, 10, 13.5, 17, 20 m (configs/ice1_80kmh.yml), front at the "
    "wall at t = 0 (d0 = 0; the config has a 10 mm gap)",
    "bouc_wen": "a = 0, A = 1, β = 0.1, γ = 0.9, n = 8, as configs/ice1_80kmh.yml",
    "integration": "HHT-α, α = −0.15, h = 0.1 ms, Newton (the peer's defaults), 0.25 s",
}


def parameters():
    """The peer's parameter overrides for the Pioneer case."""
    return {
        "n_masses": 7,
        "masses": MASSES,
        "x_init": [0.0, 3.0, 6.5, 10.0, 13.5, 17.0, 20.0],
        "y_init": [0.0] * 7,
        "v0_init": -SPEED,
        "angle_rad": 0.0,
        "d0": 0.0,
        "fy": [15.0e6] * 6,
        "uy": [0.2] * 6,
        "bw_a": 0.0,
        "bw_A": 1.0,
        "bw_beta": 0.1,
        "bw_gamma": 0.9,
        "bw_n": 8,
        "k_wall": 45.0e6,
        "cr_wall": 0.8,
        "contact_model": "hooke",
        "friction_model": "none",
        "mu_s": 0.0,
        "mu_k": 0.0,
        "sigma_0": 0.0,
        "sigma_1": 0.0,
        "sigma_2": 0.0,
        "alpha_hht": -0.15,
        "h_init": 1.0e-4,
        "T_max": 0.25,
    }


def figures(t, wall_force, accelerations):
    """Peak wall force, peak decelerations and rebound (the largest
    acceleration of the other sign) of the front mass, mass 2 and the centre
    of mass, the contact duration and the rebound speed of the centre of mass.
    `accelerations` are per mass, +x towards the wall (deceleration = −a)."""
    total = sum(MASSES)
    cg = [sum(m * a[k] for m, a in zip(MASSES, accelerations)) / total for k in range(len(t))]
    touching = [k for k, f in enumerate(wall_force) if f > 0.0]
    duration = t[touching[-1]] - t[touching[0]] if touching else 0.0
    # The centre of mass's velocity (trapezoids), from +SPEED; the car is
    # at rest where it first reaches 0.
    v, at_rest = SPEED, None
    for k in range(1, len(t)):
        v += 0.5 * (cg[k] + cg[k - 1]) * (t[k] - t[k - 1])
        if at_rest is None and v <= 0.0:
            at_rest = t[k]
    out = {
        "peak_wall_force_MN": max(wall_force) / 1e6,
        "contact_duration_s": duration,
        "main_impact_s": at_rest,
        "contact_ended": bool(touching) and touching[-1] < len(t) - 1,
        "rebound_speed_m_s": -v,
    }
    for name, a in [("front", accelerations[0]), ("body", accelerations[1]), ("cg", cg)]:
        out[f"{name}_peak_deceleration_g"] = -min(a) / G
        out[f"{name}_rebound_g"] = max(a) / G
    return out


def run_case(rayleigh, runs):
    """Runs the case `runs` times; returns its figures and wall times."""
    from railway_simulator.core import engine

    original = engine.StructuralDynamics.compute_rayleigh_damping
    if not rayleigh:
        engine.StructuralDynamics.compute_rayleigh_damping = staticmethod(
            lambda M, K, zeta=0.05: 0.0 * M
        )
    try:
        times = []
        for _ in range(runs):
            start = time.perf_counter()
            df = engine.run_simulation(parameters(), emit_peak_diagnostics=False)
            times.append(time.perf_counter() - start)
    finally:
        engine.StructuralDynamics.compute_rayleigh_damping = original
    t = df["Time_s"].to_list()
    # The peer's masses move in −x; flip to +x towards the wall.
    acc = [(-df[f"Mass{i}_Acceleration_x_m_s2"]).to_list() for i in range(1, 8)]
    force = df["Impact_Force_wall_total_MN"].abs().mul(1e6).to_list()
    result = figures(t, force, acc)
    result["wall_time_per_run_s"] = {
        "median": statistics.median(times),
        "runs": times,
    }
    return result


def inside(args):
    import railway_simulator

    version = getattr(railway_simulator, "__version__", "unknown")
    report = {
        "tool": "railway-impact-simulator",
        "version": version,
        "source": "github.com/sflabbe/railway-impact-simulator (MIT)",
        "command": "python3 benches/peer/railway/run_peer.py PEER_CHECKOUT --runs "
        f"{args.runs}",
        "python": sys.version.split()[0],
        "parameters": parameters(),
        "differences_from_configs_ice1_80kmh_yml": DIFFERENCES,
        "definitions": {
            "peak_deceleration_g": "largest deceleration of the mass (or of the centre of "
            "mass, Σ m·a / Σ m), unfiltered, over the run",
            "rebound_g": "largest acceleration of the other sign (towards the wall), unfiltered",
            "contact_duration_s": "first to last sample with a wall force",
            "main_impact_s": "first contact until the centre of mass first comes to rest "
            "(the end of the compression phase)",
            "rebound_speed_m_s": "velocity of the centre of mass at the end of the run, "
            "away from the wall positive",
        },
        "cases": {
            "as_shipped_with_rayleigh_5pct": run_case(True, args.runs),
            "without_rayleigh_damping": run_case(False, args.runs),
        },
    }
    Path(args.out).write_text(json.dumps(report, indent=2) + "\n")
    print(json.dumps(report["cases"], indent=2))


def outside(args):
    checkout = Path(args.checkout).resolve()
    venv = Path(args.venv).resolve() if args.venv else checkout / ".venv-lagrangian"
    python = venv / "bin" / "python"
    if not python.exists():
        subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    probe = subprocess.run([str(python), "-c", "import railway_simulator"], capture_output=True)
    if probe.returncode != 0:
        subprocess.run([str(python), "-m", "pip", "install", "-q", str(checkout)], check=True)
    env = dict(os.environ, LAGRANGIAN_PEER_INSIDE="1")
    command = [str(python), __file__, str(checkout), "--runs", str(args.runs), "--out", args.out]
    sys.exit(subprocess.run(command, env=env).returncode)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("checkout", help="source tree of railway-impact-simulator")
    parser.add_argument("--venv", help="virtual environment to use or create")
    parser.add_argument("--runs", type=int, default=5, help="timed runs per case (median)")
    here = Path(__file__).resolve().parent
    parser.add_argument("--out", default=str(here / "pioneer_peer.json"))
    args = parser.parse_args()
    if os.environ.get("LAGRANGIAN_PEER_INSIDE") == "1":
        inside(args)
    else:
        outside(args)


if __name__ == "__main__":
    main()
