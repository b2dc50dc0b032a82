//! The reconstruction filters with negative lobes, as Mitsuba 3 defines them: the
//! Mitchell-Netravali cubics (`mitchell`, and `catmullrom`, its B = 0, C = 1/2 member), radius 2,
//! and the Lanczos-windowed sinc (`lanczos`), radius = its number of lobes. Both are separable
//! and tabulated as Mitsuba 3 tabulates every filter; they are sampled through
//! [`SignedProfile`], so their samples carry weights. Their scene parameters are declared with
//! the loader, in `scene/src/filter.rs`.
use super::filter_table::FilterTable;
use super::signed_profile::SignedProfile;
use super::step_profile::STEPS;

/// A Mitchell-Netravali cubic (Mitchell and Netravali 1988, "Reconstruction filters in computer
/// graphics"), of radius 2 pixels.
#[derive(Clone, Debug)]
pub struct MitchellFilter {
    /// The B parameter.
    pub b: f32,
    /// The C parameter.
    pub c: f32,
    pub(super) profile: SignedProfile,
    pub(super) table: FilterTable,
}

impl MitchellFilter {
    /// Support radius in pixels, as in Mitsuba 3.
    pub const RADIUS: f32 = 2.0;

    /// The cubic with parameters `b` and `c`; `None` if its tabulated integral is not positive.
    pub fn new(b: f32, c: f32) -> Option<Self> {
        let r = Self::RADIUS;
        let value = |i: usize| mitchell(b, c, r * i as f32 / STEPS as f32);
        let profile = SignedProfile::new(r, value)?;
        Some(MitchellFilter {
            b,
            c,
            profile,
            table: FilterTable::new(r, value),
        })
    }

    /// Catmull-Rom: B = 0, C = 1/2.
    pub fn catmull_rom() -> Self {
        match MitchellFilter::new(0.0, 0.5) {
            Some(f) => f,
            None => unreachable!("the Catmull-Rom spline has integral 1"),
        }
    }
}

/// The Mitchell-Netravali cubic at `x`, zero beyond 2.
fn mitchell(b: f32, c: f32, x: f32) -> f64 {
    let x = libm::fabsf(x);
    let (x2, x3) = (x * x, x * x * x);
    let v = if x < 1.0 {
        (12.0 - 9.0 * b - 6.0 * c) * x3 + (-18.0 + 12.0 * b + 6.0 * c) * x2 + (6.0 - 2.0 * b)
    } else if x < 2.0 {
        (-b - 6.0 * c) * x3
            + (6.0 * b + 30.0 * c) * x2
            + (-12.0 * b - 48.0 * c) * x
            + (8.0 * b + 24.0 * c)
    } else {
        0.0
    };
    (v / 6.0) as f64
}

/// The Lanczos-windowed sinc: `sinc(x) * sinc(x / lobes)` for `|x| <= lobes`, radius `lobes`.
#[derive(Clone, Debug)]
pub struct LanczosFilter {
    /// Number of lobes, which is also the radius in pixels.
    pub lobes: u32,
    pub(super) profile: SignedProfile,
    pub(super) table: FilterTable,
}

impl LanczosFilter {
    /// The filter with `lobes` lobes (at least 1); `None` if its tabulated integral is not
    /// positive (with many lobes, 31 steps no longer resolve them).
    pub fn new(lobes: u32) -> Option<Self> {
        let r = lobes.max(1) as f32;
        let value = |i: usize| lanczos(r, r * i as f32 / STEPS as f32);
        let profile = SignedProfile::new(r, value)?;
        Some(LanczosFilter {
            lobes,
            profile,
            table: FilterTable::new(r, value),
        })
    }
}

/// The Lanczos filter of radius `r` at `x`.
fn lanczos(r: f32, x: f32) -> f64 {
    let x = libm::fabsf(x);
    if x < f32::EPSILON {
        return 1.0;
    }
    if x > r {
        return 0.0;
    }
    let x1 = core::f32::consts::PI * x;
    let x2 = x1 / r;
    ((libm::sinf(x1) * libm::sinf(x2)) / (x1 * x2)) as f64
}
