//! BSDF sample and eval (+ pdf) per second for diffuse, roughconductor and roughdielectric, built
//! from Mitsuba 3 XML as a scene would build them.
//!
//! `cargo bench -p tessera-benches --bench bsdf`.
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::{Vec2, Vec3};
use std::hint::black_box;
use std::path::Path;
use std::time::Duration;
use tessera_benches::Rng;
use tessera_core::bsdf::Bsdf;
use tessera_core::math::Norm;
use tessera_scene::xml::Kind;

const CASES: [(&str, &str); 3] = [
    (
        "diffuse",
        r#"<bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.5, 0.3"/></bsdf>"#,
    ),
    (
        "roughconductor",
        r#"<bsdf type="roughconductor">
            <string name="material" value="Au"/>
            <string name="distribution" value="ggx"/>
            <float name="alpha" value="0.2"/>
        </bsdf>"#,
    ),
    (
        "roughdielectric",
        r#"<bsdf type="roughdielectric">
            <string name="distribution" value="ggx"/>
            <float name="alpha" value="0.2"/>
            <float name="int_ior" value="1.5"/>
        </bsdf>"#,
    ),
];
const N: usize = 4096;

fn build(xml: &str) -> Bsdf {
    let text = format!("<scene version=\"3.0.0\">\n{xml}\n</scene>\n");
    let root = tessera_scene::xml::load_str(&text, Path::new("bench.xml"), &[]).expect("parses");
    let child = root.children_of(Kind::Bsdf).next().expect("a <bsdf>");
    tessera_scene::build_bsdf_object(&child.obj).expect("builds")
}

fn upper(rng: &mut Rng) -> Vec3 {
    let d = rng.dir();
    Vec3::new(d.x, d.y, d.z.abs().max(1e-3)).unit()
}

fn bsdfs(c: &mut Criterion) {
    let mut rng = Rng(11);
    let uv = Vec2::new(0.5, 0.5);
    let dirs: Vec<(Vec3, Vec3)> = (0..N).map(|_| (upper(&mut rng), rng.dir())).collect();
    let us: Vec<(f32, Vec2)> = (0..N)
        .map(|_| (rng.f(), Vec2::new(rng.f(), rng.f())))
        .collect();
    let mut g = c.benchmark_group("bsdf");
    g.sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(2))
        .throughput(Throughput::Elements(N as u64));
    for (name, xml) in CASES {
        let b = build(xml);
        g.bench_function(format!("{name}/sample"), |bench| {
            bench.iter(|| {
                let mut acc = 0.0f32;
                for ((wi, _), (u1, u2)) in dirs.iter().zip(&us) {
                    if let Some(s) = b.sample(black_box(*wi), *u1, *u2, uv) {
                        acc += s.pdf;
                    }
                }
                acc
            })
        });
        g.bench_function(format!("{name}/eval_pdf"), |bench| {
            bench.iter(|| {
                let mut acc = 0.0f32;
                for (wi, wo) in &dirs {
                    let f = b.eval(black_box(*wi), *wo, uv);
                    acc += f.x + b.pdf(*wi, *wo, uv);
                }
                acc
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bsdfs);
criterion_main!(benches);
