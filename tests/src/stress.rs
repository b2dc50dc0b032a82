//! Helpers of the numerical-stability suite (`tests/tests/stress_*.rs`): scenes placed at a
//! scale and an offset from the origin, the Cornell box rewritten for a placement, and a scratch
//! folder for generated mesh files.
use std::path::PathBuf;
use tessera_core::glam::DVec3;
use tessera_scene::xml::RECENTRE_FROM;

/// Where a stress scene sits: every point `p` of the unit-scale scene maps to
/// `p * scale + offset`, lengths to `l * scale`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// Uniform scale factor.
    pub scale: f64,
    /// Translation applied after the scale.
    pub offset: DVec3,
}

/// How far (unit-scale units) every camera of the stress scenes is from what it sees.
pub const CAMERA_REACH: f64 = 8.0;

impl Placement {
    /// The unit-scale scene at the origin.
    pub const UNIT: Placement = Placement {
        scale: 1.0,
        offset: DVec3::ZERO,
    };

    /// Scaled about the origin by `s`.
    pub fn scaled(s: f64) -> Self {
        Placement {
            scale: s,
            offset: DVec3::ZERO,
        }
    }

    /// The unit scene moved 1e6 along each axis: f32 coordinates there are 0.0625 apart.
    pub fn far() -> Self {
        Placement::moved(DVec3::splat(1e6))
    }

    /// Unit scale, moved by `d`.
    pub fn moved(d: DVec3) -> Self {
        Placement {
            scale: 1.0,
            offset: d,
        }
    }

    /// Every placement of the suite: uniform scales 1e-4, 1e-2, 1, 1e2, 1e4, and the unit scene
    /// moved 1e3 and 1e5 along each axis (away from the origin in x, y and z at once).
    pub fn all() -> Vec<Placement> {
        // (The 1e6 placement is [`Placement::far`], for the analytic scenes.)
        let mut v: Vec<Placement> = [1e-4, 1e-2, 1.0, 1e2, 1e4]
            .into_iter()
            .map(Placement::scaled)
            .collect();
        v.extend([1e3, 1e5].map(|d| Placement::moved(DVec3::splat(d))));
        v
    }

    /// A short description for messages.
    pub fn label(&self) -> String {
        if self.offset == DVec3::ZERO {
            format!("scale {:e}", self.scale)
        } else {
            format!(
                "scale {:e} moved by {:?}",
                self.scale,
                self.offset.to_array()
            )
        }
    }

    /// The placed point, as an XML `value` string `"x, y, z"`.
    pub fn p(&self, x: f64, y: f64, z: f64) -> String {
        let q = DVec3::new(x, y, z) * self.scale + self.offset;
        format!("{:e}, {:e}, {:e}", q.x, q.y, q.z)
    }

    /// The relative spacing of f32 coordinates across an object of unit-scale size `size` at this
    /// placement, in the frame the core renders in: `eps * (largest coordinate + placed size) /
    /// placed size`. Nothing finer than this is represented, so an answer can be off by a small
    /// multiple of it however exact the arithmetic. The loader renders a scene whose camera is
    /// [`RECENTRE_FROM`] or more from the origin in a frame centred on the camera (every
    /// camera here is within [`CAMERA_REACH`] unit-scale units of what it sees); nearer, the
    /// offset from the origin counts.
    pub fn resolution(&self, size: f64) -> f64 {
        let placed = size * self.scale;
        let far = self.offset.abs().max_element() + CAMERA_REACH * self.scale;
        let largest = match far >= RECENTRE_FROM {
            true => CAMERA_REACH * self.scale,
            false => self.offset.abs().max_element(),
        };
        f32::EPSILON as f64 * (largest + placed) / placed
    }

    /// A placed length.
    pub fn len(&self, l: f64) -> f64 {
        l * self.scale
    }

    /// The transform steps that move a unit-scale object into place (append them to the end of
    /// a shape's `to_world`).
    pub fn ops(&self) -> String {
        format!(
            r#"<scale value="{:e}"/><translate x="{:e}" y="{:e}" z="{:e}"/>"#,
            self.scale, self.offset.x, self.offset.y, self.offset.z
        )
    }

    /// A perspective sensor at `origin` looking at `target` (unit-scale coordinates), with the
    /// clip planes scaled along (Mitsuba's defaults 0.01 and 1e4 times the scale) and a box
    /// filter.
    pub fn sensor(
        &self,
        origin: [f64; 3],
        target: [f64; 3],
        up: &str,
        fov: f64,
        res: u32,
    ) -> String {
        format!(
            r#"<sensor type="perspective">
    <float name="fov" value="{fov}"/>
    <float name="near_clip" value="{:e}"/>
    <float name="far_clip" value="{:e}"/>
    <transform name="to_world"><lookat origin="{}" target="{}" up="{up}"/></transform>
    <film type="hdrfilm"><integer name="width" value="{res}"/><integer name="height" value="{res}"/><rfilter type="box"/></film>
  </sensor>"#,
            self.len(0.01),
            self.len(1e4),
            self.p(origin[0], origin[1], origin[2]),
            self.p(target[0], target[1], target[2]),
        )
    }
}

/// The text of `scenes/cbox.xml` with every shape, the light and the camera moved into place:
/// the meshes' `to_world` scale 0.01 becomes `0.01 * scale` plus the offset, the camera's
/// look-at points are placed the same way, and its clip planes scale along.
pub fn cbox_xml(pl: &Placement) -> String {
    let text = std::fs::read_to_string(crate::scenes_dir().join("cbox.xml")).expect("cbox.xml");
    let mesh_tf = r#"<scale value="0.01"/>"#;
    assert_eq!(text.matches(mesh_tf).count(), 8, "cbox.xml has changed");
    let placed = Placement {
        scale: pl.scale * 0.01,
        offset: pl.offset,
    };
    let lookat = r#"<lookat origin="2.78, 2.73, -8.0" target="2.78, 2.73, -7.99" up="0, 1, 0"/>"#;
    assert!(text.contains(lookat), "cbox.xml camera has changed");
    let sensor_open = r#"<sensor type="perspective">"#;
    let text = text.replace(mesh_tf, &placed.ops()).replace(
        lookat,
        &format!(
            r#"<lookat origin="{}" target="{}" up="0, 1, 0"/>"#,
            pl.p(2.78, 2.73, -8.0),
            pl.p(2.78, 2.73, -7.99)
        ),
    );
    text.replace(
        sensor_open,
        &format!(
            r#"{sensor_open}<float name="near_clip" value="{:e}"/><float name="far_clip" value="{:e}"/>"#,
            pl.len(0.01),
            pl.len(1e4)
        ),
    )
}

/// A scratch folder for files a test writes (in the system's temporary folder, one per process).
pub fn scratch_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("tessera-stress-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).expect("scratch dir");
    d
}

/// Student t-test of each channel of pixel `p` against `expected`, like
/// [`crate::assert_pixel_matches`], with a systematic term `rel_sys * expected` joining the
/// standard error in quadrature: the answer cannot be trusted beyond the scene's own resolution
/// ([`Placement::resolution`]). No non-finite sample is allowed.
pub fn assert_pixel_within(
    label: &str,
    p: &tessera_core::film::PixelAccum,
    expected: [f64; 3],
    alpha: f64,
    rel_sys: f64,
) {
    use statrs::distribution::{ContinuousCDF, StudentsT};
    assert_eq!(p.dropped, 0, "{label}: non-finite samples");
    for (k, &want) in expected.iter().enumerate() {
        let (n, mean) = (p.count as f64, p.sum[k] / p.count as f64);
        let var = ((p.sum_sq[k] - n * mean * mean) / (n - 1.0)).max(0.0);
        let ulp = want.abs() * f32::EPSILON as f64;
        let sys = rel_sys * want.abs();
        let se = (var / n + (4.0 * ulp).powi(2) + sys * sys).sqrt();
        let t = (mean - want) / se;
        let p_value = 2.0 * StudentsT::new(0.0, 1.0, n - 1.0).expect("dof").sf(t.abs());
        assert!(
            p_value >= alpha,
            "{label} channel {k}: mean {mean} vs expected {} (t = {t:.3}, p = {p_value:.3e}, \
             systematic allowance {rel_sys:.2e})",
            want
        );
    }
}
