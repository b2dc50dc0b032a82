#!/usr/bin/env python3
"""Directional albedo of Chalmers' Blinn-Phong materials by numerical quadrature.

Usage: scripts/blinnphong_albedo.py            (prints the references used by
                                                tests/tests/bsdf_chalmers.rs)
       scripts/blinnphong_albedo.py --energy   (scans white parameters for albedo > 1)

Independent of Tessera's code: written from the formulas of the Chalmers tutorial (seed 003),
in double precision with numpy. With h the half vector of (wi, wo), s the shininess:
  F = r0 + (1 - r0)(1 - h.wi)^5,  D = (s + 2)/(2 pi) (n.h)^s,
  G = min(1, 2 (n.h)(n.wo)/(wo.h), 2 (n.h)(n.wi)/(wo.h)),
  f = F D G / (4 (n.wi)(n.wo)) + T rho / pi         (blinnphong over a diffuse base rho),
  f = color F D G / (4 (n.wi)(n.wo))                (blinnphong_metal).
albedo(wi) = integral over the upper hemisphere of f cos(theta_o) d wo. The base's share T is
Tessera's (1 - F(n.wi))(1 - F(n.wo)) (Schlick at the macro normal, both crossings of the
coating); the tutorial's own choice, T = 1 - F(h.wi), is computed too by --energy, which shows
that it returns more energy than arrives at grazing incidence (up to 1.8 times).

The lobe term is integrated over half vectors (d wo = 4 (wo.h) d h) with the substitution
t = (n.h)^(s+1), which flattens D: the integrand becomes F G (wi.h)/(n.wi) (s+2)/(2 pi (s+1))
over t in [0, 1], phi in [0, 2 pi), restricted to wo above the surface. The base term is
integrated over wo directly. Both use Gauss-Legendre product rules (1000 x 2000 nodes for the
lobe); halving or doubling the rule changes the printed values by less than 1e-6.
"""
import sys

import numpy as np


def gauss(n, a, b):
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (b - a) * x + 0.5 * (b + a), 0.5 * (b - a) * w


def schlick(r0, c):
    return r0 + (1.0 - r0) * np.clip(1.0 - c, 0.0, 1.0) ** 5


def lobe_albedo(theta_deg, s, r0, n=1500):
    th = np.radians(theta_deg)
    wi = np.array([np.sin(th), 0.0, np.cos(th)])
    t, wt = gauss(n, 0.0, 1.0)
    ph, wp = gauss(2 * n, 0.0, 2.0 * np.pi)
    T, P = np.meshgrid(t, ph, indexing="ij")
    W = np.outer(wt, wp)
    mu = T ** (1.0 / (s + 1.0))
    sn = np.sqrt(np.maximum(0.0, 1.0 - mu * mu))
    h = np.stack([sn * np.cos(P), sn * np.sin(P), mu], axis=-1)
    ih = h @ wi
    wo = 2.0 * ih[..., None] * h - wi
    ok = (ih > 0.0) & (wo[..., 2] > 0.0)
    g = np.minimum(1.0, np.minimum(2.0 * mu * wo[..., 2] / ih, 2.0 * mu * wi[2] / ih))
    val = schlick(r0, ih) * g * ih / wi[2] * (s + 2.0) / (2.0 * np.pi * (s + 1.0))
    return float(np.sum(np.where(ok, val, 0.0) * W))


def base_albedo(theta_deg, r0, rho, n=600, tutorial=False):
    """Integral of T rho / pi cos(theta_o) over the hemisphere, where the base's weight T is
    Tessera's (1 - F(n.wi))(1 - F(n.wo)), or with `tutorial` the tutorial's 1 - F(h.wi)."""
    th = np.radians(theta_deg)
    wi = np.array([np.sin(th), 0.0, np.cos(th)])
    mu, wm = gauss(n, 0.0, 1.0)
    ph, wp = gauss(2 * n, 0.0, 2.0 * np.pi)
    M, P = np.meshgrid(mu, ph, indexing="ij")
    W = np.outer(wm, wp)
    sn = np.sqrt(1.0 - M * M)
    wo = np.stack([sn * np.cos(P), sn * np.sin(P), M], axis=-1)
    if tutorial:
        h = wo + wi
        h /= np.linalg.norm(h, axis=-1, keepdims=True)
        f = 1.0 - schlick(r0, h @ wi)
    else:
        f = (1.0 - schlick(r0, wi[2])) * (1.0 - schlick(r0, M))
    return float(np.sum(f * rho / np.pi * M * W))


def blinnphong(theta, s, r0, rho, n=1000, tutorial=False):
    a = lobe_albedo(theta, s, r0, n)
    return a + (base_albedo(theta, r0, rho, n // 2, tutorial) if rho > 0 else 0.0)


CASES = [
    # (name, theta_deg, s, r0, diffuse base rho (0: none), metal colour (None: dielectric))
    ("lobe s=1 r0=0.04", [0.0, 45.0, 75.0], 1.0, 0.04, 0.0),
    ("s=20 r0=0.5 over diffuse 0.8", [0.0, 40.0, 80.0], 20.0, 0.5, 0.8),
    ("s=200 r0=1", [10.0, 60.0, 85.0], 200.0, 1.0, 0.0),
    ("metal s=50 r0=0.3 (per unit colour)", [30.0, 70.0], 50.0, 0.3, 0.0),
]


def main():
    if "--energy" in sys.argv:
        # White diffuse base; the lobe alone is the r0 = 1 rows' first number... every row
        # prints Tessera's albedo, then the tutorial's (1 - F(h.wi)) variant's.
        worst = [(0.0, None), (0.0, None)]
        for s in [0.0, 1.0, 5.0, 25.0, 100.0, 1000.0, 1e4]:
            for r0 in [0.0, 0.04, 0.2, 0.5, 1.0]:
                for th in [0.0, 30.0, 45.0, 60.0, 70.0, 80.0, 85.0, 89.0]:
                    lobe = lobe_albedo(th, s, r0, 200)
                    a = [lobe + base_albedo(th, r0, 1.0, 100, t) for t in (False, True)]
                    for k in range(2):
                        if a[k] > worst[k][0]:
                            worst[k] = (a[k], (s, r0, th))
                    print(f"s={s:g} r0={r0:g} theta={th:g}: lobe {lobe:.6f}, "
                          f"tessera {a[0]:.6f}, tutorial {a[1]:.6f}")
        print("largest albedo, Tessera's base weighting:", worst[0])
        print("largest albedo, the tutorial's base weighting:", worst[1])
        return
    for name, thetas, s, r0, rho in CASES:
        for th in thetas:
            print(f"{name}, theta {th:g}: {blinnphong(th, s, r0, rho):.9f}")


if __name__ == "__main__":
    main()
