//! Walks the scene tree and assembles the core scene.
use super::bsdfs::Bsdfs;
use super::emitters::{build_emitter, AREA};
use super::families::{declared_params, families, Family};
use super::integrator::read_integrator;
use super::loaded::{LoadedScene, PluginNames};
use super::media::interfaces::Media;
use super::sampler::build_sampler;
use super::sensor::build_sensor;
use super::shape_numbering::Numbering;
use super::shapes::instancing::{Groups, INSTANCE, SHAPEGROUP};
use super::shapes::{build_shape, plan_mesh_reads};
use super::threads::Threads;
use super::util::Result;
use crate::error::InputError;
use crate::xml::{Kind, Object};
use std::collections::HashSet;
use tessera_core::bsdf::Bsdf;
use tessera_core::camera::Camera;
use tessera_core::emitter::{AreaLight, Emitter};
use tessera_core::geometry::{Disk, Instance, Shape, ShapeKind};
use tessera_core::integrator::Integrator;
use tessera_core::medium::{MediumInterface, SceneMedia};
use tessera_core::sampling::{SamplerKind, MAX_LOG2_SPP};
use tessera_core::scene::{Scene, SceneParts};
use tessera_core::texture::Texture;

/// Builds a loaded scene from the root `<scene>` object.
pub fn build(root: &Object) -> Result<LoadedScene> {
    if root.kind != Kind::Scene {
        return Err(root.error("the root element must be <scene>"));
    }
    // A mesh file several shapes name is parsed once (`mesh/file_cache.rs`).
    let _mesh_reads = plan_mesh_reads(root).enter();
    let mut warnings = root.load_warnings.clone();
    let mut acc = Acc::default();
    let mut groups = Groups::default();
    let mut integrator_obj = None;
    let mut sensor = None;
    let mut scene_sampler = None;
    let mut camera_medium = None;
    for c in &root.children {
        let obj = &c.obj;
        match obj.kind {
            Kind::Integrator => {
                if integrator_obj.replace(obj).is_some() {
                    return Err(obj.error("the scene has more than one integrator"));
                }
            }
            Kind::Sensor => {
                if sensor.is_some() {
                    return Err(obj.error("the scene has more than one sensor"));
                }
                camera_medium = acc.media.sensor_medium(obj)?;
                sensor = Some(build_sensor(obj, &mut warnings)?);
            }
            Kind::Sampler => scene_sampler = Some(build_sampler(obj, &mut warnings)?),
            Kind::Bsdf => {
                acc.bsdfs.index_of(obj)?;
            }
            // An area emitter declared to be referenced is built on each shape that refers
            // to it (Mitsuba adds surface emitters to the scene through their shapes).
            Kind::Emitter if obj.plugin == AREA.name && obj.is_referenced() => {}
            Kind::Emitter => {
                acc.emitters.push(build_emitter(obj, None)?);
                acc.names.emitters.push(obj.plugin.clone());
            }
            // Declared to be referenced (`<ref>`); built where it is used.
            Kind::Texture => {}
            Kind::Volume if obj.is_referenced() => {}
            // A volume nobody refers to is still checked.
            Kind::Volume => {
                crate::media::build_volume(obj)?;
            }
            // Built here, so that a medium nobody refers to is still checked.
            Kind::Medium => {
                acc.media.index_of(obj)?;
            }
            Kind::Shape if obj.plugin == SHAPEGROUP.name => {
                groups.group_of(obj, &mut |o| add_shape(o, &mut acc, true))?;
            }
            Kind::Shape if obj.plugin == INSTANCE.name => {
                let instance = groups.instance(obj, &mut |o| add_shape(o, &mut acc, true))?;
                acc.numbering.instance(acc.instances.len() as u32);
                acc.instances.push(instance);
            }
            Kind::Shape => {
                add_shape(obj, &mut acc, false)?;
            }
            _ => {
                return Err(InputError::at(
                    &c.loc,
                    format!(
                        "{} is not allowed at the top level of a scene",
                        obj.describe()
                    ),
                ))
            }
        }
        c.mark_used();
    }
    let sensor = sensor.ok_or_else(|| root.error("the scene has no sensor (camera)"))?;
    let mut integrator_spec = read_integrator(integrator_obj.map(|o| &**o))?;
    warnings.append(&mut integrator_spec.warnings);
    let integrator = integrator_spec
        .build()
        .expect("read_integrator checks the name");
    let sampler_named = sensor.spp.is_some() || scene_sampler.is_some();
    let (spp, seed, sampler) = match (sensor.spp, scene_sampler) {
        (Some(n), _) => (
            n,
            sensor.seed.unwrap_or(0),
            sensor.sampler.unwrap_or_default(),
        ),
        (None, Some((n, s, k))) => (n, s, k),
        // A file that names no sampler renders with Tessera's best: zsobol, set up once for
        // any count (see `LoadedScene::sampler_named`).
        (None, None) => (
            4,
            0,
            SamplerKind::ZSobol {
                log2_spp: MAX_LOG2_SPP,
            },
        ),
    };
    root.check_unused()?;
    warn_ignored(root, &families(), &mut warnings, &mut HashSet::new());
    let Acc {
        bsdfs,
        shapes,
        disks,
        emitters,
        mut names,
        instances,
        numbering,
        media,
        interfaces,
    } = acc;
    let shape_numbering = numbering.finish(&shapes, instances.len());
    let parts = SceneParts {
        shapes,
        disks,
        bsdfs: bsdfs.list,
        emitters,
        groups: groups.into_shape_lists(),
        instances,
        camera: Camera {
            to_world: root.dialect.camera_to_world(sensor.camera.to_world),
            ..sensor.camera
        },
        filter: sensor.filter,
        light_selection: integrator_spec.light_selection,
    };
    let accel_start = std::time::Instant::now();
    let mut scene = Scene::new_forked(parts, &Threads::of_machine())
        .map_err(|e| root.error(format!("cannot build the scene: {e:?}")))?;
    let accel_seconds = accel_start.elapsed().as_secs_f64();
    scene.sampler = sampler;
    scene.shape_numbering = shape_numbering;
    if !media.list.is_empty() {
        check_integrator_for_media(&integrator, integrator_obj.map(|o| &**o), &media)?;
        scene
            .set_media(SceneMedia {
                media: media.list,
                interfaces,
                camera: camera_medium,
            })
            .map_err(|e| root.error(format!("cannot build the scene's media: {e:?}")))?;
    }
    names.bsdfs = bsdfs.names;
    let mut loaded = LoadedScene {
        scene,
        integrator,
        integrator_spec,
        spp,
        seed,
        sampler_named,
        warnings,
        names,
        source_hash: 0,
        accel_seconds,
        frame_origin: root.frame_origin.to_array(),
        dialect: root.dialect,
    };
    loaded.sync_environment_sampling();
    Ok(loaded)
}

/// What the scene walk has built so far.
#[derive(Default)]
struct Acc {
    bsdfs: Bsdfs,
    shapes: Vec<Shape>,
    disks: Vec<Disk>,
    emitters: Vec<Emitter>,
    names: PluginNames,
    instances: Vec<Instance>,
    /// Mitsuba's numbering of the top-level shapes.
    numbering: Numbering,
    /// Participating media.
    media: Media,
    /// The media on each shape's sides, by shape index.
    interfaces: Vec<MediumInterface>,
}

/// Builds the shape `obj` (and its OBJ material parts) into `acc`; returns the indices of the
/// shapes added. `in_group`: it is a member of a shape group, which carries no emitter.
fn add_shape(obj: &Object, acc: &mut Acc, in_group: bool) -> Result<Vec<u32>> {
    if obj.plugin == SHAPEGROUP.name || obj.plugin == INSTANCE.name {
        return Err(obj.error(format!(
            "{} inside a shapegroup: nested shape groups and instances are not permitted (as \
             in Mitsuba 3)",
            obj.describe()
        )));
    }
    let parts = build_shape(obj)?;
    let interface = acc.media.interface_of(obj)?;
    let (bsdf_child, attributed) = (parts.bsdf, parts.mesh_attributes);
    let mut added = Vec::new();
    if in_group {
        if let Some(e) = parts.emitter {
            return Err(InputError::at(
                &e.loc,
                "an emitter on a shape inside a shapegroup: instancing of emitters is not \
                 supported (as in Mitsuba 3)",
            ));
        }
        if parts
            .mtl_parts
            .iter()
            .any(|p| p.material.emission.is_some())
        {
            return Err(obj.error(
                "an MTL material with Ke emission inside a shapegroup: instancing of emitters \
                 is not supported (as in Mitsuba 3)",
            ));
        }
    }
    if let Some(kind) = parts.kind {
        let shape_index = acc.shapes.len() as u32;
        let bsdf = match parts.bsdf {
            Some(b) => acc.bsdfs.index_of(&b.obj)?,
            None => acc.bsdfs.default_index(parts.emitter.is_some()),
        };
        let emitter = match parts.emitter {
            Some(e) => {
                acc.emitters.push(build_emitter(&e.obj, Some(shape_index))?);
                acc.names.emitters.push(e.obj.plugin.clone());
                Some(acc.emitters.len() as u32 - 1)
            }
            None => None,
        };
        check_mesh_attributes(obj, &kind, &acc.bsdfs.list[bsdf as usize])?;
        let kind = match (kind, parts.disk) {
            (ShapeKind::Disk(_), Some(d)) => {
                acc.disks.push(d);
                ShapeKind::Disk(acc.disks.len() as u32 - 1)
            }
            (k, _) => k,
        };
        added.push(shape_index);
        acc.interfaces.push(interface);
        acc.shapes.push(Shape {
            kind,
            bsdf,
            emitter,
            flip_normals: parts.flip_normals,
        });
        acc.names.shapes.push(obj.plugin.clone());
    }
    // OBJ faces with MTL materials: one shape each, with its own BSDF and light.
    for part in parts.mtl_parts {
        let shape_index = acc.shapes.len() as u32;
        let emitter = part.material.emission.map(|radiance| {
            acc.emitters
                .push(Emitter::Area(AreaLight::new(shape_index, radiance)));
            acc.names.emitters.push("area (MTL Ke)".into());
            acc.emitters.len() as u32 - 1
        });
        added.push(shape_index);
        acc.interfaces.push(interface);
        acc.shapes.push(Shape {
            kind: ShapeKind::Mesh(part.mesh),
            bsdf: acc.bsdfs.push(part.material.bsdf, "MTL material".into()),
            emitter,
            flip_normals: parts.flip_normals,
        });
        acc.names.shapes.push(format!("{} (MTL part)", obj.plugin));
    }
    match in_group {
        true => acc.numbering.member(obj, &added),
        false => acc
            .numbering
            .shape(obj, bsdf_child, attributed, &added, &acc.shapes),
    }
    parts.plugin.check_unused(obj)?;
    Ok(added)
}

/// Refuses a shape whose BSDF reads a mesh attribute (a `mesh_attribute` texture) that the
/// shape does not have, at the shape: Mitsuba 3 stops there too, when it renders.
fn check_mesh_attributes(obj: &Object, kind: &ShapeKind, bsdf: &Bsdf) -> Result<()> {
    let have: Vec<&str> = match kind {
        ShapeKind::Mesh(m) => m.attributes.iter().map(|a| a.name.as_str()).collect(),
        _ => Vec::new(),
    };
    let mut missing = None;
    bsdf.for_each_texture(&mut |t| {
        if let Texture::MeshAttribute(a) = t {
            if missing.is_none() && !have.contains(&a.name.as_str()) {
                missing = Some(a.name.clone());
            }
        }
    });
    match missing {
        None => Ok(()),
        Some(name) => Err(obj.error(format!(
            "the BSDF of {} reads mesh attribute \"{name}\", which the shape does not have \
             ({})",
            obj.describe(),
            if have.is_empty() {
                "it has none".to_string()
            } else {
                format!("it has {}", have.join(", "))
            }
        ))),
    }
}

/// Refuses to render a scene with media by an integrator that would ignore them (`path`,
/// `direct` and the other surface-only light transport), at the integrator element, or at the
/// first medium when the scene names none (its default is `path`).
fn check_integrator_for_media(
    integrator: &Integrator,
    obj: Option<&Object>,
    media: &Media,
) -> Result<()> {
    match crate::loaded::media_refusal(integrator) {
        None => Ok(()),
        Some(msg) => Err(match obj {
            Some(o) => o.error(msg),
            None => InputError::at(&media.locs[0], msg),
        }),
    }
}

/// Adds a located warning for each parameter the file gives that is declared without effect
/// (`Param::ignored`), once per object however often it is referenced.
fn warn_ignored(
    obj: &Object,
    families: &[Family],
    warnings: &mut Vec<String>,
    seen: &mut HashSet<*const Object>,
) {
    if !seen.insert(obj as *const Object) {
        return;
    }
    if let Some(params) = declared_params(families, obj.kind, &obj.plugin) {
        for p in params.iter().filter(|p| p.ignored) {
            if let Some(prop) = obj.props.iter().find(|q| q.name == p.name) {
                warnings.push(format!(
                    "{}: \"{}\" of {} is accepted but ignored ({})",
                    prop.loc,
                    p.name,
                    obj.describe(),
                    p.doc
                ));
            }
        }
    }
    for c in &obj.children {
        warn_ignored(&c.obj, families, warnings, seen);
    }
}
