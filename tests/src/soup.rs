//! Ray-casting test data shared by the BVH tests: a flat scene of triangles (one mesh) and
//! spheres (or any shapes and disks) with a diffuse BSDF and no emitters, random triangle soups with degenerate
//! triangles, and random rays, some with a short extent; and the brute-force oracle (a loop over
//! every primitive) that the scene's casts are checked against.
use crate::rng::SplitMix;
use tessera_core::bsdf::{Bsdf, Diffuse};
use tessera_core::camera::{Camera, Filter, FovAxis};
use tessera_core::geometry::{Disk, Mesh, Shape, ShapeKind, Sphere, TriRay};
use tessera_core::glam::Vec3;
use tessera_core::math::{Norm, Ray, Transform};
use tessera_core::scene::{Scene, SceneParts};
use tessera_core::texture::Texture;

/// A scene of separate triangles (one mesh, three vertices each) and spheres.
pub fn scene(tris: Vec<[Vec3; 3]>, spheres: Vec<Sphere>) -> Scene {
    let positions: Vec<Vec3> = tris.iter().flatten().copied().collect();
    let indices = (0..tris.len() as u32)
        .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
        .collect();
    mesh_scene(positions, indices, spheres)
}

/// A scene of one indexed mesh (none when `indices` is empty) and spheres.
pub fn mesh_scene(positions: Vec<Vec3>, indices: Vec<[u32; 3]>, spheres: Vec<Sphere>) -> Scene {
    let mut shapes = Vec::new();
    if !indices.is_empty() {
        shapes.push(diffuse_shape(ShapeKind::Mesh(Mesh::new(
            positions,
            vec![],
            vec![],
            indices,
        ))));
    }
    shapes.extend(
        spheres
            .into_iter()
            .map(|s| diffuse_shape(ShapeKind::Sphere(s))),
    );
    scene_of(shapes, vec![])
}

/// A shape with the test scenes' one diffuse BSDF and no emitter.
pub fn diffuse_shape(kind: ShapeKind) -> Shape {
    Shape {
        kind,
        bsdf: 0,
        emitter: None,
        flip_normals: false,
    }
}

/// A scene of `shapes` (made with [`diffuse_shape`]) and the disks they refer to, with one
/// diffuse BSDF, no emitters and a small camera.
pub fn scene_of(shapes: Vec<Shape>, disks: Vec<Disk>) -> Scene {
    Scene::new(SceneParts {
        shapes,
        disks,
        bsdfs: vec![Bsdf::Diffuse(Diffuse {
            reflectance: Texture::constant(0.5),
        })],
        emitters: vec![],
        camera: Camera::perspective(Transform::IDENTITY, 4, 4, 40.0, FovAxis::X, 0.01, 1e4),
        filter: Filter::Box,
        light_selection: Default::default(),
        groups: Vec::new(),
        instances: Vec::new(),
    })
    .expect("valid scene")
}

/// The closest hit by brute force, a loop over every primitive of the scene: `(t, primitive)`.
pub fn brute_closest(scene: &Scene, ray: &Ray) -> Option<(f32, usize)> {
    let tri = TriRay::new(ray);
    let mut best: Option<(f32, usize)> = None;
    for i in 0..scene.prims.len() {
        if let Some((t, _)) = scene.intersect_prim(i, ray, &tri, best.map_or(ray.t_max, |b| b.0)) {
            best = Some((t, i));
        }
    }
    best
}

/// Checks the scene's casts ([`Scene::intersect_hit`], [`Scene::occluded`]) against brute force
/// ([`brute_closest`]) on `rays`: the same closest distance (bits) and primitive, and the same
/// any-hit answer; returns the number of rays that hit. Exact ties (a ray along an edge shared by
/// two triangles) may resolve to another primitive hit at the very same distance; there must be
/// few of them.
pub fn check_scene_casts(scene: &Scene, rays: &[Ray]) -> usize {
    let (mut hits, mut ties) = (0, 0);
    for ray in rays {
        let best = brute_closest(scene, ray);
        match (best, scene.intersect_hit(ray)) {
            (None, None) => {}
            (Some((t, i)), Some(h)) => {
                hits += 1;
                assert!(
                    h.t.is_finite() && h.t > 0.0,
                    "bad distance {} for {ray:?}",
                    h.t
                );
                assert_eq!(t, h.t, "closest distance differs for {ray:?}");
                if i as u32 != h.prim {
                    let tri = TriRay::new(ray);
                    let other = scene.intersect_prim(h.prim as usize, ray, &tri, ray.t_max);
                    assert_eq!(other.map(|o| o.0), Some(t), "closest primitive differs");
                    ties += 1;
                }
            }
            (b, h) => panic!("brute force {b:?} vs the scene {h:?} for {ray:?}"),
        }
        assert_eq!(scene.occluded(ray), best.is_some(), "any hit differs");
    }
    assert!(ties * 20 <= hits, "{ties} ties in {hits} hits");
    hits
}

/// `n` triangles in a cube of side 20: mostly small, every tenth large, and degenerate ones (a
/// point, and a segment of three collinear corners) among them.
pub fn random_soup(rng: &mut SplitMix, n: usize) -> Vec<[Vec3; 3]> {
    (0..n)
        .map(|t| {
            let c = rng.v(20.0);
            let s = if t % 10 == 0 { 8.0 } else { 1.5 };
            match t % 17 {
                0 => [c, c, c],
                1 => {
                    let d = rng.v(s);
                    [c, c + d, c + 2.0 * d]
                }
                _ => [c + rng.v(s), c + rng.v(s), c + rng.v(s)],
            }
        })
        .collect()
}

/// `n` spheres in the soup's cube, radii 0.3 to 1.3.
pub fn random_spheres(rng: &mut SplitMix, n: usize) -> Vec<Sphere> {
    (0..n)
        .map(|_| Sphere {
            center: rng.v(20.0),
            radius: 0.3 + rng.f(),
        })
        .collect()
}

/// A scene of [`random_spheres`] (`n % 4` of them, drawn first) and a [`random_soup`] of `n`
/// triangles.
pub fn random_soup_scene(rng: &mut SplitMix, n: usize) -> Scene {
    let spheres = random_spheres(rng, n % 4);
    scene(random_soup(rng, n), spheres)
}

/// `n` rays from a cube of side 50 toward points of the soup's cube; 30% with a random extent
/// below 40.
pub fn random_rays(rng: &mut SplitMix, n: usize) -> Vec<Ray> {
    (0..n)
        .map(|_| {
            let o = rng.v(50.0);
            let mut ray = Ray::new(o, (rng.v(20.0) - o).unit());
            if rng.f() < 0.3 {
                ray.t_max = rng.f() * 40.0;
            }
            ray
        })
        .collect()
}
