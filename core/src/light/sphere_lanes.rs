//! Light selection at a vertex lit by sphere lights only, four lights per vector.
//!
//! Vertex selection (`light/vertex.rs`) weighs each light by its estimate at the
//! vertex times the BSDF toward it, light after light: on Veach's scene (four sphere lights over
//! rough plates) that was an eighth of the render. The work is the same chain of operations for
//! every light, so here the lights sit in the lanes of a vector (two vectors for five to eight),
//! laid out once when the scene is built, and each operation is done for four lights at once.
//!
//! Every lane computes what the light-by-light code computes, operation for operation and in the
//! same order (the products and sums of glam's `dot` and `length_squared`, a division for each
//! division, a correctly rounded square root for each square root), so each weight has the same
//! bits and so does every image. It covers the BSDFs whose weighing is arithmetic (diffuse, and
//! a rough conductor's lobe shape); any other BSDF, and a vertex inside a light, take the
//! light-by-light code.
use super::bound::LightBound;
use crate::bsdf::microfacet::{Microfacet, MicrofacetKind};
use crate::bsdf::Bsdf;
use crate::math::{sqrt4, Frame, PI};
use glam::{BVec4A, Vec3, Vec4};

/// Most lights the lanes hold (vertex selection's limit, which it checks is this).
pub const LANE_LIGHTS: usize = 8;

/// Vectors of four lanes that hold [`LANE_LIGHTS`] lights.
const GROUPS: usize = LANE_LIGHTS / 4;

/// The sphere lights of a scene whose lights are all spheres, in structure-of-arrays form:
/// light `k` is lane `k % 4` of group `k / 4`. Unused lanes hold zeros and are never read.
#[derive(Clone, Debug)]
pub struct SphereLanes {
    /// Number of lights.
    n: usize,
    /// Centres, per axis.
    cx: [Vec4; GROUPS],
    cy: [Vec4; GROUPS],
    cz: [Vec4; GROUPS],
    /// Squared radii (as the light-by-light estimate computes them).
    r2: [Vec4; GROUPS],
    /// Luminance of each light's radiance.
    lum: [Vec4; GROUPS],
}

impl SphereLanes {
    /// The lanes of `bounds` when there are 2 to [`LANE_LIGHTS`] and every one is a sphere;
    /// `None` otherwise.
    pub fn of(bounds: &[LightBound]) -> Option<SphereLanes> {
        if !(2..=LANE_LIGHTS).contains(&bounds.len()) {
            return None;
        }
        let mut l = SphereLanes {
            n: bounds.len(),
            cx: [Vec4::ZERO; GROUPS],
            cy: [Vec4::ZERO; GROUPS],
            cz: [Vec4::ZERO; GROUPS],
            r2: [Vec4::ZERO; GROUPS],
            lum: [Vec4::ZERO; GROUPS],
        };
        for (k, b) in bounds.iter().enumerate() {
            let LightBound::Sphere {
                center,
                radius,
                lum,
            } = *b
            else {
                return None;
            };
            let (g, i) = (k / 4, k % 4);
            l.cx[g][i] = center.x;
            l.cy[g][i] = center.y;
            l.cz[g][i] = center.z;
            l.r2[g][i] = radius * radius;
            l.lum[g][i] = lum;
        }
        Some(l)
    }

    /// Each light's weight at a vertex at `p` with shading frame `frame`, BSDF `bsdf` and local
    /// incident direction `wi` (the first `n` entries), and their sum in light order: what
    /// the light-by-light loop of `VertexSelection` finds, bit for bit. `None` where that loop
    /// must run instead: a BSDF other than diffuse or a rough conductor, or a vertex on or inside
    /// a light.
    #[inline]
    pub fn weights(
        &self,
        p: Vec3,
        frame: &Frame,
        bsdf: &Bsdf,
        wi: Vec3,
    ) -> Option<([f32; LANE_LIGHTS], f32)> {
        let lobe_of = match bsdf {
            Bsdf::Diffuse(_) => None,
            Bsdf::RoughConductor(c) => Some(&c.distribution),
            _ => return None,
        };
        let groups = self.n.div_ceil(4);
        let mut weight = [0.0f32; LANE_LIGHTS];
        for g in 0..groups {
            // The estimate (`LightBound::estimate` of a sphere, through `from_point`).
            let d = Vec3x4 {
                x: self.cx[g] - Vec4::splat(p.x),
                y: self.cy[g] - Vec4::splat(p.y),
                z: self.cz[g] - Vec4::splat(p.z),
            };
            let dist2 = d.dot(d);
            let lanes = (self.n - 4 * g).min(4);
            let outside = dist2.cmpgt(self.r2[g]).bitmask();
            if outside & ((1 << lanes) - 1) != (1 << lanes) - 1 {
                return None;
            }
            let w = d.scale(Vec4::ONE / sqrt4(dist2));
            let sin2 = self.r2[g] / dist2;
            let irradiance = self.lum[g]
                * (Vec4::splat(2.0 * PI) * sin2 / (Vec4::ONE + sqrt4(Vec4::ONE - sin2)));
            // The BSDF toward each light, in the shading frame (`Frame::to_local`).
            let wo = Vec3x4 {
                x: w.dot_splat(frame.s),
                y: w.dot_splat(frame.t),
                z: w.dot_splat(frame.n),
            };
            let f = match lobe_of {
                None => diffuse(wi, wo),
                Some(m) => lobe(m, wi, wo),
            };
            let f = Vec4::select(f.cmpgt(Vec4::ZERO), f, Vec4::ZERO);
            let product = irradiance * f;
            for i in 0..lanes {
                if irradiance[i] > 0.0 {
                    weight[4 * g + i] = product[i];
                }
            }
        }
        // Summed light by light, as the loop sums them (lights it skips add nothing).
        let mut sum = 0.0f32;
        for &w in &weight[..self.n] {
            if w != 0.0 {
                sum += w;
            }
        }
        Some((weight, sum))
    }
}

/// Four directions (or vectors), one per lane.
#[derive(Clone, Copy)]
struct Vec3x4 {
    x: Vec4,
    y: Vec4,
    z: Vec4,
}

impl Vec3x4 {
    /// Each lane's dot product, as glam's `Vec3::dot`: `(x x' + y y') + z z'`.
    #[inline(always)]
    fn dot(self, o: Vec3x4) -> Vec4 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// Each lane's dot product with the one vector `v`.
    #[inline(always)]
    fn dot_splat(self, v: Vec3) -> Vec4 {
        self.x * Vec4::splat(v.x) + self.y * Vec4::splat(v.y) + self.z * Vec4::splat(v.z)
    }

    /// Each lane's vector times its lane of `s`.
    #[inline(always)]
    fn scale(self, s: Vec4) -> Vec3x4 {
        Vec3x4 {
            x: self.x * s,
            y: self.y * s,
            z: self.z * s,
        }
    }
}

/// The diffuse weight: the cosine toward the light where both directions are above the surface.
#[inline(always)]
fn diffuse(wi: Vec3, wo: Vec3x4) -> Vec4 {
    if wi.z > 0.0 {
        Vec4::select(wo.z.cmpgt(Vec4::ZERO), wo.z, Vec4::ZERO)
    } else {
        Vec4::ZERO
    }
}

/// `RoughConductor::lobe` in each lane: `D(h) / (4 cos theta_i)` for the half vector `h` of `wi`
/// and the lane's `wo`, zero where that half vector does not exist.
#[inline(always)]
fn lobe(m: &Microfacet, wi: Vec3, wo: Vec3x4) -> Vec4 {
    if !(wi.z > 0.0) {
        return Vec4::ZERO;
    }
    // The half vector (`half_vector`: `(wi + wo).unit()`, finite, on the side of both).
    let h = Vec3x4 {
        x: Vec4::splat(wi.x) + wo.x,
        y: Vec4::splat(wi.y) + wo.y,
        z: Vec4::splat(wi.z) + wo.z,
    };
    let h = h.scale(Vec4::ONE / sqrt4(h.dot(h)));
    let finite = h.x.is_finite_mask() & h.y.is_finite_mask() & h.z.is_finite_mask();
    let exists = wo.z.cmpgt(Vec4::ZERO)
        & finite
        & h.dot_splat(wi).cmpgt(Vec4::ZERO)
        & wo.dot(h).cmpgt(Vec4::ZERO)
        & h.z.cmpgt(Vec4::ZERO);
    if !exists.any() {
        return Vec4::ZERO;
    }
    // `Microfacet::d`.
    let (ax, ay) = (Vec4::splat(m.alpha_u), Vec4::splat(m.alpha_v));
    let z2 = h.z * h.z;
    let e = (h.x / ax) * (h.x / ax) + (h.y / ay) * (h.y / ay);
    let scale = Vec4::splat(PI) * ax * ay;
    let r = match m.kind {
        MicrofacetKind::Beckmann => {
            let q = -e / z2;
            let x = Vec4::new(
                libm::expf(q.x),
                libm::expf(q.y),
                libm::expf(q.z),
                libm::expf(q.w),
            );
            x / (scale * z2 * z2)
        }
        MicrofacetKind::Ggx => {
            let t = e + z2;
            Vec4::ONE / (scale * t * t)
        }
    };
    let kept: BVec4A = exists & (r * h.z).cmpgt(Vec4::splat(1e-20)) & r.is_finite_mask();
    let d = Vec4::select(kept, r, Vec4::ZERO);
    d / Vec4::splat(4.0 * wi.z)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bsdf::{Diffuse, RoughConductor};
    use crate::geometry::Interaction;
    use crate::light::VertexSelection;
    use crate::sampling::owen::mix64;
    use crate::sampling::warp::square_to_uniform_sphere;
    use crate::texture::Texture;
    use crate::Color;
    use glam::Vec2;

    fn unit(h: u64) -> f32 {
        (h >> 40) as f32 / (1u64 << 24) as f32
    }

    /// Case `r`'s `k`-th uniform number.
    fn u(r: u64, k: u64) -> f32 {
        unit(mix64(r ^ k.wrapping_mul(0x9e37_79b9_7f4a_7c15)))
    }

    fn bsdfs() -> [Bsdf; 5] {
        let conductor = |kind, alpha_u: f32, alpha_v: f32| {
            let mut distribution = Microfacet::new(kind, alpha_u);
            distribution.alpha_v = alpha_v;
            Bsdf::RoughConductor(RoughConductor {
                distribution,
                roughness: None,
                eta: Texture::Constant(Color::ZERO),
                k: Texture::Constant(Color::ONE),
                specular_reflectance: Texture::Constant(Color::ONE),
            })
        };
        [
            Bsdf::Diffuse(Diffuse {
                reflectance: Texture::Constant(Color::splat(0.5)),
            }),
            conductor(MicrofacetKind::Ggx, 0.05, 0.05),
            conductor(MicrofacetKind::Ggx, 0.3, 0.08),
            conductor(MicrofacetKind::Beckmann, 0.01, 0.01),
            conductor(MicrofacetKind::Beckmann, 0.4, 0.2),
        ]
    }

    /// Random cases: 2 to 8 sphere lights of sizes and distances over several decades, a vertex
    /// with a random frame and incident direction (below the surface too), each BSDF.
    fn case(r: u64) -> (alloc::vec::Vec<LightBound>, Interaction, Vec3) {
        let n = 2 + (u(r, 0) * 7.0) as usize;
        let bounds = (0..n as u64)
            .map(|k| LightBound::Sphere {
                center: Vec3::new(u(r, 10 + k), u(r, 20 + k), u(r, 30 + k)) * 20.0
                    - Vec3::splat(10.0),
                radius: 10f32.powf(u(r, 40 + k) * 3.0 - 2.5),
                lum: 10f32.powf(u(r, 50 + k) * 4.0 - 2.0),
            })
            .collect();
        let n = square_to_uniform_sphere(Vec2::new(u(r, 1), u(r, 2)));
        let si = Interaction {
            p: Vec3::new(u(r, 3), u(r, 4), u(r, 5)) * 4.0 - Vec3::splat(2.0),
            p_err: Vec3::ZERO,
            t: 1.0,
            ng: n,
            frame: Frame::from_normal(n),
            uv: Vec2::ZERO,
            shape: 0,
            wi: n,
        };
        let wi = square_to_uniform_sphere(Vec2::new(u(r, 6), u(r, 7)));
        (bounds, si, wi)
    }

    fn bits(s: &VertexSelection, n: usize) -> alloc::vec::Vec<u32> {
        (0..n).map(|k| s.pdf(k).to_bits()).collect()
    }

    /// Four lights to a vector give the light-by-light probabilities bit for bit, for every
    /// BSDF the lanes weigh. Control: the same comparison with the vertex moved by 1e-3 finds
    /// different bits, so it can fail.
    #[test]
    fn lanes_give_the_light_by_light_bits() {
        let (mut compared, mut moved_differs) = (0, 0);
        for r in 0..3000u64 {
            let (bounds, si, wi) = case(r);
            let lanes = SphereLanes::of(&bounds).expect("all spheres");
            for bsdf in &bsdfs() {
                let at = Vec2::ZERO.into();
                let one = VertexSelection::new(&bounds, None, &si, bsdf, at, wi).unwrap();
                let four = VertexSelection::new(&bounds, Some(&lanes), &si, bsdf, at, wi).unwrap();
                if lanes.weights(si.p, &si.frame, bsdf, wi).is_none() {
                    continue;
                }
                assert_eq!(
                    bits(&one, bounds.len()),
                    bits(&four, bounds.len()),
                    "case {r}"
                );
                compared += 1;
                let moved = Interaction {
                    p: si.p + Vec3::X * 1e-3,
                    ..si
                };
                let other = VertexSelection::new(&bounds, None, &moved, bsdf, at, wi).unwrap();
                moved_differs +=
                    usize::from(bits(&other, bounds.len()) != bits(&four, bounds.len()));
            }
        }
        assert!(compared > 10_000, "only {compared} cases compared");
        // About a quarter differ: in most cases every light weighs zero (the incident direction
        // below the surface, a lobe facing away) and the choice is even wherever the vertex is.
        assert!(
            moved_differs > compared / 10,
            "control: {moved_differs} of {compared}"
        );
    }

    /// Lanes exist only for 2 to 8 lights that are all spheres; a vertex inside a light, or a
    /// BSDF the lanes do not weigh, leaves the weighing to the light-by-light loop.
    #[test]
    fn lanes_step_aside_where_they_do_not_apply() {
        let sphere = |x: f32| LightBound::Sphere {
            center: Vec3::new(x, 0.0, 0.0),
            radius: 1.0,
            lum: 1.0,
        };
        assert!(SphereLanes::of(&[sphere(0.0)]).is_none());
        assert!(SphereLanes::of(&[sphere(0.0); LANE_LIGHTS + 1]).is_none());
        let point = LightBound::Point {
            position: Vec3::ZERO,
            lum: 1.0,
        };
        assert!(SphereLanes::of(&[sphere(0.0), point]).is_none());
        let lanes = SphereLanes::of(&[sphere(5.0), sphere(-5.0), sphere(0.0)]).unwrap();
        let f = Frame::from_normal(Vec3::Z);
        let diffuse = &bsdfs()[0];
        assert!(lanes.weights(Vec3::Y * 3.0, &f, diffuse, Vec3::Z).is_some());
        assert!(lanes.weights(Vec3::X * 0.5, &f, diffuse, Vec3::Z).is_none());
        let mirror = Bsdf::Mirror(crate::bsdf::Mirror {});
        assert!(lanes.weights(Vec3::Y * 3.0, &f, &mirror, Vec3::Z).is_none());
    }
}
