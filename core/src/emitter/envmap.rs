//! Environment map: radiance at infinity from a latitude-longitude image, as Mitsuba 3's `envmap`.
//!
//! Scene parameters (`<emitter type="envmap">`): `filename` (string, required: an EXR, PFM or
//! RGBE `.hdr` image, relative to the scene file; at least 2x3 pixels, as in Mitsuba 3), `scale`
//! (float, default 1: multiplies the image), `to_world` (transform, default identity; a
//! rotation, optionally uniformly scaled), `mis_compensation` (boolean, default true: whether the
//! sampling tables may be MIS-compensated, see [`EnvMap::set_compensated`]; Mitsuba 3's
//! default is false). The driver loads the image; the core receives linear RGB pixels.
//!
//! Mapping (Mitsuba 3's, checked against Mitsuba 3.9.1 by evaluating its envmap at known
//! directions): +y is up. A local unit direction `d` has `u = atan2(d.x, -d.z) / 2 pi` (wrapped
//! to [0, 1)) and `v = acos(d.y) / pi`, so `u = 0` looks along -z, `u = 1/4` along +x, `u = 1/2`
//! along +z, `u = 3/4` along -x, and `v = 0` is straight up. Pixel column `x` sits at
//! `u = (x + 1/2) / width` (periodic), pixel row `y` at `v = y / (height - 1)`: the top row is the
//! north pole and the bottom row the south pole. Radiance is the bilinear interpolation of the
//! four surrounding pixels, times `scale`.
//!
//! Sampling (as Mitsuba 3's hierarchical warp does, here in two levels): every pixel gets the
//! weight luminance x sin(theta of its row) (the pole rows: the sine of a quarter row); a cell between four pixel centres (`width x
//! (height - 1)` cells) is chosen by a [`Distribution2D`] in proportion to the integral of the
//! bilinear interpolant of those weights over it (the mean of its corners), then a point of the
//! cell is drawn from that bilinear density exactly (a linear density in `v`, then in `u`). The
//! density in `(u, v)` is therefore the bilinear interpolant of luminance x sin(theta) divided by
//! its integral: proportional to the radiance's luminance up to the interpolation of
//! sin(theta), positive wherever the radiance is (so emitter sampling alone covers the map), and
//! `pdf_uv / (2 pi^2 sin theta)` is its exact solid-angle density (with MIS-compensated tables,
//! `envmap_tables.rs`, the luminance less the map's mean). For light selection the map counts
//! by the integral of luminance over the sphere its tables sample (by power: `pi r^2` times it).
use super::envmap_coords::{coords8, map_coords};
use super::envmap_tables::{tables, Tables};
use super::sample::{luminance, EmitterSample};
use crate::accel::slab_simd::Avx2;
use crate::geometry::Interaction;
use crate::math::{safe_sqrt, sincos_turns, sqrt, Norm, PI};
use crate::sampling::Distribution2D;
use crate::Color;
use alloc::vec::Vec;
use glam::{Mat3, Vec2, Vec3, Vec4};

/// A latitude-longitude environment map.
#[derive(Clone, Debug)]
pub struct EnvMap {
    /// Per pixel, row-major, top row first: the radiance (`scale` applied) in `xyz` and the
    /// sampling weight at the cell corners, luminance x sin(theta of its row), in `w`. One array
    /// so that a lookup, which needs both, reads one cache line per row, not two.
    texels: Vec<Vec4>,
    width: usize,
    height: usize,
    /// Local to world directions: a rotation.
    to_world: Mat3,
    /// World to local: the transpose of `to_world`.
    to_local: Mat3,
    /// Cell choice (`None` when the map is black).
    dist: Option<Distribution2D>,
    /// `width * (height - 1)` over the integral of the bilinear weights in cell units: turns the
    /// interpolated weight into a density on the `(u, v)` square.
    pdf_scale: f32,
    /// Integral of luminance over the sphere (W/m^2 up to the luminance weights).
    integral: f32,
    /// The part of `integral` the tables sample: all of it with the plain tables, what lies
    /// above the mean with the compensated ones.
    sampled: f32,
    /// Whether the sampling tables are compensated ([`EnvMap::set_compensated`]).
    compensated: bool,
    /// Whether they may be (the scene file's `mis_compensation`, default true).
    may_compensate: bool,
}

impl EnvMap {
    /// An environment from `width x height` linear RGB pixels (row-major, top row first), times
    /// `scale`, rotated by `to_world` (a rotation; the caller checks). `None` unless
    /// `width >= 1`, `height >= 2` and the pixel count matches. Negative or non-finite values
    /// count as 0 (the driver rejects them before).
    pub fn new(
        pixels: Vec<[f32; 3]>,
        width: usize,
        height: usize,
        scale: f32,
        to_world: Mat3,
    ) -> Option<Self> {
        if width < 1 || height < 2 || width.checked_mul(height)? != pixels.len() {
            return None;
        }
        let scale = if scale.is_finite() && scale > 0.0 {
            scale
        } else {
            0.0
        };
        let pixels: Vec<Color> = pixels
            .into_iter()
            .map(|p| {
                let c = Color::from(p) * scale;
                if c.is_finite() {
                    c.max(Color::ZERO)
                } else {
                    Color::ZERO
                }
            })
            .collect();
        let (nx, ny) = (width, height - 1);
        let lum = |x: usize, y: usize| f64::from(luminance(pixels[y * width + x % width]));
        let mut integral = 0.0f64;
        for j in 0..ny {
            // Solid angle of a cell: (cos theta0 - cos theta1) * 2 pi / width.
            let theta0 = core::f64::consts::PI * j as f64 / ny as f64;
            let theta1 = core::f64::consts::PI * (j + 1) as f64 / ny as f64;
            let band = libm::cos(theta0) - libm::cos(theta1);
            for i in 0..nx {
                integral +=
                    0.25 * (lum(i, j) + lum(i + 1, j) + lum(i, j + 1) + lum(i + 1, j + 1)) * band;
            }
        }
        let integral = (integral * core::f64::consts::TAU / nx as f64) as f32;
        let Tables {
            weights,
            dist,
            pdf_scale,
        } = tables(pixels.iter().copied(), width, height, 0.0);
        Some(EnvMap {
            dist,
            pdf_scale,
            texels: pixels
                .iter()
                .zip(&weights)
                .map(|(c, &w)| c.extend(w))
                .collect(),
            compensated: false,
            may_compensate: true,
            width,
            height,
            to_world,
            to_local: to_world.transpose(),
            integral,
            sampled: integral,
        })
    }

    /// Bytes of the image and its sampling tables.
    pub fn memory_bytes(&self) -> usize {
        core::mem::size_of_val(&*self.texels)
            + self.dist.as_ref().map_or(0, Distribution2D::memory_bytes)
    }

    /// Width in pixels.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// Samples by MIS-compensated tables (`on`: each pixel's luminance lowered by the map's
    /// mean over the sphere, see `envmap_tables.rs`) or by the plain ones, rebuilding the tables
    /// if that changes. Only for renders whose every emitter sample is weighed by MIS against a
    /// strategy that reaches every direction (the compensated density is zero where the map is
    /// dimmer than its mean). A map whose compensated tables would be empty (one of uniform
    /// brightness) keeps the plain ones. Whether the tables are compensated afterwards.
    pub fn set_compensated(&mut self, on: bool) -> bool {
        let on = on && self.may_compensate;
        if on == self.compensated {
            return on;
        }
        let floor = match on {
            true => f64::from(self.integral) / (4.0 * core::f64::consts::PI),
            false => 0.0,
        };
        let radiance = self.texels.iter().map(|t| t.truncate());
        let t = tables(radiance, self.width, self.height, floor);
        if on && (t.dist.is_none() || !(t.pdf_scale > 0.0)) {
            return false;
        }
        for (texel, w) in self.texels.iter_mut().zip(t.weights) {
            texel.w = w;
        }
        // The tables' totals are in proportion to the integrals they sample, and each
        // `pdf_scale` is inversely proportional to its table's total.
        self.sampled = match on {
            true => self.integral * (self.pdf_scale / t.pdf_scale),
            false => self.integral,
        };
        self.dist = t.dist;
        self.pdf_scale = t.pdf_scale;
        self.compensated = on;
        on
    }

    /// Whether [`EnvMap::set_compensated`] may turn compensation on (the scene file's
    /// `mis_compensation`); disallowing it brings back the plain tables.
    pub fn allow_compensation(&mut self, allow: bool) {
        self.may_compensate = allow;
        if !allow {
            self.set_compensated(false);
        }
    }

    /// Whether the sampling tables are compensated ([`EnvMap::set_compensated`]).
    pub fn is_compensated(&self) -> bool {
        self.compensated
    }

    /// Integral of the radiance's luminance over the sphere of directions.
    pub fn luminance_integral(&self) -> f32 {
        self.integral
    }

    /// The part of [`EnvMap::luminance_integral`] that emitter sampling is left to find: all
    /// of it with the plain tables; with the compensated ones, the integral of the luminance
    /// less the mean, clamped at zero (the rest is BSDF sampling's).
    pub fn sampled_luminance_integral(&self) -> f32 {
        self.sampled
    }

    /// Image coordinates `(s, v)` of a local unit direction ([`map_coords`] for this map's
    /// width).
    #[inline]
    fn coords(&self, l: Vec3) -> (f32, f32) {
        map_coords(l, self.width)
    }

    /// Bilinear interpolation of per-pixel values `at(x, y)` at image coordinates `(s, v)` (see
    /// [`EnvMap::coords`]).
    #[inline]
    fn bilinear<T>(&self, s: f32, v: f32, at: impl Fn(usize) -> T) -> T
    where
        T: core::ops::Mul<f32, Output = T> + core::ops::Add<Output = T>,
    {
        let (w, h) = (self.width, self.height);
        // Each index clamped as a float first, so that its conversion is a plain truncation
        // (`as usize` saturates through a longer sequence); the same index for every input.
        let x0 = (s.max(0.0).min((w - 1) as f32) as u32 as usize).min(w - 1);
        let fx = (s - x0 as f32).clamp(0.0, 1.0);
        let x1 = if x0 + 1 == w { 0 } else { x0 + 1 };
        let t = v.clamp(0.0, 1.0) * (h - 1) as f32;
        let y0 = (t.max(0.0).min((h - 2) as f32) as u32 as usize).min(h - 2);
        let fy = (t - y0 as f32).clamp(0.0, 1.0);
        let (r0, r1) = (y0 * w, (y0 + 1) * w);
        let top = at(r0 + x0) * (1.0 - fx) + at(r0 + x1) * fx;
        let bottom = at(r1 + x0) * (1.0 - fx) + at(r1 + x1) * fx;
        top * (1.0 - fy) + bottom * fy
    }

    /// Radiance at image coordinates `(s, v)`.
    #[inline]
    fn lookup(&self, s: f32, v: f32) -> Color {
        // In four lanes, each computed as the three-lane interpolation computes it.
        self.bilinear(s, v, |i| self.texels[i]).truncate()
    }

    /// Density on the `(u, v)` square at image coordinates `(s, v)`.
    #[inline]
    fn pdf_uv(&self, s: f32, v: f32) -> f32 {
        self.bilinear(s, v, |i| self.texels[i].w) * self.pdf_scale
    }

    /// Radiance arriving along the escaping unit direction `d`.
    #[inline]
    pub fn eval(&self, d: Vec3) -> Color {
        let l = (self.to_local * d).unit_or_zero();
        if l == Vec3::ZERO {
            return Color::ZERO;
        }
        let (s, v) = self.coords(l);
        self.lookup(s, v)
    }

    /// [`EnvMap::eval`] of eight escaping unit directions, the same bits, their map
    /// coordinates computed side by side (`envmap_coords`; in AVX2 registers when `avx2` is
    /// given).
    #[inline]
    pub fn eval8(&self, avx2: Option<Avx2>, d: &[Vec3; 8]) -> [Color; 8] {
        let c = coords8(avx2, &self.to_local, self.width, d);
        core::array::from_fn(|k| {
            if c.valid >> k & 1 != 0 {
                self.lookup(c.s[k], c.v[k])
            } else {
                Color::ZERO
            }
        })
    }

    /// Solid-angle density of `sample` for the world direction `d`.
    #[inline]
    pub fn pdf(&self, d: Vec3) -> f32 {
        if self.dist.is_none() {
            return 0.0;
        }
        let l = (self.to_local * d).unit_or_zero();
        let sin_t = sqrt(l.x * l.x + l.z * l.z);
        if !(sin_t > 0.0) {
            return 0.0;
        }
        let (s, v) = self.coords(l);
        self.pdf_uv(s, v) / (2.0 * PI * PI * sin_t)
    }

    /// [`EnvMap::eval`] and [`EnvMap::pdf`] of one direction, its map coordinates and the
    /// bilinear weights of its four pixels found once (same values as the two calls).
    #[inline]
    pub fn eval_pdf(&self, d: Vec3) -> (Color, f32) {
        let l = (self.to_local * d).unit_or_zero();
        if l == Vec3::ZERO {
            return (Color::ZERO, 0.0);
        }
        let (s, v) = self.coords(l);
        let sin_t = sqrt(l.x * l.x + l.z * l.z);
        if self.dist.is_none() || !(sin_t > 0.0) {
            return (self.lookup(s, v), 0.0);
        }
        let (le, pdf_uv) = self.lookup_and_pdf_uv(s, v);
        (le, pdf_uv / (2.0 * PI * PI * sin_t))
    }

    /// [`EnvMap::lookup`] and [`EnvMap::pdf_uv`] in one interpolation: the radiance in three
    /// lanes and the sampling weight in the fourth, each lane computed as the scalar
    /// interpolation computes it.
    #[inline]
    fn lookup_and_pdf_uv(&self, s: f32, v: f32) -> (Color, f32) {
        let both = self.bilinear(s, v, |i| self.texels[i]);
        (both.truncate(), both.w * self.pdf_scale)
    }

    /// A direction by importance: a cell of the image by its weight, then a point of the cell
    /// from the bilinear interpolant of the weights.
    pub fn sample(&self, _it: &Interaction, u: Vec2) -> Option<EmitterSample> {
        let (i, j, r, _) = self.dist.as_ref()?.sample_cell(u)?;
        let w = self.width;
        // The cell's right corners wrap around to column 0 (a test, not a division).
        let i1 = if i + 1 == w { 0 } else { i + 1 };
        let c = |x: usize, y: usize| self.texels[y * w + x].w;
        let (c00, c10, c01, c11) = (c(i, j), c(i1, j), c(i, j + 1), c(i1, j + 1));
        let fy = sample_linear(r.y, c00 + c10, c01 + c11);
        let fx = sample_linear(r.x, c00 + (c01 - c00) * fy, c10 + (c11 - c10) * fy);
        let s = i as f32 + fx;
        let v = (j as f32 + fy) / (self.height - 1) as f32;
        // The polar angle is half a turn times `v`, the azimuth `(s + 1/2) / width` of a turn.
        let (sin_t, cos_t) = sincos_turns(0.5 * v);
        if !(sin_t > 0.0) {
            return None;
        }
        let (sin_p, cos_p) = sincos_turns((s + 0.5) / w as f32);
        let local = Vec3::new(sin_p * sin_t, cos_t, -cos_p * sin_t);
        let wo = (self.to_world * local).unit_or_zero();
        let (le, pdf_uv) = self.lookup_and_pdf_uv(s, v);
        let pdf = pdf_uv / (2.0 * PI * PI * sin_t);
        if wo == Vec3::ZERO || le == Color::ZERO || !(pdf > 0.0) || !pdf.is_finite() {
            return None;
        }
        Some(EmitterSample {
            wo,
            target: None,
            weight: le / pdf,
            pdf,
            delta: false,
        })
    }
}

/// `t` in `[0, 1]` with density proportional to `(1 - t) a + t b` (`a, b >= 0`), for `u`
/// uniform in `[0, 1)`: the inverse of its cdf, in a form without cancellation.
#[inline]
fn sample_linear(u: f32, a: f32, b: f32) -> f32 {
    if a == b {
        return u;
    }
    let den = a + safe_sqrt((1.0 - u) * a * a + u * b * b);
    if !(den > 0.0) {
        return 0.0;
    }
    (u * (a + b) / den).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec;

    /// The integral over the sphere of `f(luminance)` for a `w x h` map, by the quadrature
    /// [`EnvMap::new`] uses for the whole luminance (cell corners averaged, times each row's
    /// band of solid angle).
    fn integrate(pixels: &[[f32; 3]], w: usize, h: usize, f: impl Fn(f64) -> f64) -> f64 {
        let lum = |x: usize, y: usize| f(f64::from(luminance(Color::from(pixels[y * w + x % w]))));
        let ny = h - 1;
        let mut sum = 0.0;
        for j in 0..ny {
            let band = libm::cos(core::f64::consts::PI * j as f64 / ny as f64)
                - libm::cos(core::f64::consts::PI * (j + 1) as f64 / ny as f64);
            for i in 0..w {
                sum +=
                    0.25 * (lum(i, j) + lum(i + 1, j) + lum(i, j + 1) + lum(i + 1, j + 1)) * band;
            }
        }
        sum * core::f64::consts::TAU / w as f64
    }

    /// With compensated tables, emitter sampling is left the luminance above the mean: its
    /// integral, within the difference between the tables' quadrature and the exact bands; with
    /// the plain tables, and for a map that cannot be compensated, all of it.
    #[test]
    fn sampled_integral_is_what_the_tables_sample() {
        let (w, h) = (64, 33);
        // A dim sky, brighter towards the zenith, and a small bright sun.
        let pixels: Vec<[f32; 3]> = (0..w * h)
            .map(|k| {
                let (x, y) = (k % w, k / w);
                let sun = (20..23).contains(&x) && (8..11).contains(&y);
                let v = if sun {
                    200.0
                } else {
                    1.0 + (h - y) as f32 / h as f32
                };
                [v, v * 0.9, v * 0.8]
            })
            .collect();
        let mut env = EnvMap::new(pixels.clone(), w, h, 1.0, Mat3::IDENTITY).expect("a map");
        let all = env.luminance_integral();
        assert_eq!(env.sampled_luminance_integral(), all);
        let mean = f64::from(all) / (4.0 * core::f64::consts::PI);
        let above = integrate(&pixels, w, h, |l| (l - mean).max(0.0));
        assert!(env.set_compensated(true));
        let sampled = f64::from(env.sampled_luminance_integral());
        assert!(
            (sampled / above - 1.0).abs() < 0.005,
            "sampled {sampled}, above the mean {above}, all {all}"
        );
        // Control: the part is a clear fraction of the whole, which the check above tells apart.
        assert!(above < 0.8 * f64::from(all), "{above} of {all}");
        assert!(!env.set_compensated(false));
        assert_eq!(env.sampled_luminance_integral(), all);
        // A uniform map keeps the plain tables, and all of its light to sample.
        let mut flat =
            EnvMap::new(vec![[0.5; 3]; w * h], w, h, 1.0, Mat3::IDENTITY).expect("a map");
        assert!(!flat.set_compensated(true));
        assert_eq!(flat.sampled_luminance_integral(), flat.luminance_integral());
    }
}
