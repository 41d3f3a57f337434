"""Every shipped spec that has a scenario exports as an FMU (`lpm
export-fmu --scenario`), FMPy's validator finds no problem in it, and its
variables carry the spec's own names (outputs called `crush` or
`deceleration` included) beside the FMU's `metrics.crush` and
`metrics.deceleration`."""

import re

import pytest
from fmpy import read_model_description
from fmpy.validation import validate_fmu

from conftest import SPECS, run_lpm

#: Every scenario shipped, with the spec it names (its `spec` key).
SCENARIOS = sorted((SPECS / "scenarios").glob("*.toml"))
def spec_of(scenario):
    found = re.search(r'^spec\s*=\s*"([^"]+)"', scenario.read_text(), re.MULTILINE)
    return (scenario.parent / found.group(1)).resolve()


def outputs_of(spec):
    """The names the spec declares with `output NAME [unit] = …;`."""
    return re.findall(r"^\s*output\s+([A-Za-z_][A-Za-z0-9_]*)", spec.read_text(), re.MULTILINE)


def cases():
    for scenario in SCENARIOS:
        yield pytest.param(scenario, id=scenario.stem)


def test_every_spec_of_a_scenario_is_listed():
    assert len(SCENARIOS) == 8
    assert all(spec_of(s).is_file() for s in SCENARIOS)


@pytest.mark.parametrize("scenario", list(cases()))
def test_the_fmu_exports_validates_and_keeps_the_specs_names(scenario, tmp_path):
    spec, out = spec_of(scenario), tmp_path / f"{scenario.stem}.fmu"
    run_lpm("export-fmu", spec, "--scenario", scenario, "--out", out)
    assert validate_fmu(str(out)) == []
    names = [v.name for v in read_model_description(str(out)).modelVariables]
    assert len(names) == len(set(names))
    for output in outputs_of(spec):
        assert output in names, output
    if re.search(r"^crush\s*=", scenario.read_text(), re.MULTILINE):  # [metrics] crush
        assert {"metrics.crush", "metrics.deceleration"} <= set(names)
