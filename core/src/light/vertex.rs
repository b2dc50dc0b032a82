//! Light selection at a surface vertex (`light_selection` `contribution`, the default): each light
//! is picked in proportion to an estimate of what it adds there, the light's
//! [`LightBound::estimate`] times the BSDF toward it, with a fifth of the probability spread
//! evenly so that every light keeps a share (the estimate can miss light that reaches the
//! vertex, and a light with probability zero there would bias the image).
//!
//! On Veach's plates a uniform choice spends three of four shadow rays on lights outside the
//! glossy lobe; this choice spends them on the light the plate reflects.
//!
//! Scenes with one light, or more than [`MAX_VERTEX_LIGHTS`], use the scene-wide choice.
use super::bound::LightBound;
use super::light_lanes::{LightLanes, LANE_LIGHTS};
use crate::bsdf::Bsdf;
use crate::emitter::luminance;
use crate::geometry::{Interaction, ShadingPoint};
use glam::Vec3;

/// Most lights a vertex selection weighs one by one.
pub const MAX_VERTEX_LIGHTS: usize = 8;
const _: () = assert!(
    MAX_VERTEX_LIGHTS == LANE_LIGHTS,
    "the lanes hold every light"
);

/// Share of the probability spread evenly over all lights.
pub const UNIFORM_SHARE: f32 = 0.2;

/// Probabilities of picking each light at one vertex.
#[derive(Clone, Copy, Debug)]
pub struct VertexSelection {
    /// Probability of each light (the first `n`).
    pdf: [f32; MAX_VERTEX_LIGHTS],
    /// Running sums: light `k` is picked for `u` in `[cdf[k], cdf[k + 1])`, the last one up to 1.
    cdf: [f32; MAX_VERTEX_LIGHTS],
    n: usize,
}

impl VertexSelection {
    /// The selection at `si` (BSDF `bsdf` asked at `at`, local incident direction `wi`) from the lights'
    /// bounds; `None` without bounds (the scene's own choice then applies). `lanes` are the same
    /// lights laid out for [`LightLanes`] where the scene has them (the weights are the same
    /// bits either way, found four lights at a time).
    #[inline(always)]
    pub fn new(
        bounds: &[LightBound],
        lanes: Option<&LightLanes>,
        si: &Interaction,
        bsdf: &Bsdf,
        at: &ShadingPoint,
        wi: Vec3,
    ) -> Option<VertexSelection> {
        let mut out = None;
        Self::set(&mut out, bounds, lanes, si, bsdf, at, wi);
        out
    }

    /// [`VertexSelection::new`] written into `out`, in place: the path loop keeps its vertex's
    /// selection in its state, where a returned one was copied in with wide loads of what the
    /// weighing had just stored (a store-forwarding stall).
    #[inline(always)]
    pub fn set(
        out: &mut Option<VertexSelection>,
        bounds: &[LightBound],
        lanes: Option<&LightLanes>,
        si: &Interaction,
        bsdf: &Bsdf,
        at: &ShadingPoint,
        wi: Vec3,
    ) {
        // Checked where the caller is, so that scenes without a choice to make (one light, or
        // too many) pay neither a call nor the copy of an empty selection.
        if !(2..=MAX_VERTEX_LIGHTS).contains(&bounds.len()) {
            *out = None;
            return;
        }
        let s = out.get_or_insert(VertexSelection {
            pdf: [0.0; MAX_VERTEX_LIGHTS],
            cdf: [0.0; MAX_VERTEX_LIGHTS],
            n: 0,
        });
        Self::from_bounds(s, bounds, lanes, si, bsdf, at, wi);
    }

    /// [`VertexSelection::set`] for 2 to [`MAX_VERTEX_LIGHTS`] bounds, written into `out`.
    #[inline(never)]
    fn from_bounds(
        out: &mut VertexSelection,
        bounds: &[LightBound],
        lanes: Option<&LightLanes>,
        si: &Interaction,
        bsdf: &Bsdf,
        at: &ShadingPoint,
        wi: Vec3,
    ) {
        let n = bounds.len();
        // The BSDF toward `wo` (local), in luminance, up to a factor common to every light
        // (which cancels). A diffuse BSDF is its reflectance over pi times the cosine: the
        // cosine alone weighs. A rough conductor weighs by its lobe's shape alone (no Fresnel,
        // tint or masking, which vary little over the lobe and cost square roots, divisions
        // and texture lookups per light). Any other BSDF is evaluated.
        let weigh = |wo: Vec3| match bsdf {
            Bsdf::Diffuse(_) => {
                if wi.z > 0.0 && wo.z > 0.0 {
                    wo.z
                } else {
                    0.0
                }
            }
            Bsdf::RoughConductor(c) => c.lobe(wi, wo),
            _ => luminance(bsdf.eval(wi, wo, at)),
        };
        let one = |k: usize| light_weight(&bounds[k], si, wi, &weigh);
        let (weight, sum) = match lanes.and_then(|l| l.weights(si.p, &si.frame, bsdf, wi, one)) {
            Some(found) => found,
            None => {
                let mut weight = [0.0f32; MAX_VERTEX_LIGHTS];
                let mut sum = 0.0f32;
                for (k, w) in weight[..n].iter_mut().enumerate() {
                    if let Some(x) = one(k) {
                        *w = x;
                        sum += x;
                    }
                }
                (weight, sum)
            }
        };
        out.set_weights(n, &weight, sum);
    }

    /// Sets the selection from the lights' weights (the first `n`) and their sum.
    #[inline(always)]
    fn set_weights(&mut self, n: usize, weight: &[f32; MAX_VERTEX_LIGHTS], sum: f32) {
        let even = 1.0 / n as f32;
        self.pdf = [0.0; MAX_VERTEX_LIGHTS];
        self.cdf = [0.0; MAX_VERTEX_LIGHTS];
        self.n = n;
        let scale = if sum > 0.0 && sum.is_finite() {
            (1.0 - UNIFORM_SHARE) / sum
        } else {
            0.0
        };
        let even = if scale > 0.0 {
            UNIFORM_SHARE * even
        } else {
            even
        };
        let mut c = 0.0;
        for (k, w) in weight[..n].iter().enumerate() {
            self.cdf[k] = c;
            // Without a usable sum (all zero, or a weight infinite or NaN) the choice is even:
            // no weight is read then, as 0 times infinity would be NaN.
            self.pdf[k] = if scale > 0.0 { even + w * scale } else { even };
            c += self.pdf[k];
        }
        // The last light takes what rounding left: its probability is 1 minus the others'.
        self.pdf[n - 1] = 1.0 - self.cdf[n - 1];
    }

    /// The light `u` (in [0, 1)) picks, and its probability.
    #[inline]
    pub fn pick(&self, u: f32) -> (usize, f32) {
        let mut k = 0;
        while k + 1 < self.n && u >= self.cdf[k + 1] {
            k += 1;
        }
        (k, self.pdf[k])
    }

    /// The probability of light `k`.
    #[inline]
    pub fn pdf(&self, k: usize) -> f32 {
        self.pdf[k]
    }
}

/// Light `b`'s weight at vertex `si` (local incident direction `wi`), the BSDF weighed toward a
/// local direction by `weigh`; `None` where the light is estimated to give nothing (it then
/// keeps only its even share, and adds nothing to the sum).
#[inline(always)]
fn light_weight(
    b: &LightBound,
    si: &Interaction,
    wi: Vec3,
    weigh: &impl Fn(Vec3) -> f32,
) -> Option<f32> {
    let e = b.estimate(si.p);
    if !(e.irradiance > 0.0) {
        return None;
    }
    let f = match e.toward {
        Some(d) => weigh(si.frame.to_local(d)),
        // Light from everywhere: the BSDF toward the normal or the mirror direction,
        // whichever is larger.
        None => weigh(Vec3::Z).max(weigh(Vec3::new(-wi.x, -wi.y, wi.z))),
    };
    Some(e.irradiance * f.max(0.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bsdf::Diffuse;
    use crate::geometry::Interaction;
    use crate::math::Frame;
    use crate::texture::Texture;
    use crate::Color;
    use glam::Vec2;

    fn vertex() -> (Interaction, Bsdf) {
        let si = Interaction {
            p: Vec3::ZERO,
            p_err: Vec3::ZERO,
            t: 1.0,
            ng: Vec3::Z,
            frame: Frame::from_normal(Vec3::Z),
            uv: Vec2::ZERO,
            shape: 0,
            wi: Vec3::Z,
        };
        let bsdf = Bsdf::Diffuse(Diffuse {
            reflectance: Texture::Constant(Color::splat(0.5)),
        });
        (si, bsdf)
    }

    fn point(position: Vec3, lum: f32) -> LightBound {
        LightBound::Point { position, lum }
    }

    /// Two point lights above a diffuse vertex, one four times as strong: 0.1 + 0.8 * 4/5 and
    /// 0.1 + 0.8 / 5.
    #[test]
    fn weighs_by_estimate_with_an_even_share() {
        let (si, bsdf) = vertex();
        let bounds = [point(Vec3::Z, 4.0), point(Vec3::Z * 2.0, 4.0)];
        let sel =
            VertexSelection::new(&bounds, None, &si, &bsdf, &Vec2::ZERO.into(), Vec3::Z).unwrap();
        assert!((sel.pdf(0) - 0.74).abs() < 1e-6, "{}", sel.pdf(0));
        assert!((sel.pdf(1) - 0.26).abs() < 1e-6, "{}", sel.pdf(1));
        assert_eq!(sel.pick(0.0).0, 0);
        assert_eq!(sel.pick(0.7399).0, 0);
        assert_eq!(sel.pick(0.7401).0, 1);
        assert_eq!(sel.pick(0.9999999).0, 1);
    }

    /// A light below the horizon, or with a NaN estimate, has weight zero and keeps only its
    /// even share; an infinite estimate (times a zero BSDF: NaN) or all-zero weights give the
    /// even choice, never NaN.
    #[test]
    fn degenerate_weights_fall_back_to_even() {
        let (si, bsdf) = vertex();
        for bounds in [
            [point(Vec3::Z, 1.0), point(-Vec3::Z, 1.0)],
            [point(Vec3::Z, 1.0), point(Vec3::Z, f32::NAN)],
        ] {
            let sel = VertexSelection::new(&bounds, None, &si, &bsdf, &Vec2::ZERO.into(), Vec3::Z)
                .unwrap();
            assert!((sel.pdf(1) - 0.1).abs() < 1e-6, "{}", sel.pdf(1));
        }
        for bounds in [
            [point(Vec3::Z, 1.0), point(-Vec3::Z, f32::INFINITY)],
            [point(-Vec3::Z, 1.0), point(-Vec3::Z * 2.0, 1.0)],
        ] {
            let sel = VertexSelection::new(&bounds, None, &si, &bsdf, &Vec2::ZERO.into(), Vec3::Z)
                .unwrap();
            assert_eq!((sel.pdf(0), sel.pdf(1)), (0.5, 0.5), "{bounds:?}");
        }
    }

    /// One light, or more than the maximum: no vertex selection.
    #[test]
    fn only_two_to_eight_lights() {
        let (si, bsdf) = vertex();
        let b = point(Vec3::Z, 1.0);
        assert!(
            VertexSelection::new(&[b], None, &si, &bsdf, &Vec2::ZERO.into(), Vec3::Z).is_none()
        );
        assert!(VertexSelection::new(
            &[b; MAX_VERTEX_LIGHTS + 1],
            None,
            &si,
            &bsdf,
            &Vec2::ZERO.into(),
            Vec3::Z
        )
        .is_none());
        assert!(VertexSelection::new(
            &[b; MAX_VERTEX_LIGHTS],
            None,
            &si,
            &bsdf,
            &Vec2::ZERO.into(),
            Vec3::Z
        )
        .is_some());
    }
}
