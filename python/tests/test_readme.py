"""Every `python` block of the README runs (in the repository root)."""

import math
import os
import re

import numpy as np

from conftest import ROOT


def python_blocks():
    text = (ROOT / "README.md").read_text()
    return re.findall(r"^```python\n(.*?)^```", text, flags=re.S | re.M)


def test_every_python_block_of_the_readme_runs(capsys):
    blocks = python_blocks()
    assert blocks, "the README shows no Python"
    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        for block in blocks:
            exec(compile(block, "README.md", "exec"), {})
    finally:
        os.chdir(cwd)
    printed = capsys.readouterr().out.splitlines()
    # The pendulum's q̈ = −(g/l) sin θ with l = 2 m, as numpy prints it.
    assert printed[0] == str(np.array([-9.81 / 2 * math.sin(0.5)]))
    assert printed[1].startswith("0.5") and "weld fails" in printed[1]
    # The sweep, its shards merged, and the fit.
    assert "40 runs merged" in printed
    # k1 of the 10 % stiffer front end: 1.1 × 2.4e6 N/m.
    k1 = [float(line.split()[1]) for line in printed if line.startswith("k1: ")]
    assert len(k1) == 1 and abs(k1[0] / 2.64e6 - 1) < 0.02
