//! Delta tracking in a heterogeneous medium against the exact distance density: a grid whose
//! extinction is a linear ramp along its x axis (32 voxels, so the majorant grid's 16 cells
//! differ), different per channel, crossed by an oblique ray that enters through the x = 0 face
//! and leaves through x = 1 (walking cells along all three axes). The distance to the real
//! collision, for channel c, has density `sigma_c(t) exp(-tau_c(t))` with `tau_c` closed form;
//! the path's channel is drawn uniformly, so the sampled distances follow the mean of the three.
//! Chi-square over 40 bins and the pass; the control (every extinction 5% high) must fail.
//!
use glam::{Mat4, Vec3};
use tessera_core::math::{Norm, Transform};
use tessera_core::medium::{
    ChannelRatios, GridFilter, GridVolume, GridWrap, Heterogeneous, MediumPhase, PhaseFunction,
    Volume, VolumeData, VoxelGrid,
};
use tessera_core::sampling::IndependentSampler;
use tessera_lab::stats::{chi2_test, Chi2Result, DEFAULT_MIN_EXPECTED};
use tessera_tests::bsdf::assert_chi2_passes;

/// Chi-square tests in this file.
const N_TESTS: usize = 1;
const N: usize = 32;
/// Extinction `A + B x` along the grid's x, per channel (x in voxel-centre units).
const A: [f64; 3] = [0.2, 0.6, 1.2];
const B: [f64; 3] = [2.8, 1.0, 0.1];
const BINS: usize = 40;
const SAMPLES: usize = 400_000;

fn ramp_medium() -> Heterogeneous {
    let mut data = Vec::new();
    for _z in 0..2 {
        for _y in 0..3 {
            for i in 0..N {
                let x = (i as f64 + 0.5) / N as f64;
                for k in 0..3 {
                    data.push((A[k] + B[k] * x) as f32);
                }
            }
        }
    }
    let grid = VoxelGrid::new([N as u32, 3, 2], 3, data).expect("grid");
    let sigma_t = Volume {
        data: VolumeData::Grid(GridVolume {
            grid,
            filter: GridFilter::Trilinear,
            wrap: GridWrap::Clamp,
        }),
        to_world: Transform::new(Mat4::IDENTITY).expect("identity"),
    };
    Heterogeneous::new(
        sigma_t,
        Volume::constant(Vec3::splat(0.5)),
        1.0,
        MediumPhase::Fixed(PhaseFunction::default()),
        true,
    )
}

/// `int_0^x sigma_k(s) ds` for the clamped ramp, times `factor`.
fn optical_x(k: usize, x: f64, factor: f64) -> f64 {
    let c0 = 0.5 / N as f64;
    let c1 = 1.0 - c0;
    let x = x.clamp(0.0, 1.0);
    let clamped = if x <= c0 {
        c0 * x
    } else if x <= c1 {
        c0 * c0 + (x * x - c0 * c0) / 2.0
    } else {
        c0 * c0 + (c1 * c1 - c0 * c0) / 2.0 + c1 * (x - c1)
    };
    factor * (A[k] * x + B[k] * clamped)
}

fn ray() -> (Vec3, Vec3) {
    (Vec3::new(-0.5, 0.4, 0.55), Vec3::new(1.0, 0.3, -0.2).unit())
}

fn distances_chi2(factor: f64, seed: u64) -> Chi2Result {
    let m = ramp_medium();
    let (o, d) = ray();
    let (t0, t1) = (0.5 / d.x as f64, 1.5 / d.x as f64);
    let t_max = 3.0f32;
    let mut observed = vec![0.0; BINS + 1];
    let mut nulls = 0u64;
    for i in 0..SAMPLES {
        let mut s = IndependentSampler::new(seed, 0, 0, i as u64);
        let mut ch = ChannelRatios::new(tessera_core::sampling::Sampler::next_1d(&mut s));
        let f = m.sample_flight(o, d, t_max, &mut ch, &mut s);
        nulls += f.null_collisions as u64;
        let cell = if f.scattered {
            let t = f.t as f64;
            assert!(
                t >= t0 - 1e-4 && t <= t1 + 1e-4,
                "collision at {t} outside the grid"
            );
            (((t - t0) / (t1 - t0) * BINS as f64) as usize).min(BINS - 1)
        } else {
            assert_eq!(f.t, t_max);
            BINS
        };
        observed[cell] += 1.0;
    }
    println!(
        "{:.2} null collisions per sample",
        nulls as f64 / SAMPLES as f64
    );
    let cdf = |t: f64| -> f64 {
        let x = (t - t0) * d.x as f64;
        (0..3)
            .map(|k| 1.0 - (-optical_x(k, x, factor) / d.x as f64).exp())
            .sum::<f64>()
            / 3.0
    };
    let mut expected: Vec<f64> = (0..BINS)
        .map(|i| {
            let a = t0 + (t1 - t0) * i as f64 / BINS as f64;
            let b = t0 + (t1 - t0) * (i + 1) as f64 / BINS as f64;
            (cdf(b) - cdf(a)) * SAMPLES as f64
        })
        .collect();
    expected.push((1.0 - cdf(t1)) * SAMPLES as f64);
    chi2_test(&observed, &expected, DEFAULT_MIN_EXPECTED)
}

#[test]
fn delta_tracking_distances_follow_the_ramp() {
    let r = distances_chi2(1.0, 11);
    assert_chi2_passes("delta tracking on a ramp", &r, N_TESTS);
    let control = distances_chi2(1.05, 11);
    println!("control, extinction 5% high: {control}");
    assert!(!control.passes(1e-6), "control passed: {control}");
}

#[test]
fn the_majorant_grid_bounds_every_lookup_and_varies() {
    let m = ramp_medium();
    let res = m.majorants.res();
    assert_eq!(res, [16, 3, 2]);
    let (lo, hi) = (m.majorants.cell([0, 0, 0]), m.majorants.cell([15, 0, 0]));
    assert!(hi > 2.0 * lo, "cells {lo} .. {hi}");
    let mut s = tessera_lab::stats::Pcg32::new(3);
    for _ in 0..100_000 {
        let p = Vec3::new(s.next_f32(), s.next_f32(), s.next_f32());
        let c = [0, 1, 2].map(|a| ((p[a] * res[a] as f32) as u32).min(res[a] - 1));
        let sigma = m.sigma_t_at(p, Vec3::X).max_element();
        assert!(sigma <= m.majorants.cell(c), "{sigma} above cell {c:?}");
    }
}
