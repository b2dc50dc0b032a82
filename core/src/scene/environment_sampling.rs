//! Which tables a scene's environment maps sample by: the plain ones (density following the
//! map's luminance) or the MIS-compensated ones (the map's mean luminance taken out; see
//! `emitter/envmap_tables.rs`), which only integrators that weigh every emitter sample by
//! multiple importance sampling may use. Scenes start with the plain tables; the scene loader
//! turns compensation on where the file's integrators allow it.
use super::Scene;
use crate::emitter::Emitter;

impl Scene {
    /// Makes every environment map sample by compensated tables (`on`) or by the plain ones
    /// (see [`EnvMap::set_compensated`](crate::emitter::EnvMap::set_compensated)).
    pub fn set_environment_compensation(&mut self, on: bool) {
        let mut changed = false;
        for e in &mut self.emitters {
            if let Emitter::EnvMap(m) = e {
                let was = m.is_compensated();
                changed |= m.set_compensated(on) != was;
            }
        }
        // Light selection weighs a map by the part of its light its tables sample.
        if changed {
            self.set_light_selection(self.lights.how());
        }
    }

    /// Whether any environment map samples by compensated tables.
    pub fn environment_compensated(&self) -> bool {
        self.emitters
            .iter()
            .any(|e| matches!(e, Emitter::EnvMap(m) if m.is_compensated()))
    }
}
