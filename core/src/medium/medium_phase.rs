//! A heterogeneous medium's phase function, which may vary through space: one function
//! everywhere, or SGGX flakes whose matrix comes from a 6-channel grid (Mitsuba 3's `sggx` with
//! a `gridvolume` `S`). The integrator asks for the function at a scattering point; the medium
//! asks for the flakes' matrix there, which scales its extinction by their projected area.
use super::phase::PhaseFunction;
use super::sggx::{Sggx, SggxMatrix};
use super::volume::{Volume, VolumeData};
use alloc::borrow::Cow;
use alloc::boxed::Box;
use glam::Vec3;

/// A phase function over space.
#[derive(Clone, Debug)]
pub enum MediumPhase {
    /// The same function everywhere.
    Fixed(PhaseFunction),
    /// SGGX flakes, their matrix looked up in a 6-channel grid volume.
    SggxGrid(Box<Volume>),
}

impl MediumPhase {
    /// The phase function at world point `p`.
    #[inline]
    pub fn at(&self, p: Vec3) -> Cow<'_, PhaseFunction> {
        match self {
            MediumPhase::Fixed(f) => Cow::Borrowed(f),
            MediumPhase::SggxGrid(v) => Cow::Owned(PhaseFunction::Sggx(Sggx {
                s: v.eval_matrix(p),
            })),
        }
    }
    /// The flakes' matrix at world point `p`, if the function is SGGX.
    #[inline]
    pub fn flakes_at(&self, p: Vec3) -> Option<SggxMatrix> {
        match self {
            MediumPhase::Fixed(PhaseFunction::Sggx(s)) => Some(s.s),
            MediumPhase::Fixed(_) => None,
            MediumPhase::SggxGrid(v) => Some(v.eval_matrix(p)),
        }
    }
    /// A bound on the flakes' projected area anywhere and in any direction: the factor the
    /// extinction's majorants take (1 without flakes).
    pub fn projected_area_bound(&self) -> f32 {
        match self {
            MediumPhase::Fixed(PhaseFunction::Sggx(s)) => s.s.projected_area_bound(),
            MediumPhase::Fixed(_) => 1.0,
            MediumPhase::SggxGrid(v) => match &v.data {
                VolumeData::Grid(g) => g.grid.max_projected_area(),
                VolumeData::Constant(_) => 1.0,
            },
        }
    }
}
