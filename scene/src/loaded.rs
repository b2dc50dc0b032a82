//! A loaded scene: the core scene with the settings its file asks for (integrator, sample count,
//! seed), which the command line may change before rendering.
use crate::integrator::{integrator_names, IntegratorSpec, LayerSource};
use tessera_core::integrator::Integrator;
use tessera_core::sampling::{SamplerKind, SAMPLER_NAMES};
use tessera_core::scene::Scene;

/// A loaded scene with the settings its file asks for.
#[derive(Debug)]
pub struct LoadedScene {
    /// The scene.
    pub scene: Scene,
    /// The integrator the file names (default `path`).
    pub integrator: Integrator,
    /// Its name and parameters, to rebuild it with command-line changes.
    pub integrator_spec: IntegratorSpec,
    /// Samples per pixel from the sampler (default 4, as in Mitsuba 3).
    pub spp: u64,
    /// Seed from the sampler (default 0).
    pub seed: u64,
    /// Whether the file names a sampler. One that does not renders with `zsobol` set up for
    /// the largest block (2^32 samples a pixel), whatever count is rendered: a pixel's first
    /// `n` samples are then the first `n` of one Owen-scrambled Sobol sequence (stratified at
    /// every power of two), so any `--spp`, `--time`, pass or part draws one sequence. Mitsuba
    /// 3 uses `independent` there; at equal samples zsobol's error is lower.
    pub sampler_named: bool,
    /// Things that load but are not rendered exactly as written (one line each).
    pub warnings: Vec<String>,
    /// The plugin each shape, BSDF and emitter was built from, by index.
    pub names: PluginNames,
    /// [`crate::hash::scene_hash`] of the text the scene was loaded from and its `-D` defines
    /// (0 for a scene nested in another file).
    pub source_hash: u64,
    /// Seconds spent building the core scene (its acceleration structure, mostly).
    pub accel_seconds: f64,
    /// The world position of the core scene's origin: zero, unless the camera was far from the
    /// world's origin and the loader moved the scene so that the camera sits at the core's
    /// origin (a world point `p` is then at `p - frame_origin` in the core scene).
    pub frame_origin: [f64; 3],
    /// Whose conventions the scene is rendered with (see [`crate::xml::Dialect`]).
    pub dialect: crate::xml::Dialect,
}

/// The plugin names of a scene's parts, by their index in the core scene, for reports that
/// name what a path met (`--debug-pixel`).
#[derive(Clone, Debug, Default)]
pub struct PluginNames {
    /// Per shape.
    pub shapes: Vec<String>,
    /// Per BSDF.
    pub bsdfs: Vec<String>,
    /// Per emitter.
    pub emitters: Vec<String>,
}

impl LoadedScene {
    /// Switches to another sampler by name (`None`: keep the file's) and sets it up for `spp`
    /// samples per pixel (zsobol's pixel blocks depend on it; see `ZSobolSampler`). The
    /// default of a file that names no sampler stays as it is (see [`Self::sampler_named`]).
    pub fn set_sampler(&mut self, name: Option<&str>, spp: u64) -> Result<(), String> {
        self.scene.sampler = match name {
            Some(n) => SamplerKind::from_name(n, spp)
                .ok_or_else(|| format!("unknown sampler \"{n}\" (known: {SAMPLER_NAMES})"))?,
            None if !self.sampler_named => self.scene.sampler,
            None => self.scene.sampler.for_spp(spp),
        };
        Ok(())
    }

    /// [`Self::set_sampler`] for a count the render was asked for (`tessera render --spp`, or
    /// the count a resumed render first asked for): a file that names no sampler is then set up
    /// for it too, instead of keeping its one block for any count.
    pub fn set_sampler_for(&mut self, name: Option<&str>, spp: u64) -> Result<(), String> {
        if name.is_none() && !self.sampler_named {
            self.scene.sampler = self.scene.sampler.for_spp(spp);
            return Ok(());
        }
        self.set_sampler(name, spp)
    }

    /// Switches to another integrator by name (keeping the file's parameters that apply; a name
    /// ending in `+reuse` turns on path reuse, any other name turns it off) and/or another
    /// `max_depth` (-1 = unbounded).
    pub fn set_integrator(
        &mut self,
        name: Option<&str>,
        max_depth: Option<i64>,
    ) -> Result<(), String> {
        let mut spec = self.integrator_spec.clone();
        if let Some(n) = name {
            // `NAME+reuse`: the path tracer NAME with path reuse; a name given without it
            // turns reuse off, whatever the file said.
            let (base, reuse) = match n.strip_suffix("+reuse") {
                Some(base) => (base, true),
                None => (n, false),
            };
            if reuse && !base.starts_with("path") {
                return Err(format!(
                    "\"+reuse\" needs a path tracer (path, path_mis, ...), found \"{base}\""
                ));
            }
            if base == "moment" || base == "aov" {
                return Err(format!(
                    "\"{base}\" wraps other integrators in a scene file; name the integrator \
                     to render"
                ));
            }
            spec.name = base.to_string();
            spec.reuse = reuse;
        }
        if let Some(d) = max_depth {
            if d < -1 || d > u32::MAX as i64 {
                return Err(format!("max depth must be -1 or at least 0, found {d}"));
            }
            spec.max_depth = (d >= 0).then_some(d as u32);
        }
        self.integrator = spec.build().ok_or_else(|| match spec.name.as_str() {
            "moment" => "\"moment\" wraps another integrator in a scene file; name the \
                         integrator to render"
                .to_string(),
            "simple" => "\"simple\" needs the point light (position, energy) that only its \
                         scene file can give"
                .to_string(),
            name => format!(
                "unknown integrator \"{name}\" (known: {})",
                integrator_names()
            ),
        })?;
        if !self.scene.media.is_empty() {
            if let Some(msg) = media_refusal(&self.integrator) {
                return Err(msg);
            }
        }
        if name.is_some() || max_depth.is_some() {
            // The colour may no longer be what the layers' nested integrators render.
            for layer in &mut spec.layers {
                layer.colour = false;
            }
        }
        self.integrator_spec = spec;
        self.sync_environment_sampling();
        Ok(())
    }

    /// Makes the environment maps sample by MIS-compensated tables where every integrator the
    /// scene renders with (the colour's and its layers') weighs each emitter sample by MIS
    /// ([`Integrator::weighs_light_samples_by_mis`]), by the plain tables otherwise. Called
    /// after loading and after [`LoadedScene::set_integrator`]; whoever replaces the integrator
    /// otherwise must call it too (a render job refuses a compensated scene with an integrator
    /// that cannot use it).
    pub fn sync_environment_sampling(&mut self) {
        let scene = &self.scene;
        let suits = |spec: &IntegratorSpec| {
            spec.build()
                .is_some_and(|i| i.may_use_compensated_environment(scene))
        };
        let on = self.integrator.weighs_light_samples_by_mis(scene)
            && self.integrator_spec.layers.iter().all(|l| match &l.source {
                LayerSource::Aov(_) => true,
                LayerSource::Nested(spec) | LayerSource::Moment { nested: spec, .. } => suits(spec),
            });
        self.scene.set_environment_compensation(on);
    }
}

/// Why `integrator` cannot render a scene with participating media (it would ignore them), or
/// `None` when it can: `volpath`, and the integrators that show geometry rather than light
/// (`aov`, normals, ambient occlusion), for which media do not matter.
pub(crate) fn media_refusal(integrator: &Integrator) -> Option<String> {
    let name = match integrator {
        Integrator::Path(_) => "path",
        Integrator::Direct(_) => "direct",
        Integrator::Simple(_) => "simple",
        Integrator::Whitted(_) => "whitted",
        Integrator::Moment(m) => return media_refusal(&m.inner),
        Integrator::VolPath(_)
        | Integrator::Normals(_)
        | Integrator::Visibility(_)
        | Integrator::Aov(_) => return None,
    };
    Some(format!(
        "the scene has participating media (<medium>), which integrator \"{name}\" ignores: \
         render it with \"volpath\" (<integrator type=\"volpath\">, or --integrator volpath)"
    ))
}
