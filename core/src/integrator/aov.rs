//! Arbitrary output variables (Mitsuba 3's `aov` integrator): what the first surface a camera
//! ray meets is, rather than the light arriving from it, returned in a colour's channels so
//! that the ordinary render loop averages it like radiance (same camera samples, same filter
//! weights; see `docs/guide/aov.md`).
//!
//! Each [`Aov`] fills up to three channels (unused ones are 0); a miss gives 0 in every
//! channel, as in Mitsuba 3 (except `duv_dx` and `duv_dy`, which Mitsuba 3.9.1 leaves NaN
//! there: Tessera gives 0, so a pixel its edge crosses keeps a number). The loader
//! (`scene/src/integrator/aov.rs`) names the channels.
use super::probe::{PathEnd, Probe, RayKind};
use crate::bsdf::Bsdf;
use crate::camera::Differentials;
use crate::geometry::Interaction;
use crate::math::{Norm, Ray};
use crate::scene::{Scene, SurfaceDetail};
use crate::Color;
use glam::{Vec2, Vec3};

/// One output variable of the first surface along a camera ray.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Aov {
    /// The diffuse reflectance of the surface's BSDF (RGB; see [`albedo`]).
    Albedo,
    /// Distance along the (unit-length) camera ray to the surface (one channel).
    Depth,
    /// World-space position (XYZ).
    Position,
    /// Texture coordinates (UV).
    Uv,
    /// Geometric normal (XYZ).
    GeoNormal,
    /// Shading normal (XYZ).
    ShNormal,
    /// Position's derivative along u (XYZ; see [`crate::scene::SurfaceDetail`]).
    DpDu,
    /// Position's derivative along v (XYZ).
    DpDv,
    /// Texture coordinates' change toward the next pixel to the right (UV; Mitsuba 3's `compute_uv_partials`).
    DuvDx,
    /// Texture coordinates' change toward the next pixel down (UV).
    DuvDy,
    /// The hit primitive's index in its shape, as Mitsuba 3 numbers it (one channel).
    PrimIndex,
    /// The hit shape's 1-based position in Mitsuba 3's shape list (one channel; an instanced
    /// shape gives its instance's).
    ShapeIndex,
    /// The coverage a nested integrator reports as its alpha (one channel): 1 where the ray
    /// meets a surface; where it escapes, 1 if `escaped_count` (a path tracer in a scene with an
    /// environment it does not hide), else 0.
    Alpha {
        /// Whether escaping rays count as covered.
        escaped_count: bool,
    },
    /// Black everywhere: the colour image of an `aov` integrator without a nested integrator.
    Black,
}

/// Renders one [`Aov`] as a colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AovIntegrator {
    /// The variable.
    pub aov: Aov,
    /// The render's samples per pixel: Mitsuba 3 shortens a camera ray's differentials by
    /// `1 / sqrt(spp)`, which [`Aov::DuvDx`] and [`Aov::DuvDy`] measure along.
    pub spp: u64,
}

impl AovIntegrator {
    /// The variable `aov` of a render of `spp` samples per pixel.
    pub fn new(aov: Aov, spp: u64) -> Self {
        AovIntegrator { aov, spp }
    }
}

impl AovIntegrator {
    /// The variable at the first surface `ray` meets (0 where it meets nothing, but see
    /// [`Aov::Alpha`]).
    pub fn li_probed<P: Probe>(&self, scene: &Scene, ray: Ray, probe: &mut P) -> Color {
        if self.aov == Aov::Black {
            return Color::ZERO;
        }
        let hit = probe.intersect(scene, &ray);
        probe.ray(RayKind::Camera);
        probe.hit(scene, hit.as_ref(), ray.d);
        probe.end(PathEnd::MaxDepth);
        self.value(scene, &ray, hit.as_ref())
    }

    /// The variable for camera ray `ray`, whose first surface (`scene.intersect(ray)`) is `hit`:
    /// what [`AovIntegrator::li_probed`] returns, for a caller that has already cast the ray
    /// (one cast for every variable of a sample).
    pub fn value(&self, scene: &Scene, ray: &Ray, hit: Option<&Interaction>) -> Color {
        let Some(si) = hit else {
            return match self.aov {
                Aov::Alpha {
                    escaped_count: true,
                } => Color::X,
                _ => Color::ZERO,
            };
        };
        // Camera rays are unit length, so the ray parameter is the distance.
        let length = ray.d.norm();
        match self.aov {
            Aov::Albedo => albedo(
                &scene.bsdfs[scene.shapes[si.shape as usize].bsdf as usize],
                si,
            ),
            Aov::Depth => Color::new(si.t * length, 0.0, 0.0),
            Aov::Position => si.p,
            Aov::Uv => {
                // A sphere whose material reads no coordinates was hit without them.
                let uv = if scene.reads_uv(si.shape) {
                    si.uv
                } else {
                    scene.intersect_full(ray).map_or(si.uv, |full| full.uv)
                };
                Color::new(uv.x, uv.y, 0.0)
            }
            Aov::GeoNormal => si.ng,
            Aov::ShNormal => si.frame.n,
            Aov::Alpha { .. } => Color::X,
            Aov::Black => Color::ZERO,
            Aov::DpDu | Aov::DpDv | Aov::DuvDx | Aov::DuvDy | Aov::PrimIndex | Aov::ShapeIndex => {
                let Some(d) = scene.surface_detail(ray) else {
                    return Color::ZERO;
                };
                match self.aov {
                    Aov::DpDu => d.dp_du,
                    Aov::DpDv => d.dp_dv,
                    Aov::PrimIndex => Color::new(d.prim_index as f32, 0.0, 0.0),
                    Aov::ShapeIndex => Color::new(d.shape_index as f32, 0.0, 0.0),
                    _ => {
                        let scale = 1.0 / crate::math::sqrt(self.spp.max(1) as f32);
                        let (dx, dy) = match scene.camera.differentials(ray, scale) {
                            Some(r) => duv(si, &d, r),
                            None => (Vec2::ZERO, Vec2::ZERO),
                        };
                        let v = if self.aov == Aov::DuvDx { dx } else { dy };
                        Color::new(v.x, v.y, 0.0)
                    }
                }
            }
        }
    }
}

/// Mitsuba 3's texture-coordinate partials along the camera ray's differentials: each offset
/// ray meets the hit's tangent plane (geometric normal), and the offset of that point from the
/// hit is written in the (`dp_du`, `dp_dv`) basis by least squares; zero where that basis is
/// degenerate.
fn duv(si: &Interaction, d: &SurfaceDetail, r: Differentials) -> (Vec2, Vec2) {
    let (n, p) = (si.ng, si.p);
    let along = |(o, dir): (Vec3, Vec3)| {
        let t = (n.dot(p) - n.dot(o)) / n.dot(dir);
        o + dir * t - p
    };
    let (a00, a01, a11) = (
        d.dp_du.dot(d.dp_du),
        d.dp_du.dot(d.dp_dv),
        d.dp_dv.dot(d.dp_dv),
    );
    let inv_det = 1.0 / (a00 * a11 - a01 * a01);
    let inv_det = if inv_det.is_finite() { inv_det } else { 0.0 };
    let solve = |dp: Vec3| {
        let (b0, b1) = (d.dp_du.dot(dp), d.dp_dv.dot(dp));
        Vec2::new(a11 * b0 - a01 * b1, a00 * b1 - a01 * b0) * inv_det
    };
    (solve(along(r.x)), solve(along(r.y)))
}

/// The diffuse reflectance Mitsuba 3's `albedo` output gives: a Lambertian model's reflectance
/// (on either side), a two-sided model's side facing the ray; for any other model `pi` times
/// the BSDF (cosine included) from the ray's direction toward the shading normal, Mitsuba 3's
/// fallback (its `plastic`, `roughplastic` and `principled` give their diffuse parameter
/// instead; Tessera uses the fallback for them too).
pub fn albedo(bsdf: &Bsdf, si: &Interaction) -> Color {
    let wi = si.frame.to_local(si.wi);
    side_albedo(bsdf, wi, si)
}

fn side_albedo(bsdf: &Bsdf, wi: Vec3, si: &Interaction) -> Color {
    match bsdf {
        Bsdf::Diffuse(d) => d.reflectance.eval(si.uv),
        Bsdf::TwoSided(t) if wi.z < 0.0 => side_albedo(&t.back, Vec3::new(wi.x, wi.y, -wi.z), si),
        Bsdf::TwoSided(t) => side_albedo(&t.front, wi, si),
        b => b.eval(wi, Vec3::Z, si.uv) * core::f32::consts::PI,
    }
}
