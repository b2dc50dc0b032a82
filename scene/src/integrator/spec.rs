//! What an integrator plugin reads from the file, before the core integrator is made: the
//! [`IntegratorSpec`] (which the command line may change), the extra image channels a wrapper
//! asks for ([`Layer`]), and the shape of a plugin's builder.
use crate::plugin::Plugin;
use crate::util::Result;
use crate::xml::Object;
use tessera_core::glam::Vec3;
use tessera_core::integrator::{Aov, Heuristic, Integrator};
use tessera_core::light::LightSelection;
use tessera_core::Color;

/// An integrator's name and parameters as the scene file gives them; the command line may
/// change the name or the depth and build again.
#[derive(Clone, Debug)]
pub struct IntegratorSpec {
    /// Plugin name.
    pub name: String,
    /// Longest path (`None` = unbounded).
    pub max_depth: Option<u32>,
    /// Russian roulette start depth.
    pub rr_depth: u32,
    /// Hide emitters seen by the camera.
    pub hide_emitters: bool,
    /// Share light among 4x2 pixel groups (path tracers' `reuse`).
    pub reuse: bool,
    /// MIS heuristic, when the file names one.
    pub heuristic: Option<Heuristic>,
    /// Emitter samples (`direct`).
    pub emitter_samples: u32,
    /// BSDF samples (`direct`).
    pub bsdf_samples: u32,
    /// How emitter sampling picks a light.
    pub light_selection: LightSelection,
    /// The point light of Nori's `simple`: position and energy.
    pub point_light: Option<(Vec3, Color)>,
    /// Segment length of `av`.
    pub visibility_length: f32,
    /// Whether `volpathmis` weighs the colour channels together (`use_spectral_mis`).
    pub spectral_mis: bool,
    /// Located warnings about what the file asks and the integrator does not do (a wrapper's
    /// extra outputs), reported with the scene's other warnings.
    pub warnings: Vec<String>,
    /// Extra image channels (`aov`, `moment`), each group rendered by its own integrator with
    /// the same seed and sampler; empty for every other integrator.
    pub layers: Vec<Layer>,
}

impl Default for IntegratorSpec {
    fn default() -> Self {
        IntegratorSpec {
            name: "path".into(),
            max_depth: None,
            rr_depth: 5,
            hide_emitters: false,
            reuse: false,
            heuristic: None,
            emitter_samples: 1,
            bsdf_samples: 1,
            light_selection: LightSelection::Contribution,
            point_light: None,
            visibility_length: 1.0,
            spectral_mis: true,
            warnings: Vec::new(),
            layers: Vec::new(),
        }
    }
}

/// Up to three image channels rendered together, as the channels of one colour.
#[derive(Clone, Debug)]
pub struct Layer {
    /// The channel names (one to three), in the order of the colour's channels.
    pub names: Vec<String>,
    /// What is rendered.
    pub source: LayerSource,
    /// Whether the colour image's integrator is this layer's (the first one nested in `aov` or
    /// `moment`), so that its values follow from the colour's own samples: the colour as it is
    /// (`aov`), converted to XYZ (a first moment), or each sample's XYZ squared as the colour's
    /// pass gathers it (a second moment), instead of rendering the same samples again.
    /// Cleared when the command line changes the colour's integrator; whoever replaces
    /// `LoadedScene::integrator` otherwise must clear it too.
    pub colour: bool,
}

/// What a [`Layer`] renders.
#[derive(Clone, Debug)]
pub enum LayerSource {
    /// A nested integrator's colour.
    Nested(Box<IntegratorSpec>),
    /// A surface variable.
    Aov(Aov),
    /// A nested integrator's XYZ (`square` false) or its square.
    Moment {
        /// The nested integrator.
        nested: Box<IntegratorSpec>,
        /// Second moment.
        square: bool,
    },
}

/// How an integrator plugin is built: `read` takes the file's parameters into a spec, `make`
/// turns a spec (perhaps changed by the command line) into the core integrator.
pub struct IntegratorBuild {
    /// Reads the parameters (the spec's name is already set).
    pub read: fn(&Object, &mut IntegratorSpec, Nest) -> Result<()>,
    /// Makes the core integrator (`None` for a wrapper, whose spec is its nested
    /// integrator's).
    pub make: Option<fn(&IntegratorSpec) -> Integrator>,
}

/// An integrator plugin.
pub(crate) type IntegratorPlugin = Plugin<IntegratorBuild>;

/// Reads a nested `<integrator>` (or the default) through the family's table; the table passes
/// it to a wrapper's reader, so that the wrapper's file need not know the table.
pub(crate) type Nest = fn(Option<&Object>) -> Result<IntegratorSpec>;
