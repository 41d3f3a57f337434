#!/usr/bin/env python3
"""The crush parameters of the Pioneer car (specs/scenarios/pioneer_wagon.toml)
and what a rigid-plastic crush predicts for them: the short calculation the
scenario's values come from. Plain Python, no packages.

Each input is marked with where it comes from: *source* (a document), *spec*
(specs/pioneer_wagon.lpm), *estimate* (no source at hand; the reasoning is
given) or *derived* (computed here from the others).

The closed form it predicts with: a rigid mass ``m`` at speed ``v`` stopped
by a constant force ``F`` travels ``C = m v^2 / (2 F)`` in ``t = m v / F``
and dissipates all of ``m v^2 / 2`` (nothing comes back). The chain's
elastic parts (the wall contact and the springs below their yield) store
some energy at the yield force; that energy is what can come back as
rebound, which sets the size of the rebound and the tolerance of the
comparison.

Run from the repository root: ``python3 tests/reference/pioneer_crush.py``.
sim/tests/pioneer.rs holds the run against the figures printed here.
"""

import math

LBF = 4.4482216152605  # N per pound-force (exact by definition)
MPH = 0.44704  # m/s per mile an hour (exact)

# --- Inputs -----------------------------------------------------------------
# *spec*: the seven masses of the chain (the railway-impact-simulator's
# Pioneer / ICE-1 lumping, 40 t in all; the test car's weight is not at hand).
MASSES = [4e3, 10e3, 4e3, 4e3, 4e3, 10e3, 4e3]
# *source*: the test speed, 35 mph (FRA single passenger rail car impact
# test, 16 November 1999).
V0 = 35 * MPH
# *source*: the static end-load (buff) requirement the car was built to and
# 49 CFR 238.203 still states, 800 000 lbf at the buffer beam without
# permanent deformation.
END_LOAD = 800_000 * LBF
# *estimate*: the load at which the body's structure yields. It must carry
# the end load without permanent set, so it yields above it; we take a
# quarter more (1 000 000 lbf). The same for all six springs: the end load
# passes through every cross-section of the body, each designed to it.
YIELD_FACTOR = 1.25
# *estimate*: the yield strain of the body's steel, about 0.2 % (a yield
# stress of 350-500 MPa over E = 200 GPa).
YIELD_STRAIN = 0.002
# *source*: where the peer lumps the seven masses along the car
# (railway-impact-simulator's Pioneer / ICE-1 case, as
# benches/peer/railway/pioneer_peer.json records it: x_init [m]); the six
# springs span the gaps between them.
POSITIONS = [0.0, 3.0, 6.5, 10.0, 13.5, 17.0, 20.0]
SEGMENTS = len(POSITIONS) - 1

# --- Derived parameters -----------------------------------------------------
M = sum(MASSES)
F_Y = YIELD_FACTOR * END_LOAD  # yield force of each spring [N]
SEGMENT = (POSITIONS[-1] - POSITIONS[0]) / SEGMENTS  # mean length [m]
# The deflection at which a segment yields: its steel at the yield strain
# over the segment's length (the whole segment stressed alike).
U_Y = round(YIELD_STRAIN * SEGMENT, 4)  # [m], rounded to 0.1 mm
K_E = F_Y / U_Y  # elastic stiffness of a segment [N/m]
# The wall is rigid: its contact spring is a penalty, taken as stiff as a
# segment of the car (it then stores no more than one segment does at the
# same force, and its penetration at the yield force is U_Y).
K_WALL = K_E


def predictions():
    """What the rigid-plastic crush and the elastic parts predict."""
    energy = 0.5 * M * V0**2
    crush = M * V0**2 / (2 * F_Y)  # the car's centre of mass, since first contact
    stop = M * V0 / F_Y
    # Quasi-statically, while spring 1 yields, the car behind it decelerates
    # as one body at F_Y over its mass; spring i carries the deceleration of
    # the masses behind it, and the wall that of the whole car.
    behind = [sum(MASSES[i + 1 :]) for i in range(SEGMENTS)]
    a = F_Y / behind[0]
    spring_forces = [a * b for b in behind]
    wall_force = a * M
    # Energy stored elastically at those forces: the wall as a linear
    # spring, each Bouc-Wen spring F_y u_y z^2 / 2 with z = F / F_y.
    stored_wall = wall_force**2 / (2 * K_WALL)
    stored_springs = sum(F_Y * U_Y * (f / F_Y) ** 2 / 2 for f in spring_forces)
    stored = stored_wall + stored_springs
    return {
        "impact energy [J]": energy,
        "yield force [N]": F_Y,
        "yield deflection [m]": U_Y,
        "segment stiffness [N/m]": K_E,
        "wall stiffness [N/m]": K_WALL,
        "rigid-plastic crush [m]": crush,
        "rigid-plastic time to stop [s]": stop,
        "mean deceleration [g]": F_Y / M / 9.80665,
        "wall force while spring 1 yields [N]": wall_force,
        "stored elastically at the yield force [J]": stored,
        "stored share": stored / energy,
        "dissipated share if all of it comes back": 1 - stored / energy,
        "restitution if all of it comes back": math.sqrt(stored / energy),
    }


if __name__ == "__main__":
    for name, value in predictions().items():
        print(f"{name:45} {value:.6g}")
