#!/usr/bin/env python3
"""Writes yaris_barrier_forces.csv, the barrier-force input of the default
Yaris full-frontal scenario (specs/scenarios/yaris_full_frontal.toml).

The paper (Noorsumar et al., eqs 37-39) takes the barrier forces F_bx1,
F_bz1, F_bx2, F_bz2 from its LS-DYNA model and does not publish them. Here:

* F_bx1 = F_bx2 = 0: the horizontal barrier reaction on body 1 is already the
  crush spring and damper (eqs 1-2) acting along the radius; adding it again
  would count it twice. Body 2 does not touch the barrier.
* F_bz1: a vertical force on the front (friction of the crushing front end on
  the wall face), a half sine of 20 kN peak over the first 80 ms. Estimate:
  about 0.1 x a typical 200-250 kN crush force (steel on a rigid face,
  friction coefficient ~0.1-0.2). It is illustrative, not measured; set the
  column to zero, or `--set barrier_z1=0`, to leave it out.
* F_bz2 = 0.

Run: python3 specs/data/make_barrier_forces.py (standard library only).
"""

import math
import os

PEAK_N = 20_000.0
DURATION_S = 0.080
STEP_S = 0.001
END_S = 0.200


def main():
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)),
                        "yaris_barrier_forces.csv")
    rows = ["t [s],Fx1 [N],Fz1 [N],Fx2 [N],Fz2 [N]"]
    for i in range(round(END_S / STEP_S) + 1):
        t = i * STEP_S
        fz1 = PEAK_N * math.sin(math.pi * t / DURATION_S) if t <= DURATION_S else 0.0
        rows.append(f"{t:.3f},0,{fz1:.1f},0,0")
    with open(path, "w") as f:
        f.write("# Illustrative barrier forces; see make_barrier_forces.py\n")
        f.write("\n".join(rows) + "\n")


if __name__ == "__main__":
    main()
