//! Participating media: what fills the space between surfaces, and how light scatters in it.
//!
//! - `phase`: the closed enum of phase functions (the directional law of a scattering event),
//!   with `isotropic`, `hg` (Henyey-Greenstein), `rayleigh`, `tabulated` (`tabphase`) and
//!   `blend` (`blendphase`, over any [`PhaseModel`]) and `sggx` (microflakes) each in its own
//!   file, and the sample they return (`phase_sample`); `medium_phase`: a phase function that
//!   varies through space (SGGX flakes from a grid);
//! - `homogeneous`: a medium of constant extinction and albedo (Mitsuba 3's `homogeneous`);
//! - `heterogeneous`: extinction and albedo from volumes (Mitsuba 3's `heterogeneous`), with
//!   delta and ratio tracking; `volume` and `voxel_grid` (the `<volume>` data) and `majorant`
//!   (per-cell bounds on the extinction) below it;
//! - `free_flight`: sampling the distance to the next collision in a medium whose extinction
//!   differs per colour channel;
//! - `media`: which media a scene has, which surfaces bound them, and where the camera sits.
//!
//! The integrator that uses them is `integrator::volpath`. Parameters are declared with their
//! loader, in `scene/src/media/`.
mod blend;
mod free_flight;
mod heterogeneous;
mod hg;
mod homogeneous;
mod isotropic;
mod majorant;
mod media;
mod medium_phase;
mod phase;
mod phase_model;
mod phase_sample;
mod rayleigh;
mod sggx;
mod tabulated;
mod volume;
mod voxel_grid;

pub use blend::Blend;
pub use free_flight::{sample_free_flight, ChannelRatios, FreeFlight};
pub use heterogeneous::{Heterogeneous, TrackedFlight};
pub use hg::HenyeyGreenstein;
pub use homogeneous::Homogeneous;
pub use isotropic::Isotropic;
pub use majorant::{MajorantGrid, MAJORANT_CELLS};
pub use media::{MediumInterface, SceneMedia};
pub use medium_phase::MediumPhase;
pub use phase::PhaseFunction;
pub use phase_model::PhaseModel;
pub use phase_sample::PhaseSample;
pub use rayleigh::Rayleigh;
pub use sggx::{Sggx, SggxMatrix};
pub use tabulated::{TableError, Tabulated};
pub use volume::{GridVolume, Volume, VolumeData};
pub use voxel_grid::{GridFilter, GridWrap, VoxelGrid};

/// The media a scene can hold: a closed enum.
#[derive(Clone, Debug)]
pub enum Medium {
    /// Constant extinction (`homogeneous`; boxed, as its albedo may be a grid).
    Homogeneous(alloc::boxed::Box<Homogeneous>),
    /// Extinction and albedo from volumes (`heterogeneous`; boxed, as it holds its grids).
    Heterogeneous(alloc::boxed::Box<Heterogeneous>),
}

impl Medium {
    /// The medium's phase function at world point `p`.
    #[inline]
    pub fn phase_at(&self, p: glam::Vec3) -> alloc::borrow::Cow<'_, PhaseFunction> {
        match self {
            Medium::Homogeneous(m) => alloc::borrow::Cow::Borrowed(&m.phase),
            Medium::Heterogeneous(m) => m.phase.at(p),
        }
    }
    /// Whether a scattering event in this medium samples emitters (`sample_emitters`).
    #[inline]
    pub fn sample_emitters(&self) -> bool {
        match self {
            Medium::Homogeneous(m) => m.sample_emitters,
            Medium::Heterogeneous(m) => m.sample_emitters,
        }
    }
}
