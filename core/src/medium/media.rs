//! Which media a scene holds and where they are: the surfaces that bound them and the medium the
//! camera sits in.
//!
//! As in Mitsuba 3, a medium has no extent of its own: a shape names the medium on its inside
//! (`interior`, the side its normal points away from) and on its outside (`exterior`), and a
//! path that crosses the shape enters the one on the side it moves to. A shape that names
//! neither leaves the current medium unchanged. The camera's medium is where camera rays start.
use super::Medium;
use alloc::vec::Vec;
use glam::Vec3;

/// The media on either side of one shape (indices into [`SceneMedia::media`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MediumInterface {
    /// Medium behind the surface (opposite its geometric normal).
    pub interior: Option<u32>,
    /// Medium in front of the surface (along its geometric normal).
    pub exterior: Option<u32>,
}

impl MediumInterface {
    /// Whether crossing the surface can change the medium.
    #[inline]
    pub fn is_transition(&self) -> bool {
        self.interior.is_some() || self.exterior.is_some()
    }
    /// The medium a ray leaving the surface along `d` enters, for geometric normal `ng`.
    #[inline]
    pub fn target(&self, ng: Vec3, d: Vec3) -> Option<u32> {
        if ng.dot(d) > 0.0 {
            self.exterior
        } else {
            self.interior
        }
    }
}

/// A scene's media (empty for a scene without any: nothing of it is then consulted).
#[derive(Clone, Debug, Default)]
pub struct SceneMedia {
    /// The media.
    pub media: Vec<Medium>,
    /// Per shape index, the media on its sides (empty, or one entry per shape).
    pub interfaces: Vec<MediumInterface>,
    /// The medium camera rays start in.
    pub camera: Option<u32>,
}

impl SceneMedia {
    /// Whether the scene has any medium.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.media.is_empty()
    }
    /// The media on either side of shape `shape`.
    #[inline]
    pub fn interface(&self, shape: u32) -> MediumInterface {
        self.interfaces
            .get(shape as usize)
            .copied()
            .unwrap_or_default()
    }
}
