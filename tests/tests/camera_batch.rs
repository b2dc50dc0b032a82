//! A pixel's camera rays are cast eight at a time and the paths of the batch taken first vertex
//! first when the probe observes nothing; a probe that counts takes the sample-by-sample loop.
//! Both must give the same bits for every sample, with each path-tracing strategy, in scenes
//! without an environment (escaped rays followed as paths), with several lights, with a map
//! whose escaped rays are looked up together, with emitters hidden from the camera (no
//! lookups), and at depths that end paths at the first vertex or before it. Control: another
//! seed changes the values, so the comparison sees a difference when there is one.
use tessera_core::integrator::{Counters, Integrator, NoProbe};
use tessera_core::render::{PixelCache, RenderJob};
use tessera_core::sampling::SamplerKind;
use tessera_core::Color;
use tessera_tests::load_file;

/// Every sample's value and offset bits of pixels along a column crossing a 32-pixel image,
/// `spp` samples each (17 here: two full batches and one of a single sample).
pub(crate) fn values<P: tessera_core::integrator::Probe>(
    job: &RenderJob,
    probe: &mut P,
    spp: u64,
) -> Vec<[u32; 3]> {
    let mut out = Vec::new();
    let mut cache = PixelCache::default();
    for y in (0..32).step_by(3) {
        job.pixel(13, y, 0..spp, &mut cache, probe, |c: Color, o| {
            out.push(c.to_array().map(f32::to_bits));
            out.push(o.extend(0.0).to_array().map(f32::to_bits));
        });
    }
    out
}

#[test]
fn batched_first_vertices_give_the_sample_by_sample_bits() {
    let cases = [
        ("cbox.xml", "4", false),
        ("cbox.xml", "1", false),
        ("cbox.xml", "0", false),
        ("veach_mis.xml", "3", false),
        ("envmap.xml", "2", true),
        ("envmap.xml", "5", false),
    ];
    for (file, depth, hide) in cases {
        for integrator in ["path", "path_ems", "path_mats", "path_half"] {
            let mut l = load_file(file, &[("res", "32"), ("max_depth", depth)]);
            l.set_integrator(Some(integrator), None)
                .unwrap_or_else(|e| panic!("{e}"));
            l.scene.sampler = SamplerKind::Independent;
            if let Integrator::Path(p) = &mut l.integrator {
                p.hide_emitters = hide;
            }
            let job = RenderJob::new(&l.scene, &l.integrator, 3);
            let mut counters = Counters::default();
            let fast = values(&job, &mut NoProbe, 17);
            let slow = values(&job, &mut counters, 17);
            let case = format!("{file} depth {depth} hide {hide} {integrator}");
            let first = fast.iter().zip(&slow).position(|(a, b)| a != b);
            assert!(
                fast.len() == slow.len() && first.is_none(),
                "{case}: values differ, first at {first:?}"
            );
            if depth != "0" {
                let other = values(
                    &RenderJob::new(&l.scene, &l.integrator, 4),
                    &mut NoProbe,
                    17,
                );
                assert_ne!(fast, other, "control: another seed ({case})");
            }
        }
    }
}
