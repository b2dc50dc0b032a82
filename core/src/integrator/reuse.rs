//! Path reuse across the pixels of a 4x2 group (after Bekaert, Sbert and Halton, "Accelerating
//! path tracing by re-using paths", EGWR 2002): each pixel's first vertex `x` gathers the light
//! reflected at every group member's second vertex `y`, not only at its own.
//!
//! Scene parameter (`<integrator type="path">`): `reuse` (boolean, default false). Used only where
//! it can apply: `max_depth` of 3 or more (a second vertex that reflects light) and `rr_depth` of
//! 2 or more (no roulette before the second vertex).
//!
//! The estimator. Each pixel `k` traces its path as usual up to its second vertex `y_k` (the
//! prefix, `reuse_halves.rs`, made of the path tracer's own steps), counting everything found on
//! the way (emission at `x_k` and `y_k`, emitter sampling at `x_k`). Where
//! `y_k` is Lambertian ([`crate::bsdf::Bsdf::is_lambertian`]) and was reached by a smooth bounce,
//! the light it reflects, `L_k`, is the same toward every direction on the side `x_k` is on; the
//! rest of the path (the suffix) estimates it once (throughput 1 from `y_k`, Russian roulette still seeing
//! the whole path's throughput). Pixel `i` then adds, for each such `y_j` seen from its side,
//!
//! `f_i(x_i -> y_j) G(x_i, y_j) V(x_i, y_j) L_j / sum_m p_m(y_j)`,
//!
//! where `p_m(y)` is the area density with which pixel `m`'s BSDF sampling at `x_m` reaches `y`
//! (its solid-angle density times `|cos| / dist^2`, times the visibility of `y` from `x_m`; zero
//! for an `x_m` on the other side of `y`'s surface). This is the balance heuristic over the
//! group's samplers, one sample from each, so each pixel's estimate stays unbiased; with no
//! neighbour it is the usual `f G L / p_i`. Second vertices that are not Lambertian, or that a
//! delta component reached, go on as ordinary paths for their own pixel. Emission at `y` keeps
//! its own pixel's MIS weight and is not shared.
//!
//! The cost: up to 56 shadow rays per group of eight (each pair of first and second vertices,
//! seven per pixel), eight BSDF densities and evaluations per second vertex. Neighbouring pixels' noise becomes
//! correlated; each pixel's error does not grow.
use super::path::PathIntegrator;
use super::path_state::PathState;
use super::probe::{Probe, RayKind};
use super::reuse_halves::Prefix;
use super::strategy::{Strategy, BSDF, EMITTER, HALF, MIS};
use crate::geometry::{Interaction, LookupMemo, ShadingPoint};
use crate::math::{offset_ray_origin, Ray};
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::Color;

/// Columns of a reuse group: groups are `GROUP_W x GROUP_H` blocks of pixels at multiples of
/// these (clipped at the image's edge). Measured on cbox (128x128, zsobol, 4 seeds, error and
/// time at 8 spp): 4x2 groups have 0.71x the error of 2x2 for 1.13x the time, 4x4 0.56x for
/// 1.41x and 3x3 0.69x for 1.47x; 4x2 reaches relMSE 1e-2 first (0.095 s, 2x2 0.112 s, 4x4
/// 0.097 s, 3x3 0.119 s).
pub const GROUP_W: u32 = 4;
/// Rows of a reuse group.
pub const GROUP_H: u32 = 2;
/// Most pixels in a reuse group.
pub const GROUP: usize = (GROUP_W * GROUP_H) as usize;

impl PathIntegrator {
    /// Whether [`PathIntegrator::li_group`] shares light among pixels with these settings.
    pub fn reuses(&self) -> bool {
        self.reuse && self.max_depth.is_none_or(|d| d >= 3) && self.rr_depth >= 2
    }

    /// One sample's radiance for each pixel of a group: `rays[k]` is pixel `k`'s camera ray,
    /// drawn from `samplers[k]`, which the path goes on drawing from, or `None` for a pixel that
    /// does not take this sample (it neither shares nor receives light; its `samplers[k]` is not
    /// touched and `out[k]` is zero). Writes `out[..rays.len()]`. Without
    /// [`PathIntegrator::reuses`], each value is [`PathIntegrator::li_probed`]'s.
    pub fn li_group<S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        rays: &[Option<Ray>],
        samplers: &mut [S],
        probe: &mut P,
        out: &mut [Color],
    ) {
        let n = rays.len().min(GROUP);
        out[..n].fill(Color::ZERO);
        if !self.reuses() {
            for k in 0..n {
                if let Some(ray) = rays[k] {
                    out[k] = self.li_probed(scene, ray, &mut samplers[k], probe);
                }
            }
            return;
        }
        // One estimator per strategy, so that the strategy's tests fold away in each.
        match self.strategy {
            Strategy::Bsdf => self.share::<BSDF, S, P>(scene, rays, samplers, probe, out),
            Strategy::Emitter => self.share::<EMITTER, S, P>(scene, rays, samplers, probe, out),
            Strategy::Half => self.share::<HALF, S, P>(scene, rays, samplers, probe, out),
            Strategy::Mis => self.share::<MIS, S, P>(scene, rays, samplers, probe, out),
        }
    }

    /// The group estimator for the strategy numbered `ST`: each pixel's prefix, then the
    /// suffixes (from a throughput of 1 at a shared second vertex), then each shared vertex's
    /// light gathered by every pixel. Adds to `out[k]` (zero on entry).
    #[inline(always)]
    fn share<const ST: u8, S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        rays: &[Option<Ray>],
        samplers: &mut [S],
        probe: &mut P,
        out: &mut [Color],
    ) {
        let n = rays.len().min(GROUP);
        let mut pre = [Prefix::default(); GROUP];
        for k in 0..n {
            let Some(ray) = rays[k] else { continue };
            out[k] = self.prefix::<ST, S, P>(scene, ray, &mut samplers[k], probe, &mut pre[k]);
        }
        // The second vertices whose reflected light is shared, and what they reflect.
        let mut shared: [Option<(Interaction, Color)>; GROUP] = [None; GROUP];
        for k in 0..n {
            let Some((state, y)) = pre[k].y else { continue };
            let lambertian = scene
                .bsdf_traits(scene.shapes[y.shape as usize].bsdf)
                .lambertian;
            if pre[k].x.is_some() && !pre[k].delta && lambertian {
                let from_y = PathState {
                    throughput: Color::ONE,
                    ..state
                };
                let rr_scale = state.throughput;
                let l =
                    self.suffix::<ST, S, P>(scene, from_y, &y, rr_scale, &mut samplers[k], probe);
                shared[k] = Some((y, l));
            } else {
                out[k] +=
                    self.suffix::<ST, S, P>(scene, state, &y, Color::ONE, &mut samplers[k], probe);
            }
        }
        // Each first vertex's image lookups, made once for all the second vertices it gathers.
        let memos: [LookupMemo; GROUP] = Default::default();
        for (j, s) in shared.iter().enumerate().take(n) {
            let Some((y, l)) = *s else { continue };
            if !l.is_finite() || l == Color::ZERO {
                continue;
            }
            gather(scene, &pre[..n], &memos, j, &y, l, probe, &mut out[..n]);
        }
    }
}

/// Adds to each pixel's value its share of the light `l` reflected at `y`, pixel `j`'s second
/// vertex; `memos[m]` holds the image lookups at pixel `m`'s first vertex.
#[allow(clippy::too_many_arguments)]
fn gather<P: Probe>(
    scene: &Scene,
    pre: &[Prefix],
    memos: &[LookupMemo; GROUP],
    j: usize,
    y: &Interaction,
    l: Color,
    probe: &mut P,
    out: &mut [Color],
) {
    let Some((xj, ..)) = pre[j].x else { return };
    let side = |x: &Interaction| y.frame.n.dot(x.p - y.p) > 0.0;
    let own_side = side(&xj);
    // Per pixel: the BSDF value toward y (cosine included), |cos| / dist^2 at y, and the density.
    let mut terms = [(Color::ZERO, 0.0f32, 0.0f32); GROUP];
    let mut sum = 0.0f32;
    for (m, p) in pre.iter().enumerate() {
        let Some((xm, bsdf, wi, g)) = p.x else {
            continue;
        };
        let at = ShadingPoint {
            uv: xm.uv,
            partials: g.as_ref(),
            memo: scene.bsdf_traits(bsdf).reads_images.then_some(&memos[m]),
        };
        if side(&xm) != own_side {
            continue;
        }
        let d = y.p - xm.p;
        let dist2 = d.length_squared();
        if !(dist2 > 0.0) {
            continue;
        }
        let dir = d / crate::math::sqrt(dist2);
        let g = y.ng.dot(dir).abs() / dist2;
        let wo = xm.frame.to_local(dir);
        let bsdf = &scene.bsdfs[bsdf as usize];
        let pdf = bsdf.pdf(wi, wo, at) * g;
        if !(pdf > 0.0 && pdf.is_finite()) {
            continue;
        }
        if m != j {
            let target = offset_ray_origin(y.p, y.p_err, y.ng, xm.p - y.p);
            let blocked = probe.occluded(scene, &xm.spawn_ray_to(target));
            probe.ray(RayKind::Shadow);
            probe.shadow(blocked);
            if blocked {
                continue;
            }
        }
        terms[m] = (bsdf.eval(wi, wo, at), g, pdf);
        sum += pdf;
    }
    if !(sum > 0.0) {
        return;
    }
    for (o, (f, g, pdf)) in out.iter_mut().zip(terms) {
        if pdf > 0.0 {
            *o += f * l * (g / sum);
        }
    }
}
