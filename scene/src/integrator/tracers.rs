//! The integrators that trace light: Mitsuba 3's `path` and `direct` with Tessera's variants
//! of each (a fixed strategy, Wakame's names), and the course integrators (Nori's `whitted`,
//! `normals`, `ao`, `av`, `simple`), with their parameters.
use super::spec::{IntegratorBuild, IntegratorPlugin, IntegratorSpec, Nest};
use crate::plugin::{Param, Plugin, Range};
use crate::util::vec3;
use crate::util::Result;
use crate::xml::Object;
use tessera_core::glam::Vec3;
use tessera_core::integrator::{
    DirectIntegrator, Heuristic, Integrator, MediumMis, NormalsIntegrator, PathIntegrator,
    SimpleIntegrator, Strategy, Visibility, VolPathIntegrator, WhittedIntegrator,
};
use tessera_core::light::LightSelection;
use tessera_core::Color;

const MAX_DEPTH: Param = Param::integer(
    "max_depth",
    -1,
    Range::Note("-1 (unbounded) or at least 0"),
    "longest path in segments (1: emitters seen directly only)",
);
const RR_DEPTH: Param = Param::integer(
    "rr_depth",
    5,
    Range::Note("at least 1"),
    "path length from which Russian roulette may end a path",
);
const HIDE_EMITTERS: Param = Param::boolean(
    "hide_emitters",
    false,
    "emitters seen directly by the camera are black",
);
const HEURISTIC: Param = Param::new(
    "heuristic",
    crate::plugin::ParamType::Choice,
    crate::plugin::Default::Note("power (balance for direct_mis)"),
    Range::OneOf(&["power", "balance"]),
    "multiple importance sampling weights (Tessera's parameter)",
);
const REUSE: Param = Param::boolean(
    "reuse",
    false,
    "share light among 4x2 pixel groups (path reuse; Tessera's parameter)",
);
const LIGHT_SELECTION: Param = Param::choice(
    "light_selection",
    "contribution",
    &["contribution", "power", "uniform"],
    "how emitter sampling picks a light (Tessera's parameter)",
);

fn path(s: &IntegratorSpec, strategy: Strategy) -> Integrator {
    Integrator::Path(PathIntegrator {
        strategy,
        max_depth: s.max_depth,
        rr_depth: s.rr_depth,
        hide_emitters: s.hide_emitters,
        heuristic: s.heuristic.unwrap_or(Heuristic::Power),
        reuse: s.reuse,
    })
}

fn direct(s: &IntegratorSpec, emitter_samples: u32, bsdf_samples: u32, h: Heuristic) -> Integrator {
    Integrator::Direct(DirectIntegrator {
        emitter_samples,
        bsdf_samples,
        heuristic: h,
        hide_emitters: s.hide_emitters,
    })
}

/// A path tracer: the same parameters, another strategy.
const fn path_plugin(
    name: &'static str,
    aliases: &'static [&'static str],
    doc: &'static str,
    make: fn(&IntegratorSpec) -> Integrator,
) -> IntegratorPlugin {
    Plugin {
        name,
        aliases,
        doc,
        params: &[
            MAX_DEPTH,
            RR_DEPTH,
            HIDE_EMITTERS,
            HEURISTIC,
            REUSE,
            LIGHT_SELECTION,
        ],
        nested: "",
        build: IntegratorBuild {
            read: read_path,
            make: Some(make),
        },
    }
}

fn read_path(obj: &Object, spec: &mut IntegratorSpec, _: Nest) -> Result<()> {
    let max_depth = MAX_DEPTH.read_i64_where(obj, |d| (-1..=u32::MAX as i64).contains(&d))?;
    spec.max_depth = (max_depth >= 0).then_some(max_depth as u32);
    spec.rr_depth = RR_DEPTH.read_i64_where(obj, |d| (1..=u32::MAX as i64).contains(&d))? as u32;
    spec.reuse = REUSE.read_bool(obj)?;
    read_heuristic(obj, spec)?;
    read_common(obj, spec)
}

fn read_heuristic(obj: &Object, spec: &mut IntegratorSpec) -> Result<()> {
    spec.heuristic = HEURISTIC.read_choice_opt(obj)?.map(|h| match h {
        "balance" => Heuristic::Balance,
        _ => Heuristic::Power,
    });
    Ok(())
}

/// `hide_emitters` and `light_selection`, which every integrator takes.
fn read_common(obj: &Object, spec: &mut IntegratorSpec) -> Result<()> {
    spec.light_selection = match LIGHT_SELECTION.read_choice(obj)? {
        "power" => LightSelection::Power,
        "uniform" => LightSelection::Uniform,
        _ => LightSelection::Contribution,
    };
    spec.hide_emitters = HIDE_EMITTERS.read_bool(obj)?;
    Ok(())
}

const SAMPLES: Range = Range::Note("between 0 and 2^20");
const SHADING_SAMPLES: Param = Param::integer(
    "shading_samples",
    1,
    SAMPLES,
    "the default of emitter_samples and bsdf_samples",
);
const EMITTER_SAMPLES: Param = Param::new(
    "emitter_samples",
    crate::plugin::ParamType::Integer,
    crate::plugin::Default::Note("shading_samples"),
    SAMPLES,
    "emitter samples per pixel sample",
);
const BSDF_SAMPLES: Param = Param::new(
    "bsdf_samples",
    crate::plugin::ParamType::Integer,
    crate::plugin::Default::Note("shading_samples"),
    SAMPLES,
    "BSDF samples per pixel sample (emitter_samples + bsdf_samples must be above 0)",
);

/// `direct`.
pub(crate) const DIRECT: IntegratorPlugin = Plugin {
    name: "direct",
    aliases: &[],
    doc: "Direct lighting only (Mitsuba 3's direct): emitter and BSDF samples combined by \
          multiple importance sampling.",
    params: &[
        SHADING_SAMPLES,
        EMITTER_SAMPLES,
        BSDF_SAMPLES,
        HEURISTIC,
        HIDE_EMITTERS,
        LIGHT_SELECTION,
    ],
    nested: "",
    build: IntegratorBuild {
        read: read_direct,
        make: Some(|s| {
            direct(
                s,
                s.emitter_samples,
                s.bsdf_samples,
                s.heuristic.unwrap_or(Heuristic::Power),
            )
        }),
    },
};

fn read_direct(obj: &Object, spec: &mut IntegratorSpec, _: Nest) -> Result<()> {
    let count = |p: &Param, default: i64| -> Result<u32> {
        Ok(p.read_i64_or(obj, default, |n| (0..=1 << 20).contains(&n))? as u32)
    };
    let shading = count(&SHADING_SAMPLES, 1)?;
    spec.emitter_samples = count(&EMITTER_SAMPLES, shading as i64)?;
    spec.bsdf_samples = count(&BSDF_SAMPLES, shading as i64)?;
    if spec.emitter_samples + spec.bsdf_samples == 0 {
        return Err(obj.error("a direct integrator needs emitter_samples or bsdf_samples above 0"));
    }
    read_heuristic(obj, spec)?;
    read_common(obj, spec)
}

/// A Wakame direct integrator with fixed sample counts.
const fn fixed_direct(
    name: &'static str,
    doc: &'static str,
    make: fn(&IntegratorSpec) -> Integrator,
) -> IntegratorPlugin {
    Plugin {
        name,
        aliases: &[],
        doc,
        params: &[HIDE_EMITTERS, LIGHT_SELECTION],
        nested: "",
        build: IntegratorBuild {
            read: |obj, spec, _| read_common(obj, spec),
            make: Some(make),
        },
    }
}

/// `direct_mis`.
pub(crate) const DIRECT_MIS: IntegratorPlugin = Plugin {
    name: "direct_mis",
    aliases: &[],
    doc: "The Wakame assignment's direct lighting: one emitter and one BSDF sample, combined by \
          the balance heuristic.",
    params: &[HEURISTIC, HIDE_EMITTERS, LIGHT_SELECTION],
    nested: "",
    build: IntegratorBuild {
        read: |obj, spec, _| {
            read_heuristic(obj, spec)?;
            read_common(obj, spec)
        },
        make: Some(|s| direct(s, 1, 1, s.heuristic.unwrap_or(Heuristic::Balance))),
    },
};

/// A course integrator without parameters.
const fn course(
    name: &'static str,
    doc: &'static str,
    make: fn(&IntegratorSpec) -> Integrator,
) -> IntegratorPlugin {
    Plugin {
        name,
        aliases: &[],
        doc,
        params: &[],
        nested: "",
        build: IntegratorBuild {
            read: |_, _, _| Ok(()),
            make: Some(make),
        },
    }
}

/// `whitted`.
pub(crate) const WHITTED: IntegratorPlugin = course(
    "whitted",
    "Nori's Whitted-style ray tracer: direct light by one emitter sample at surfaces with a \
     smooth BSDF; at mirrors and smooth glass one specular direction followed with probability \
     0.95 (weighted by 1/0.95).",
    |_| Integrator::Whitted(WhittedIntegrator),
);

/// `normals`.
pub(crate) const NORMALS: IntegratorPlugin = course(
    "normals",
    "Nori's normals view: the absolute shading normal at the first hit as a colour, black \
     where nothing is hit.",
    |_| Integrator::Normals(NormalsIntegrator),
);

/// `ao`.
pub(crate) const AO: IntegratorPlugin = course(
    "ao",
    "Nori's ambient occlusion: the cosine-weighted fraction of the hemisphere above the first \
     hit from which a ray escapes (one ray per sample), black where nothing is hit.",
    |_| Integrator::Visibility(Visibility::AmbientOcclusion),
);

const LENGTH: Param = Param::float(
    "length",
    1.0,
    Range::Positive,
    "length of each visibility segment",
);

/// `av`.
pub(crate) const AV: IntegratorPlugin = Plugin {
    name: "av",
    aliases: &[],
    doc: "The Wakame assignment's average visibility: the uniformly weighted fraction of the \
          hemisphere above the first hit in which a segment of the given length meets nothing \
          (one segment per sample), white where nothing is hit.",
    params: &[LENGTH],
    nested: "",
    build: IntegratorBuild {
        read: |obj, spec, _| {
            spec.visibility_length = LENGTH.read_f32(obj)?;
            Ok(())
        },
        make: Some(|s| {
            Integrator::Visibility(Visibility::Average {
                length: s.visibility_length,
            })
        }),
    },
};

const LIGHT_POSITION: Param = Param::new(
    "position",
    crate::plugin::ParamType::Point,
    crate::plugin::Default::Required,
    Range::Any,
    "the point light's position",
);
const ENERGY: Param = Param::rgb(
    "energy",
    crate::plugin::Default::Required,
    Range::NonNegative,
    "the point light's power (flux)",
);

/// `simple`.
pub(crate) const SIMPLE: IntegratorPlugin = Plugin {
    name: "simple",
    aliases: &[],
    doc: "Nori's point-light integrator: every surface is a white diffuse reflector lit by one \
          point light with shadows, energy / (4 pi^2) * cos / distance^2; nothing else counts.",
    params: &[LIGHT_POSITION, ENERGY],
    nested: "",
    build: IntegratorBuild {
        read: |obj, spec, _| {
            let position = obj
                .point_opt(LIGHT_POSITION.name)?
                .ok_or_else(|| obj.missing(LIGHT_POSITION.name))?;
            spec.point_light = Some((vec3(position), ENERGY.read_color(obj)?));
            Ok(())
        },
        // `IntegratorSpec::build` makes nothing without the light (a command line naming
        // `simple` for a file that does not give it).
        make: Some(|s| {
            let (position, energy) = s.point_light.unwrap_or((Vec3::ZERO, Color::ZERO));
            Integrator::Simple(SimpleIntegrator { position, energy })
        }),
    },
};

/// `path`.
pub(crate) const PATH: IntegratorPlugin = path_plugin(
    "path",
    &["path_mis"],
    "Unidirectional path tracing with next-event estimation and multiple importance \
     sampling (Mitsuba 3's path).",
    |s| path(s, Strategy::Mis),
);

/// `volpath`.
pub(crate) const VOLPATH: IntegratorPlugin = Plugin {
    name: "volpath",
    aliases: &[],
    doc: "Volumetric path tracing (Mitsuba 3's volpath): paths through homogeneous \
          participating media and surfaces, with phase-function and BSDF sampling combined \
          with emitter sampling by the power heuristic, shadow rays through null surfaces \
          attenuated by the media they cross. On a scene without media it renders what path \
          renders. Emitter sampling picks lights by the scene-wide choice (by power for \
          contribution).",
    params: &[MAX_DEPTH, RR_DEPTH, HIDE_EMITTERS, LIGHT_SELECTION],
    nested: "",
    build: IntegratorBuild {
        read: read_volpath,
        make: Some(|s| {
            Integrator::VolPath(VolPathIntegrator {
                max_depth: s.max_depth,
                rr_depth: s.rr_depth,
                hide_emitters: s.hide_emitters,
                mis: MediumMis::Separate,
            })
        }),
    },
};

const USE_SPECTRAL_MIS: Param = Param::boolean(
    "use_spectral_mis",
    true,
    "whether the colour channels' free-flight strategies are combined by the balance heuristic \
     (else each path is weighed by the channel it drew its distances from alone)",
);

/// `volpathmis`.
pub(crate) const VOLPATHMIS: IntegratorPlugin = Plugin {
    name: "volpathmis",
    aliases: &[],
    doc: "Volumetric path tracing with spectral MIS (Mitsuba 3's volpathmis): volpath's paths, \
          each contribution weighed by the balance heuristic over the colour channels and the \
          two directional strategies (emitter sampling, phase-function or BSDF sampling) \
          together, the channels' probabilities of passing the segment to the light included. \
          Where that segment crosses a heterogeneous medium, volpath's weights are used. Shadow \
          rays evaluate the transmittance (exactly, or by ratio tracking) rather than sampling it.",
    params: &[
        MAX_DEPTH,
        RR_DEPTH,
        HIDE_EMITTERS,
        USE_SPECTRAL_MIS,
        LIGHT_SELECTION,
    ],
    nested: "",
    build: IntegratorBuild {
        read: |obj, spec, nest| {
            spec.spectral_mis = USE_SPECTRAL_MIS.read_bool(obj)?;
            read_volpath(obj, spec, nest)
        },
        make: Some(|s| {
            Integrator::VolPath(VolPathIntegrator {
                max_depth: s.max_depth,
                rr_depth: s.rr_depth,
                hide_emitters: s.hide_emitters,
                mis: MediumMis::Joint {
                    spectral: s.spectral_mis,
                },
            })
        }),
    },
};

fn read_volpath(obj: &Object, spec: &mut IntegratorSpec, _: Nest) -> Result<()> {
    let max_depth = MAX_DEPTH.read_i64_where(obj, |d| (-1..=u32::MAX as i64).contains(&d))?;
    spec.max_depth = (max_depth >= 0).then_some(max_depth as u32);
    spec.rr_depth = RR_DEPTH.read_i64_where(obj, |d| (1..=u32::MAX as i64).contains(&d))? as u32;
    read_common(obj, spec)
}

/// `path_half`.
pub(crate) const PATH_HALF: IntegratorPlugin = path_plugin(
    "path_half",
    &[],
    "Path tracing that adds emitter and BSDF sampling with weight 1/2 each (a simpler \
     unbiased combination than MIS, for comparison).",
    |s| path(s, Strategy::Half),
);

/// `path_ems`.
pub(crate) const PATH_EMS: IntegratorPlugin = path_plugin(
    "path_ems",
    &[],
    "Path tracing with emitter sampling only at every vertex (lights seen through delta \
     bounces still count).",
    |s| path(s, Strategy::Emitter),
);

/// `path_mats`.
pub(crate) const PATH_MATS: IntegratorPlugin = path_plugin(
    "path_mats",
    &[],
    "Path tracing with BSDF sampling only: light is found by hitting it.",
    |s| path(s, Strategy::Bsdf),
);

/// `direct_ems`.
pub(crate) const DIRECT_EMS: IntegratorPlugin = fixed_direct(
    "direct_ems",
    "The Wakame assignment's direct lighting by emitter sampling (one sample).",
    |s| direct(s, 1, 0, Heuristic::Balance),
);

/// `direct_mats`.
pub(crate) const DIRECT_MATS: IntegratorPlugin = fixed_direct(
    "direct_mats",
    "The Wakame assignment's direct lighting by BSDF sampling (one sample).",
    |s| direct(s, 0, 1, Heuristic::Balance),
);
