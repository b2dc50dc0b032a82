#!/usr/bin/env python3
"""Prints the RGB colours Mitsuba 3 (scalar_rgb) gives <spectrum> values in each context, for
scene/src/xml/tests/spectra.rs, which checks Tessera's conversion against them.

Each case is loaded through Mitsuba's own XML parser and plugin, and the colour read back
from the texture it built (mi.traverse), so the numbers include Mitsuba's choice of
conversion (D65 weighting, clamping) for reflectances, emitters and unbounded parameters.

    bash scripts/install_mitsuba.sh && python3 scripts/mitsuba_spectrum_rgb.py
"""
import mitsuba as mi

mi.set_variant("scalar_rgb")

REFLECTANCE = "400:0.092, 450:0.104, 500:0.285, 550:0.4, 600:0.16, 650:0.118, 700:0.159"
SATURATED = "400:0, 560:0, 580:1, 700:1"
LIGHT = "400:0, 500:8, 600:15.6, 700:18.4"
ETA = "300:1.8, 400:1.65, 500:0.9, 600:0.2, 700:0.16, 800:0.18"
K = "300:1.92, 400:1.95, 500:1.95, 600:2.97, 700:3.8, 800:5.12"

CASES = [
    # (constant name, plugin element, spectrum element(s), parameter read back)
    ("REFLECTANCE", '<bsdf version="3.0.0" type="diffuse">',
     f'<spectrum name="reflectance" value="{REFLECTANCE}"/>', "reflectance.value"),
    ("SATURATED", '<bsdf version="3.0.0" type="diffuse">',
     f'<spectrum name="reflectance" value="{SATURATED}"/>', "reflectance.value"),
    ("LIGHT", '<emitter version="3.0.0" type="point">',
     f'<spectrum name="intensity" value="{LIGHT}"/>', "intensity.value"),
    ("FLAT_LIGHT", '<emitter version="3.0.0" type="point">',
     '<spectrum name="intensity" value="2"/>', "intensity.value"),
    ("ETA", '<bsdf version="3.0.0" type="conductor">',
     f'<spectrum name="eta" value="{ETA}"/><spectrum name="k" value="{K}"/>', "eta.value"),
    ("K", '<bsdf version="3.0.0" type="conductor">',
     f'<spectrum name="eta" value="{ETA}"/><spectrum name="k" value="{K}"/>', "k.value"),
]

for name, open_tag, body, key in CASES:
    close_tag = "</" + open_tag[1:].split()[0] + ">"
    obj = mi.load_string(open_tag + body + close_tag)
    c = mi.traverse(obj)[key]
    vals = ", ".join(repr(float(f"{float(x):.9g}")) for x in (c[0], c[1], c[2]))
    print(f"const {name}: [f64; 3] = [{vals}];")
