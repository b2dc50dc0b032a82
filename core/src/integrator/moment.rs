//! Mitsuba 3's `moment` channels: a nested integrator's radiance converted to CIE XYZ (with
//! Mitsuba 3's linear sRGB to XYZ matrix), or the square of each of those values, per sample.
//! Averaged over a pixel's samples, they are the first and second moments from which a
//! pixel's sample variance follows. Rendered with the nested integrator's seed and sampler,
//! every sample squares exactly the value the nested integrator's own render averages.
use super::probe::Probe;
use super::radiance::Radiance;
use crate::math::Ray;
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::Color;
use alloc::boxed::Box;
use glam::Mat3;

/// Linear sRGB (Rec. 709 primaries, D65) to CIE XYZ, as Mitsuba 3's `srgb_to_xyz` gives it.
pub const SRGB_TO_XYZ: Mat3 = Mat3::from_cols_array(&[
    0.412453, 0.212671, 0.019334, // column R
    0.357580, 0.715160, 0.119193, // column G
    0.180423, 0.072169, 0.950227, // column B
]);

/// The XYZ of a nested integrator's samples, or their squares; `I` is the nested integrator's
/// type (the `Integrator` enum, which holds this wrapper as one of its variants).
#[derive(Clone, Debug)]
pub struct MomentIntegrator<I> {
    /// The integrator whose samples are converted.
    pub inner: Box<I>,
    /// Squares each XYZ value (the second moment) instead of passing it on (the first).
    pub square: bool,
}

impl<I: Radiance> MomentIntegrator<I> {
    /// XYZ (or its square) of the nested integrator's value along `ray`.
    #[inline]
    pub fn li_probed<S: Sampler, P: Probe>(
        &self,
        scene: &Scene,
        ray: Ray,
        sampler: &mut S,
        probe: &mut P,
    ) -> Color {
        let c = self.inner.li_probed(scene, ray, sampler, probe);
        match self.square {
            true => xyz_squared(c),
            false => SRGB_TO_XYZ * c,
        }
    }
}

/// The square of each XYZ value of a linear sRGB colour: a second moment's sample. Renders that
/// take the second moment in the colour's own pass square each colour sample with this, so the
/// bits are those of a render of the `moment` integrator.
#[inline]
pub fn xyz_squared(c: Color) -> Color {
    let xyz = SRGB_TO_XYZ * c;
    xyz * xyz
}
