//! Uses `tessera-core` alone (no scene file, no threads, no std-only crate): builds a white
//! furnace in code (a grey diffuse sphere under a uniform sky of radiance 1), traces samples of
//! the centre pixel and of a corner pixel, and checks them against the analytic answer.
//!
//! A convex Lambertian object of albedo `a` under a uniform environment of radiance 1 reflects
//! exactly `a` in every direction, so the centre pixel converges to 0.5 and the corner, which
//! sees only the sky, to 1.
//!
//! Run: `cargo run --release -p tessera-core --example furnace`
use tessera_core::bsdf::{Bsdf, Diffuse};
use tessera_core::camera::{Camera, Filter, FovAxis};
use tessera_core::emitter::{ConstantEnv, Emitter};
use tessera_core::film::PixelAccum;
use tessera_core::geometry::{Shape, ShapeKind, Sphere};
use tessera_core::glam::{Mat4, Vec3, Vec4};
use tessera_core::integrator::{Integrator, PathIntegrator};
use tessera_core::light::LightSelection;
use tessera_core::math::{Norm, Transform};
use tessera_core::render::RenderJob;
use tessera_core::scene::{Scene, SceneParts};
use tessera_core::texture::Texture;
use tessera_core::Color;

/// Camera-to-world of a camera at `origin` looking at `target` (Mitsuba's convention: the camera
/// looks along its local +z, +y is up and +x points to the image's left).
fn look_at(origin: Vec3, target: Vec3, up: Vec3) -> Transform {
    let dir = (target - origin).unit();
    let left = up.cross(dir).unit();
    let new_up = dir.cross(left);
    let m = Mat4::from_cols(
        left.extend(0.0),
        new_up.extend(0.0),
        dir.extend(0.0),
        Vec4::new(origin.x, origin.y, origin.z, 1.0),
    );
    Transform::new(m).expect("a rigid transform is invertible")
}

fn main() {
    let (width, height) = (32, 32);
    let camera = Camera::perspective(
        look_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, Vec3::Y),
        width,
        height,
        40.0,
        FovAxis::X,
        0.01,
        1e4,
    );
    let parts = SceneParts {
        shapes: vec![Shape {
            kind: ShapeKind::Sphere(Sphere {
                center: Vec3::ZERO,
                radius: 1.0,
            }),
            bsdf: 0,
            emitter: None,
            flip_normals: false,
        }],
        disks: Vec::new(),
        bsdfs: vec![Bsdf::Diffuse(Diffuse {
            reflectance: Texture::Constant(Color::splat(0.5)),
        })],
        emitters: vec![Emitter::Constant(ConstantEnv {
            radiance: Color::ONE,
        })],
        camera,
        filter: Filter::Box,
        light_selection: LightSelection::Power,
        groups: Vec::new(),
        instances: Vec::new(),
    };
    let scene = Scene::new(parts).expect("the parts refer to each other correctly");
    let integrator = Integrator::Path(PathIntegrator::default());
    let spp = 4096;
    let job = RenderJob::new(&scene, &integrator, 7);
    for (name, x, y, expected) in [("centre", 16, 16, 0.5), ("corner", 0, 0, 1.0)] {
        let mut acc = PixelAccum::default();
        job.accumulate(x, y, 0..spp, &mut acc);
        let mean = acc.mean();
        let n = acc.count as f64;
        let var = acc.sum_sq[1] / n - (acc.sum[1] / n).powi(2);
        let stderr = (var.max(0.0) / n).sqrt();
        println!(
            "{name} pixel ({x}, {y}): mean {:.4} {:.4} {:.4} (green standard error {stderr:.1e}), expected {expected}",
            mean[0], mean[1], mean[2]
        );
        assert!(
            (mean[1] as f64 - expected).abs() <= 5.0 * stderr + 1e-6,
            "{name}: {} is not {expected}",
            mean[1]
        );
    }
}
