//! `lean x8 zsobol in step`: the robust zsobol lean loop over the eight samples of one
//! aligned group at a time, in step, as a wavefront renderer runs its lanes.
//!
//! All eight lanes start together at the camera and go through the same bounce together; a
//! lane whose path ended is masked, not refilled, until the last lane ends. Because the lanes
//! are at the same depth, each stage is a loop over the eight lanes with no early exit, for the
//! compiler to vectorise; only the ray casts stay one ray at a time. The arithmetic is the lean
//! loop's, operation for operation, and a pixel's samples reach the film in the same order, so
//! the image has the bits of `lean x1 zsobol robust` (the bench checks it when it renders both).
use super::{bounce_draws, cosine_bounce, Lean, INV_PI, MAX_DEPTH, RR_DEPTH};
use glam::Vec3;
use tessera_core::geometry::{interpolate_point, SHADOW_EPSILON};
use tessera_core::math::{offset_ray_origin, Ray};
use tessera_core::sampling::zsobol::log2_spp_for;
use tessera_core::sampling::{Sampler, ZSobolPixel};

const L: usize = 8;

/// Three components of eight lanes.
type V3 = [[f32; L]; 3];

fn get(v: &V3, i: usize) -> Vec3 {
    Vec3::new(v[0][i], v[1][i], v[2][i])
}

fn set(v: &mut V3, i: usize, x: Vec3) {
    for k in 0..3 {
        v[k][i] = x[k];
    }
}

impl Lean<'_> {
    /// Renders every pixel's `spp` samples (a multiple of 8) eight in step; returns the sums.
    #[inline(never)]
    pub fn render_in_step(&self, pixels: u32) -> Vec<[f32; 3]> {
        assert!(
            self.spp.is_multiple_of(L as u32),
            "in-step lanes need spp a multiple of 8"
        );
        let t = &self.t;
        let log2_spp = log2_spp_for(u64::from(self.spp));
        let mut zs = ZSobolPixel::new(0, 0, 0, 0);
        let mut film = vec![[0f32; 3]; pixels as usize];
        for pixel in 0..pixels {
            zs.move_to(0, pixel % self.width, pixel / self.width, log2_spp);
            zs.set_run(0..u64::from(self.spp));
            for base in (0..self.spp).step_by(L) {
                let mut o: V3 = [[0.0; L]; 3];
                let mut d: V3 = [[0.0; L]; 3];
                for i in 0..L {
                    let off = zs.sampler(u64::from(base) + i as u64).next_2d();
                    let ray = self.camera_ray(pixel, off);
                    set(&mut o, i, ray.o);
                    set(&mut d, i, ray.d);
                }
                let mut throughput: V3 = [[1.0; L]; 3];
                let mut radiance: V3 = [[0.0; L]; 3];
                let mut prev_pdf = [0f32; L];
                let mut live = [true; L];
                for depth in 0..MAX_DEPTH {
                    if !live.iter().any(|&a| a) {
                        break;
                    }
                    // Closest hits, one ray at a time.
                    let mut dist = [0f32; L];
                    let mut prim = [0usize; L];
                    let mut b1 = [0f32; L];
                    let mut b2 = [0f32; L];
                    for i in 0..L {
                        if !live[i] {
                            continue;
                        }
                        let ray = Ray {
                            o: get(&o, i),
                            d: get(&d, i),
                            t_max: f32::INFINITY,
                        };
                        match self.scene.intersect_hit(&ray) {
                            Some(h) => {
                                (dist[i], prim[i]) = (h.t, h.prim as usize);
                                (b1[i], b2[i]) = (h.uv.x, h.uv.y);
                            }
                            None => live[i] = false,
                        }
                    }
                    // Draws: the group's first lane fills each dimension for all eight.
                    let mut u = [[0f32; L]; 6];
                    for i in 0..L {
                        let v = bounce_draws(&mut zs.sampler(u64::from(base) + i as u64), depth);
                        for k in 0..6 {
                            u[k][i] = v[k];
                        }
                    }
                    // The hit primitives' rows and the hit points with their error bounds.
                    let mut n: V3 = [[0.0; L]; 3];
                    let mut albedo: V3 = [[0.0; L]; 3];
                    let mut emission: V3 = [[0.0; L]; 3];
                    let mut p: V3 = [[0.0; L]; 3];
                    let mut p_err: V3 = [[0.0; L]; 3];
                    for i in 0..L {
                        let r = prim[i];
                        let [a, b, c] = t.corners[r];
                        let (q, e) = interpolate_point(a, b, c, b1[i], b2[i]);
                        set(&mut p, i, q);
                        set(&mut p_err, i, e);
                        for k in 0..3 {
                            n[k][i] = t.normal[r][k];
                            albedo[k][i] = t.albedo[r][k];
                            emission[k][i] = t.emission[r][k];
                        }
                    }
                    // Emission found by the ray.
                    let mut go_on = [false; L];
                    for i in 0..L {
                        let dn = n[0][i] * d[0][i] + n[1][i] * d[1][i] + n[2][i] * d[2][i];
                        let cos_at_light = -dn;
                        let flip = if dn > 0.0 { -1.0 } else { 1.0 };
                        for nk in n.iter_mut() {
                            nk[i] *= flip;
                        }
                        let emits = live[i]
                            && emission[0][i] + emission[1][i] + emission[2][i] > 0.0
                            && cos_at_light > 0.0;
                        let light_pdf = dist[i] * dist[i] / (cos_at_light * t.light_area);
                        let w = if depth == 0 {
                            1.0
                        } else {
                            let b = prev_pdf[i] * prev_pdf[i];
                            b / (b + light_pdf * light_pdf)
                        };
                        for k in 0..3 {
                            let add = throughput[k][i] * emission[k][i] * w;
                            radiance[k][i] += if emits { add } else { 0.0 };
                        }
                        go_on[i] = live[i] && depth + 1 < MAX_DEPTH;
                    }
                    // One emitter sample per lane and its shadow segment.
                    let mut shadow_o: V3 = [[0.0; L]; 3];
                    let mut shadow_d: V3 = [[0.0; L]; 3];
                    let mut ok = [false; L];
                    let mut light_value: V3 = [[0.0; L]; 3];
                    for i in 0..L {
                        let second = t.light.len() > 1 && u[0][i] >= t.light[0].cdf;
                        let tri = &t.light[usize::from(second)];
                        let su = u[1][i].sqrt();
                        let (lb1, lb2) = (1.0 - su, u[2][i] * su);
                        let [a, b, c] = tri.corners;
                        let (lp, lp_err) = interpolate_point(a, b, c, lb1, lb2);
                        let pi = get(&p, i);
                        let mut wo = lp - pi;
                        let d2 = wo.x * wo.x + wo.y * wo.y + wo.z * wo.z;
                        let dl = d2.sqrt();
                        wo /= dl;
                        let cos_l =
                            -(tri.normal[0] * wo.x + tri.normal[1] * wo.y + tri.normal[2] * wo.z);
                        let ni = get(&n, i);
                        let cos_s = ni.x * wo.x + ni.y * wo.y + ni.z * wo.z;
                        let light_pdf = d2 / (cos_l * t.light_area);
                        let bsdf_pdf = cos_s * INV_PI;
                        let w =
                            light_pdf * light_pdf / (light_pdf * light_pdf + bsdf_pdf * bsdf_pdf);
                        ok[i] = go_on[i] && cos_l > 0.0 && cos_s > 0.0;
                        let tn = Vec3::from(tri.normal);
                        let target = offset_ray_origin(lp, lp_err, tn, pi - lp);
                        let so = offset_ray_origin(pi, get(&p_err, i), ni, target - pi);
                        set(&mut shadow_o, i, so);
                        set(&mut shadow_d, i, target - so);
                        for k in 0..3 {
                            light_value[k][i] = throughput[k][i]
                                * albedo[k][i]
                                * INV_PI
                                * cos_s
                                * t.radiance[k]
                                * w
                                / light_pdf;
                        }
                    }
                    // Shadow rays, one at a time.
                    for i in 0..L {
                        if !ok[i] {
                            continue;
                        }
                        let shadow = Ray {
                            o: get(&shadow_o, i),
                            d: get(&shadow_d, i),
                            t_max: 1.0 - SHADOW_EPSILON,
                        };
                        if !self.scene.occluded(&shadow) {
                            for k in 0..3 {
                                radiance[k][i] += light_value[k][i];
                            }
                        }
                    }
                    // Cosine-weighted bounce (Duff et al.'s frame), then Russian roulette.
                    for i in 0..L {
                        let (dir, lz) = cosine_bounce(get(&n, i).to_array(), u[3][i], u[4][i]);
                        for k in 0..3 {
                            d[k][i] = dir[k];
                            throughput[k][i] *= albedo[k][i];
                        }
                        let origin =
                            offset_ray_origin(get(&p, i), get(&p_err, i), get(&n, i), get(&d, i));
                        set(&mut o, i, origin);
                        prev_pdf[i] = lz * INV_PI;
                        let mut keep = go_on[i] && lz > 0.0;
                        if depth + 1 >= RR_DEPTH {
                            let q = throughput[0][i]
                                .max(throughput[1][i])
                                .max(throughput[2][i])
                                .min(0.95);
                            keep &= u[5][i] < q;
                            for k in 0..3 {
                                throughput[k][i] /= q;
                            }
                        }
                        live[i] = keep;
                    }
                }
                for i in 0..L {
                    for k in 0..3 {
                        film[pixel as usize][k] += radiance[k][i];
                    }
                }
            }
        }
        film
    }
}
