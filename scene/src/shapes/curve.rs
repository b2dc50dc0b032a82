//! The `linearcurve` and `bsplinecurve` shapes, as Mitsuba 3 reads them: control points from a
//! text file (`crate::mesh::curve_file`), their positions carried by `to_world` and their radii
//! kept as written (Mitsuba does not scale radii, even under a non-uniform scale). The geometry,
//! hits and parameterisation are the core's (`tessera_core::geometry::Curve`). Mitsuba cannot
//! sample points on curves, so an emitter on one is refused (`table.rs`), and it does not flip
//! their normals, so `flip_normals` is accepted with a warning and ignored.
use super::{Geometry, ShapePlugin, TO_WORLD};
use crate::mesh::curve_file::load_curves;
use crate::plugin::{Param, Plugin};
use crate::util::{at_prop, Result};
use crate::xml::Object;
use glam::{DMat4, DVec3, DVec4};
use tessera_core::geometry::{Curve, CurveBasis, ShapeKind};

const FILENAME: Param = Param::file(
    "relative to the scene file",
    "the curve file: one control point `x y z radius` per line, a blank line between curves",
);

/// `flip_normals`, which Mitsuba 3's curves read and ignore.
const FLIP_IGNORED: Param = Param::boolean(
    "flip_normals",
    false,
    "no effect: Mitsuba 3's curves do not flip their normals",
)
.ignored();

const SILHOUETTE_WEIGHT: Param = Param::float(
    "silhouette_sampling_weight",
    1.0,
    crate::plugin::Range::NonNegative,
    "Mitsuba's weight for sampling silhouettes in differentiable rendering",
)
.ignored();

/// `linearcurve`.
pub(crate) const LINEARCURVE: ShapePlugin = Plugin {
    name: "linearcurve",
    aliases: &[],
    doc: "Round linear curves read from a file: each segment is the cone tangent to the spheres \
          of its two control points, with a sphere at every joint and at both ends of each \
          curve (at least two points per curve). uv: u around the curve, v along all segments \
          of the file. Only hits from outside count (a ray starting inside passes through). \
          to_world moves the control points; radii are not scaled. Cannot be an emitter.",
    params: &[FILENAME, TO_WORLD, FLIP_IGNORED],
    nested: "an optional `<bsdf>`",
    build: build_linear,
};

/// `bsplinecurve`.
pub(crate) const BSPLINECURVE: ShapePlugin = Plugin {
    name: "bsplinecurve",
    aliases: &[],
    doc: "Uniform cubic B-spline curves read from a file (at least four points per curve, one \
          segment per point beyond the third): tubes of circles perpendicular to the curve, \
          their radius interpolated like the positions, open at both ends. uv: u around the \
          curve, v along all segments of the file. Only hits from outside count. to_world \
          moves the control points; radii are not scaled. Cannot be an emitter.",
    params: &[FILENAME, TO_WORLD, FLIP_IGNORED, SILHOUETTE_WEIGHT],
    nested: "an optional `<bsdf>`",
    build: build_bspline,
};

fn build_linear(obj: &Object) -> Result<Geometry> {
    build_curve(obj, CurveBasis::Linear)
}

fn build_bspline(obj: &Object) -> Result<Geometry> {
    SILHOUETTE_WEIGHT.read_f32(obj)?;
    build_curve(obj, CurveBasis::BSpline)
}

fn build_curve(obj: &Object, basis: CurveBasis) -> Result<Geometry> {
    let name = obj
        .string_opt(FILENAME.name)?
        .ok_or_else(|| obj.error(format!("{} needs \"filename\"", obj.describe())))?;
    let path = obj.resolve_file(&name);
    let (min_points, kind) = match basis {
        CurveBasis::Linear => (2, "linear curve"),
        CurveBasis::BSpline => (4, "B-spline curve"),
    };
    let data = load_curves(&path, min_points, kind).map_err(|e| {
        if e.loc.is_some() {
            e
        } else {
            at_prop(obj, "filename", format!("{}: {}", path.display(), e.msg))
        }
    })?;
    let tf = obj.transform(TO_WORLD.name, DMat4::IDENTITY)?;
    let points: Vec<DVec4> = data
        .points
        .iter()
        .map(|p| {
            let w = tf.transform_point3(DVec3::new(p[0].into(), p[1].into(), p[2].into()));
            // Stored as f32, as Mitsuba stores them.
            DVec4::new(w.x, w.y, w.z, f64::from(p[3]))
                .as_vec4()
                .as_dvec4()
        })
        .collect();
    if points.iter().any(|p| !p.is_finite()) {
        return Err(obj.error(format!(
            "{} has a control point that to_world sends to infinity",
            obj.describe()
        )));
    }
    let span = min_points - 1;
    let mut segments = Vec::new();
    let mut first = Vec::new();
    for &(start, n) in &data.curves {
        for k in 0..n - span {
            segments
                .push(u32::try_from(start + k).map_err(|_| obj.error("too many control points"))?);
            first.push(k == 0);
        }
    }
    Geometry::of(ShapeKind::Curve(Curve {
        basis,
        points,
        segments,
        first,
    }))
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    fn load(shape: &str) -> Result<crate::LoadedScene, String> {
        let root = env!("CARGO_MANIFEST_DIR");
        let text = format!(
            "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"/>\n{}\n</scene>\n",
            shape.replace("ROOT", root)
        );
        crate::load_scene_str(&text, Path::new("/nowhere/c.xml"), &[]).map_err(|e| e.to_string())
    }

    #[test]
    fn an_emitter_on_a_curve_is_refused_where_it_is() {
        let e = load(
            "<shape type=\"linearcurve\">\n<string name=\"filename\" \
             value=\"ROOT/../tests/curve_cases/wave.txt\"/>\n<emitter type=\"area\"/>\n</shape>",
        )
        .unwrap_err();
        assert!(
            e.starts_with("/nowhere/c.xml:5:1:") && e.contains("cannot emit"),
            "{e}"
        );
        // The control: the same shape without the emitter loads.
        load(
            "<shape type=\"linearcurve\">\n<string name=\"filename\" \
             value=\"ROOT/../tests/curve_cases/wave.txt\"/>\n</shape>",
        )
        .unwrap();
    }

    #[test]
    fn a_bad_curve_file_is_located_in_it_and_flip_normals_warns() {
        let dir = std::env::temp_dir().join(format!("tessera-curve-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let f = dir.join("bad.txt");
        std::fs::write(&f, "0 0 0 1\n1 0 0 1\n2 0 0 1\n").unwrap();
        let shape = format!(
            "<shape type=\"bsplinecurve\">\n<string name=\"filename\" value=\"{}\"/>\n</shape>",
            f.display()
        );
        let e = load(&shape).unwrap_err();
        assert!(
            e.starts_with(&format!("{}:1:1:", f.display())) && e.contains("at least 4"),
            "{e}"
        );
        let l = load(
            "<shape type=\"linearcurve\">\n<string name=\"filename\" \
             value=\"ROOT/../tests/curve_cases/wave.txt\"/>\n<boolean name=\"flip_normals\" \
             value=\"true\"/>\n</shape>",
        )
        .unwrap();
        assert!(
            l.warnings
                .iter()
                .any(|w| w.contains("\"flip_normals\"") && w.contains("ignored")),
            "{:?}",
            l.warnings
        );
        assert!(!l.scene.shapes[0].flip_normals);
        std::fs::remove_dir_all(&dir).ok();
    }
}
