//! Arbitrary output variables (Mitsuba 3's `aov` integrator): what the first surface a camera
//! ray meets is, rather than the light arriving from it, returned in a colour's channels so
//! that the ordinary render loop averages it like radiance (same camera samples, same filter
//! weights; see `docs/guide/aov.md`).
//!
//! Each [`Aov`] fills up to three channels (unused ones are 0); a miss gives 0 in every
//! channel, as in Mitsuba 3. The loader (`scene/src/integrator/aov.rs`) names the channels.
use super::probe::{PathEnd, Probe, RayKind};
use crate::bsdf::Bsdf;
use crate::geometry::Interaction;
use crate::math::{Norm, Ray};
use crate::scene::Scene;
use crate::Color;
use glam::Vec3;

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
                &si,
            ),
            Aov::Depth => Color::new(si.t * length, 0.0, 0.0),
            Aov::Position => si.p,
            Aov::Uv => Color::new(si.uv.x, si.uv.y, 0.0),
            Aov::GeoNormal => si.ng,
            Aov::ShNormal => si.frame.n,
            Aov::Alpha { .. } => Color::X,
            Aov::Black => Color::ZERO,
        }
    }
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
