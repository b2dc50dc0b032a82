//! Camera rays that escape to an environment map are finished eight at a time (their lookups
//! side by side, in AVX2 registers where the CPU has them) when the probe observes nothing; a
//! probe that counts takes the sample-by-sample loop. Both must give the same bits for every
//! sample, with each path-tracing strategy and both samplers, in a scene where some camera
//! rays escape and others meet surfaces. Control: another seed changes the values, so the
//! comparison sees a difference when there is one.
use super::camera_batch::values;
use tessera_core::integrator::{Counters, NoProbe};
use tessera_core::render::RenderJob;
use tessera_core::sampling::SamplerKind;
use tessera_tests::load_file;

#[test]
fn batched_escapes_give_the_sample_by_sample_bits() {
    for integrator in ["path", "path_ems", "path_mats", "path_half"] {
        for sampler in [
            SamplerKind::Independent,
            SamplerKind::ZSobol { log2_spp: 4 },
        ] {
            let mut l = load_file("envmap.xml", &[("res", "32"), ("max_depth", "4")]);
            l.set_integrator(Some(integrator), None)
                .unwrap_or_else(|e| panic!("{e}"));
            l.scene.sampler = sampler;
            let job = RenderJob::new(&l.scene, &l.integrator, 3);
            let mut counters = Counters::default();
            let fast = values(&job, &mut NoProbe, 16);
            let slow = values(&job, &mut counters, 16);
            assert_eq!(fast, slow, "{integrator} {sampler:?}");
            // Rays escaped, and camera rays met surfaces (continuation rays leave only those).
            assert!(
                counters.escaped > 0 && counters.continuation_rays > 0,
                "{counters:?}"
            );
            let other = values(
                &RenderJob::new(&l.scene, &l.integrator, 4),
                &mut NoProbe,
                16,
            );
            assert_ne!(fast, other, "control: another seed");
        }
    }
}
