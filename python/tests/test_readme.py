"""Every `python` block of the README and of the book (`docs/book/`) runs
(in the repository root), the README's first."""

import math
import os
import re

import numpy as np

from conftest import ROOT


def documents():
    """The README, then the book's chapters in path order."""
    book = sorted((ROOT / "docs" / "book").rglob("*.md"))
    return [ROOT / "README.md", *book]


def python_blocks():
    blocks = []
    for path in documents():
        text = path.read_text()
        found = re.findall(r"^```python\n(.*?)^```", text, flags=re.S | re.M)
        blocks += [(path.relative_to(ROOT), block) for block in found]
    return blocks


def test_every_python_block_of_the_readme_runs(capsys):
    blocks = python_blocks()
    assert blocks, "the README shows no Python"
    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        for path, block in blocks:
            exec(compile(block, str(path), "exec"), {})
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
