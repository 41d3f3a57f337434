"""Numbers with units ("36 km/h", "100 ms", "1.2 t") give one answer on
every surface: the Python package and the command line with units run
exactly as they do with the SI numbers, and an FMU exported from a
scenario written with units runs as `lpm simulate` does."""

import json

import pandas
import pytest
from fmpy import simulate_fmu

import lagrangian
from conftest import SPECS, run_lpm

YARIS = SPECS / "yaris_double_pendulum.lpm"
SCENARIO = SPECS / "scenarios" / "yaris_full_frontal.toml"


def summary_of_lpm(tmp_path, *settings):
    args = [arg for s in settings for arg in ("--set", s)]
    run_lpm("simulate", YARIS, *args, "--out", tmp_path)
    return json.loads((tmp_path / "summary.json").read_text())


def test_python_and_the_command_line_read_units_as_their_si_numbers(tmp_path):
    # 36 km/h is 10 m/s, 100 ms is 0.1 s and 0.7 t is 700 kg, exactly.
    with_units = lagrangian.simulate(YARIS, t_end="100 ms", m1="0.7 t",
                                     set={"initial.velocities.r": "-36 km/h"})
    in_si = lagrangian.simulate(YARIS, t_end=0.1, m1=700.0, set={"initial.velocities.r": -10.0})
    assert with_units.summary == in_si.summary
    cli = summary_of_lpm(tmp_path, "simulation.t_end=100 ms", "m1=0.7 t", "initial.velocities.r=-36 km/h")
    assert cli == in_si.summary
    with pytest.raises(lagrangian.ScenarioError, match="km is a length, but this entry needs a velocity"):
        lagrangian.simulate(YARIS, set={"initial.velocities.r": "-36 km"})


def test_an_fmu_of_a_scenario_written_with_units_runs_as_lpm_simulate(tmp_path):
    text = SCENARIO.read_text()
    text = text.replace('spec = "../yaris_double_pendulum.lpm"', f'spec = "{YARIS}"')
    text = text.replace("velocities = { r = -15.5556 }", 'velocities = { r = "-50 km/h" }')
    text = text.replace("t_end = 0.150 ", 't_end = "150 ms" ')
    assert '"-50 km/h"' in text and '"150 ms"' in text
    # Beside the tables it names (`../data/…`), as the shipped one is.
    (tmp_path / "data").symlink_to(SPECS / "data")
    (tmp_path / "scenarios").mkdir()
    scenario = tmp_path / "scenarios" / "units.toml"
    scenario.write_text(text)
    fmu = tmp_path / "units.fmu"
    run_lpm("export-fmu", YARIS, "--scenario", scenario, "--out", fmu)
    expected = lagrangian.simulate(YARIS, scenario).summary["max_crush_m"]
    slower = lagrangian.simulate(YARIS).summary["max_crush_m"]
    assert abs(expected - slower) / slower > 0.05  # 50 km/h is not the paper's 56 km/h
    for fmi_type in ["CoSimulation", "ModelExchange"]:
        result = simulate_fmu(str(fmu), fmi_type=fmi_type, relative_tolerance=1e-8,
                              output=["metrics.crush"])
        assert result["time"][-1] == pytest.approx(0.15)
        assert abs(result["metrics.crush"].max() - expected) / expected < 0.005, fmi_type


def test_a_sweep_with_units_is_the_sweep_of_their_si_numbers(tmp_path):
    # 43.2 km/h is 12 m/s and 64.8 km/h 18 m/s, exactly; 5e4 and 1e5 N/m.
    grid = {"initial.velocities.r": ["-43.2 km/h", "-64.8 km/h"], "k1": ["50 kN/m", "100 kN/m"]}
    with_units = lagrangian.sweep(scenario=SCENARIO, grid=grid, t_end="20 ms")
    in_si = lagrangian.sweep(scenario=SCENARIO, grid={"initial.velocities.r": [-12.0, -18.0],
                                                      "k1": [5e4, 1e5]}, t_end=0.02)
    assert with_units.equals(in_si)
    assert with_units["initial.velocities.r"].tolist() == [-12.0, -12.0, -18.0, -18.0]
    out = tmp_path / "sampled.csv"
    run_lpm("sweep", SCENARIO, "--samples", "4", "--vary", "k1=50 kN/m:100 kN/m",
            "--set", "simulation.t_end=20 ms", "--quiet", "--out", out)
    sampled = lagrangian.sweep(scenario=SCENARIO, samples=4, vary={"k1": (5e4, 1e5)}, t_end=0.02)
    assert sampled.equals(pandas.read_csv(out))
    with pytest.raises(lagrangian.UsageError, match="km is a length, but this entry needs a velocity"):
        lagrangian.sweep(scenario=SCENARIO, grid={"initial.velocities.r": ["-36 km", "-40 km/h"]})
