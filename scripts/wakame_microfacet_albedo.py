#!/usr/bin/env python3
"""Directional albedo of Wakame's `microfacet` BRDF by numerical quadrature, for the Student
t-test in tests/tests/bsdf_wakame.rs.

Written from the assignment's formula (seed 004), independently of Tessera's code:
  f(wi, wo) = kd / pi + ks D(h) F(h.wi) G1(wi, h) G1(wo, h) / (4 cos_i cos_o),  ks = 1 - max(kd)
with the Beckmann D(h) = exp(-tan^2 th / a^2) / (pi a^2 cos^4 th), the unpolarised dielectric
Fresnel reflectance F (eta_e -> eta_i), and the rational Smith approximation
  G1(v, h) = chi(v.h / v.n) * [(3.535 b + 2.181 b^2) / (1 + 2.276 b + 2.577 b^2) if b < 1.6 else 1],
  b = 1 / (a tan th_v).

The albedo is A(wi) = integral over the hemisphere of f cos_o dwo = kd + ks S(wi), where the
specular part S is integrated over half vectors h (dwo = 4 (h.wo) dwh, so the integrand
becomes D(h) F G (h.wi) / cos_i). S is computed two ways, and both must agree:
  1. tensor Gauss-Legendre in (theta_h, phi_h) after the substitution tan th_h = a t,
     t in [0, 6] (the Beckmann density has decayed by e^-36 there), 800 x 800 nodes (the
     difference to 400 x 400 is printed as a convergence check);
  2. for the wider lobes (alpha >= 0.3), a brute-force midpoint rule over wo in
     (cos th_o, phi_o), 4000 x 4000 cells.
Prints S for each (alpha, eta, theta_i) of the test; the test adds kd itself.
"""
import numpy as np

CASES_ALPHA = [0.1, 0.3, 0.6]
ETA_INT, ETA_EXT = 1.5046, 1.000277
THETAS = [0.0, 30.0, 60.0, 80.0]


def fresnel(cos_i, eta_e, eta_i):
    """Unpolarised Fresnel reflectance for light arriving from the eta_e side (cos_i > 0)."""
    eta = eta_e / eta_i
    sin_t2 = eta * eta * (1.0 - cos_i * cos_i)
    cos_t = np.sqrt(np.maximum(0.0, 1.0 - sin_t2))
    rs = (eta_e * cos_i - eta_i * cos_t) / (eta_e * cos_i + eta_i * cos_t)
    rp = (eta_i * cos_i - eta_e * cos_t) / (eta_i * cos_i + eta_e * cos_t)
    return np.where(sin_t2 >= 1.0, 1.0, 0.5 * (rs * rs + rp * rp))


def beckmann_d(cos_h, a):
    c2 = cos_h * cos_h
    tan2 = (1.0 - c2) / c2
    return np.exp(-tan2 / (a * a)) / (np.pi * a * a * c2 * c2)


def g1(v, h, a):
    """v, h: arrays of shape (..., 3)."""
    vz = v[..., 2]
    vh = np.sum(v * h, axis=-1)
    tan_t = np.sqrt(np.maximum(0.0, 1.0 - vz * vz)) / np.abs(vz)
    with np.errstate(divide="ignore", invalid="ignore"):
        b = 1.0 / (a * tan_t)
        r = np.where(b < 1.6, (3.535 * b + 2.181 * b * b) / (1.0 + 2.276 * b + 2.577 * b * b), 1.0)
    r = np.where(np.isfinite(b), r, 1.0)
    return np.where(vh / vz > 0.0, r, 0.0)


def gauss_legendre(n, lo, hi):
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (hi - lo) * x + 0.5 * (hi + lo), 0.5 * (hi - lo) * w


def spec_half_vector(theta_i, a, n=800):
    wi = np.array([np.sin(theta_i), 0.0, np.cos(theta_i)])
    t, wt = gauss_legendre(n, 0.0, 6.0)
    p, wp = gauss_legendre(n, 0.0, 2.0 * np.pi)
    T, P = np.meshgrid(t, p, indexing="ij")
    W = np.outer(wt, wp)
    th = np.arctan(a * T)
    # dw_h = sin th dth dphi, dth = a / (1 + a^2 t^2) dt
    jac = np.sin(th) * a / (1.0 + (a * T) ** 2)
    h = np.stack([np.sin(th) * np.cos(P), np.sin(th) * np.sin(P), np.cos(th)], axis=-1)
    hi = h @ wi
    wo = 2.0 * hi[..., None] * h - wi
    ok = (hi > 0) & (wo[..., 2] > 0)
    val = beckmann_d(h[..., 2], a) * fresnel(np.abs(hi), ETA_EXT, ETA_INT) \
        * g1(np.broadcast_to(wi, h.shape), h, a) * g1(wo, h, a) * hi / wi[2]
    return float(np.sum(np.where(ok, val, 0.0) * jac * W))


def spec_brute(theta_i, a, n=4000):
    wi = np.array([np.sin(theta_i), 0.0, np.cos(theta_i)])
    z = (np.arange(n) + 0.5) / n
    phi = 2.0 * np.pi * (np.arange(n) + 0.5) / n
    total = 0.0
    for zc in np.array_split(z, 20):
        Z, P = np.meshgrid(zc, phi, indexing="ij")
        r = np.sqrt(1.0 - Z * Z)
        wo = np.stack([r * np.cos(P), r * np.sin(P), Z], axis=-1)
        hv = wo + wi
        h = hv / np.linalg.norm(hv, axis=-1, keepdims=True)
        hi = h @ wi
        val = beckmann_d(h[..., 2], a) * fresnel(hi, ETA_EXT, ETA_INT) \
            * g1(np.broadcast_to(wi, wo.shape), h, a) * g1(wo, h, a) / (4.0 * wi[2])
        total += float(np.sum(val))
    return total * (2.0 * np.pi / n) / n


def main():
    for a in CASES_ALPHA:
        for deg in THETAS:
            th = np.radians(deg)
            s1 = spec_half_vector(th, a)
            line = f"alpha {a} theta_i {deg:4.1f}: S = {s1:.7f}"
            line += f"  (half the nodes: diff {s1 - spec_half_vector(th, a, 400):+.1e})"
            if a >= 0.3:  # the brute-force grid resolves the wider lobes only
                s2 = spec_brute(th, a)
                line += f"  (brute force {s2:.7f}, diff {s1 - s2:+.1e})"
            print(line)


if __name__ == "__main__":
    main()
