"""Reference for sim/src/components/bouc_wen.rs: the area of a Bouc-Wen loop.

A Bouc-Wen spring (F = a k u + (1 - a) Fy z, k = Fy/uy,
uy z' = A u' - beta |u'| |z|^(n-1) z - gamma u' |z|^n) is driven through
u(t) = U sin(w t) from z = 0. The area of its loop in the fourth cycle,
the integral of F du = F u' dt over [3T, 4T], is computed with SciPy
(solve_ivp, the area integrated as an extra state), independently of the
simulator and of its formula for the dissipated power. The fourth cycle's
loop is closed to the printed change of z.

Run: python tests/reference/bouc_wen_loop.py
"""
import numpy as np
from scipy.integrate import solve_ivp

FY, UY, A_RATIO, A, BETA, GAMMA, N = 1000.0, 0.01, 0.1, 1.0, 0.5, 0.5, 2.0
U, W = 0.02, 20.0
K = FY / UY
T = 2 * np.pi / W


def rhs(t, y):
    z = y[0]
    u, du = U * np.sin(W * t), U * W * np.cos(W * t)
    zn = abs(z) ** N
    dz = (A * du - BETA * abs(du) * np.sign(z) * zn - GAMMA * du * zn) / UY
    force = A_RATIO * K * u + (1 - A_RATIO) * FY * z
    return [dz, force * du]


def state_at(t):
    sol = solve_ivp(rhs, (0, t), [0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-14)
    return sol.y[:, -1]


z3, area3 = state_at(3 * T)
z4, area4 = state_at(4 * T)
print(f"loop area of the 4th cycle: {area4 - area3:.12e} J")
print(f"z at 3T, 4T: {z3:.12e} {z4:.12e}")
