"""`lpm export-fmu` end to end with FMPy: the FMU validates, and its
Co-Simulation and Model Exchange runs of the paper scenario agree with
`lpm simulate` (maximum crush within 0.5 %), a parameter set through FMI
included."""

import shlex

import pytest
from fmpy import simulate_fmu
from fmpy.validation import validate_fmu

import lagrangian
from conftest import ROOT, SPECS, run_lpm

YARIS = SPECS / "yaris_double_pendulum.lpm"
RUNTIME = ROOT / "target" / "debug" / "liblagrangian_fmu.so"
#: The README's command line (run in the repository root, writing into the
#: test's folder instead of the current one).
README_COMMAND = "lpm export-fmu specs/yaris_double_pendulum.lpm --out yaris.fmu"


def readme_shows_the_command():
    return README_COMMAND in (ROOT / "README.md").read_text()


@pytest.fixture(scope="module")
def fmu(tmp_path_factory):
    """The paper scenario's FMU, exported by the README's command line."""
    out = tmp_path_factory.mktemp("fmu") / "yaris.fmu"
    args = shlex.split(README_COMMAND)[1:]
    args[args.index("--out") + 1] = str(out)
    run_lpm(*args)
    return out


def max_crush_of_lpm_simulate(**settings):
    return lagrangian.simulate(YARIS, **settings).summary["max_crush_m"]


def relative(a, b):
    return abs(a - b) / abs(b)


def test_the_readme_shows_the_command_tested_here():
    assert readme_shows_the_command()


def test_fmpy_finds_no_problem_in_the_fmu(fmu):
    assert validate_fmu(str(fmu)) == []


def test_co_simulation_agrees_with_lpm_simulate(fmu):
    result = simulate_fmu(str(fmu), fmi_type="CoSimulation", output=["metrics.crush", "front_end.force"])
    assert result["time"][-1] == pytest.approx(0.15)
    assert relative(result["metrics.crush"].max(), max_crush_of_lpm_simulate()) < 0.005
    assert result["front_end.force"].max() > 1e5  # the crush force reaches hundreds of kN


def test_model_exchange_with_cvode_agrees_with_lpm_simulate(fmu):
    result = simulate_fmu(str(fmu), fmi_type="ModelExchange", solver="CVode",
                          relative_tolerance=1e-8, output=["metrics.crush"])
    assert relative(result["metrics.crush"].max(), max_crush_of_lpm_simulate()) < 0.005


def test_model_exchange_with_euler_agrees_with_lpm_simulate(fmu):
    result = simulate_fmu(str(fmu), fmi_type="ModelExchange", solver="Euler",
                          step_size=1e-6, output_interval=1e-4, output=["metrics.crush"])
    assert relative(result["metrics.crush"].max(), max_crush_of_lpm_simulate()) < 0.005


def test_a_parameter_set_through_fmi_changes_the_run_as_set_does(fmu):
    default = max_crush_of_lpm_simulate()
    heavier = max_crush_of_lpm_simulate(m1=700.0)
    assert relative(heavier, default) > 0.01  # m1 matters
    for fmi_type in ["CoSimulation", "ModelExchange"]:
        result = simulate_fmu(str(fmu), fmi_type=fmi_type, start_values={"m1": 700.0},
                              relative_tolerance=1e-8, output=["metrics.crush"])
        assert relative(result["metrics.crush"].max(), heavier) < 0.005, fmi_type


def test_export_fmu_from_python_writes_the_same_model(fmu, tmp_path):
    out = lagrangian.export_fmu(YARIS, out=tmp_path / "y.fmu", runtime=RUNTIME)
    assert out == tmp_path / "y.fmu"
    assert validate_fmu(str(out)) == []
    result = simulate_fmu(str(out), fmi_type="CoSimulation", output=["metrics.crush"])
    assert relative(result["metrics.crush"].max(), max_crush_of_lpm_simulate()) < 0.005


def test_a_bad_spec_fails_as_lpm_simulate_does(tmp_path):
    bad = tmp_path / "bad.lpm"
    bad.write_text("model Bad;\ncoordinates { x }\nkinetic = 0.5 * m * pow(dot(x), 2);\n")
    simulate = run_lpm("simulate", bad, "--out", tmp_path / "sim", check=False)
    export = run_lpm("export-fmu", bad, "--out", tmp_path / "bad.fmu", check=False)
    assert export.returncode == simulate.returncode == 3
    assert export.stderr == simulate.stderr
    assert not (tmp_path / "bad.fmu").exists()
    with pytest.raises(lagrangian.SpecError):
        lagrangian.export_fmu(bad, out=tmp_path / "bad.fmu", runtime=RUNTIME)


def test_a_missing_runtime_says_what_to_build(tmp_path):
    with pytest.raises(lagrangian.UsageError, match="cargo build -p lagrangian-fmu"):
        lagrangian.export_fmu(YARIS, out=tmp_path / "y.fmu", runtime=tmp_path / "none.so")
    assert not (tmp_path / "y.fmu").exists()
