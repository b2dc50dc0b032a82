//! The integrators skip work a scene does not need, shown by the `--stats` counters: each
//! claim "no X" comes with a control scene or integrator where X does happen, so a counter that
//! never counts cannot pass.
use tessera::render::RenderOptions;
use tessera::render_stats::render_with_stats;
use tessera_core::integrator::Counters;
use tessera_core::render::RenderJob;
use tessera_scene::LoadedScene;
use tessera_tests::load_xml;

/// A 16x16 scene looking at the origin from +z, with `body` as its shapes and emitters.
fn xml(body: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="6"/><integer name="rr_depth" value="2"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="50"/>
        <transform name="to_world"><lookat origin="0, 1, 6" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
        <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/></film>
    </sensor>
    {body}
</scene>"#
    )
}

/// Asserts that each named counter of `c` is zero, printing all counters otherwise (a macro:
/// the counters are named fields).
macro_rules! assert_zero {
    ($c:expr, $($field:ident),+) => {
        $(assert_eq!($c.$field, 0, "{}: {:?}", stringify!($field), $c);)+
    };
}

const DIFFUSE_SPHERE: &str = r#"<shape type="sphere"><point name="center" value="0, 0, 0"/><float name="radius" value="1"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.6"/></bsdf></shape>"#;
const FLOOR: &str = r#"<shape type="rectangle"><transform name="to_world"><scale value="10"/><rotate x="1" angle="-90"/><translate y="-1"/></transform>
        <bsdf type="diffuse"/></shape>"#;
const AREA_SPHERE: &str = r#"<shape type="sphere"><point name="center" value="1.5, 2.5, 1"/><float name="radius" value="0.5"/>
        <emitter type="area"><rgb name="radiance" value="5"/></emitter></shape>"#;
const POINT: &str = r#"<emitter type="point"><point name="position" value="1, 3, 2"/><rgb name="intensity" value="10"/></emitter>"#;
const SKY: &str = r#"<emitter type="constant"><rgb name="radiance" value="0.5"/></emitter>"#;
const DELTA_SPHERES: &str = r#"
    <shape type="sphere"><point name="center" value="-1.2, 0, 0"/><float name="radius" value="1"/><bsdf type="dielectric"/></shape>
    <shape type="sphere"><point name="center" value="1.2, 0, 0"/><float name="radius" value="1"/><bsdf type="conductor"/></shape>
    <shape type="sphere"><point name="center" value="0, -101, 0"/><float name="radius" value="100"/>
        <bsdf type="conductor"><string name="material" value="Au"/></bsdf></shape>"#;

fn load(parts: &[&str], integrator: Option<&str>, max_depth: Option<i64>) -> LoadedScene {
    let mut l = load_xml(&xml(&parts.concat()), &[]);
    l.set_integrator(integrator, max_depth)
        .unwrap_or_else(|e| panic!("{e}"));
    l
}

fn stats(l: &LoadedScene) -> Counters {
    let opts = RenderOptions {
        threads: 2,
        tile_size: 8,
        ..Default::default()
    };
    let job = RenderJob::new(&l.scene, &l.integrator, 1);
    let (fb, c) = render_with_stats(&job, 0..l.spp, &opts, &mut |_, _| {});
    assert_eq!(c.samples, 16 * 16 * l.spp);
    assert_eq!(c.camera_rays, c.samples);
    assert_eq!(fb.dropped(), 0);
    c
}

#[test]
fn no_emitters_no_shadow_rays_no_emitter_samples() {
    let c = stats(&load(&[DIFFUSE_SPHERE, FLOOR], None, None));
    assert_zero!(c, shadow_rays, emitter_samples, bsdf_evals, mis_weights);
    assert!(c.continuation_rays > 0 && c.bsdf_samples > 0, "{c:?}");
    // Control: one emitter, and there are shadow rays and emitter samples.
    let c = stats(&load(&[DIFFUSE_SPHERE, FLOOR, AREA_SPHERE], None, None));
    assert!(
        c.shadow_rays > 0 && c.emitter_samples > 0 && c.bsdf_evals > 0,
        "{c:?}"
    );
    assert!(c.mis_weights > 0 && c.bsdf_pdfs > 0, "{c:?}");
}

#[test]
fn delta_bsdfs_only_no_emitter_samples_no_bsdf_evals() {
    for integrator in ["path", "path_ems", "path_half", "direct"] {
        let c = stats(&load(&[DELTA_SPHERES, SKY, POINT], Some(integrator), None));
        assert_eq!(
            (c.emitter_samples, c.bsdf_evals, c.bsdf_pdfs, c.shadow_rays),
            (0, 0, 0, 0),
            "{integrator}: {c:?}"
        );
        assert!(
            c.emission_hits > 0 && c.bsdf_samples > 0,
            "{integrator}: {c:?}"
        );
    }
    // Control: one diffuse sphere among them, and emitters are sampled.
    let c = stats(&load(&[DELTA_SPHERES, DIFFUSE_SPHERE, SKY], None, None));
    assert!(c.emitter_samples > 0 && c.bsdf_evals > 0, "{c:?}");
}

#[test]
fn no_environment_no_environment_lookups() {
    for integrator in ["path", "path_mats", "direct"] {
        let c = stats(&load(
            &[DIFFUSE_SPHERE, AREA_SPHERE],
            Some(integrator),
            None,
        ));
        assert_eq!(c.env_lookups, 0, "{integrator}: {c:?}");
        assert!(c.escaped > 0, "{integrator}: rays do escape: {c:?}");
        let c = stats(&load(
            &[DIFFUSE_SPHERE, AREA_SPHERE, SKY],
            Some(integrator),
            None,
        ));
        assert!(c.env_lookups > 0, "{integrator}, control: {c:?}");
    }
}

#[test]
fn sphere_only_scene_never_touches_triangles() {
    let l = load(&[DIFFUSE_SPHERE, AREA_SPHERE, SKY], None, None);
    // No triangle primitive exists, so the BVH's leaves hold none and no triangle test runs.
    assert!(!l.scene.features.has_triangles && l.scene.features.has_spheres);
    assert!(l
        .scene
        .shapes
        .iter()
        .all(|s| !matches!(s.kind, tessera_core::geometry::ShapeKind::Mesh(_))));
    let c = stats(&l);
    assert_eq!(c.triangle_hits, 0, "{c:?}");
    assert!(c.sphere_hits > 0, "{c:?}");
    // Control: with a floor, triangles are hit.
    let l = load(&[DIFFUSE_SPHERE, AREA_SPHERE, SKY, FLOOR], None, None);
    assert!(l.scene.features.has_triangles);
    assert!(stats(&l).triangle_hits > 0);
}

#[test]
fn max_depth_one_sees_only_emitters() {
    let c = stats(&load(
        &[DIFFUSE_SPHERE, FLOOR, AREA_SPHERE, SKY],
        None,
        Some(1),
    ));
    assert_zero!(
        c,
        shadow_rays,
        bsdf_samples,
        continuation_rays,
        emitter_samples
    );
    assert!(c.emission_hits > 0, "{c:?}");
}

#[test]
fn last_segment_skipped_when_no_ray_can_find_light() {
    // Only a point light: at max_depth 2 the second segment could only find emission.
    let c = stats(&load(&[DIFFUSE_SPHERE, FLOOR, POINT], None, Some(2)));
    assert_eq!((c.continuation_rays, c.bsdf_samples), (0, 0), "{c:?}");
    assert!(c.shadow_rays > 0, "{c:?}");
    // Deeper paths still need their inner segments (but not the last one).
    let c = stats(&load(&[DIFFUSE_SPHERE, FLOOR, POINT], None, Some(3)));
    assert!(c.continuation_rays > 0, "{c:?}");
    assert!(c.continuation_rays <= c.bsdf_samples, "{c:?}");
    // Control: an area light can be hit, so the last segment is traced.
    let c = stats(&load(&[DIFFUSE_SPHERE, FLOOR, AREA_SPHERE], None, Some(2)));
    assert!(c.continuation_rays > 0, "{c:?}");
}

#[test]
fn path_ems_does_not_trace_a_last_segment_it_would_weigh_zero() {
    let c = stats(&load(
        &[DIFFUSE_SPHERE, FLOOR, AREA_SPHERE],
        Some("path_ems"),
        Some(2),
    ));
    assert_eq!(c.continuation_rays, 0, "{c:?}");
    assert_eq!((c.mis_weights, c.bsdf_pdfs), (0, 0), "{c:?}");
    assert!(c.shadow_rays > 0, "{c:?}");
    // Control: path_mis weighs what that segment finds.
    let c = stats(&load(
        &[DIFFUSE_SPHERE, FLOOR, AREA_SPHERE],
        Some("path_mis"),
        Some(2),
    ));
    assert!(c.continuation_rays > 0 && c.mis_weights > 0, "{c:?}");
}

#[test]
fn strategies_without_mis_compute_no_weights_or_bsdf_densities() {
    for integrator in ["path_ems", "path_half", "direct_ems"] {
        let c = stats(&load(
            &[DIFFUSE_SPHERE, FLOOR, AREA_SPHERE, SKY],
            Some(integrator),
            None,
        ));
        assert_eq!((c.mis_weights, c.bsdf_pdfs), (0, 0), "{integrator}: {c:?}");
        assert!(c.emitter_samples > 0, "{integrator}: {c:?}");
    }
    let c = stats(&load(
        &[DIFFUSE_SPHERE, FLOOR, AREA_SPHERE, SKY],
        Some("path_mats"),
        None,
    ));
    assert_zero!(c, shadow_rays, emitter_samples, bsdf_evals, mis_weights);
    assert!(c.emission_hits > 0, "{c:?}");
}

#[test]
fn direct_with_only_delta_lights_traces_no_bsdf_rays() {
    let c = stats(&load(&[DIFFUSE_SPHERE, FLOOR, POINT], Some("direct"), None));
    assert_eq!(
        (c.continuation_rays, c.bsdf_samples, c.mis_weights),
        (0, 0, 0),
        "{c:?}"
    );
    assert!(c.shadow_rays > 0, "{c:?}");
    let c = stats(&load(
        &[DIFFUSE_SPHERE, FLOOR, AREA_SPHERE],
        Some("direct"),
        None,
    ));
    assert!(c.continuation_rays > 0 && c.mis_weights > 0, "{c:?}");
}

/// With only a point light, the path tracer at max_depth 2 (last segment skipped) and the direct
/// integrator use the same sample dimensions the same way: the same bits, pixel for pixel. Shows
/// the skipped segment added nothing.
#[test]
fn skipped_last_segment_changes_nothing() {
    let path = load(&[DIFFUSE_SPHERE, FLOOR, POINT], Some("path"), Some(2));
    let direct = load(&[DIFFUSE_SPHERE, FLOOR, POINT], Some("direct"), None);
    let (a, b) = (
        tessera_tests::render_loaded(&path, 4, 3),
        tessera_tests::render_loaded(&direct, 4, 3),
    );
    assert!(a.pixels.iter().filter(|p| p.sum[0] > 0.0).count() > 50);
    assert_eq!(a, b);
    // Control: with a sky the path tracer's second segment finds light and the images differ.
    let path = load(&[DIFFUSE_SPHERE, FLOOR, POINT, SKY], Some("path"), Some(3));
    let direct = load(&[DIFFUSE_SPHERE, FLOOR, POINT, SKY], Some("direct"), None);
    assert_ne!(
        tessera_tests::render_loaded(&path, 4, 3),
        tessera_tests::render_loaded(&direct, 4, 3)
    );
}

#[test]
fn traversal_counts_follow_the_rays() {
    // One sphere and a point light: the hierarchy is a root holding one leaf, so every ray
    // (camera, continuation, shadow) visits exactly one node, a leaf reached is one block, and
    // only rays whose path crosses the sphere's box reach it.
    let c = stats(&load(&[DIFFUSE_SPHERE, POINT], None, None));
    let rays = c.camera_rays + c.continuation_rays + c.shadow_rays;
    assert!(c.shadow_rays > 0 && c.continuation_rays > 0, "{c:?}");
    assert_eq!(c.bvh_nodes, rays, "{c:?}");
    assert_eq!(c.prim_blocks, c.bvh_leaves, "{c:?}");
    assert!(c.bvh_leaves > 0 && c.bvh_leaves < rays, "{c:?}");
    // Control: 100 spheres need a deeper hierarchy (more leaves than the root's eight lanes), so
    // rays visit more nodes than there are rays.
    let grid: String = (0..100)
        .map(|i| {
            format!(
                r#"<shape type="sphere"><point name="center" value="{}, {}, 0"/><float name="radius" value="0.15"/></shape>"#,
                (i % 10) as f32 * 0.45 - 2.0,
                (i / 10) as f32 * 0.45 - 2.0
            )
        })
        .collect();
    let c = stats(&load(&[&grid, POINT], None, None));
    let rays = c.camera_rays + c.continuation_rays + c.shadow_rays;
    assert!(c.bvh_nodes > rays, "{c:?}");
    assert!(c.prim_blocks >= c.bvh_leaves && c.bvh_leaves > 0, "{c:?}");
}

/// The Cornell box's ceiling light is flat and one-sided, and the ceiling lies 5 mm behind it:
/// light sampling at ceiling points stops before drawing a point on the light
/// (`light::Behind`). The image is bit for bit the one rendered without that test, with both
/// samplers; and the test does fire there (control: points of the ceiling are behind, points of
/// the floor are not).
#[test]
fn behind_a_flat_light_is_skipped_without_changing_the_image() {
    use tessera_core::emitter::Emitter;
    use tessera_tests::{load_file, render_loaded};
    for sampler in ["independent", "zsobol"] {
        let mut l = load_file("cbox.xml", &[("res", "24"), ("rfilter", "box")]);
        l.set_sampler(Some(sampler), 8).expect("a known sampler");
        let behind = l
            .scene
            .emitters
            .iter()
            .find_map(|e| match e {
                Emitter::Area(a) => a.behind,
                _ => None,
            })
            .expect("the cbox light is flat: it has a half-space");
        // Ceiling at y = 5.488, light at 5.483, floor at 0 (scene units).
        assert!(behind.contains(glam::Vec3::new(2.0, 5.488, 2.0)));
        assert!(!behind.contains(glam::Vec3::new(2.0, 0.0, 2.0)));
        let with = render_loaded(&l, 8, 3);
        for e in &mut l.scene.emitters {
            if let Emitter::Area(a) = e {
                a.behind = None;
            }
        }
        let without = render_loaded(&l, 8, 3);
        assert_eq!(with.pixels.len(), without.pixels.len());
        for (i, (p, q)) in with.pixels.iter().zip(&without.pixels).enumerate() {
            let bits = |a: &tessera_core::film::PixelAccum| {
                (a.sum.map(f64::to_bits), a.sum_sq.map(f64::to_bits), a.count)
            };
            assert!(bits(p) == bits(q), "{sampler}: pixel {i} differs");
        }
    }
}
