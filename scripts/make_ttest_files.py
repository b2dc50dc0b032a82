#!/usr/bin/env python3
"""Writes tests/scenes/test-lambert.xml and tests/scenes/test-lights.xml: Nori-style scene t-test
files whose references are computed here, independently of Tessera, with numpy.

Each scene: a diffuse floor (albedo a) seen straight down through a tiny field of view at the
origin, lit by one emitter; max_depth 2 for path tracers, so the answer is direct light only:
- a rectangular area light (Mitsuba `rectangle`, scaled, rotated about x, translated): radiance
  a/pi * E with E from Lambert's polygon formula E = L/2 |sum theta_i n.unit(v_i x v_i+1)|;
- a point light of intensity I at height h: a I / (pi h^2);
- a closed emitting box seen from inside: 1/(1-a) for path tracers, 1+a for direct lighting.
test-lights.xml uses the same floor under the other light types:
- a spot light of intensity I at height h pointing down (the lit point inside the full beam):
  a I / (pi h^2);
- a directional light of irradiance E at angle t from the normal: a E cos(t) / pi;
- a distant disk (Nori's `distantdisk`, `thetaA`) of radiance L centred on the normal:
  a L sin^2(thetaA); tilted by `toWorld` so its centre is at angle t (cap above the horizon):
  a L sin^2(thetaA) cos(t);
- a constant environment of radiance L, and an `envmap` whose image is constant L
  (tests/scenes/const_env.exr, written here): a L.
References are luminances (Nori's weights), as Nori's ttest compares.
"""
import numpy as np

LUM = np.array([0.212671, 0.715160, 0.072169])


def rot_x(deg):
    t = np.radians(deg)
    c, s = np.cos(t), np.sin(t)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def lambert(x, n, verts, radiance):
    total = 0.0
    for i in range(len(verts)):
        a = verts[i] - x
        b = verts[(i + 1) % len(verts)] - x
        a, b = a / np.linalg.norm(a), b / np.linalg.norm(b)
        theta = np.arccos(np.clip(a @ b, -1, 1))
        g = np.cross(a, b)
        total += theta * (n @ (g / np.linalg.norm(g)))
    return 0.5 * radiance * abs(total)


CAMERA = """    <camera type="perspective">
      <transform name="toWorld"><lookat origin="0, 0, 0.01" target="0, 0, 0" up="0, 1, 0"/></transform>
      <float name="fov" value="1e-4"/>
      <integer name="width" value="1"/>
      <integer name="height" value="1"/>
    </camera>"""
FLOOR = """    <mesh type="rectangle">
      <transform name="toWorld"><scale value="100"/></transform>
      <bsdf type="diffuse"><color name="albedo" value="{a}"/></bsdf>
    </mesh>"""


def integrator(name):
    if name.startswith("path"):
        return f'    <integrator type="{name}"><integer name="maxDepth" value="2"/></integrator>'
    return f'    <integrator type="{name}"/>'


def main():
    scenes, refs = [], []
    albedo = np.array([0.7, 0.5, 0.3])
    a_text = ", ".join(str(v) for v in albedo)
    rects = [((0.8, 0.5), 150.0, (0.3, 0.2, 2.0), 5.0), ((1.5, 1.0), 200.0, (-0.5, 1.5, 1.2), 3.0), ((0.3, 0.3), 180.0, (0.0, 0.0, 0.7), 10.0)]
    integrators = ["direct_ems", "direct_mats", "direct_mis", "direct", "path_mis", "path_half", "path_ems"]
    for (sx, sy), angle, t, radiance in rects:
        corners = [rot_x(angle) @ np.array([x * sx, y * sy, 0.0]) + np.array(t) for x, y in [(-1, -1), (1, -1), (1, 1), (-1, 1)]]
        normal = rot_x(angle) @ np.array([0, 0, 1.0])
        assert normal @ (np.zeros(3) - np.array(t)) > 0, "the light must face the origin"
        e = lambert(np.zeros(3), np.array([0, 0, 1.0]), corners, radiance)
        ref = float(LUM @ (albedo * e / np.pi))
        for name in integrators:
            scenes.append(f"""  <scene>
{integrator(name)}
{CAMERA}
{FLOOR.format(a=a_text)}
    <mesh type="rectangle">
      <transform name="toWorld"><scale x="{sx}" y="{sy}" z="1"/><rotate x="1" angle="{angle}"/><translate x="{t[0]}" y="{t[1]}" z="{t[2]}"/></transform>
      <emitter type="area"><color name="radiance" value="{radiance}"/></emitter>
    </mesh>
  </scene>""")
            refs.append(ref)
    # A point light at height h: a I / (pi h^2).
    for name in ["direct_ems", "direct_mis", "path_mis", "path_ems"]:
        h, intensity = 1.5, 4.0
        scenes.append(f"""  <scene>
{integrator(name)}
{CAMERA}
{FLOOR.format(a=a_text)}
    <emitter type="point"><point name="position" value="0, 0, {h}"/><color name="intensity" value="{intensity}"/></emitter>
  </scene>""")
        refs.append(float(LUM @ (albedo * intensity / (np.pi * h * h))))
    # A closed emitting box from inside.
    for name in ["path_mis", "path_mats", "direct_mis", "direct_ems"]:
        ref = LUM @ (1 / (1 - albedo)) if name.startswith("path") else LUM @ (1 + albedo)
        integ = f'    <integrator type="{name}"/>'
        scenes.append(f"""  <scene>
{integ}
    <camera type="perspective">
      <transform name="toWorld"><lookat origin="0.1, 0.2, 0" target="1, 0.3, 0.4" up="0, 1, 0"/></transform>
      <float name="fov" value="1"/>
      <integer name="width" value="1"/>
      <integer name="height" value="1"/>
    </camera>
    <mesh type="cube">
      <boolean name="flipNormals" value="true"/>
      <bsdf type="diffuse"><color name="albedo" value="{a_text}"/></bsdf>
      <emitter type="area"><color name="radiance" value="1"/></emitter>
    </mesh>
  </scene>""")
        refs.append(float(ref))
    ref_text = ", ".join(f"{r:.9g}" for r in refs)
    body = "\n".join(scenes)
    out = f"""<?xml version="1.0" encoding="utf-8"?>
<!-- Written by scripts/make_ttest_files.py (references computed there with numpy). -->
<test type="ttest">
  <string name="references" value="{ref_text}"/>
  <integer name="sampleCount" value="100000"/>
{body}
</test>
"""
    with open("tests/scenes/test-lambert.xml", "w") as f:
        f.write(out)
    print(f"wrote {len(refs)} cases")


def lights():
    """tests/scenes/test-lights.xml (and the constant map it uses)."""
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    env = np.full((8, 16, 3), 0.8, dtype=np.float32)
    mi.Bitmap(env, mi.Bitmap.PixelFormat.RGB).write("tests/scenes/const_env.exr")
    albedo = np.array([0.7, 0.5, 0.3])
    a_text = ", ".join(str(v) for v in albedo)
    scenes, refs = [], []

    def add(name, light, ref):
        scenes.append(f"""  <scene>
{integrator(name)}
{CAMERA}
{FLOOR.format(a=a_text)}
    {light}
  </scene>""")
        refs.append(float(ref))

    delta_integrators = ["direct_ems", "direct_mis", "direct", "path_mis", "path_ems"]
    all_integrators = delta_integrators + ["direct_mats", "path_mats", "path_half"]
    h, intensity = 2.0, 6.0
    spot = (f'<emitter type="spot"><color name="intensity" value="{intensity}"/>'
            f'<float name="cutoffAngle" value="30"/><float name="beamWidth" value="20"/>'
            f'<transform name="toWorld"><lookat origin="0, 0, {h}" target="0, 0, 0" up="0, 1, 0"/></transform></emitter>')
    for name in delta_integrators:
        add(name, spot, LUM @ (albedo * intensity / (np.pi * h * h)))
    e, t = 3.0, 40.0
    d = np.array([np.sin(np.radians(t)), 0.0, -np.cos(np.radians(t))])
    directional = (f'<emitter type="directional"><color name="irradiance" value="{e}"/>'
                   f'<vector name="direction" value="{d[0]:.9f}, {d[1]:.9f}, {d[2]:.9f}"/></emitter>')
    for name in delta_integrators:
        add(name, directional, LUM @ (albedo * e * np.cos(np.radians(t)) / np.pi))
    big_l, theta_a = 2.0, 25.0
    disk = (f'<emitter type="distantdisk"><color name="radiance" value="{big_l}"/>'
            f'<float name="thetaA" value="{theta_a}"/></emitter>')
    for name in all_integrators:
        add(name, disk, LUM @ (albedo * big_l * np.sin(np.radians(theta_a)) ** 2))
    tilt = 50.0
    tilted = (f'<emitter type="distantdisk"><color name="radiance" value="{big_l}"/>'
              f'<float name="thetaA" value="{theta_a}"/>'
              f'<transform name="toWorld"><rotate y="1" angle="{tilt}"/></transform></emitter>')
    for name in all_integrators:
        add(name, tilted, LUM @ (albedo * big_l * np.sin(np.radians(theta_a)) ** 2
                                 * np.cos(np.radians(tilt))))
    const = '<emitter type="constant"><color name="radiance" value="0.8"/></emitter>'
    envmap = '<emitter type="envmap"><string name="filename" value="const_env.exr"/></emitter>'
    for name in all_integrators:
        add(name, const, LUM @ (albedo * 0.8))
        add(name, envmap, LUM @ (albedo * 0.8))
    ref_text = ", ".join(f"{r:.9g}" for r in refs)
    body = "\n".join(scenes)
    out = f"""<?xml version="1.0" encoding="utf-8"?>
<!-- Written by scripts/make_ttest_files.py (references computed there with numpy). -->
<test type="ttest">
  <string name="references" value="{ref_text}"/>
  <integer name="sampleCount" value="100000"/>
{body}
</test>
"""
    with open("tests/scenes/test-lights.xml", "w") as f:
        f.write(out)
    print(f"wrote {len(refs)} light cases")


if __name__ == "__main__":
    main()
    lights()
