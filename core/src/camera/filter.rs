//! Pixel reconstruction filters, applied in one of two ways (see `splat.rs`):
//! - splatting (the default, as Mitsuba 3 does): samples are placed uniformly in their pixel and
//!   each counts, weighted by the filter ([`Filter::table`]), in every pixel the filter reaches;
//! - filter importance sampling (as pbrt-v4 does): each camera sample is offset from its pixel's
//!   centre with density proportional to the filter, so every sample lands in exactly one pixel.
//!   Samples of the non-negative filters (`box`, `gaussian`, `tent`) weigh exactly 1; those of the
//!   filters with negative lobes (`mitchell`, `catmullrom`, `lanczos`) are drawn proportionally to
//!   `|f|` and carry a weight ([`Filter::sample_weighted`]).
//!
//! The filters other than `box` are tabulated as step functions as Mitsuba 3 tabulates them
//! ([`StepProfile`]). Their scene parameters are declared with the loader, in
//! `scene/src/filter.rs`.
use super::filter_table::FilterTable;
use super::negative_lobes::{LanczosFilter, MitchellFilter};
use super::step_profile::{StepProfile, STEPS};
use glam::Vec2;

/// A truncated Gaussian (`gaussian`, Mitsuba 3's default), shifted to zero at its radius of 4
/// standard deviations and tabulated as Mitsuba 3 does.
#[derive(Clone, Debug)]
pub struct GaussianFilter {
    /// Standard deviation in pixels.
    pub stddev: f32,
    /// Support radius in pixels.
    pub radius: f32,
    profile: StepProfile,
    table: FilterTable,
}

impl GaussianFilter {
    /// The filter with the given standard deviation (radius = 4 stddev).
    pub fn new(stddev: f32) -> Self {
        let radius = 4.0 * stddev;
        let alpha = -1.0 / (2.0 * stddev * stddev);
        let bias = libm::expf(alpha * radius * radius);
        let value = |i: usize| {
            let x = radius * i as f32 / STEPS as f32;
            (libm::expf(alpha * x * x) - bias).max(0.0) as f64
        };
        GaussianFilter {
            stddev,
            radius,
            profile: StepProfile::new(radius, value),
            table: FilterTable::new(radius, value),
        }
    }
}

/// A tent (`tent`): `max(0, 1 - |x| / radius)`, tabulated as Mitsuba 3 does.
#[derive(Clone, Debug)]
pub struct TentFilter {
    /// Support radius in pixels.
    pub radius: f32,
    profile: StepProfile,
    table: FilterTable,
}

impl TentFilter {
    /// The tent of the given radius (positive).
    pub fn new(radius: f32) -> Self {
        let inv = 1.0 / radius;
        let value = |i: usize| {
            let x = radius * i as f32 / STEPS as f32;
            (1.0 - libm::fabsf(x * inv)).max(0.0) as f64
        };
        TentFilter {
            radius,
            profile: StepProfile::new(radius, value),
            table: FilterTable::new(radius, value),
        }
    }
}

/// A reconstruction filter.
#[derive(Clone, Debug)]
pub enum Filter {
    /// The pixel's own square.
    Box,
    /// Truncated Gaussian.
    Gaussian(GaussianFilter),
    /// Tent.
    Tent(TentFilter),
    /// Mitchell-Netravali cubic (`mitchell`, `catmullrom`): weighted samples.
    Mitchell(MitchellFilter),
    /// Lanczos-windowed sinc: weighted samples.
    Lanczos(LanczosFilter),
}

impl Filter {
    /// The filter's family, as reports name it (`mitchell` also for Catmull-Rom).
    pub fn name(&self) -> &'static str {
        match self {
            Filter::Box => "box",
            Filter::Gaussian(_) => "gaussian",
            Filter::Tent(_) => "tent",
            Filter::Mitchell(_) => "mitchell",
            Filter::Lanczos(_) => "lanczos",
        }
    }

    /// The filter's values as splatting looks them up: `None` for `box`, whose samples count
    /// in their own pixel only.
    pub fn table(&self) -> Option<&FilterTable> {
        match self {
            Filter::Box => None,
            Filter::Gaussian(g) => Some(&g.table),
            Filter::Tent(t) => Some(&t.table),
            Filter::Mitchell(m) => Some(&m.table),
            Filter::Lanczos(l) => Some(&l.table),
        }
    }

    /// Offset of a sample from its pixel's centre, in pixels (its weight dropped: see
    /// [`Filter::sample_weighted`]).
    #[inline]
    pub fn sample(&self, u: Vec2) -> Vec2 {
        self.sample_weighted(u).0
    }

    /// Offset of a sample from its pixel's centre, in pixels, and the weight its radiance must
    /// be multiplied by: `None` for the filters whose samples weigh exactly 1 (nothing to
    /// multiply, so their images stay bit for bit what they were), else
    /// `sign(f(x) f(y)) * (∫|f| / ∫f)^2` for the separable filter `f(x) f(y)`.
    #[inline]
    pub fn sample_weighted(&self, u: Vec2) -> (Vec2, Option<f32>) {
        match self {
            Filter::Box => (u - Vec2::splat(0.5), None),
            Filter::Gaussian(g) => (
                Vec2::new(g.profile.sample(u.x), g.profile.sample(u.y)),
                None,
            ),
            Filter::Tent(t) => (
                Vec2::new(t.profile.sample(u.x), t.profile.sample(u.y)),
                None,
            ),
            Filter::Mitchell(MitchellFilter { profile, .. })
            | Filter::Lanczos(LanczosFilter { profile, .. }) => {
                let (x, nx) = profile.sample(u.x);
                let (y, ny) = profile.sample(u.y);
                let r = profile.ratio();
                let w = r * r;
                (Vec2::new(x, y), Some(if nx != ny { -w } else { w }))
            }
        }
    }
}
