//! A heterogeneous medium (`heterogeneous`, Mitsuba 3's): extinction and albedo given by volumes
//! (constants or voxel grids), one phase function.
//!
//! The extinction is `scale * sigma_t(p)`; outside the extinction volume's extent (its unit cube
//! placed by its `to_world`) there is none, as in Mitsuba 3, whose medium intersects rays with
//! that extent. The albedo volume is looked up wherever a collision happens (its own `to_world`
//! and wrap mode apply). With SGGX flakes the extinction along direction `w` is also scaled by
//! their projected area `sigma(w)` at the point (as in Mitsuba 3), and the majorants by a bound
//! on it.
//!
//! Distances are sampled by delta tracking against the majorant grid (`majorant`): tentative
//! collisions are drawn from the piecewise-constant majorant `m`; at each, with the path's
//! channel `c`, the collision is real with probability `sigma_t,c / m` and null otherwise. The
//! event's values and densities per channel (real: `sigma_s` and `sigma_t`; null: `sigma_n =
//! m - sigma_t` for both), the majorant's common factors left out as they cancel, go into the
//! path's [`ChannelRatios`] exactly as a homogeneous medium's free flights do, so the balance
//! heuristic over the channels covers both. Transmittance on shadow rays is estimated by ratio
//! tracking: the product of `sigma_n / m` over the tentative collisions, per channel.
use super::free_flight::{ChannelRatios, FreeFlight};
use super::majorant::MajorantGrid;
use super::medium_phase::MediumPhase;
use super::volume::Volume;
use crate::sampling::Sampler;
use crate::Color;
use glam::Vec3;

/// Tentative collisions one tracking walk takes at most (a guard against a runaway majorant;
/// real media take a few dozen).
const MAX_COLLISIONS: u32 = 1 << 16;

/// A medium whose extinction and albedo vary through space.
#[derive(Clone, Debug)]
pub struct Heterogeneous {
    /// Extinction per unit length before `scale`; its extent bounds the medium.
    pub sigma_t: Volume,
    /// Single-scattering albedo.
    pub albedo: Volume,
    /// Factor on the extinction.
    pub scale: f32,
    /// How scattered light is distributed over directions, perhaps varying through space.
    pub phase: MediumPhase,
    /// Whether scattering events in it sample emitters.
    pub sample_emitters: bool,
    /// Bounds on `scale * sigma_t` per cell of its extent.
    pub majorants: MajorantGrid,
}

/// The outcome of delta tracking along one segment.
#[derive(Clone, Copy, Debug)]
pub struct TrackedFlight {
    /// Distance to the real collision, or the segment's length when it passed.
    pub t: f32,
    /// Whether a real collision (a scattering event) happened.
    pub scattered: bool,
    /// The factor on the path's throughput.
    pub weight: Color,
    /// Null collisions on the way.
    pub null_collisions: u32,
}

impl Heterogeneous {
    /// The medium, its majorant grid built.
    pub fn new(
        sigma_t: Volume,
        albedo: Volume,
        scale: f32,
        phase: MediumPhase,
        sample_emitters: bool,
    ) -> Self {
        let majorants = MajorantGrid::new(&sigma_t, scale * phase.projected_area_bound());
        Heterogeneous {
            sigma_t,
            albedo,
            scale,
            phase,
            sample_emitters,
            majorants,
        }
    }
    /// Extinction at world point `p` along unit direction `d` (scale applied; for SGGX
    /// flakes, times their projected area).
    #[inline]
    pub fn sigma_t_at(&self, p: Vec3, d: Vec3) -> Color {
        let s = self.sigma_t.eval(p) * self.scale;
        match self.phase.flakes_at(p) {
            Some(m) => s * m.projected_area(d),
            None => s,
        }
    }
    /// The part of the ray `o + t d`, `t` in `[0, t_max]`, inside the extent, in local
    /// coordinates: `(o_local, d_local, t0, t1)`.
    fn clip(&self, o: Vec3, d: Vec3, t_max: f32) -> Option<(Vec3, Vec3, f32, f32)> {
        let inv = &self.sigma_t.to_world.inv;
        let (ol, dl) = (inv.transform_point3(o), inv.transform_vector3(d));
        let (mut t0, mut t1) = (0.0f32, t_max);
        for a in 0..3 {
            let r = 1.0 / dl[a];
            let (mut n, mut f) = ((0.0 - ol[a]) * r, (1.0 - ol[a]) * r);
            if n > f {
                core::mem::swap(&mut n, &mut f);
            }
            if n.is_nan() || f.is_nan() {
                // Parallel to the slab: inside it or not at all.
                if !(0.0..=1.0).contains(&ol[a]) {
                    return None;
                }
                continue;
            }
            t0 = t0.max(n);
            t1 = t1.min(f);
        }
        (t0 < t1).then_some((ol, dl, t0, t1))
    }
    /// The next tentative collision after `t_from` and before `t_max` along the world ray
    /// `o + t d` from the exponential number `tau`: its distance and the majorant there.
    fn tentative(&self, o: Vec3, d: Vec3, t_from: f32, t_max: f32, tau: f32) -> Option<(f32, f32)> {
        let (ol, dl, t0, t1) = self.clip(o, d, t_max)?;
        let t0 = t0.max(t_from);
        if t0 >= t1 {
            return None;
        }
        self.majorants.march(ol, dl, t0, t1, tau)
    }
    /// Delta tracking along the world ray `o + t d` (`d` of unit length) up to `t_max`, from
    /// the path's channel; records every event into `channels`.
    pub fn sample_flight<S: Sampler>(
        &self,
        o: Vec3,
        d: Vec3,
        t_max: f32,
        channels: &mut ChannelRatios,
        sampler: &mut S,
    ) -> TrackedFlight {
        let mut weight = Color::ONE;
        let mut t = 0.0f32;
        let mut nulls = 0u32;
        for _ in 0..MAX_COLLISIONS {
            let tau = -libm::log1pf(-sampler.next_1d());
            let Some((tc, m)) = self.tentative(o, d, t, t_max, tau) else {
                break;
            };
            t = tc;
            let p = o + d * t;
            let sigma_t = self.sigma_t_at(p, d);
            let real = sampler.next_1d() * m < sigma_t[channels.channel.min(2)];
            if real {
                let sigma_s = sigma_t * self.albedo.eval(p);
                let ev = FreeFlight {
                    t,
                    scattered: true,
                    value: sigma_s,
                    pdf: sigma_t,
                };
                weight *= channels.record(&ev);
                return TrackedFlight {
                    t,
                    scattered: true,
                    weight,
                    null_collisions: nulls,
                };
            }
            nulls += 1;
            let sigma_n = (Color::splat(m) - sigma_t).max(Color::ZERO);
            let ev = FreeFlight {
                t,
                scattered: false,
                value: sigma_n,
                pdf: sigma_n,
            };
            weight *= channels.record(&ev);
            if weight == Color::ZERO {
                break;
            }
        }
        TrackedFlight {
            t: t_max,
            scattered: false,
            weight,
            null_collisions: nulls,
        }
    }
    /// Ratio tracking along the world ray `o + t d` (`d` of unit length) up to `t_max`: an
    /// unbiased estimate of the transmittance per channel, and the null collisions counted.
    pub fn transmittance<S: Sampler>(
        &self,
        o: Vec3,
        d: Vec3,
        t_max: f32,
        sampler: &mut S,
    ) -> (Color, u32) {
        let mut tr = Color::ONE;
        let mut t = 0.0f32;
        let mut n = 0u32;
        for _ in 0..MAX_COLLISIONS {
            let tau = -libm::log1pf(-sampler.next_1d());
            let Some((tc, m)) = self.tentative(o, d, t, t_max, tau) else {
                return (tr, n);
            };
            t = tc;
            n += 1;
            let sigma_t = self.sigma_t_at(o + d * t, d);
            tr *= (Color::ONE - sigma_t / m).max(Color::ZERO);
            if tr == Color::ZERO {
                return (tr, n);
            }
        }
        (tr, n)
    }
}
