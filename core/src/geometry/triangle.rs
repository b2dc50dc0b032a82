//! Watertight ray-triangle intersection (Woop, Benthin and Wald 2013, as in pbrt-v4).
//!
//! The ray is sheared so it runs along +z; the edge functions are then evaluated in 2-D. Rays
//! through a shared edge or vertex hit exactly one of the triangles around it (or both, never
//! neither). Edge functions that round to exactly zero are recomputed in f64. The hit distance is
//! accepted only beyond its own error bound, so a ray leaving a surface never re-hits it; a
//! distance within the f32 bound is recomputed in f64 and judged against the f64 bound, so a
//! ray leaving a surface very near another (a concave edge or corner) still hits the other.
use crate::math::{gamma, Ray};
use glam::{DVec3, Vec3};

/// The per-ray part of the test, computed once per ray and reused for every triangle: the axis
/// permutation making the direction's largest component z, and the shear to +z.
#[derive(Clone, Copy, Debug)]
pub struct TriRay {
    o: Vec3,
    /// `kx, ky, kz`: the permutation (`kz` the largest direction component).
    k: [usize; 3],
    sx: f32,
    sy: f32,
    sz: f32,
}

impl TriRay {
    /// Precomputes the permutation and shear of `ray`.
    #[inline]
    pub fn new(ray: &Ray) -> TriRay {
        let d_abs = ray.d.abs();
        // The largest component by selects, not nested branches: a ray's dominant axis is as
        // good as random, so branches here mispredicted often. Ties resolve as before (x over
        // y only when strictly larger, then z unless strictly smaller).
        let x_over_y = d_abs.x > d_abs.y;
        let big = if x_over_y { d_abs.x } else { d_abs.y };
        let kz = if big > d_abs.z {
            (!x_over_y) as usize
        } else {
            2
        };
        const NEXT: [usize; 3] = [1, 2, 0];
        let kx = NEXT[kz];
        let ky = NEXT[kx];
        let d = ray.d.to_array();
        let sz = 1.0 / d[kz];
        TriRay {
            o: ray.o,
            k: [kx, ky, kz],
            sx: -d[kx] * sz,
            sy: -d[ky] * sz,
            sz,
        }
    }

    /// The setup with origin `o`, axis permutation `k` and shear `s`, as [`TriRay::parts`]
    /// returns them (so `from_parts` of `parts` is the same setup, bit for bit).
    #[inline(always)]
    pub(crate) fn from_parts(o: Vec3, k: [usize; 3], s: [f32; 3]) -> TriRay {
        TriRay {
            o,
            k,
            sx: s[0],
            sy: s[1],
            sz: s[2],
        }
    }

    /// The origin, the axis permutation `[kx, ky, kz]` (the ray is sheared along `kz`, its
    /// largest direction component) and the shear `(sx, sy, sz)`: what the four-lane test
    /// (`accel::tri_block`) needs to repeat this test's operations exactly.
    #[inline(always)]
    pub fn parts(&self) -> (Vec3, [usize; 3], [f32; 3]) {
        (self.o, self.k, [self.sx, self.sy, self.sz])
    }

    /// Intersects the ray (within `[0, t_max)`) with the triangle; returns `(t, b0, b1, b2)`.
    #[inline]
    pub fn intersect(
        &self,
        t_max: f32,
        p0: Vec3,
        p1: Vec3,
        p2: Vec3,
    ) -> Option<(f32, f32, f32, f32)> {
        match self.k[2] {
            0 => self.hit::<1, 2, 0>(t_max, p0, p1, p2),
            1 => self.hit::<2, 0, 1>(t_max, p0, p1, p2),
            _ => self.hit::<0, 1, 2>(t_max, p0, p1, p2),
        }
    }

    #[inline(always)]
    fn hit<const KX: usize, const KY: usize, const KZ: usize>(
        &self,
        t_max: f32,
        p0: Vec3,
        p1: Vec3,
        p2: Vec3,
    ) -> Option<(f32, f32, f32, f32)> {
        let permute = |v: Vec3| Vec3::new(v[KX], v[KY], v[KZ]);
        let mut a = permute(p0 - self.o);
        let mut b = permute(p1 - self.o);
        let mut c = permute(p2 - self.o);
        let (sx, sy, sz) = (self.sx, self.sy, self.sz);
        a.x += sx * a.z;
        a.y += sy * a.z;
        b.x += sx * b.z;
        b.y += sy * b.z;
        c.x += sx * c.z;
        c.y += sy * c.z;
        let mut e0 = b.x * c.y - b.y * c.x;
        let mut e1 = c.x * a.y - c.y * a.x;
        let mut e2 = a.x * b.y - a.y * b.x;
        if e0 == 0.0 || e1 == 0.0 || e2 == 0.0 {
            let (ad, bd, cd) = (a.as_dvec3(), b.as_dvec3(), c.as_dvec3());
            e0 = (bd.x * cd.y - bd.y * cd.x) as f32;
            e1 = (cd.x * ad.y - cd.y * ad.x) as f32;
            e2 = (ad.x * bd.y - ad.y * bd.x) as f32;
        }
        if (e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0) {
            return None;
        }
        let det = e0 + e1 + e2;
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        // The shear's error grows with the unscaled depths (|sx|, |sy| <= 1): keep their bound
        // before z is divided by d.z, which makes it a ray parameter, not a length.
        let max_z_len = Vec3::new(a.z, b.z, c.z).abs().max_element();
        a.z *= sz;
        b.z *= sz;
        c.z *= sz;
        let t_scaled = e0 * a.z + e1 * b.z + e2 * c.z;
        if det < 0.0 && (t_scaled >= 0.0 || t_scaled < t_max * det) {
            return None;
        }
        if det > 0.0 && (t_scaled <= 0.0 || t_scaled > t_max * det) {
            return None;
        }
        let inv_det = 1.0 / det;
        let t = t_scaled * inv_det;
        if t.partial_cmp(&t_max) != Some(core::cmp::Ordering::Less) {
            return None;
        }
        // Conservative lower bound: t must exceed its own rounding error.
        let max_zt = Vec3::new(a.z, b.z, c.z).abs().max_element();
        let delta_z = gamma(3) * max_zt;
        let max_xt = Vec3::new(a.x, b.x, c.x).abs().max_element();
        let max_yt = Vec3::new(a.y, b.y, c.y).abs().max_element();
        let delta_x = gamma(5) * (max_xt + max_z_len);
        let delta_y = gamma(5) * (max_yt + max_z_len);
        let delta_e = 2.0 * (gamma(2) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
        let max_e = Vec3::new(e0, e1, e2).abs().max_element();
        let delta_t =
            3.0 * (gamma(3) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) * inv_det.abs();
        if t <= delta_t {
            return self.near_hit::<KX, KY, KZ>(t_max, delta_t, p0, p1, p2);
        }
        Some((t, e0 * inv_det, e1 * inv_det, e2 * inv_det))
    }

    /// A hit the f32 test found inside the triangle but no farther than its own error bound
    /// `delta_t`: the distance recomputed in f64 from the same corners, origin and shear, and
    /// accepted beyond the same bound in f64 arithmetic. Each of the bound's terms is linear in
    /// one `gamma(n)`, and f64's are at most 4/3 x 2^-29 of f32's (one more rounding, for the
    /// subtraction from the origin), so `2^-28 delta_t` bounds the f64 distance's error with
    /// room for the rounding of the bound itself. The f32 bound is loose when the
    /// corners lie far along the ray's main axis, so a surface a ray leaves within ~1e-6 of
    /// another (at a concave edge or corner) would otherwise let the ray through the neighbour;
    /// a ray leaving its own surface, whose offset origin lies strictly on the departing side,
    /// still finds a negative distance here.
    #[inline(never)]
    fn near_hit<const KX: usize, const KY: usize, const KZ: usize>(
        &self,
        t_max: f32,
        delta_t: f32,
        p0: Vec3,
        p1: Vec3,
        p2: Vec3,
    ) -> Option<(f32, f32, f32, f32)> {
        let o = self.o.as_dvec3();
        let (sx, sy, sz) = (self.sx as f64, self.sy as f64, self.sz as f64);
        let sheared = |v: Vec3| {
            let d = v.as_dvec3() - o;
            let (x, y, z) = (d[KX], d[KY], d[KZ]);
            DVec3::new(x + sx * z, y + sy * z, z)
        };
        let (a, b, c) = (sheared(p0), sheared(p1), sheared(p2));
        let e0 = b.x * c.y - b.y * c.x;
        let e1 = c.x * a.y - c.y * a.x;
        let e2 = a.x * b.y - a.y * b.x;
        let det = e0 + e1 + e2;
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let inv_det = 1.0 / det;
        let t = (e0 * a.z + e1 * b.z + e2 * c.z) * sz * inv_det;
        let t32 = t as f32;
        if !(t > delta_t as f64 * F64_BOUND_SCALE && t32 > 0.0 && t32 < t_max) {
            return None;
        }
        // The f32 edge functions decided the ray is inside; f64 ones of a ray along an edge
        // may be a rounding below zero.
        let bary = |e: f64| (e * inv_det).max(0.0) as f32;
        Some((t32, bary(e0), bary(e1), bary(e2)))
    }
}

/// 2^-28: the f64 distance's error bound as a fraction of the f32 test's (see
/// `TriRay::near_hit`).
const F64_BOUND_SCALE: f64 = 1.0 / (1u64 << 28) as f64;

/// Intersects `ray` (within `[0, t_max)`) with the triangle; returns `(t, b0, b1, b2)`.
/// Same as [`TriRay::intersect`] after [`TriRay::new`]; prefer those when testing many
/// triangles against one ray.
#[inline]
pub fn intersect_triangle(
    ray: &Ray,
    t_max: f32,
    p0: Vec3,
    p1: Vec3,
    p2: Vec3,
) -> Option<(f32, f32, f32, f32)> {
    TriRay::new(ray).intersect(t_max, p0, p1, p2)
}
