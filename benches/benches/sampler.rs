//! Sampler cost: one sample's typical request pattern (camera 2D, then per bounce 1D, 2D, 1D,
//! 2D: 5 bounces, 26 values) for the independent and zsobol samplers.
//!
//! `cargo bench -p tessera-benches --bench sampler`.
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;
use std::time::Duration;
use tessera_core::sampling::{IndependentSampler, Sampler, ZSobolSampler};

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

criterion_group!(benches, samplers);
criterion_main!(benches);
