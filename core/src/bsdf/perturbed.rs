//! A nested model evaluated in a shading frame tilted away from the surface's own, the common
//! part of `normalmap` and `bumpmap`, as Mitsuba 3.9.1 does it. The nested model gets the
//! shading point's partials and geometric normal in the tilted frame.
//!
//! The tilted normal `n` is given in the local (unperturbed) frame. With
//! `flip_invalid_normals`, a normal that faces away from `wi` (`wi.z (wi . n) <= 0`) has its
//! tangential part negated first. The tilted frame is `(s, t, n)` with
//! `s = normalize(x - n n.x)` (the surface's own tangent, which follows `dp/du`, projected;
//! `bumpmap` projects its local `dp/du` itself),
//! `t = n x s`. Directions are rotated into it, the nested model is asked there, and a pair
//! whose `wo` lies on different sides of the two frames (`wo.z * wo'.z <= 0`) scatters nothing.
//! With `use_shadowing_function`, values are multiplied by the shadowing term of Estevez et al.
//! 2019 ("A Microfacet-Based Shadowing Function to Solve the Bump Terminator Problem"):
//! `2 / (1 + sqrt(1 + a2 tan^2 theta_o))` with `a2 = min(tan^2 theta_n / 8, 1)`.
//!
//! Where Mitsuba divides by zero (a texture value of exactly `(1/2, 1/2, 1/2)`, whose normal
//! has no length, or a normal along the tangent), the unperturbed frame is used instead, so no
//! NaN is produced.
use super::model::Model;
use super::sample::BsdfSample;
use crate::geometry::{Partials, ShadingPoint};
use crate::math::{Frame, Norm};
use crate::Color;
use glam::{Vec2, Vec3};

/// How the tilted frame is built and weighted (the two switches of Mitsuba 3's adapters).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PerturbOptions {
    /// Mirror the normal's tangential part when it faces away from `wi`.
    pub flip_invalid_normals: bool,
    /// Multiply by the bump-terminator shadowing term.
    pub use_shadowing_function: bool,
}

/// `tan^2 theta` of a unit vector (infinite at grazing).
#[inline]
fn tan2(v: Vec3) -> f32 {
    (1.0 - v.z * v.z).max(0.0) / (v.z * v.z)
}

/// The shadowing term for tilted normal `n` toward `wo` (both in the unperturbed frame).
#[inline]
pub(crate) fn shadow_terminator(n: Vec3, wo: Vec3) -> f32 {
    let a2 = (0.125 * tan2(n)).min(1.0);
    let v = 2.0 / (1.0 + crate::math::sqrt(1.0 + a2 * tan2(wo)));
    if v.is_finite() {
        v
    } else {
        0.0
    }
}

/// A tilted frame for one incident direction.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tilted {
    /// The tilted frame, in unperturbed local coordinates.
    pub frame: Frame,
    options: PerturbOptions,
}

impl Tilted {
    /// The frame around the (not necessarily unit) normal `n` for incident `wi`, its first
    /// tangent the local `x` projected (`normalmap`).
    #[inline]
    pub fn new(n: Vec3, wi: Vec3, options: PerturbOptions) -> Self {
        Self::with_tangent(n, Vec3::X, wi, options)
    }

    /// The frame around `n` for incident `wi` whose first tangent is `tangent` (local)
    /// projected onto the plane normal to `n` (`bumpmap` gives `dp/du`); where that
    /// projection vanishes, any frame around `n`.
    pub fn with_tangent(n: Vec3, tangent: Vec3, wi: Vec3, options: PerturbOptions) -> Self {
        let mut n = n;
        if options.flip_invalid_normals && wi.z * wi.dot(n) <= 0.0 {
            n = Vec3::new(-n.x, -n.y, n.z);
        }
        let frame = match n.try_unit() {
            Some(n) => match (tangent - n * n.dot(tangent)).try_unit() {
                Some(s) => Frame {
                    s,
                    t: n.cross(s),
                    n,
                },
                None => Frame::from_normal(n),
            },
            None => Frame {
                s: Vec3::X,
                t: Vec3::Y,
                n: Vec3::Z,
            },
        };
        Tilted { frame, options }
    }

    /// The partials of `at` in the tilted frame (what a nested perturbation reads), if it has
    /// them.
    #[inline]
    fn partials<'a>(&self, at: &ShadingPoint<'a>) -> Option<Partials<'a>> {
        at.partials.map(|g| Partials {
            dp_du: self.frame.to_local(g.dp_du),
            dp_dv: self.frame.to_local(g.dp_dv),
            ng: self.frame.to_local(g.ng),
            site: g.site,
        })
    }

    #[inline]
    fn shadow(&self, wo: Vec3) -> f32 {
        if self.options.use_shadowing_function {
            shadow_terminator(self.frame.n, wo)
        } else {
            1.0
        }
    }

    /// `nested`'s value in the tilted frame (times the shadowing term).
    pub fn eval<B: Model>(&self, nested: &B, wi: Vec3, wo: Vec3, at: ShadingPoint) -> Color {
        let two = self.frame.to_local(wo);
        if !(wo.z * two.z > 0.0) {
            return Color::ZERO;
        }
        let g = self.partials(&at);
        let at = ShadingPoint {
            uv: at.uv,
            partials: g.as_ref(),
            memo: at.memo,
        };
        nested.eval(self.frame.to_local(wi), two, at) * self.shadow(wo)
    }

    /// `nested`'s density in the tilted frame.
    pub fn pdf<B: Model>(&self, nested: &B, wi: Vec3, wo: Vec3, at: ShadingPoint) -> f32 {
        let two = self.frame.to_local(wo);
        if !(wo.z * two.z > 0.0) {
            return 0.0;
        }
        let g = self.partials(&at);
        let at = ShadingPoint {
            uv: at.uv,
            partials: g.as_ref(),
            memo: at.memo,
        };
        nested.pdf(self.frame.to_local(wi), two, at)
    }

    /// Samples `nested` in the tilted frame; the direction is returned in the unperturbed one.
    pub fn sample<B: Model>(
        &self,
        nested: &B,
        wi: Vec3,
        u1: f32,
        u2: Vec2,
        at: ShadingPoint,
    ) -> Option<BsdfSample> {
        let g = self.partials(&at);
        let at = ShadingPoint {
            uv: at.uv,
            partials: g.as_ref(),
            memo: at.memo,
        };
        let s = nested.sample(self.frame.to_local(wi), u1, u2, at)?;
        let wo = self.frame.to_world(s.wo);
        if !(s.wo.z * wo.z > 0.0) {
            return None;
        }
        Some(BsdfSample {
            wo,
            weight: s.weight * self.shadow(wo),
            ..s
        })
    }
}
