//! The sampling tables of an environment map: a weight per pixel, the distribution over the
//! cells between pixels that samples them, and the scale that turns an interpolated weight into
//! a density.
//!
//! A pixel's weight is its luminance times the sine of its row's polar angle (the solid angle a
//! row of the latitude-longitude image covers shrinks towards the poles). With a `floor`, each
//! luminance is first lowered by it and clamped at zero: MIS compensation (Karlík, Šik, Vévoda,
//! Skřivan and Křivánek, "MIS Compensation: Optimizing Sampling Techniques in Multiple Importance
//! Sampling", 2019). Where emitter sampling is combined with BSDF sampling by multiple
//! importance sampling, the BSDF's strategy already finds light from the dim, broad parts of the
//! sky; taking the map's mean luminance out of its table sends the emitter's samples to the parts
//! brighter than the mean, where they help most. The estimate stays unbiased only where every
//! emitter sample is weighed against a strategy that covers the directions the table no longer
//! reaches, which is why the scene turns it on only for such integrators.
use super::sample::luminance;
use crate::sampling::Distribution2D;
use crate::Color;
use alloc::vec::Vec;

/// The tables built by [`tables`].
pub(super) struct Tables {
    /// Per pixel, the weight at the cell corners.
    pub weights: Vec<f32>,
    /// Cell choice (`None` when every weight is zero).
    pub dist: Option<Distribution2D>,
    /// `width * (height - 1)` over the integral of the bilinear weights in cell units.
    pub pdf_scale: f32,
}

/// The tables of the `width x height` radiance `pixels` (row-major, top row first), each
/// luminance lowered by `floor` (0 for the plain tables) and clamped at zero.
pub(super) fn tables(
    pixels: impl ExactSizeIterator<Item = Color>,
    width: usize,
    height: usize,
    floor: f64,
) -> Tables {
    let (nx, ny) = (width, height - 1);
    let mut weights = Vec::with_capacity(pixels.len());
    // The pole rows (sin theta = 0) get the sine of a quarter row instead, so that the density
    // stays positive wherever the radiance is, even when only a pole row is bright.
    let sin_floor = libm::sin(core::f64::consts::PI / (4 * ny) as f64);
    for (k, p) in pixels.enumerate() {
        let y = k / width;
        let sin_t = libm::sin(core::f64::consts::PI * y as f64 / ny as f64).max(sin_floor);
        let lum = f64::from(luminance(p));
        let lum = if floor > 0.0 {
            (lum - floor).max(0.0)
        } else {
            lum
        };
        weights.push((lum * sin_t) as f32);
    }
    let corner = |x: usize, y: usize| f64::from(weights[y * width + x % width]);
    let mut cells = Vec::with_capacity(nx * ny);
    let mut total = 0.0f64;
    for j in 0..ny {
        for i in 0..nx {
            let mean =
                0.25 * (corner(i, j) + corner(i + 1, j) + corner(i, j + 1) + corner(i + 1, j + 1));
            total += mean;
            cells.push(mean as f32);
        }
    }
    let pdf_scale = ((nx * ny) as f64 / total) as f32;
    Tables {
        dist: Distribution2D::new(&cells, nx, ny),
        pdf_scale: if pdf_scale.is_finite() {
            pdf_scale
        } else {
            0.0
        },
        weights,
    }
}
