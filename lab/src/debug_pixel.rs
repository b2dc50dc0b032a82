//! `tessera render --debug-pixel x,y[,sample]`: renders one pixel with a path recorder and prints
//! every sample's path (vertices, BSDF and emitter samples, MIS weights, Russian roulette,
//! throughput) and its value.
//!
//! The values printed are those the full render accumulates: each sample is
//! `RenderJob::sample_probed` (the same value as `RenderJob::sample`; the recorder only observes), the
//! pixel mean is a [`PixelAccum`] fed in sample-index order, and every float is printed with
//! `{:?}`, which round-trips an `f32` exactly.
use std::fmt::Write;
use std::ops::Range;
use tessera_core::film::PixelAccum;
use tessera_core::glam::Vec3;
use tessera_core::integrator::{Event, PathRecord, RayKind};
use tessera_core::math::Norm;
use tessera_core::render::RenderJob;
use tessera_scene::error::InputError;
use tessera_scene::LoadedScene;

/// The pixel (and optionally the one sample index) to trace.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DebugPixel {
    /// Column.
    pub x: u32,
    /// Row.
    pub y: u32,
    /// One sample index, or all of the render's samples.
    pub sample: Option<u64>,
}

/// Parses `x,y` or `x,y,sample` (for clap).
pub fn parse_debug_pixel(s: &str) -> Result<DebugPixel, String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let bad = || format!("expected x,y or x,y,sample (non-negative integers), found \"{s}\"");
    if !(2..=3).contains(&parts.len()) {
        return Err(bad());
    }
    let x = parts[0].parse().map_err(|_| bad())?;
    let y = parts[1].parse().map_err(|_| bad())?;
    let sample = match parts.get(2) {
        Some(p) => Some(p.parse().map_err(|_| bad())?),
        None => None,
    };
    Ok(DebugPixel { x, y, sample })
}

/// Traces the pixel and prints its report to stdout; returns the exit code (2 for a pixel or
/// sample outside the render).
pub fn run(loaded: &LoadedScene, job: &RenderJob, samples: Range<u64>, dp: DebugPixel) -> i32 {
    match report(loaded, job, samples, dp) {
        Ok(text) => {
            print!("{text}");
            0
        }
        Err(msg) => {
            eprintln!("error: {msg}");
            InputError::EXIT_CODE
        }
    }
}

/// The report of [`run`], or why the pixel cannot be traced.
pub fn report(
    loaded: &LoadedScene,
    job: &RenderJob,
    render: Range<u64>,
    dp: DebugPixel,
) -> Result<String, String> {
    let scene = &loaded.scene;
    let (w, h) = (scene.camera.width, scene.camera.height);
    if dp.x >= w || dp.y >= h {
        return Err(format!(
            "--debug-pixel {},{} is outside the {w}x{h} image",
            dp.x, dp.y
        ));
    }
    let samples = match dp.sample {
        Some(s) if !render.contains(&s) => {
            return Err(format!(
                "--debug-pixel sample {s} is outside the render's samples {}..{}",
                render.start, render.end
            ))
        }
        Some(s) => s..s + 1,
        None => render,
    };
    let mut out = String::new();
    let _ = writeln!(
        out,
        "pixel ({}, {}), samples {}..{}, seed {}, integrator {}",
        dp.x, dp.y, samples.start, samples.end, job.seed, loaded.integrator_spec.name
    );
    let mut acc = PixelAccum::default();
    for index in samples {
        let mut rec = PathRecord::default();
        let c = job.sample_probed(dp.x, dp.y, index, &mut rec);
        acc.add(c);
        let _ = writeln!(out, "sample {index}:");
        write_events(&mut out, loaded, &rec);
        let _ = writeln!(out, "  value: {}", v3(c));
    }
    if dp.sample.is_none() {
        let m = acc.mean();
        let _ = writeln!(
            out,
            "pixel mean: [{:?}, {:?}, {:?}] over {} samples ({} non-finite dropped)",
            m[0], m[1], m[2], acc.count, acc.dropped
        );
    }
    Ok(out)
}

/// A vector with full `f32` precision.
fn v3(v: Vec3) -> String {
    format!("[{:?}, {:?}, {:?}]", v.x, v.y, v.z)
}

fn write_events(out: &mut String, loaded: &LoadedScene, rec: &PathRecord) {
    let scene = &loaded.scene;
    let mut vertex = 0;
    let mut env_lookups = 0;
    for e in &rec.events {
        let ind = if vertex == 0 { "  " } else { "    " };
        let _ = match e {
            Event::Camera { pos, ray } => writeln!(
                out,
                "  film position [{:?}, {:?}], camera ray o {} d {}",
                pos.x,
                pos.y,
                v3(ray.o),
                v3(ray.d)
            ),
            Event::Ray(RayKind::Shadow) => Ok(()),
            Event::Ray(k) => writeln!(out, "  {} ray", ray_name(*k)),
            Event::Vertex(si) => {
                vertex += 1;
                let shape = &scene.shapes[si.shape as usize];
                let emitter = shape
                    .emitter
                    .map_or(String::new(), |i| format!(", emitter {i}"));
                writeln!(
                    out,
                    "  vertex {vertex}: p {} n {} ng {} uv [{:?}, {:?}] wi {}\n    shape {} ({}), bsdf {} ({}){emitter}",
                    v3(si.p),
                    v3(si.frame.n),
                    v3(si.ng),
                    si.uv.x,
                    si.uv.y,
                    v3(si.wi),
                    si.shape,
                    name_of(&loaded.names.shapes, si.shape as usize),
                    shape.bsdf,
                    name_of(&loaded.names.bsdfs, shape.bsdf as usize),
                )
            }
            Event::Escaped(d) => writeln!(out, "  escaped along {}", v3(d.unit())),
            Event::Shadow { blocked } => writeln!(
                out,
                "{ind}shadow ray: {}",
                if *blocked { "blocked" } else { "clear" }
            ),
            Event::EnvLookup => {
                env_lookups += 1;
                Ok(())
            }
            Event::Emission {
                le,
                weight,
                contribution,
            } => writeln!(
                out,
                "{ind}emission found: Le {} weight {weight:?} adds {}",
                v3(*le),
                v3(*contribution)
            ),
            Event::EmitterSample {
                index,
                select_pdf,
                sample,
            } => {
                let name = name_of(&loaded.names.emitters, *index);
                match sample {
                    Some(s) => writeln!(
                        out,
                        "{ind}emitter sample: emitter {index} ({name}, picked with p {select_pdf:?}) wo {} pdf {:?} delta {} Le/pdf {}",
                        v3(s.wo),
                        s.pdf,
                        s.delta,
                        v3(s.weight)
                    ),
                    None => writeln!(
                        out,
                        "{ind}emitter sample: emitter {index} ({name}) gave no sample"
                    ),
                }
            }
            Event::BsdfEval(f) => writeln!(out, "{ind}bsdf eval: f cos {}", v3(*f)),
            Event::BsdfPdf(p) => writeln!(out, "{ind}bsdf pdf: {p:?}"),
            Event::Light {
                sample,
                weight,
                contribution,
            } => writeln!(
                out,
                "{ind}emitter sample arrives: value {} light pdf {:?} bsdf pdf {:?} mis weight {weight:?} adds {}",
                v3(sample.value),
                sample.light_pdf,
                sample.bsdf_pdf,
                v3(*contribution)
            ),
            Event::MisWeight => Ok(()),
            Event::BsdfSample {
                sample: Some(s),
                wo,
                throughput,
            } => writeln!(
                out,
                "{ind}bsdf sample: wo {} pdf {:?} weight {} delta {} eta {:?}; throughput {}",
                v3(*wo),
                s.pdf,
                v3(s.weight),
                s.delta,
                s.eta,
                v3(*throughput)
            ),
            Event::BsdfSample { sample: None, .. } => {
                writeln!(out, "{ind}bsdf sample: no direction")
            }
            Event::Roulette {
                q,
                survived,
                throughput,
            } => writeln!(
                out,
                "{ind}russian roulette: survival probability {q:?}, {}; throughput {}",
                if *survived { "survives" } else { "killed" },
                v3(*throughput)
            ),
            Event::End(why) => writeln!(out, "  path ends: {why:?}"),
        };
    }
    if env_lookups > 0 {
        let _ = writeln!(out, "  environment lookups: {env_lookups}");
    }
}

fn ray_name(k: RayKind) -> &'static str {
    match k {
        RayKind::Camera => "camera",
        RayKind::Continuation => "continuation",
        RayKind::Shadow => "shadow",
    }
}

/// The plugin name the scene file gave part `i` (as the loader recorded it).
fn name_of(names: &[String], i: usize) -> &str {
    names.get(i).map_or("?", String::as_str)
}
