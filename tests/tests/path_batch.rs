//! The ordinary render steps the paths of a pixel's camera batch together
//! (`PathIntegrator::li_batch`); a probe that observes each path in order (here the `--stats`
//! counters) makes the render loop trace the same samples one path at a time. Every value must
//! come out with the same bits either way, for each way of finding light, under an environment
//! map (the batch locates escaped rays on it ahead) and in the material scene, over sample runs
//! that end with a partial batch.
use tessera_core::integrator::{Counters, NoProbe, Probe};
use tessera_core::render::{PixelCache, RenderJob};
use tessera_scene::LoadedScene;
use tessera_tests::load_file;

/// Every sample value (bits) of a few pixels' samples `first..first + count`, traced with
/// `probe`.
fn values<P: Probe>(l: &LoadedScene, seed: u64, first: u64, count: u64, probe: &mut P) -> Vec<u32> {
    let job = RenderJob::new(&l.scene, &l.integrator, seed);
    let mut cache = PixelCache::default();
    let mut out = Vec::new();
    for (x, y) in [(3, 5), (20, 20), (31, 9), (40, 50), (63, 63)] {
        job.pixel_alone(x, y, first..first + count, &mut cache, probe, |c, o, _| {
            out.extend([c.x, c.y, c.z, o.x, o.y].map(f32::to_bits))
        });
    }
    out
}

fn scene(file: &str, integrator: &str) -> LoadedScene {
    let mut l = load_file(file, &[("res", "64")]);
    l.set_integrator(Some(integrator), None)
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(
        l.integrator.batched_path(&l.scene).is_some(),
        "{file} {integrator}: not a batched integrator"
    );
    l
}

#[test]
fn batched_paths_give_the_values_of_paths_one_at_a_time() {
    for file in ["envmap.xml", "materials.xml"] {
        for integrator in ["path", "path_ems", "path_half", "path_mats", "volpath"] {
            let l = scene(file, integrator);
            // 13 samples: a full batch of eight, then five; from 3, runs that start mid-pixel.
            for (first, count) in [(0, 13), (3, 1), (5, 9)] {
                let batched = values(&l, 7, first, count, &mut NoProbe);
                let mut counters = Counters::default();
                let one_by_one = values(&l, 7, first, count, &mut counters);
                assert!(counters.samples > 0, "the counting probe saw no sample");
                assert_eq!(batched.len(), (5 * 5 * count) as usize);
                assert!(
                    batched == one_by_one,
                    "{file} {integrator} samples {first}..{}: values differ",
                    first + count
                );
                // Control: another seed gives other values, so equal lists mean something.
                assert_ne!(batched, values(&l, 8, first, count, &mut NoProbe));
            }
        }
    }
}

#[test]
fn reuse_and_other_integrators_are_not_batched() {
    for integrator in ["path+reuse", "direct", "ao"] {
        let mut l = load_file("materials.xml", &[("res", "64")]);
        if l.set_integrator(Some(integrator), None).is_err() {
            continue;
        }
        assert!(
            l.integrator.batched_path(&l.scene).is_none(),
            "{integrator}"
        );
    }
    // Nor is a scene without an environment map, where the batch gains nothing.
    let mut l = load_file("cbox.xml", &[("res", "64")]);
    l.set_integrator(Some("path"), None)
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(l.integrator.batched_path(&l.scene).is_none());
    // Control: the plain path tracer under an environment map is.
    let l = scene("materials.xml", "path");
    assert!(l.integrator.batched_path(&l.scene).is_some());
}
