//! Sampling of Mitsuba 3's `principled` BSDF and its density, as Mitsuba 3.9.1 does them.
//!
//! `u1` chooses a lobe, `u2` draws its direction. From the front the lobes are chosen with
//! probabilities proportional to `rate_d (1 - m)(1 - t)` (diffuse, cosine-weighted),
//! `rate_c clearcoat / 4` (clearcoat, GTR1 normals by `D cos`), and `rate_s` for the main
//! microfacet lobes, split by the dielectric Fresnel `F` of the sampled visible GGX normal
//! into reflection `1 - (1 - m) t (1 - F)` and transmission `(1 - m) t (1 - F)`. From the back
//! only the main lobes are sampled, reflection with probability `F`, transmission `1 - F`;
//! without a transmission lobe nothing is sampled from the back (but, as in Mitsuba, the
//! density there is still that of the reflection lobe, whose value is 0).
use super::fresnel::{fresnel_dielectric, reflect, refract};
use super::principled::{half_vector, Principled, Weights};
use super::principled_lobes::{micro_compatible, mulsign};
use super::sample::BsdfSample;
use crate::geometry::ShadingPoint;
use crate::sampling::warp::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};
use glam::{Vec2, Vec3};

/// The lobe probabilities, normalised.
#[derive(Clone, Copy, Debug)]
struct LobeProbabilities {
    spec_reflect: f32,
    spec_trans: f32,
    clearcoat: f32,
    diffuse: f32,
}

impl Principled {
    /// The lobe probabilities for weights `w`, the dielectric Fresnel `f` of the main lobe's
    /// micro normal and the side of `wi`; `None` when they do not sum to a positive number.
    fn lobe_probabilities(&self, w: &Weights, f: f32, front: bool) -> Option<LobeProbabilities> {
        let r = &self.p.rates;
        let bsdf = w.bsdf();
        let (mut sr, mut st, mut cc, mut d) = if front {
            (
                r.specular * (1.0 - bsdf * (1.0 - f)),
                r.specular * bsdf * (1.0 - f),
                0.25 * w.clearcoat * r.clearcoat,
                w.brdf() * r.diffuse,
            )
        } else {
            (f, 1.0 - f, 0.0, 0.0)
        };
        if !self.has_spec_trans() {
            st = 0.0;
        }
        if !self.has_clearcoat() {
            cc = 0.0;
        }
        let total = sr + st + cc + d;
        if !(total > 0.0 && total.is_finite()) {
            return None;
        }
        let inv = 1.0 / total;
        sr *= inv;
        st *= inv;
        cc *= inv;
        d *= inv;
        Some(LobeProbabilities {
            spec_reflect: sr,
            spec_trans: st,
            clearcoat: cc,
            diffuse: d,
        })
    }

    /// Solid-angle density with which [`Principled::sample`] produces `wo`.
    pub fn pdf(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> f32 {
        let p = self.pdf_lobes(wi, wo, at);
        if p.is_finite() && p > 0.0 {
            p
        } else {
            0.0
        }
    }

    fn pdf_lobes(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> f32 {
        let (ci, co) = (wi.z, wo.z);
        if ci == 0.0 || !(ci * co != 0.0) {
            return 0.0;
        }
        let w = self.weights(at);
        let front = ci > 0.0;
        let eta_path = if front { self.eta } else { 1.0 / self.eta };
        let is_reflect = ci * co > 0.0;
        let wh = half_vector(wi, wo, is_reflect, eta_path);
        let distr = w.distribution();
        let f = fresnel_dielectric(wi.dot(wh), self.eta).f;
        let Some(prob) = self.lobe_probabilities(&w, f, front) else {
            return 0.0;
        };
        let (cos_ih, cos_oh) = (wi.dot(wh), wo.dot(wh));
        let jacobian = if is_reflect || !self.has_spec_trans() {
            (1.0 / (4.0 * cos_oh)).abs()
        } else {
            let den = cos_ih + eta_path * cos_oh;
            (eta_path * eta_path * cos_oh / (den * den)).abs()
        };
        let wi_up = mulsign(wi, ci);
        let mut pdf = 0.0;
        if is_reflect {
            if micro_compatible(wh, wi, wo, ci, true) {
                pdf += prob.spec_reflect * distr.pdf(wi_up, wh) * jacobian;
                if self.has_clearcoat() {
                    pdf += prob.clearcoat * self.clearcoat_distribution(at).pdf(wh) * jacobian;
                }
            }
            pdf += prob.diffuse * cosine_hemisphere_pdf(wo);
        } else if self.has_spec_trans() && micro_compatible(wh, wi, wo, ci, false) {
            pdf += prob.spec_trans * distr.pdf(wi_up, wh) * jacobian;
        }
        pdf
    }

    /// Chooses a lobe with `u1` and draws its direction with `u2`; the weight is `eval / pdf`
    /// of the whole mixture. `None` at grazing `wi`, from the back without a transmission
    /// lobe, and when the drawn direction leaves the lobe's side.
    pub fn sample(&self, wi: Vec3, u1: f32, u2: Vec2, at: ShadingPoint) -> Option<BsdfSample> {
        let ci = wi.z;
        if ci == 0.0 || !ci.is_finite() {
            return None;
        }
        let w = self.weights(at);
        let front = ci > 0.0;
        let bsdf = if self.has_spec_trans() { w.bsdf() } else { 0.0 };
        if !(front || bsdf > 0.0) {
            return None;
        }
        let m_spec = w.distribution().sample(mulsign(wi, ci), u2).map(|(m, _)| m);
        let fr = fresnel_dielectric(wi.dot(m_spec.unwrap_or(Vec3::Z)), self.eta);
        let prob = self.lobe_probabilities(&w, fr.f, front)?;
        let (wo, eta, is_reflect, m) = if u1 < prob.diffuse {
            (square_to_cosine_hemisphere(u2), 1.0, true, None)
        } else if u1 < prob.diffuse + prob.clearcoat {
            let m = self.clearcoat_distribution(at).sample(u2);
            (reflect(wi, m), 1.0, true, Some(m))
        } else if u1 < prob.diffuse + prob.clearcoat + prob.spec_trans {
            let m = m_spec?;
            (
                refract(wi, m, fr.cos_t, fr.eta_ti),
                fr.eta_it,
                false,
                Some(m),
            )
        } else {
            let m = m_spec?;
            (reflect(wi, m), 1.0, true, Some(m))
        };
        let side_ok = if is_reflect {
            ci * wo.z > 0.0
        } else {
            ci * wo.z < 0.0
        };
        if !side_ok {
            return None;
        }
        if let Some(m) = m {
            if !micro_compatible(m, wi, wo, ci, is_reflect) {
                return None;
            }
        }
        let pdf = self.pdf(wi, wo, at);
        if !(pdf > 0.0) {
            return None;
        }
        let weight = self.eval(wi, wo, at) / pdf;
        if !weight.is_finite() {
            return None;
        }
        Some(BsdfSample {
            wo,
            weight,
            pdf,
            delta: false,
            eta,
        })
    }
}
