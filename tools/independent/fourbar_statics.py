#!/usr/bin/env python3
"""Independent check of the transient model's loading (used by test_mechanism_model).

Rigid-body statics of Tennant's four-bar (FORMULATION.md 8.1) at crank angle 0,
crank speed 150 rad/s, no angular acceleration: the inertia of the coupler and
rocker (distributed, translational only) is carried by the pins; the crank is a
cantilever clamped at A whose tip carries the pin force at B.  Prints the crank
root moment and curvature M/EI, which a quasi-static solution K q = F of the
flexible model must reproduce.  Needs numpy.
"""
from math import atan2, cos, sin, sqrt
import numpy as np

rho, area, e1, inertia = 2.536e-4, 0.25, 10.87e6, 0.25 / 12.0
w = 150.0
a, b, c = 5.0, 11.0, 10.5
B, D = np.array([a, 0.0]), np.array([10.0, 0.0])
dx = D - B
L = np.linalg.norm(dx)
ex, ey = dx / L, np.array([-dx[1], dx[0]]) / L
x = (b * b - c * c + L * L) / (2 * L)
C = B + x * ex + sqrt(b * b - x * x) * ey          # open branch
phic, phir = atan2(*(C - B)[::-1]), atan2(*(C - D)[::-1])
M = np.array([[-(C - B)[1], (C - D)[1]], [(C - B)[0], -(C - D)[0]]])
vB = np.array([-w * B[1], w * B[0]])
wc, wr = np.linalg.solve(M, -vB)
aB = -w * w * B
ac, ar = np.linalg.solve(M, -(aB - wc * wc * (C - B) + wr * wr * (C - D)))


def inertia_load(phi, om, al, a0, length, n=4000):
    """Resultant and moment (about the link's end 1) of -rho A a ds."""
    e, p = np.array([cos(phi), sin(phi)]), np.array([-sin(phi), cos(phi)])
    force, moment, ds = np.zeros(2), 0.0, length / n
    for i in range(n):
        r = (i + 0.5) * ds * e
        f = -rho * area * ds * (a0 + al * (i + 0.5) * ds * p - om * om * r)
        force += f
        moment += r[0] * f[1] - r[1] * f[0]
    return force, moment


Fc, Mc = inertia_load(phic, wc, ac, aB, b)
Fr, Mr = inertia_load(phir, wr, ar, np.zeros(2), c)
rC, rD = C - B, C - D
A = np.array([[1, 0, 1, 0], [0, 1, 0, 1], [0, 0, -rC[1], rC[0]], [0, 0, rD[1], -rD[0]]])
Bx, By, Cx, Cy = np.linalg.solve(A, [-Fc[0], -Fc[1], -Mc, -Mr])
root_moment = -By * a
print(f"crank root moment {root_moment:.8g} lb in, curvature {root_moment / (e1 * inertia):.8e} /in")
