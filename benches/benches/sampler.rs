//! Sampler cost: one sample's typical request pattern (camera 2D, then per bounce 1D, 2D, 1D,
//! 2D: 5 bounces, 26 values) for the independent and zsobol samplers; and a path's draws at the
//! renderer's dimensions (camera, then per bounce the emitter position, paired with the draw
//! before it, and the BSDF direction: 4 bounces, 18 values) for runs of 1 to 16 samples of a
//! pixel through the per-pixel cache, with and without telling it the run (`grouped` draws eight
//! samples at a time, `alone` one by one).
//!
//! `cargo bench -p tessera-benches --bench sampler`.
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;
use std::time::Duration;
use tessera_core::sampling::{IndependentSampler, Sampler, Stage, ZSobolPixel, ZSobolSampler};

/// Draws one path's worth of values; returns their sum (so nothing is optimized away).
#[inline]
fn path_draws<S: Sampler>(s: &mut S) -> f32 {
    let mut acc = s.next_2d().x;
    for _ in 0..5 {
        acc += s.next_1d();
        acc += s.next_2d().y;
        acc += s.next_1d();
        acc += s.next_2d().x;
    }
    acc
}

fn samplers(c: &mut Criterion) {
    let mut g = c.benchmark_group("sampler");
    g.measurement_time(Duration::from_secs(3));
    g.throughput(Throughput::Elements(1024));
    g.bench_function("independent/path_26_values", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for i in 0..1024u64 {
                let mut s = IndependentSampler::new(1, (i % 32) as u32, (i / 32) as u32, 7);
                acc += path_draws(&mut s);
            }
            black_box(acc)
        })
    });
    g.bench_function("zsobol/path_26_values", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for i in 0..1024u64 {
                let mut s = ZSobolSampler::new(1, (i % 32) as u32, (i / 32) as u32, 7, 10);
                acc += path_draws(&mut s);
            }
            black_box(acc)
        })
    });
    g.finish();
}

/// A path's draws at the renderer's dimensions (see the header).
#[inline]
fn layout_draws<S: Sampler>(s: &mut S) -> f32 {
    let mut acc = s.next_2d().x;
    for depth in 0..4 {
        s.start_stage(depth, Stage::Light);
        s.skip_1d();
        acc += s.next_2d().y;
        s.start_stage(depth, Stage::Bsdf);
        s.skip_1d();
        acc += s.next_2d().x;
    }
    acc
}

fn pixel_runs(c: &mut Criterion) {
    let mut g = c.benchmark_group("zsobol_pixel_runs");
    g.measurement_time(Duration::from_secs(2));
    // 256 pixels, each taking a run of `run` samples: samples per iteration.
    for run in [1u64, 2, 4, 8, 16] {
        g.throughput(Throughput::Elements(256 * run));
        for grouped in [false, true] {
            let name = format!("{}/{run}", if grouped { "grouped" } else { "alone" });
            let mut px = ZSobolPixel::new(1, 0, 0, 6);
            g.bench_function(name, |b| {
                b.iter(|| {
                    let mut acc = 0.0;
                    for p in 0..256u32 {
                        px.move_to(1, p % 16, p / 16, 6);
                        // Runs start at 16 (a later wave of a benchmark curve).
                        let samples = 16..16 + run;
                        if grouped {
                            px.set_run(samples.clone());
                        }
                        for i in samples {
                            acc += layout_draws(&mut px.sampler(i));
                        }
                    }
                    black_box(acc)
                })
            });
        }
    }
    g.finish();
}

criterion_group!(benches, samplers, pixel_runs);
criterion_main!(benches);
