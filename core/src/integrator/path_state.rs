//! A path's state between vertices (what it carries from one bounce to the next, including how it
//! left the last vertex, [`Prev`]), and the two halves the group estimator of
//! `reuse` splits a path into ([`PREFIX`], [`SUFFIX`]).
use crate::geometry::Interaction;
use crate::light::VertexSelection;
use crate::math::Ray;
use crate::Color;
use glam::Vec3;

/// How the path loop runs: a whole path, or one of the two halves the group
/// estimator of `reuse` splits it into.
pub(super) const WHOLE: u8 = 0;
/// Stops once the second vertex's emission is counted, keeping the first vertex and the state.
pub(super) const PREFIX: u8 = 1;
/// Starts from a paused state at an already-found vertex; Russian roulette sees the throughput
/// times the state's `rr_scale`.
pub(super) const SUFFIX: u8 = 2;

/// What the next vertex needs to know about how the path left the previous one.
#[derive(Clone, Copy)]
pub(super) struct Prev {
    /// Where the path left the previous vertex.
    pub p: Vec3,
    /// BSDF density of the sampled direction.
    pub pdf: f32,
    /// Whether emitter sampling ran there and could have produced this direction.
    pub nee: bool,
    /// The light selection used there, when it was the vertex's own.
    pub sel: Option<VertexSelection>,
}

/// A path's state between two vertices: what the loop carries from one bounce to the next.
#[derive(Clone, Copy)]
pub(super) struct PathState {
    /// The next segment (already cast when `pending` holds its hit).
    pub ray: Ray,
    /// Product of the weights so far.
    pub throughput: Color,
    /// Product of the relative indices crossed (Russian roulette undoes their scaling).
    pub eta: f32,
    /// Segments so far (0 for the camera ray).
    pub depth: u32,
    /// How the path left the previous vertex.
    pub prev: Option<Prev>,
    /// Scales the throughput in Russian roulette's survival probability (`SUFFIX` only).
    pub rr_scale: Color,
    /// The vertex the ray already reached, its emission counted (a `PREFIX` run leaves it for
    /// `SUFFIX`, which starts there).
    pub pending: Option<Interaction>,
}

impl PathState {
    /// A camera ray's state.
    #[inline(always)]
    pub(super) fn start(ray: Ray) -> Self {
        PathState {
            ray,
            throughput: Color::ONE,
            eta: 1.0,
            depth: 0,
            prev: None,
            rr_scale: Color::ONE,
            pending: None,
        }
    }
}

/// What a `PREFIX` run leaves: the first vertex where the path sampled its BSDF, and the vertex
/// that bounce reached with the state to go on from it.
#[derive(Clone, Copy, Default)]
pub(super) struct Prefix {
    /// First vertex, its BSDF index and `wi` in its shading frame (set when it has a smooth
    /// component and the path sampled its BSDF there).
    pub x: Option<(Interaction, u32, Vec3)>,
    /// Whether the bounce from `x` took a delta component.
    pub delta: bool,
    /// The state at the second vertex, which its `pending` holds (emission already counted).
    pub y: Option<PathState>,
}
