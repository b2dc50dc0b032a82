//! `<rotate>` builds the matrix Mitsuba 3 builds: a rotation for a unit axis, and for any other
//! axis the same formula with the axis as given (Mitsuba does not normalise it), with a located
//! warning. The expected matrices are Mitsuba 3.9.1's own
//! (`mi.ScalarTransform4f().rotate(axis, angle).matrix` in the `scalar_rgb` variant).
use super::*;

fn rotation(axis: &str, angle: f64) -> (DMat4, Vec<String>) {
    let s = load(&format!(
        "<scene version=\"3.0.0\">\n  <shape type=\"sphere\">\n    <transform name=\"to_world\">\n      \
         <rotate {axis} angle=\"{angle}\"/>\n    </transform>\n  </shape>\n</scene>"
    ));
    let m = s.children[0]
        .obj
        .transform_opt("to_world")
        .unwrap()
        .unwrap();
    (m, s.load_warnings.clone())
}

/// Row-major 3x3 rows as a matrix.
fn rows(r: [[f64; 3]; 3]) -> DMat4 {
    let c = |j: usize| DVec3::new(r[0][j], r[1][j], r[2][j]);
    DMat4::from_mat3(glam::DMat3::from_cols(c(0), c(1), c(2)))
}

/// Equal to the precision Mitsuba printed its matrices with (six significant digits).
fn near(a: DMat4, b: DMat4) -> bool {
    a.abs_diff_eq(b, 5e-6)
}

#[test]
fn a_rotate_axis_is_used_as_mitsuba_uses_it() {
    // mitsuba-data's hello.xml: axis (0, 1, 1), 15 degrees.
    let (m, w) = rotation("x=\"0\" y=\"1\" z=\"1\"", 15.0);
    let mitsuba = rows([
        [0.965926, -0.258819, 0.258819],
        [0.258819, 1.0, 0.0340742],
        [-0.258819, 0.0340742, 1.0],
    ]);
    assert!(near(m, mitsuba), "{m:?}");
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(
        w[0].starts_with("dir/scene.xml:4:7:") && w[0].contains("unit length"),
        "{w:?}"
    );
    // Control: the normalised rotation is not Mitsuba's matrix.
    let normalised = DMat4::from_axis_angle(DVec3::new(0.0, 1.0, 1.0).unit(), 15f64.to_radians());
    assert!(!near(normalised, mitsuba));

    let (m, _) = rotation("axis=\"1, 2, -0.5\"", 40.0);
    let mitsuba = rows([
        [1.0, 0.789305, 1.1686],
        [0.146517, 1.70187, -0.876743],
        [-1.40255, 0.408832, 0.824533],
    ]);
    assert!(near(m, mitsuba), "{m:?}");
}

#[test]
fn a_unit_axis_is_a_rotation_without_warning() {
    let axis = DVec3::new(1.0, 2.0, -0.5).unit();
    let (m, w) = rotation(
        &format!("x=\"{}\" y=\"{}\" z=\"{}\"", axis.x, axis.y, axis.z),
        40.0,
    );
    assert!(w.is_empty(), "{w:?}");
    assert!(
        near(m, DMat4::from_axis_angle(axis, 40f64.to_radians())),
        "{m:?}"
    );
}
