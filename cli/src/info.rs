//! `tessera info SCENE.xml`: loads a scene without rendering it and prints what it holds: the
//! image and sampling settings, shapes and primitives, BSDFs and emitters by plugin, image
//! textures and their memory, the acceleration structure's size and build time, and the
//! loader's warnings. Bad input is the same one-line located error as `render` gives.
use clap::Args;
use std::collections::{BTreeMap, HashSet};
use std::fmt::Write;
use std::path::PathBuf;
use std::time::Instant;
use tessera_core::camera::Projection;
use tessera_core::emitter::Emitter;
use tessera_core::geometry::Prim;
use tessera_scene::{load_scene_as, LoadedScene};

/// Arguments of `tessera info`.
#[derive(Args, Debug, Clone)]
pub struct InfoArgs {
    /// Scene file (Mitsuba 3 or Nori XML).
    pub scene: PathBuf,
    /// Define a scene parameter (`-D name=value`), as for `render`.
    #[arg(short = 'D', value_parser = super::define::parse_define)]
    pub defines: Vec<(String, String)>,
    /// Whose conventions to load a Nori-vocabulary file with (nori or wakame), as for `render`.
    #[arg(long, value_parser = tessera_scene::Dialect::parse)]
    pub dialect: Option<tessera_scene::Dialect>,
}

/// Loads the scene and prints its report; returns the exit code (2 for bad input).
pub fn run(args: &InfoArgs) -> i32 {
    let start = Instant::now();
    match load_scene_as(&args.scene, &args.defines, args.dialect) {
        Ok(loaded) => {
            let seconds = start.elapsed().as_secs_f64();
            print!(
                "{}",
                report(&args.scene.display().to_string(), &loaded, seconds)
            );
            0
        }
        Err(e) => {
            eprintln!("error: {e}");
            tessera::InputError::EXIT_CODE
        }
    }
}

/// `name count, name count` over `names`, most first (ties by name), after the total.
fn by_plugin(names: &[String]) -> String {
    let mut counts: BTreeMap<&str, usize> = BTreeMap::new();
    for n in names {
        *counts.entry(n).or_default() += 1;
    }
    let mut v: Vec<(&str, usize)> = counts.into_iter().collect();
    v.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(b.0)));
    let list: Vec<String> = v.iter().map(|(n, c)| format!("{n} {c}")).collect();
    match list.is_empty() {
        true => "0".into(),
        false => format!("{}: {}", names.len(), list.join(", ")),
    }
}

/// Bytes in KiB below a MiB, else in MiB, with one decimal.
fn mib(bytes: usize) -> String {
    let kib = bytes as f64 / 1024.0;
    match kib < 1024.0 {
        true => format!("{kib:.1} KiB"),
        false => format!("{:.1} MiB", kib / 1024.0),
    }
}

/// The report `tessera info` prints for `loaded`, read from `file` in `seconds`.
pub fn report(file: &str, loaded: &LoadedScene, seconds: f64) -> String {
    let s = &loaded.scene;
    let spec = &loaded.integrator_spec;
    let mut out = String::new();
    let mut row = |k: &str, v: String| {
        let _ = writeln!(out, "  {k:<12} {v}");
    };
    row(
        "image",
        format!(
            "{} x {}, {} spp, seed {}",
            s.camera.width, s.camera.height, loaded.spp, loaded.seed
        ),
    );
    let camera = match &s.camera.projection {
        Projection::ThinLens(l) => format!(
            "thinlens (aperture_radius {}, focus_distance {})",
            l.aperture_radius, l.focus_distance
        ),
        p => p.name().to_string(),
    };
    let camera = match loaded.dialect {
        tessera_scene::Dialect::Nori => camera,
        d => format!("{camera}, {d} conventions (image mirrored left to right)"),
    };
    row("camera", camera);
    let depth = spec.max_depth.map_or("unbounded".into(), |d| d.to_string());
    row("integrator", format!("{} (max_depth {depth})", spec.name));
    row("sampler", s.sampler.name().to_string());
    row(
        "filter",
        match &s.splat {
            Some(f) => {
                let side = 2 * f.reach() + 1;
                format!(
                    "{}, splatted over {side}x{side} pixels ({} bytes a pixel)",
                    s.filter.name(),
                    4 * f.stride()
                )
            }
            None => format!("{}, each sample in its own pixel", s.filter.name()),
        },
    );
    row("shapes", by_plugin(&loaded.names.shapes));
    let (mut tris, mut spheres, mut disks, mut cylinders) = (0usize, 0usize, 0usize, 0usize);
    let mut curves = 0usize;
    for p in &s.prims {
        match p {
            Prim::Triangle { .. } => tris += 1,
            Prim::Sphere { .. } => spheres += 1,
            Prim::Disk { .. } => disks += 1,
            Prim::Cylinder { .. } => cylinders += 1,
            Prim::Curve { .. } => curves += 1,
            Prim::Instance { .. } => {}
        }
    }
    let cyl = match cylinders {
        0 => String::new(),
        n => format!(", {n} cylinders"),
    };
    let cyl = match curves {
        0 => cyl,
        n => format!("{cyl}, {n} curve segments"),
    };
    let inst = match s.instances.len() {
        0 => "no instances".to_string(),
        n => {
            let inner: usize = s.groups.iter().map(|g| g.prims.len()).sum();
            format!(
                "{n} instances of {} shape groups ({inner} primitives in the groups)",
                s.groups.len()
            )
        }
    };
    row(
        "primitives",
        format!("{tris} triangles, {spheres} spheres, {disks} disks{cyl}; {inst}"),
    );
    row("bsdfs", by_plugin(&loaded.names.bsdfs));
    row("emitters", by_plugin(&loaded.names.emitters));
    if !s.media.is_empty() {
        let bounding = s
            .media
            .interfaces
            .iter()
            .filter(|i| i.is_transition())
            .count();
        let camera = match s.media.camera {
            Some(_) => "the camera in one",
            None => "the camera in none",
        };
        let homogeneous = s
            .media
            .media
            .iter()
            .filter(|m| matches!(m, tessera_core::medium::Medium::Homogeneous(_)))
            .count();
        let heterogeneous = s.media.media.len() - homogeneous;
        row(
            "media",
            format!(
                "{}: homogeneous {homogeneous}, heterogeneous {heterogeneous}; shapes bounding \
                 them: {bounding}; {camera}",
                s.media.media.len(),
            ),
        );
    }
    let (mut images, mut seen, mut bytes, mut procedural) = (0, HashSet::new(), 0, 0);
    for b in &s.bsdfs {
        b.for_each_texture(&mut |t| match t.bitmap() {
            Some(bm) => {
                images += 1;
                if seen.insert(bm.storage_id()) {
                    bytes += bm.memory_bytes();
                }
            }
            None if !matches!(t, tessera_core::texture::Texture::Constant(_)) => procedural += 1,
            None => {}
        });
    }
    row(
        "textures",
        format!(
            "{images} image uses ({} distinct images, {}), {procedural} procedural",
            seen.len(),
            mib(bytes)
        ),
    );
    let env: usize = s
        .emitters
        .iter()
        .map(|e| match e {
            Emitter::EnvMap(m) => m.memory_bytes(),
            _ => 0,
        })
        .sum();
    if env > 0 {
        row("envmaps", format!("{} with sampling tables", mib(env)));
    }
    let m = s.accel_memory();
    row(
        "accel",
        format!(
            "8-wide BVH: nodes {}, triangle blocks {}, primitive records {}; built in {:.3} s",
            mib(m.nodes),
            mib(m.triangles),
            mib(m.prims),
            loaded.accel_seconds
        ),
    );
    if !s.instances.is_empty() {
        let n = s.instances.len();
        let groups: usize = s.groups.iter().map(|g| g.memory_bytes()).sum();
        row(
            "instancing",
            format!(
                "{n} instances, {} bytes each (their record {} bytes, and their share of the top \
                 level: primitive record, block lane, nodes); {} shape groups, {} each on average",
                (m.nodes + m.triangles + m.prims + m.instances) / n,
                m.instances / n,
                s.groups.len(),
                mib(groups / s.groups.len().max(1))
            ),
        );
    }
    row("load", format!("{seconds:.3} s in all"));
    row("warnings", loaded.warnings.len().to_string());
    for w in &loaded.warnings {
        let _ = writeln!(out, "    {w}");
    }
    format!("{file}\n{out}")
}
