#!/usr/bin/env python3
"""Writes Nori-style BSDF test files for `tessera test`, with references computed by Mitsuba 3.

Usage: scripts/make_bsdf_ttests.py [NAME ...]   (default: every entry of FILES)

For each entry of FILES the script writes, in tests/bsdf_tests/ (tests/bsdf_tests/pending/ for
entries marked pending, i.e. BSDFs Tessera does not implement yet):

- ttest_NAME.xml: <test type="ttest"> with the entry's <bsdf>s, its incident `angles` and one
  reference per bsdf and angle (bsdf-major, Nori's order): the luminance (Nori's weights) of the
  directional albedo, i.e. of the expected sampled weight E[f |cos| / pdf];
- chi2_NAME.xml: <test type="chi2test"> with the same <bsdf>s (no references needed).

References are computed independently of Tessera, with Mitsuba 3 (scalar_rgb) at
uv = (0.5, 0.5) and wi = (sin t, 0, cos t) for angle t:

    albedo = integral over the sphere of bsdf.eval (cosine included)  +  delta part.

The integral is a deterministic cubature, per hemisphere, in (theta, phi) about +z / -z: nested
globally adaptive Gauss-Kronrod (7/15) rules, phi inside theta, started from panels broken at
the integrand's maximum (found on a coarse grid) so that glossy peaks are not missed; jumps and
kinks (the edge of a refracted lobe, total internal reflection, Mitsuba's tabulated Fresnel
integrals) are bisected down to f32 round-off. The sum of |Kronrod - Gauss| is the error
estimate; the script stops if it could shift a t-test statistic by more than T_SHIFT.
The delta part is the expectation of the weights of Mitsuba's delta samples over the component
choice u1: u1 is scanned on a grid, the switches between components are located by bisection,
and each delta run contributes its length times its (constant) weight.
As a check, the mean of 20000 of Mitsuba's own sampled weights must agree with the reference
(within 5 standard errors); the file's comments show both.

Mitsuba 3.9.1's blendbsdf reports, for a sampled delta component, the delta probability plus
the smooth density as its pdf, so its delta sample weights are not the blend's albedo: a blend
of a diffuse and a smooth conductor came out 5% low (measured against the closed form
0.4 diffuse + 0.6 Fresnel). The blendbsdf entry therefore blends smooth models only; blends
with delta parts are tested by chi-square here and in tests/tests/bsdf_chalmers.rs.

Adding a Mitsuba BSDF is one entry in FILES: the <bsdf> elements are written in Mitsuba 3 syntax
and read by both Mitsuba and Tessera.
"""
import heapq
import math
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np
import mitsuba as mi

mi.set_variant("scalar_rgb")

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "bsdf_tests")
LUM = np.array([0.212671, 0.715160, 0.072169])
UV = (0.5, 0.5)
# Accuracy demanded of a reference: its cubature error estimate may shift the t statistic of
# the test by at most T_SHIFT (the standard error of the test's mean is estimated from 20000 of
# Mitsuba's sampled weights), and never needs to be below F32_LEVEL (deterministic weights, e.g.
# diffuse, are compared at f32 rounding; they integrate to about 1e-8 here).
T_SHIFT = 0.05
F32_LEVEL = 1e-7


class Entry:
    """One pair of test files: a name, the <bsdf> elements, the t-test's incident angles."""

    def __init__(self, name, bsdfs, angles, pending=False, samples=100000, chi2_resolution=10,
                 both_sides=False):
        self.name = name
        self.bsdfs = bsdfs
        self.angles = angles
        self.pending = pending
        self.samples = samples
        self.chi2_resolution = chi2_resolution
        self.both_sides = both_sides


def rgb(name, v):
    return f'<rgb name="{name}" value="{v}"/>'


FRONT = [0, 30, 60, 85]
BOTH = [0, 30, 60, 85, 100, 135, 170]

FILES = [
    Entry("diffuse", [
        '<bsdf type="diffuse">' + rgb("reflectance", "0.7, 0.5, 0.3") + '</bsdf>',
        '<bsdf type="diffuse"/>',
        '<bsdf type="diffuse">' + rgb("reflectance", "0.05, 0.95, 1") + '</bsdf>',
    ], FRONT + [120], pending=False, samples=10000),
    Entry("twosided", [
        '<bsdf type="twosided"><bsdf type="diffuse">' + rgb("reflectance", "0.7, 0.5, 0.3")
        + '</bsdf></bsdf>',
        '<bsdf type="twosided"><bsdf type="diffuse">' + rgb("reflectance", "0.2, 0.4, 0.8")
        + '</bsdf><bsdf type="diffuse">' + rgb("reflectance", "0.9, 0.6, 0.1")
        + '</bsdf></bsdf>',
    ], BOTH, pending=False, samples=10000, both_sides=True),
    Entry("roughconductor", [
        '<bsdf type="roughconductor"><string name="distribution" value="beckmann"/>'
        '<float name="alpha" value="0.1"/>' + rgb("eta", "0.2, 0.9, 1.1")
        + rgb("k", "3.9, 2.4, 2.2") + '</bsdf>',
        '<bsdf type="roughconductor"><string name="distribution" value="ggx"/>'
        '<float name="alpha" value="0.4"/>' + rgb("eta", "0.27, 0.68, 1.3")
        + rgb("k", "3.6, 2.6, 2.3") + '</bsdf>',
        '<bsdf type="roughconductor"><string name="distribution" value="ggx"/>'
        '<float name="alpha_u" value="0.05"/><float name="alpha_v" value="0.3"/>'
        + rgb("eta", "1.5, 1.0, 0.6") + rgb("k", "2.0, 3.0, 4.0") + '</bsdf>',
    ], FRONT, chi2_resolution=20),
    Entry("roughplastic", [
        '<bsdf type="roughplastic"><string name="distribution" value="beckmann"/>'
        '<float name="alpha" value="0.1"/>' + rgb("diffuse_reflectance", "0.7, 0.5, 0.3")
        + '<float name="int_ior" value="1.5"/></bsdf>',
        '<bsdf type="roughplastic"><string name="distribution" value="ggx"/>'
        '<float name="alpha" value="0.3"/>' + rgb("diffuse_reflectance", "0.2, 0.6, 0.9")
        + '<float name="int_ior" value="1.9"/><boolean name="nonlinear" value="true"/></bsdf>',
    ], FRONT, chi2_resolution=20),
    Entry("roughdielectric", [
        '<bsdf type="roughdielectric"><string name="distribution" value="beckmann"/>'
        '<float name="alpha" value="0.1"/><float name="int_ior" value="1.5"/></bsdf>',
        '<bsdf type="roughdielectric"><string name="distribution" value="ggx"/>'
        '<float name="alpha" value="0.3"/><float name="int_ior" value="1.33"/>'
        '<float name="ext_ior" value="1.0"/></bsdf>',
    ], [0, 30, 60, 85, 150, 170], chi2_resolution=20, both_sides=True),
    Entry("plastic", [
        '<bsdf type="plastic">' + rgb("diffuse_reflectance", "0.7, 0.5, 0.3")
        + '<float name="int_ior" value="1.5"/></bsdf>',
        '<bsdf type="plastic">' + rgb("diffuse_reflectance", "0.2, 0.6, 0.9")
        + '<float name="int_ior" value="1.9"/><boolean name="nonlinear" value="true"/></bsdf>',
    ], FRONT),
    Entry("conductor", [
        '<bsdf type="conductor">' + rgb("eta", "0.2, 0.9, 1.1") + rgb("k", "3.9, 2.4, 2.2")
        + '</bsdf>',
        '<bsdf type="conductor">' + rgb("eta", "1.5, 1.0, 0.6") + rgb("k", "2.0, 3.0, 4.0")
        + rgb("specular_reflectance", "0.9, 0.8, 0.7") + '</bsdf>',
    ], FRONT),
    Entry("dielectric", [
        '<bsdf type="dielectric"><float name="int_ior" value="1.5"/></bsdf>',
        '<bsdf type="dielectric"><float name="int_ior" value="1.33"/>'
        '<float name="ext_ior" value="1.0"/></bsdf>',
    ], [0, 30, 60, 85, 120, 150, 170], both_sides=True),
    Entry("blendbsdf", [
        '<bsdf type="blendbsdf"><float name="weight" value="0.3"/>'
        '<bsdf type="diffuse">' + rgb("reflectance", "0.7, 0.5, 0.3") + '</bsdf>'
        '<bsdf type="roughconductor"><float name="alpha" value="0.2"/>'
        + rgb("eta", "0.2, 0.9, 1.1") + rgb("k", "3.9, 2.4, 2.2") + '</bsdf></bsdf>',
        '<bsdf type="blendbsdf"><float name="weight" value="0.6"/>'
        '<bsdf type="diffuse">' + rgb("reflectance", "0.2, 0.4, 0.8") + '</bsdf>'
        '<bsdf type="roughplastic"><string name="distribution" value="ggx"/>'
        '<float name="alpha" value="0.15"/>' + rgb("diffuse_reflectance", "0.6, 0.3, 0.1")
        + '</bsdf></bsdf>',
    ], FRONT, chi2_resolution=20),
]


def load(snippet):
    node = ET.fromstring(snippet)
    node.set("version", "3.0.0")
    return mi.load_string(ET.tostring(node, encoding="unicode"))


def interaction(wi):
    si = mi.SurfaceInteraction3f()
    si.wi = mi.Vector3f(wi)
    si.uv = mi.Point2f(UV)
    si.n = mi.Normal3f(0, 0, 1)
    si.sh_frame = mi.Frame3f(mi.Vector3f(0, 0, 1))
    return si


# Gauss-Kronrod 7/15 nodes on [-1, 1] (positive half, descending to 0) and weights.
XGK = [0.991455371120812639, 0.949107912342758525, 0.864864423359769073, 0.741531185599394440,
       0.586087235467691130, 0.405845151377397167, 0.207784955007898468, 0.0]
WGK = [0.022935322010529225, 0.063092092629978553, 0.104790010322250184, 0.140653259715525919,
       0.169004726639267903, 0.190350578064785410, 0.204432940075298892, 0.209482141084727828]
WG = [0.129484966168869693, 0.279705391489276668, 0.381830050505118945, 0.417959183673469388]
REL_TOL = 5e-8  # Mitsuba evaluates in f32: |K - G| does not go much below 1e-7 relative


def gk15(f, a, b):
    """(Kronrod 15-point value, |Kronrod - Gauss 7|) of f on [a, b]; f returns a vector whose
    first three entries (RGB) decide the error."""
    c, h = 0.5 * (a + b), 0.5 * (b - a)
    fc = f(c)
    k, g = WGK[7] * fc, WG[3] * fc
    for j in range(7):
        x = h * XGK[j]
        pair = f(c - x) + f(c + x)
        k = k + WGK[j] * pair
        if j % 2 == 1:
            g = g + WG[j // 2] * pair
    return k * h, float(np.abs((k - g)[:3]).max()) * h


def adaptive(f, breaks, tol, rel_tol=REL_TOL, max_panels=400):
    """Integral of f over [breaks[0], breaks[-1]], globally adaptive: starting from the panels
    between the breakpoints, the panel with the largest |K - G| is bisected until the sum of
    the panels' |K - G| is at most `tol + rel_tol * |value|` or there are `max_panels` panels (a
    jump of the integrand, or a fuzzy f32 edge, then costs a bounded effort and shows in the
    estimate). Returns (value, sum of the panels' |K - G|)."""
    heap = []
    for a, b in zip(breaks[:-1], breaks[1:]):
        if b > a:
            v, e = gk15(f, a, b)
            heapq.heappush(heap, (-e, a, b, v))
    err = sum(-h[0] for h in heap)
    value = sum(h[3] for h in heap)
    while err > tol + rel_tol * float(np.abs(value[:3]).max()) and len(heap) < max_panels:
        e0, a, b, v0 = heapq.heappop(heap)
        err += e0
        m = 0.5 * (a + b)
        value = value - v0
        for lo, hi in ((a, m), (m, b)):
            v, e = gk15(f, lo, hi)
            heapq.heappush(heap, (-e, lo, hi, v))
            err, value = err + e, value + v
    return sum(h[3] for h in heap), sum(-h[0] for h in heap)


def direction(theta, phi, side):
    s = math.sin(theta)
    return (s * math.cos(phi), s * math.sin(phi), side * math.cos(theta))


def hemisphere_integral(bsdf, ctx, si, side, tol=1e-9):
    """Integral of eval over one hemisphere (side = +1 upper, -1 lower), per channel, and its
    error estimate: nested adaptive Gauss-Kronrod, phi inside theta. Jumps of the integrand
    (the edge of a refracted lobe) are thereby bracketed to round-off from both directions."""
    def f(theta, phi):
        v = bsdf.eval(ctx, si, mi.Vector3f(direction(theta, phi, side)))
        return np.array([v[0], v[1], v[2]], dtype=np.float64)

    # The integrand's maximum on a coarse grid (its sin(theta) Jacobian included): initial
    # breakpoints there, so that narrow peaks are not missed.
    best, tp, pp = -1.0, 0.0, math.pi
    for i in range(60):
        t = (i + 0.5) / 60 * (math.pi / 2)
        for j in range(120):
            p = (j + 0.5) / 120 * 2 * math.pi
            v = float(LUM @ f(t, p)) * max(math.sin(t), 1e-3)
            if v > best:
                best, tp, pp = v, t, p
    if best <= 0.0:
        return np.zeros(3), 0.0
    phis = sorted({pp - math.pi + k * math.pi / 4 for k in range(9)} | {pp - 0.05, pp + 0.05})

    def row(theta):
        # phi integral at this theta; the 4th entry carries its error estimate outward.
        v, e = adaptive(lambda p: f(theta, p), phis, tol)
        return math.sin(theta) * np.append(v, e)

    thetas = sorted({k * math.pi / 16 for k in range(9)} | {tp, max(tp - 0.05, 0.0),
                                                            min(tp + 0.05, math.pi / 2)})
    v, e = adaptive(row, thetas, tol)
    return v[:3], e + float(v[3])


def delta_albedo(bsdf, si):
    """E[weight of delta samples] over u1: runs of u1 giving the same delta direction have
    constant weight; their boundaries are found by bisection."""
    ctx = mi.BSDFContext()
    u2 = mi.Point2f(0.37, 0.61)

    def probe(u1):
        bs, w = bsdf.sample(ctx, si, float(u1), u2)
        if not mi.has_flag(bs.sampled_type, mi.BSDFFlags.Delta) or not (bs.pdf > 0):
            return None, None
        wo = bs.wo
        key = (round(wo[0], 4), round(wo[1], 4), round(wo[2], 4))
        return key, np.array([w[0], w[1], w[2]], dtype=np.float64)

    n = 512
    grid = [(k + 0.5) / n for k in range(n)]
    keys = [probe(u)[0] for u in grid]
    edges = [0.0]
    for k in range(n - 1):
        if keys[k] != keys[k + 1]:
            a, b = grid[k], grid[k + 1]
            for _ in range(60):
                m = 0.5 * (a + b)
                if probe(m)[0] == keys[k]:
                    a = m
                else:
                    b = m
            edges.append(0.5 * (a + b))
    edges.append(1.0)
    total = np.zeros(3)
    for a, b in zip(edges[:-1], edges[1:]):
        key, w = probe(0.5 * (a + b))
        if key is None:
            continue
        # The weight must be constant over the run.
        for u in (a + 1e-6 * (b - a), b - 1e-6 * (b - a)):
            k2, w2 = probe(u)
            if k2 != key or np.abs(w2 - w).max() > 1e-5 * max(1.0, np.abs(w).max()):
                sys.exit(f"delta weight varies over u1 in [{a}, {b}]: {w} vs {w2}")
        total += (b - a) * w
    return total


def albedo(bsdf, angle):
    t = math.radians(angle)
    si = interaction((math.sin(t), 0.0, math.cos(t)))
    ctx = mi.BSDFContext()
    (up, e_up), (down, e_down) = (hemisphere_integral(bsdf, ctx, si, s) for s in (1, -1))
    smooth, err = up + down, e_up + e_down
    return smooth + delta_albedo(bsdf, si), err, weight_stats(bsdf, si)


def weight_stats(bsdf, si, n=20000):
    """Mean and standard deviation of the luminance of Mitsuba's sampled weight (a fixed random
    set of samples): Mitsuba's own Monte Carlo estimate of the albedo, to check the cubature."""
    ctx = mi.BSDFContext()
    rng = np.random.default_rng(1)
    u = rng.random((n, 3))
    lum = np.empty(n)
    for k in range(n):
        bs, w = bsdf.sample(ctx, si, float(u[k, 0]), mi.Point2f(float(u[k, 1]), float(u[k, 2])))
        lum[k] = float(LUM @ np.array([w[0], w[1], w[2]])) if bs.pdf > 0 else 0.0
    return float(lum.mean()), float(lum.std())


def header(kind, entry):
    return (f'<?xml version="1.0" encoding="utf-8"?>\n'
            f"<!-- Written by scripts/make_bsdf_ttests.py ({kind}, entry \"{entry.name}\")."
            f" Do not edit: change the script. -->")


def write_ttest(entry, path):
    refs, notes = [], []
    for b, snippet in enumerate(entry.bsdfs):
        bsdf = load(snippet)
        for angle in entry.angles:
            a, err, (mc_mean, std) = albedo(bsdf, angle)
            ref = float(LUM @ a)
            # Mitsuba's sampling must agree with the cubature (|z| < 5 by chance for 1e2 cases;
            # a deterministic weight within f32 rounding).
            se = std / math.sqrt(20000)
            if abs(mc_mean - ref) > 5 * se + 1e-6 * abs(ref):
                sys.exit(f"{entry.name} bsdf {b + 1} angle {angle}: Mitsuba's sampled weights "
                         f"average {mc_mean:.7f} +- {se:.1e}, the cubature gives {ref:.7f}")
            tolerance = max(T_SHIFT * std / math.sqrt(entry.samples), F32_LEVEL)
            if err > tolerance:
                sys.exit(f"{entry.name} bsdf {b + 1} angle {angle}: cubature error {err:.2e} "
                         f"above {tolerance:.2e}")
            refs.append(ref)
            notes.append(f"bsdf {b + 1}, angle {angle:g}: albedo rgb "
                         f"({a[0]:.9f}, {a[1]:.9f}, {a[2]:.9f}), cubature error {err:.1e}; "
                         f"Mitsuba's sampling: {mc_mean:.9f} +- {se:.1e}")
            print(f"  {notes[-1]}", flush=True)
    lines = [header("Mitsuba " + mi.__version__ + " scalar_rgb references, uv = 0.5, 0.5",
                    entry), '<test type="ttest">']
    lines += [f"  <!-- {n} -->" for n in notes]
    lines.append(f'  <string name="angles" value="{", ".join(f"{a:g}" for a in entry.angles)}"/>')
    lines.append(f'  <string name="references" value="{", ".join(f"{r:.10g}" for r in refs)}"/>')
    lines.append(f'  <integer name="sampleCount" value="{entry.samples}"/>')
    lines += [f"  {s}" for s in entry.bsdfs]
    lines.append("</test>")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def write_chi2(entry, path):
    lines = [header("chi-square of sample against pdf", entry), '<test type="chi2test">']
    lines.append(f'  <integer name="resolution" value="{entry.chi2_resolution}"/>')
    lines.append('  <integer name="testCount" value="5"/>')
    if entry.both_sides:
        lines.append('  <boolean name="bothSides" value="true"/>')
    lines += [f"  {s}" for s in entry.bsdfs]
    lines.append("</test>")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    names = sys.argv[1:]
    known = {e.name for e in FILES}
    for n in names:
        if n not in known:
            sys.exit(f"unknown entry {n} (known: {', '.join(sorted(known))})")
    for entry in FILES:
        if names and entry.name not in names:
            continue
        folder = os.path.join(ROOT, "pending") if entry.pending else ROOT
        os.makedirs(folder, exist_ok=True)
        for kind in ("ttest", "chi2"):
            stale = os.path.join(ROOT if entry.pending else os.path.join(ROOT, "pending"),
                                 f"{kind}_{entry.name}.xml")
            if os.path.exists(stale):
                os.remove(stale)
        print(f"{entry.name}:", flush=True)
        write_ttest(entry, os.path.join(folder, f"ttest_{entry.name}.xml"))
        write_chi2(entry, os.path.join(folder, f"chi2_{entry.name}.xml"))


if __name__ == "__main__":
    main()
