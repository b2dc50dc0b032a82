//! The `<integrator>` plugins (`INTEGRATORS`, in `table.rs`), with Mitsuba 3's names and
//! parameters plus Tessera's own (`heuristic`, `reuse`, `light_selection`). A scene without an
//! integrator uses `path`. Each plugin reads its parameters into an [`IntegratorSpec`], which the
//! command line may change (another name, another depth) before the core integrator is made
//! from it.
mod aov;
mod spec;
mod table;
mod tracers;

pub use spec::{IntegratorSpec, Layer, LayerSource};
pub use table::INTEGRATORS;
pub(crate) use table::{integrator_names, read_integrator};
