//! Numerical stability on awkward geometry.
//!
//! - Inside a closed emitting box whose mesh has duplicate vertices (each face its own copies),
//!   zero-area and collinear triangles, the camera sees Le / (1 - a) (t-test, 0.01
//!   Sidak-corrected), with nothing dropped.
//! - Spheres of radius 1e-6 and 1e6 in a constant environment reflect albedo x radiance.
//! - Very thin (1e-6 wide) and very large (1e6) triangles: rays aimed inside them all hit.
//! - Rays leaving a wall near a concave corner of a closed cube stay inside (and a cracked cube
//!   lets them out).
//! - Vertex normals pointing against the faces: finite, nothing dropped.
//! - NaN or Inf in an OBJ's vertex data: an error naming the file, line and column.
use tessera_core::geometry::intersect_triangle;
use tessera_core::glam::DVec3;
use tessera_core::math::{Norm, Ray};
use tessera_lab::stats::{sidak_alpha, Pcg32};
use tessera_tests::analytic_scenes as scenes;
use tessera_tests::stress::{assert_pixel_within, scratch_dir, Placement};
use tessera_tests::{load_xml, render_loaded};

/// t-tests in this file: 3 scenes x 3 channels.
fn alpha() -> f64 {
    sidak_alpha(0.01, 9)
}

fn write(name: &str, text: &str) -> std::path::PathBuf {
    let p = scratch_dir("geometry").join(name);
    std::fs::write(&p, text).expect("write");
    p
}

/// A cube [-1,1]^3 with each face's four corners written separately (duplicate vertices),
/// wound outward, plus degenerate triangles: a repeated index, three collinear points on an
/// edge, and a triangle of one point repeated.
fn messy_cube() -> std::path::PathBuf {
    let faces: [[[f64; 3]; 4]; 6] = [
        [
            [-1., -1., -1.],
            [-1., 1., -1.],
            [1., 1., -1.],
            [1., -1., -1.],
        ],
        [[-1., -1., 1.], [1., -1., 1.], [1., 1., 1.], [-1., 1., 1.]],
        [
            [-1., -1., -1.],
            [1., -1., -1.],
            [1., -1., 1.],
            [-1., -1., 1.],
        ],
        [[-1., 1., -1.], [-1., 1., 1.], [1., 1., 1.], [1., 1., -1.]],
        [
            [-1., -1., -1.],
            [-1., -1., 1.],
            [-1., 1., 1.],
            [-1., 1., -1.],
        ],
        [[1., -1., -1.], [1., 1., -1.], [1., 1., 1.], [1., -1., 1.]],
    ];
    let mut text = String::new();
    for f in &faces {
        for v in f {
            text += &format!("v {} {} {}\n", v[0], v[1], v[2]);
        }
    }
    text += "v 1 -1 0\nv 1 -1 0.5\n";
    for i in 0..6 {
        let b = 4 * i + 1;
        text += &format!("f {} {} {} {}\n", b, b + 1, b + 2, b + 3);
    }
    // Degenerate: repeated index, three points on the edge x = 1, y = -1, one point thrice.
    // (A coplanar but non-degenerate extra triangle would overlap a face: area sampling would
    // then count that patch twice, a modelling error that biases any renderer.)
    text += "f 1 1 2\nf 21 25 26\nf 3 3 3\n";
    write("messy_cube.obj", &text)
}

/// The camera inside a closed emitting box of messy mesh data (near a corner, looking into
/// it): Le / (1 - a).
#[test]
fn camera_inside_a_messy_closed_mesh() {
    let obj = messy_cube();
    let body = format!(
        r#"  <shape type="obj">
    <string name="filename" value="{}"/>
    <boolean name="face_normals" value="true"/>
    <boolean name="flip_normals" value="true"/>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.3, 0.5, 0.7"/></bsdf>
    <emitter type="area"><rgb name="radiance" value="1"/></emitter>
  </shape>"#,
        obj.display()
    );
    let lookat = r#"origin="0.9, -0.95, 0.97" target="1, -1, 1" up="0, 1, 0""#;
    let xml = scenes::scene(1.0, lookat, 1, &body);
    let mut l = load_xml(&xml, &[]);
    l.set_integrator(Some("path_mis"), Some(-1))
        .expect("integrator");
    // 400k samples: enough to see the 0.16-0.55% the image lost when rays leaving a wall near
    // the corner it looks into went through the next wall (t = -12 and worse).
    let fb = render_loaded(&l, 400_000, 5);
    assert_pixel_within(
        "inside a messy box",
        fb.at(0, 0),
        [0.3f64, 0.5, 0.7].map(|a| 1.0 / (1.0 - a)),
        alpha(),
        0.0,
    );
}

/// Spheres of radius 1e-6 and 1e6 (camera scaled along) under a constant environment.
#[test]
fn tiny_and_huge_spheres() {
    for s in [1e-6, 1e6] {
        let pl = Placement::scaled(s);
        let xml = format!(
            r#"<scene version="3.0.0">
  {}
  <shape type="sphere"><float name="radius" value="{:e}"/>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.5, 0.8"/></bsdf>
  </shape>
  <emitter type="constant"><rgb name="radiance" value="1.5"/></emitter>
</scene>"#,
            pl.sensor([0.0, 0.0, 5.0], [0.0, 0.0, 0.0], "0, 1, 0", 1.0, 1),
            pl.len(1.0)
        );
        let mut l = load_xml(&xml, &[]);
        l.set_integrator(Some("path_mis"), Some(-1))
            .expect("integrator");
        let fb = render_loaded(&l, 20_000, 5);
        assert_pixel_within(
            &format!("sphere radius {s:e}"),
            fb.at(0, 0),
            [0.3, 0.75, 1.2],
            alpha(),
            0.0,
        );
    }
}

/// Rays aimed at points inside a sliver (1e-6 wide, 1 long) and inside a triangle of size 1e6
/// all hit, from a spread of origins.
#[test]
fn thin_and_large_triangles_are_hit() {
    let tris = [
        [
            DVec3::ZERO,
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.5, 1e-6, 0.0),
        ],
        [
            DVec3::new(-1e6, -1e6, 3.0),
            DVec3::new(1e6, -1e6, 3.0),
            DVec3::new(0.0, 1e6, 3.0),
        ],
    ];
    let (mut tested, mut tested_sliver) = (0, 0);
    for (k, t) in tris.iter().enumerate() {
        let p = t.map(|v| v.as_vec3());
        // Origins a thousand sliver widths away: seen from farther, a 1e-6 sliver is thinner
        // than the rounding of coordinates relative to the origin, and no f32 test resolves it.
        let size = if k == 0 { 1e-3 } else { (t[1] - t[0]).norm() };
        for i in 0..200 {
            let (u, v) = (
                (i % 20) as f64 / 20.0 + 0.02,
                (i / 20) as f64 / 10.0 * 0.9 + 0.02,
            );
            let (u, v) = if u + v < 0.98 {
                (u, v)
            } else {
                (0.98 - v, v * 0.5)
            };
            let target = t[0] * (1.0 - u - v) + t[1] * u + t[2] * v;
            for o in [DVec3::new(0.3, 0.2, 1.0), DVec3::new(-2.0, 5.0, -3.0)] {
                let o = (o * size + target).as_vec3();
                let d = target.as_vec3() - o;
                // Where the f32 ray really crosses the plane (f64 on its f32 numbers): only a
                // crossing inside by a margin must hit.
                let (od, dd) = (o.as_dvec3(), d.as_dvec3());
                let q = od + dd * ((t[0].z - od.z) / dd.z);
                let b = barycentric(t, q);
                // Distances to the edges (b_i times the altitude onto edge i) must exceed the
                // rounding of the origin-relative coordinates the test works in.
                let area2 = (t[1] - t[0]).cross(t[2] - t[0]).norm();
                let edges = [t[2] - t[1], t[0] - t[2], t[1] - t[0]];
                let slack = 16.0 * f32::EPSILON as f64 * (target - od).abs().max_element();
                if (0..3).any(|i| b[i] * area2 / edges[i].norm() < slack) {
                    continue;
                }
                let hit = intersect_triangle(&Ray::new(o, d), f32::INFINITY, p[0], p[1], p[2]);
                assert!(
                    hit.is_some(),
                    "triangle {k}: missed the point {b:?} from {o:?}"
                );
                tested += 1;
                tested_sliver += usize::from(k == 0);
            }
        }
    }
    assert!(tested > 600, "only {tested} rays tested");
    assert!(
        tested_sliver > 200,
        "only {tested_sliver} rays at the sliver"
    );
}

/// Barycentric coordinates of `q` in the plane of triangle `t` (f64).
fn barycentric(t: &[DVec3; 3], q: DVec3) -> [f64; 3] {
    let n = (t[1] - t[0]).cross(t[2] - t[0]);
    let area = |a: DVec3, b: DVec3, c: DVec3| (b - a).cross(c - a).dot(n) / n.length_squared();
    [
        area(q, t[1], t[2]),
        area(t[0], q, t[2]),
        area(t[0], t[1], q),
    ]
}

/// Vertex normals pointing against their faces (a floor whose normals point down, lit from
/// above): every pixel finite, nothing dropped.
#[test]
fn normals_pointing_the_wrong_way() {
    let obj = write(
        "flipped_normals.obj",
        "v -5 -5 0\nv 5 -5 0\nv 5 5 0\nv -5 5 0\nvn 0 0 -1\nvn 0.1 0 -1\nvn 0 0 -1\nvn 0 0.1 -1\n\
         f 1//1 2//2 3//3 4//4\n",
    );
    let body = format!(
        r#"  <shape type="obj"><string name="filename" value="{}"/>
    <bsdf type="roughplastic"><float name="alpha" value="0.2"/></bsdf></shape>
  <shape type="sphere"><point name="center" value="0, 0, 2"/><float name="radius" value="0.3"/>
    <emitter type="area"><rgb name="radiance" value="10"/></emitter></shape>"#,
        obj.display()
    );
    let lookat = r#"origin="0, -4, 3" target="0, 0, 0" up="0, 0, 1""#;
    let xml = scenes::scene(40.0, lookat, 8, &body);
    for integ in ["path_mis", "path_mats", "path_ems"] {
        let mut l = load_xml(&xml, &[]);
        l.set_integrator(Some(integ), Some(-1)).expect("integrator");
        let fb = render_loaded(&l, 32, 5);
        assert_eq!(fb.dropped(), 0, "{integ}: non-finite samples");
    }
}

/// NaN and Inf in an OBJ's vertex data are errors naming the file, line and column.
#[test]
fn non_finite_vertex_data_is_a_located_error() {
    let cases = [
        "# a triangle\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 nan 0\nf 1 2 4\n",
        "# a triangle\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 inf\nf 4 2 3\n",
        "# a triangle\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 -inf 1\nf 1//1 2//1 3//1\n",
    ];
    for (k, text) in cases.iter().enumerate() {
        let bad = text.lines().nth(4).unwrap_or_default();
        let name = format!("non_finite_{k}.obj");
        let obj = write(&name, text);
        let xml = format!(
            r#"<scene version="3.0.0"><sensor type="perspective"/>
  <shape type="obj"><string name="filename" value="{}"/></shape></scene>"#,
            obj.display()
        );
        let err = tessera_scene::load_scene_str(
            &xml,
            &tessera_tests::scenes_dir().join("inline-test.xml"),
            &[],
        )
        .err()
        .unwrap_or_else(|| panic!("{bad}: loaded"))
        .to_string();
        assert!(
            err.contains(&format!("{name}:5:")),
            "{bad}: the error does not name the file and line 5: {err}"
        );
    }
}

/// Counts, of `n` rays from a point near the corner (1, -1, 1) of the cube `obj` toward that
/// corner, those that find nothing or whose next ray (leaving where it lands, uniformly over
/// the inner hemisphere) finds nothing: they went out through the walls.
fn corner_escapes(obj: &std::path::Path, n: usize) -> usize {
    use tessera_core::glam::Vec3;
    let body = format!(
        r#"<shape type="obj"><string name="filename" value="{}"/>
    <boolean name="face_normals" value="true"/></shape>"#,
        obj.display()
    );
    let lookat = r#"origin="0.9, -0.95, 0.97" target="1, -1, 1" up="0, 1, 0""#;
    let l = load_xml(&scenes::scene(1.0, lookat, 1, &body), &[]);
    let mut rng = Pcg32::new(7);
    let mut u = || rng.next_f32();
    let o = Vec3::new(0.9, -0.95, 0.97);
    let mut escaped = 0;
    for _ in 0..n {
        let jitter = Vec3::new(u() - 0.5, u() - 0.5, u() - 0.5) * 0.004;
        let ray = Ray::new(o, (Vec3::new(1.0, -1.0, 1.0) + jitter - o).unit());
        let Some(si) = l.scene.intersect(&ray) else {
            escaped += 1;
            continue;
        };
        let inward = if si.ng.dot(ray.d) < 0.0 {
            si.ng
        } else {
            -si.ng
        };
        let d = loop {
            let v = Vec3::new(2.0 * u() - 1.0, 2.0 * u() - 1.0, 2.0 * u() - 1.0);
            if v.length_squared() <= 1.0 && v.dot(inward) > 1e-3 {
                break v.unit();
            }
        };
        escaped += usize::from(l.scene.intersect(&si.spawn_ray(d)).is_none());
    }
    escaped
}

/// Rays leaving a wall within a millionth of the wall beside it (near a concave corner) hit
/// that wall: their distance to it is within the f32 test's error bound, and is judged again
/// in f64. Before that, 0.19% of these rays went through the neighbour and out of the closed
/// cube (a render of its inside came out 0.2-0.7% dark); what is left is hit points rounded
/// past an edge, about 1 in 10^5. Control: a cube whose side x = 1 stands 10^-4 off the others
/// lets rays out through the crack.
#[test]
fn rays_near_a_concave_corner_stay_inside() {
    let n = 200_000;
    let inside = corner_escapes(&messy_cube(), n);
    assert!(
        inside * 10_000 <= n,
        "{inside} of {n} rays escaped a closed cube"
    );
    let cracked = cube_with_a_crack();
    let out = corner_escapes(&cracked, n);
    assert!(
        out * 1000 > n,
        "control: only {out} of {n} rays escaped through a crack"
    );
}

/// The cube [-1,1]^3 with its side x = 1 moved out to x = 1.0001 (same winding as
/// [`messy_cube`], shared corners).
fn cube_with_a_crack() -> std::path::PathBuf {
    let text =
        "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n\
        v 1.0001 -1 -1\nv 1.0001 1 -1\nv 1.0001 1 1\nv 1.0001 -1 1\n\
        f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 9 10 11 12\n";
    write("cracked_cube.obj", text)
}
