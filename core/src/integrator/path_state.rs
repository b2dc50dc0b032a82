//! A path's state between vertices: what the path loop carries from one bounce to the next,
//! including how the path left the last vertex ([`Prev`]), and whether it still carries light.
use super::probe::{PathEnd, Probe};
use crate::light::VertexSelection;
use crate::math::Ray;
use crate::Color;
use glam::Vec3;

/// What the next vertex needs to know about how the path left the previous one.
#[derive(Clone, Copy)]
pub(super) struct Prev {
    /// Where the path left the previous vertex.
    pub p: Vec3,
    /// BSDF density of the sampled direction.
    pub pdf: f32,
    /// Whether emitter sampling ran there and could have produced this direction.
    pub nee: bool,
    /// Whether the sampled direction came from a delta component of the BSDF.
    pub delta: bool,
}

/// A path's state between two vertices: what the loop carries from one bounce to the next.
#[derive(Clone, Copy)]
pub(super) struct PathState {
    /// The next segment, not cast yet.
    pub ray: Ray,
    /// Product of the weights so far.
    pub throughput: Color,
    /// Product of the relative indices crossed: radiance scaling at refractions is undone for
    /// Russian roulette, as in Mitsuba 3.
    pub eta: f32,
    /// Segments so far (0 for the camera ray).
    pub depth: u32,
    /// How the path left the previous vertex.
    pub prev: Option<Prev>,
    /// The light selection at the last vertex that sampled emitters, when it was the vertex's
    /// own. Kept here rather than in [`Prev`] so that the selection is written once, in place,
    /// where the vertex finds it: moved into a fresh `Prev` at each bounce, its 80 bytes were
    /// copied through the stack by loads wider than the stores that wrote them, which stall.
    pub sel: Option<VertexSelection>,
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
            sel: None,
        }
    }
}

/// Whether the path still carries light: false (the path ends) once its throughput is zero or
/// not finite.
#[inline(always)]
pub(super) fn alive<P: Probe>(path: &PathState, probe: &mut P) -> bool {
    let alive = path.throughput != Color::ZERO && path.throughput.is_finite();
    if !alive {
        probe.end(PathEnd::ZeroThroughput);
    }
    alive
}
