//! Light selection at a vertex, four lights per vector.
//!
//! Vertex selection (`light/vertex.rs`) weighs each light by its estimate at the vertex times the
//! BSDF toward it, light after light: on Veach's scene (four sphere lights over rough plates)
//! that was an eighth of the render. The work is the same chain of operations for every light
//! that has a position (spheres, flat and other area lights, point lights), so those lights sit
//! in the lanes of a vector (two vectors for five to eight), laid out once when the scene is
//! built, and each operation is done for four lights at once; lights without a position (an
//! environment, a directional light) are weighed one by one as before.
//!
//! Every lane computes what the light-by-light code computes, operation for operation and in the
//! same order (the products and sums of glam's `dot` and `length_squared`, a division for each
//! division, a correctly rounded square root for each square root, NaN and the signs of zero
//! handled as `f32::max` and `min` handle them where it matters), so each weight has the same
//! bits and so does every image. It covers the BSDFs whose weighing is arithmetic (diffuse, and a
//! rough conductor's lobe shape); any other BSDF, and a vertex on or inside a light, take the
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

/// One group of four lights, structure-of-arrays. Lanes of lights without a position, and
/// unused lanes, hold zeros and are never read.
#[derive(Clone, Copy, Debug, Default)]
struct Group {
    /// Centres (or positions), per axis.
    cx: Vec4,
    cy: Vec4,
    cz: Vec4,
    /// Squared distance at or within which the point is on or inside the light: a sphere's
    /// squared radius (as the light-by-light estimate computes it), else zero.
    inside2: Vec4,
    /// Luminance of the radiance (or intensity).
    lum: Vec4,
    /// Area of flat and other area lights.
    area: Vec4,
    /// Unit normal of the lit side of flat lights, per axis.
    nx: Vec4,
    ny: Vec4,
    nz: Vec4,
    /// Which lanes hold lights with a position, and of which kind.
    placed: u32,
    sphere: BVec4A,
    flat: BVec4A,
    solid: BVec4A,
    point: BVec4A,
}

/// A scene's 2 to [`LANE_LIGHTS`] lights four to a vector: light `k` is lane `k % 4` of group
/// `k / 4`.
#[derive(Clone, Debug)]
pub struct LightLanes {
    /// Number of lights.
    n: usize,
    groups: [Group; GROUPS],
    /// Bit `k` set: light `k` has no position and is weighed on its own.
    alone: u32,
}

impl LightLanes {
    /// The lanes of `bounds` when there are 2 to [`LANE_LIGHTS`] of them, at least two with a
    /// position (one vector would otherwise hold a single light); `None` otherwise.
    pub fn of(bounds: &[LightBound]) -> Option<LightLanes> {
        if !(2..=LANE_LIGHTS).contains(&bounds.len()) {
            return None;
        }
        let mut l = LightLanes {
            n: bounds.len(),
            groups: [Group::default(); GROUPS],
            alone: 0,
        };
        for (k, b) in bounds.iter().enumerate() {
            let g = &mut l.groups[k / 4];
            let i = k % 4;
            let at = match *b {
                LightBound::Sphere {
                    center,
                    radius,
                    lum,
                } => {
                    g.inside2[i] = radius * radius;
                    g.lum[i] = lum;
                    g.sphere.set(i, true);
                    center
                }
                LightBound::Flat {
                    center,
                    normal,
                    area,
                    lum,
                } => {
                    (g.nx[i], g.ny[i], g.nz[i]) = (normal.x, normal.y, normal.z);
                    (g.area[i], g.lum[i]) = (area, lum);
                    g.flat.set(i, true);
                    center
                }
                LightBound::Solid { center, area, lum } => {
                    (g.area[i], g.lum[i]) = (area, lum);
                    g.solid.set(i, true);
                    center
                }
                LightBound::Point { position, lum } => {
                    g.lum[i] = lum;
                    g.point.set(i, true);
                    position
                }
                LightBound::Direction { .. } | LightBound::Environment { .. } => {
                    l.alone |= 1 << k;
                    continue;
                }
            };
            (g.cx[i], g.cy[i], g.cz[i]) = (at.x, at.y, at.z);
            g.placed |= 1 << i;
        }
        let placed = l.groups.iter().map(|g| g.placed.count_ones()).sum::<u32>();
        (placed >= 2).then_some(l)
    }

    /// Each light's weight at a vertex at `p` with shading frame `frame`, BSDF `bsdf` and local
    /// incident direction `wi` (the first `n` entries), and their sum in light order: what
    /// the light-by-light loop of vertex selection finds, bit for bit. Lights without a
    /// position take their weight from `alone(k)` (the loop's own code: `None` where it skips
    /// the light). `None` where that loop must run instead: a BSDF other than diffuse or a
    /// rough conductor, or a vertex on or inside a light.
    #[inline]
    pub fn weights(
        &self,
        p: Vec3,
        frame: &Frame,
        bsdf: &Bsdf,
        wi: Vec3,
        alone: impl Fn(usize) -> Option<f32>,
    ) -> Option<([f32; LANE_LIGHTS], f32)> {
        let lobe_of = match bsdf {
            Bsdf::Diffuse(_) => None,
            Bsdf::RoughConductor(c) => Some(&c.distribution),
            _ => return None,
        };
        let mut weight = [0.0f32; LANE_LIGHTS];
        // Bit `k`: light `k` counts in the sum (the loop skips lights estimated at zero).
        let mut counted = 0u32;
        for (gi, g) in self.groups[..self.n.div_ceil(4)].iter().enumerate() {
            if g.placed == 0 {
                continue;
            }
            // The estimate (`LightBound::estimate`, through `from_point`).
            let d = Vec3x4 {
                x: g.cx - Vec4::splat(p.x),
                y: g.cy - Vec4::splat(p.y),
                z: g.cz - Vec4::splat(p.z),
            };
            let dist2 = d.dot(d);
            if dist2.cmpgt(g.inside2).bitmask() & g.placed != g.placed {
                return None;
            }
            let w = d.scale(Vec4::ONE / sqrt4(dist2));
            let irradiance = irradiance(g, w, dist2);
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
            let lit = irradiance.cmpgt(Vec4::ZERO).bitmask() & g.placed;
            for i in 0..4 {
                if lit & (1 << i) != 0 {
                    weight[4 * gi + i] = product[i];
                    counted |= 1 << (4 * gi + i);
                }
            }
        }
        let mut rest = self.alone;
        while rest != 0 {
            let k = rest.trailing_zeros() as usize;
            rest &= rest - 1;
            if let Some(w) = alone(k) {
                weight[k] = w;
                counted |= 1 << k;
            }
        }
        // Summed light by light, as the loop sums them.
        let mut sum = 0.0f32;
        for (k, &w) in weight[..self.n].iter().enumerate() {
            if counted & (1 << k) != 0 {
                sum += w;
            }
        }
        Some((weight, sum))
    }
}

/// Each lane's estimated irradiance (`LightBound::estimate`'s formula for the lane's kind), given
/// the unit direction `w` toward the light and the squared distance `dist2`. Only the kinds the
/// group holds are computed.
#[inline(always)]
fn irradiance(g: &Group, w: Vec3x4, dist2: Vec4) -> Vec4 {
    let two_pi = Vec4::splat(2.0 * PI);
    // `x.min(2 pi)` as `f32::min` gives it: 2 pi where `x` is NaN.
    let capped = |x: Vec4| Vec4::select(x.cmplt(two_pi), x, two_pi);
    let mut e = Vec4::ZERO;
    if g.sphere.any() {
        // 2 pi (1 - cos theta_max), without cancellation for small spheres.
        let sin2 = g.inside2 / dist2;
        let s = g.lum * (two_pi * sin2 / (Vec4::ONE + sqrt4(Vec4::ONE - sin2)));
        e = Vec4::select(g.sphere, s, e);
    }
    if g.flat.any() {
        let cos = -(w.x * g.nx + w.y * g.ny + w.z * g.nz);
        let cos = Vec4::select(cos.cmpgt(Vec4::ZERO), cos, Vec4::ZERO);
        let f = g.lum * capped(g.area * cos / dist2);
        e = Vec4::select(g.flat, f, e);
    }
    if g.solid.any() {
        let f = g.lum * capped(Vec4::splat(0.25) * g.area / dist2);
        e = Vec4::select(g.solid, f, e);
    }
    if g.point.any() {
        e = Vec4::select(g.point, g.lum / dist2, e);
    }
    e
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
mod tests;
