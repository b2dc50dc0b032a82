//! The scene's light sampler: how emitter sampling picks one light, set up once from the scene's
//! emitters (and again when the selection changes). It holds the scene-wide choice (by power, or
//! uniform) and, for the per-vertex choice, each light's bound; the integrators ask it for a
//! light and for the probability of the one a ray found.
use super::bound::LightBound;
use super::light_lanes::LightLanes;
use super::vertex::MAX_VERTEX_LIGHTS;
use crate::emitter::{Emitter, EmitterCtx};
use crate::sampling::Discrete1D;
use alloc::vec::Vec;

/// How emitter sampling picks one light.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LightSelection {
    /// At each vertex, in proportion to an estimate of each light's contribution there (its
    /// irradiance times the BSDF toward it), a fifth spread evenly: the default
    /// ([`VertexSelection`](super::vertex::VertexSelection)). Scenes with one light or more than
    /// [`MAX_VERTEX_LIGHTS`] choose by power instead.
    #[default]
    Contribution,
    /// In proportion to each light's emitted power (luminance), so shadow rays go where the light
    /// is. Falls back to uniform when no light reports a positive power.
    Power,
    /// Every light with the same probability (the seeds' and Mitsuba 3's default).
    Uniform,
}

/// The scene-wide light choice and the per-light bounds of vertex selection.
#[derive(Clone, Debug)]
pub struct LightSampler {
    /// How it chooses.
    how: LightSelection,
    /// Number of lights.
    count: usize,
    /// Light choice by power (None: uniform), where no vertex selection applies.
    selection: Option<Discrete1D>,
    /// Each light as vertex selection sees it (empty: the scene-wide `selection` applies).
    bounds: Vec<LightBound>,
    /// The same lights four to a vector, where at least two have a position.
    lanes: Option<LightLanes>,
}

impl LightSampler {
    /// The sampler of `emitters` (in the context `ctx`) choosing as `how` says: by power, or
    /// `None` for uniform, scene-wide; per-light bounds for vertex selection only when `how` is
    /// `Contribution` and 2 to [`MAX_VERTEX_LIGHTS`] lights exist (the scene-wide choice is by
    /// power then).
    pub fn new(how: LightSelection, emitters: &[Emitter], ctx: &EmitterCtx) -> LightSampler {
        let by_power = || Discrete1D::new(emitters.iter().map(|e| e.power(ctx)));
        let (selection, bounds) = match how {
            LightSelection::Contribution => {
                let bounds = if (2..=MAX_VERTEX_LIGHTS).contains(&emitters.len()) {
                    emitters.iter().map(|e| LightBound::of(e, ctx)).collect()
                } else {
                    Vec::new()
                };
                (by_power(), bounds)
            }
            LightSelection::Power => (by_power(), Vec::new()),
            LightSelection::Uniform => (None, Vec::new()),
        };
        LightSampler {
            how,
            count: emitters.len(),
            selection,
            lanes: LightLanes::of(&bounds),
            bounds,
        }
    }

    /// How it chooses.
    pub fn how(&self) -> LightSelection {
        self.how
    }

    /// Each light as vertex selection sees it; empty where the scene-wide choice applies.
    #[inline]
    pub fn bounds(&self) -> &[LightBound] {
        &self.bounds
    }

    /// [`Self::bounds`] four to a vector, where at least two have a position.
    #[inline]
    pub fn lanes(&self) -> Option<&LightLanes> {
        self.lanes.as_ref()
    }

    /// Picks a light for emitter sampling: its index and the probability it was picked.
    #[inline]
    pub fn pick(&self, u: f32) -> Option<(usize, f32)> {
        let n = self.count;
        if n == 0 {
            return None;
        }
        match &self.selection {
            Some(d) => {
                let (i, _) = d.sample_reuse(u);
                Some((i, d.pmf(i)))
            }
            None => Some((((u * n as f32) as usize).min(n - 1), 1.0 / n as f32)),
        }
    }

    /// The probability that [`LightSampler::pick`] picks light `i`.
    #[inline]
    pub fn pdf(&self, i: usize) -> f32 {
        match &self.selection {
            Some(d) => d.pmf(i),
            None => 1.0 / self.count as f32,
        }
    }
}
