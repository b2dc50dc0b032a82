//! `lean x8 zsobol avx2`: `lean x8 zsobol in step` (`in_step.rs`) with every stage between the
//! casts written for the vector unit by hand ([`F8`]: eight lanes in one AVX register) instead
//! of left to the compiler. The question it answers: does shading eight paths per instruction
//! pay, once it is not the compiler's partial vectorisation (measured before: in step was 8% slower
//! than one path at a time)?
//!
//! What stays one lane at a time: the ray casts, the sampler's draws (Tessera's `ZSobolPixel`,
//! one call per lane and dimension) and the gathers of each lane's primitive rows. Everything
//! else (hit points and their error bounds, emission and its MIS weight, the light point, its
//! error bound and both ray offsets, the shadow segment, the cosine bounce with its frame and
//! the polynomial sine and cosine, Russian roulette) runs on eight lanes per instruction, with
//! the scalar code's operations in the scalar code's order, so every lane computes the same bits
//! and the image is that of `lean x1 zsobol robust` (the bench checks it).
use super::f8::{step_away, F8, M8};
use super::{bounce_draws, Lean, INV_PI, MAX_DEPTH, RR_DEPTH};
use glam::Vec3;
use tessera_core::geometry::SHADOW_EPSILON;
use tessera_core::math::{gamma, Ray};
use tessera_core::sampling::zsobol::log2_spp_for;
use tessera_core::sampling::{Sampler, ZSobolPixel};

const L: usize = 8;

/// A vector of eight lanes per component.
type V3 = [F8; 3];

fn splat3(x: f32) -> V3 {
    [F8::splat(x); 3]
}

/// `a . b`, summed left to right (glam's order).
#[inline(always)]
fn dot(a: &V3, b: &V3) -> F8 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The renderer's `interpolate_point` on eight lanes: the point at barycentrics `(b1, b2)` and its
/// error bound.
#[inline(always)]
fn interpolate(c: &[V3; 3], b1: F8, b2: F8) -> (V3, V3) {
    let b0 = F8::splat(1.0) - b1 - b2;
    let g7 = F8::splat(gamma(7));
    let p = [0, 1, 2].map(|k| c[0][k] * b0 + c[1][k] * b1 + c[2][k] * b2);
    let e = [0, 1, 2]
        .map(|k| ((c[0][k] * b0).abs() + (c[1][k] * b1).abs() + (c[2][k] * b2).abs()) * g7);
    (p, e)
}

/// The renderer's `offset_ray_origin` on eight lanes.
#[inline(always)]
fn offset_ray_origin(p: &V3, p_err: &V3, n: &V3, w: &V3) -> V3 {
    let d = n[0].abs() * p_err[0] + n[1].abs() * p_err[1] + n[2].abs() * p_err[2];
    let toward = dot(w, n).lt(F8::splat(0.0));
    let d = toward.select(-d, d);
    [0, 1, 2].map(|k| {
        let off = n[k] * d;
        step_away(p[k] + off, off)
    })
}

/// The lean loop's `sincos_turns_poly` on eight lanes.
#[inline(always)]
fn sincos_turns(u: F8) -> (F8, F8) {
    let s1 = F8::splat;
    let h = (u - (u + s1(0.5)).floor()) * s1(std::f32::consts::PI);
    let h2 = h * h;
    let s = h
        * (s1(1.0)
            + h2 * (s1(-1.0 / 6.0)
                + h2 * (s1(1.0 / 120.0) + h2 * (s1(-1.0 / 5040.0) + h2 / s1(362_880.0)))));
    let c = s1(1.0)
        + h2 * (s1(-0.5)
            + h2 * (s1(1.0 / 24.0)
                + h2 * (s1(-1.0 / 720.0) + h2 * (s1(1.0 / 40_320.0) - h2 / s1(3_628_800.0)))));
    (s1(2.0) * s * c, c * c - s * s)
}

/// The lean loop's `cosine_bounce` on eight lanes: direction and its cosine to `n`.
#[inline(always)]
fn cosine_bounce(n: &V3, u1: F8, u2: F8) -> (V3, F8) {
    let s1 = F8::splat;
    let r = u1.sqrt();
    let (s, c) = sincos_turns(u2);
    let lz = (s1(1.0) - u1).max(s1(0.0)).sqrt();
    let (lx, ly) = (r * c, r * s);
    let [nx, ny, nz] = *n;
    let sign = nz.ge(s1(0.0)).select(s1(1.0), s1(-1.0));
    let a = s1(-1.0) / (sign + nz);
    let b = nx * ny * a;
    let tan1 = [s1(1.0) + sign * nx * nx * a, sign * b, -sign * nx];
    let tan2 = [b, sign + ny * ny * a, -ny];
    (
        [0, 1, 2].map(|k| tan1[k] * lx + tan2[k] * ly + n[k] * lz),
        lz,
    )
}

/// Lane `i` of a vector triple.
fn lane(v: &V3, i: usize) -> Vec3 {
    let mut a = [[0f32; L]; 3];
    for k in 0..3 {
        v[k].store(&mut a[k]);
    }
    Vec3::new(a[0][i], a[1][i], a[2][i])
}

/// Eight lanes' values of `f(i)`.
#[inline(always)]
fn gather(f: impl Fn(usize) -> f32) -> F8 {
    F8::load(&std::array::from_fn(f))
}

impl Lean<'_> {
    /// Renders every pixel's `spp` samples (a multiple of 8) eight in step, stages on the vector
    /// unit; returns the sums.
    #[inline(never)]
    pub fn render_in_step_avx2(&self, pixels: u32) -> Vec<[f32; 3]> {
        assert!(
            self.spp.is_multiple_of(L as u32),
            "in-step lanes need spp a multiple of 8"
        );
        let t = &self.t;
        let s1 = F8::splat;
        let log2_spp = log2_spp_for(u64::from(self.spp));
        let mut zs = ZSobolPixel::new(0, 0, 0, 0);
        let mut film = vec![[0f32; 3]; pixels as usize];
        let light_area = s1(t.light_area);
        let two_lights = t.light.len() > 1;
        let (l0, l1) = (&t.light[0], &t.light[usize::from(two_lights)]);
        let light_cdf0 = s1(l0.cdf);
        for pixel in 0..pixels {
            zs.move_to(0, pixel % self.width, pixel / self.width, log2_spp);
            zs.set_run(0..u64::from(self.spp));
            for base in (0..self.spp).step_by(L) {
                let mut oa = [[0f32; L]; 3];
                let mut da = [[0f32; L]; 3];
                for i in 0..L {
                    let off = zs.sampler(u64::from(base) + i as u64).next_2d();
                    let ray = self.camera_ray(pixel, off);
                    for k in 0..3 {
                        oa[k][i] = ray.o[k];
                        da[k][i] = ray.d[k];
                    }
                }
                let mut o: V3 = oa.map(|a| F8::load(&a));
                let mut d: V3 = da.map(|a| F8::load(&a));
                let mut throughput = splat3(1.0);
                let mut radiance = splat3(0.0);
                let mut prev_pdf = s1(0.0);
                let mut live = 0xffu32;
                for depth in 0..MAX_DEPTH {
                    if live == 0 {
                        break;
                    }
                    // Closest hits, one ray at a time.
                    let (mut oa, mut da) = ([[0f32; L]; 3], [[0f32; L]; 3]);
                    for k in 0..3 {
                        o[k].store(&mut oa[k]);
                        d[k].store(&mut da[k]);
                    }
                    let mut dist = [0f32; L];
                    let mut prim = [0usize; L];
                    let mut b1 = [0f32; L];
                    let mut b2 = [0f32; L];
                    for i in 0..L {
                        if live & (1 << i) == 0 {
                            continue;
                        }
                        let ray = Ray {
                            o: Vec3::new(oa[0][i], oa[1][i], oa[2][i]),
                            d: Vec3::new(da[0][i], da[1][i], da[2][i]),
                            t_max: f32::INFINITY,
                        };
                        match self.scene.intersect_hit(&ray) {
                            Some(h) => {
                                (dist[i], prim[i]) = (h.t, h.prim as usize);
                                (b1[i], b2[i]) = (h.uv.x, h.uv.y);
                            }
                            None => live &= !(1 << i),
                        }
                    }
                    let live_m = M8::from_bits(live);
                    // Draws, one lane at a time.
                    let mut ua = [[0f32; L]; 6];
                    for i in 0..L {
                        let v = bounce_draws(&mut zs.sampler(u64::from(base) + i as u64), depth);
                        for k in 0..6 {
                            ua[k][i] = v[k];
                        }
                    }
                    let u = ua.map(|a| F8::load(&a));
                    // The hit primitives' rows (gathered), the hit points and error bounds.
                    let corner: [V3; 3] = std::array::from_fn(|c| {
                        std::array::from_fn(|k| gather(|i| t.corners[prim[i]][c][k]))
                    });
                    let mut n: V3 = std::array::from_fn(|k| gather(|i| t.normal[prim[i]][k]));
                    let albedo: V3 = std::array::from_fn(|k| gather(|i| t.albedo[prim[i]][k]));
                    let emission: V3 = std::array::from_fn(|k| gather(|i| t.emission[prim[i]][k]));
                    let (p, p_err) = interpolate(&corner, F8::load(&b1), F8::load(&b2));
                    let dist = F8::load(&dist);
                    // Emission found by the ray.
                    let dn = dot(&n, &d);
                    let cos_at_light = -dn;
                    let flip = dn.gt(s1(0.0)).select(s1(-1.0), s1(1.0));
                    n = n.map(|nk| nk * flip);
                    let emits = live_m
                        .and((emission[0] + emission[1] + emission[2]).gt(s1(0.0)))
                        .and(cos_at_light.gt(s1(0.0)));
                    let light_pdf = dist * dist / (cos_at_light * light_area);
                    let w = if depth == 0 {
                        s1(1.0)
                    } else {
                        let b = prev_pdf * prev_pdf;
                        b / (b + light_pdf * light_pdf)
                    };
                    for k in 0..3 {
                        let add = throughput[k] * emission[k] * w;
                        radiance[k] = radiance[k] + emits.select(add, s1(0.0));
                    }
                    let go_on = if depth + 1 < MAX_DEPTH { live } else { 0 };
                    // One emitter sample per lane and its shadow segment.
                    let second = if two_lights {
                        u[0].ge(light_cdf0)
                    } else {
                        M8::from_bits(0)
                    };
                    let pick = |a: f32, b: f32| second.select(s1(b), s1(a));
                    let lc: [V3; 3] = std::array::from_fn(|c| {
                        std::array::from_fn(|k| pick(l0.corners[c][k], l1.corners[c][k]))
                    });
                    let tn: V3 = std::array::from_fn(|k| pick(l0.normal[k], l1.normal[k]));
                    let su = u[1].sqrt();
                    let (lp, lp_err) = interpolate(&lc, s1(1.0) - su, u[2] * su);
                    let mut wo: V3 = [0, 1, 2].map(|k| lp[k] - p[k]);
                    let d2 = wo[0] * wo[0] + wo[1] * wo[1] + wo[2] * wo[2];
                    let dl = d2.sqrt();
                    wo = wo.map(|x| x / dl);
                    let cos_l = -dot(&tn, &wo);
                    let cos_s = dot(&n, &wo);
                    let light_pdf = d2 / (cos_l * light_area);
                    let bsdf_pdf = cos_s * s1(INV_PI);
                    let w = light_pdf * light_pdf / (light_pdf * light_pdf + bsdf_pdf * bsdf_pdf);
                    let ok = go_on & cos_l.gt(s1(0.0)).and(cos_s.gt(s1(0.0))).bits();
                    let to_p = [0, 1, 2].map(|k| p[k] - lp[k]);
                    let target = offset_ray_origin(&lp, &lp_err, &tn, &to_p);
                    let to_target = [0, 1, 2].map(|k| target[k] - p[k]);
                    let so = offset_ray_origin(&p, &p_err, &n, &to_target);
                    let sd: V3 = [0, 1, 2].map(|k| target[k] - so[k]);
                    let light_value: V3 = std::array::from_fn(|k| {
                        throughput[k] * albedo[k] * s1(INV_PI) * cos_s * s1(t.radiance[k]) * w
                            / light_pdf
                    });
                    // Shadow rays, one at a time.
                    let mut unoccluded = 0u32;
                    let mut m = ok;
                    while m != 0 {
                        let i = m.trailing_zeros() as usize;
                        m &= m - 1;
                        let shadow = Ray {
                            o: lane(&so, i),
                            d: lane(&sd, i),
                            t_max: 1.0 - SHADOW_EPSILON,
                        };
                        if !self.scene.occluded(&shadow) {
                            unoccluded |= 1 << i;
                        }
                    }
                    let add = M8::from_bits(unoccluded);
                    for k in 0..3 {
                        radiance[k] = add.select(radiance[k] + light_value[k], radiance[k]);
                    }
                    // Cosine-weighted bounce (Duff et al.'s frame), then Russian roulette.
                    let (dir, lz) = cosine_bounce(&n, u[3], u[4]);
                    d = dir;
                    for k in 0..3 {
                        throughput[k] = throughput[k] * albedo[k];
                    }
                    o = offset_ray_origin(&p, &p_err, &n, &d);
                    prev_pdf = lz * s1(INV_PI);
                    let mut keep = go_on & lz.gt(s1(0.0)).bits();
                    if depth + 1 >= RR_DEPTH {
                        let q = throughput[0]
                            .max(throughput[1])
                            .max(throughput[2])
                            .min(s1(0.95));
                        keep &= u[5].lt(q).bits();
                        throughput = throughput.map(|x| x / q);
                    }
                    live = keep;
                }
                let mut ra = [[0f32; L]; 3];
                for k in 0..3 {
                    radiance[k].store(&mut ra[k]);
                }
                for i in 0..L {
                    for k in 0..3 {
                        film[pixel as usize][k] += ra[k][i];
                    }
                }
            }
        }
        film
    }
}
