//! The BVH tests' harness: 8-wide hierarchies of either collapse (`Wide`) over a scene's
//! primitives with the scene's leaf code (`WideScene`), and `compare`, which checks the 8-wide
//! hierarchy's closest and any hits against brute force, the greedy collapse, the portable box
//! test, the counted walks and the scene's own casts. Used by `tests/bvh8.rs` and
//! `tests/bvh8_mixed.rs`.
use crate::soup::brute_closest;
use tessera_core::accel::tri_block::Ray4;
use tessera_core::accel::{Bvh, Bvh8, Collapse, LeafRanges, TriBlocks};
use tessera_core::geometry::{Hit, TriRay};
use tessera_core::glam::Vec3;
use tessera_core::math::{Aabb, Ray};
use tessera_core::scene::Scene;

/// Traversal of an 8-wide hierarchy of either collapse (the default [`Bvh8`] or [`Greedy8`]),
/// so one harness checks both: the counted walk when given a node counter, else the ordinary
/// one (they are compiled separately).
pub trait Wide: LeafRanges + Sized {
    /// Builds over `bounds`: the hierarchy and its primitive order.
    fn build(bounds: &[Aabb]) -> (Self, Vec<u32>);
    /// Closest-hit walk (counted when given a counter).
    fn closest(&self, ray: &Ray, leaf: impl FnMut(usize, usize, f32) -> f32, n: Option<&mut u64>);
    /// Any-hit walk (counted when given a counter).
    fn any(&self, ray: &Ray, leaf: impl FnMut(usize, usize, f32) -> bool, n: Option<&mut u64>);
}

impl Wide for Bvh8 {
    fn build(bounds: &[Aabb]) -> (Self, Vec<u32>) {
        Bvh8::build(bounds)
    }
    fn closest(&self, ray: &Ray, leaf: impl FnMut(usize, usize, f32) -> f32, n: Option<&mut u64>) {
        match n {
            Some(n) => self.traverse_closest_counted(ray, leaf, n),
            None => self.traverse_closest(ray, leaf),
        }
    }
    fn any(&self, ray: &Ray, leaf: impl FnMut(usize, usize, f32) -> bool, n: Option<&mut u64>) {
        match n {
            Some(n) => self.traverse_any_counted(ray, leaf, n),
            None => self.traverse_any(ray, leaf),
        }
    }
}

/// The 8-wide hierarchy collapsed greedily (the default is the surface-area collapse).
pub struct Greedy8(pub Bvh8);

impl LeafRanges for Greedy8 {
    fn map_leaves(&mut self, f: impl FnMut(usize, usize) -> u32) {
        self.0.map_leaves(f);
    }
}

impl Wide for Greedy8 {
    fn build(bounds: &[Aabb]) -> (Self, Vec<u32>) {
        let (bin, order) = Bvh::build_with(bounds, Bvh8::PARAMS);
        (
            Greedy8(Bvh8::from_binary_with(&bin, Collapse::Greedy)),
            order,
        )
    }
    fn closest(&self, ray: &Ray, leaf: impl FnMut(usize, usize, f32) -> f32, n: Option<&mut u64>) {
        self.0.closest(ray, leaf, n)
    }
    fn any(&self, ray: &Ray, leaf: impl FnMut(usize, usize, f32) -> bool, n: Option<&mut u64>) {
        self.0.any(ray, leaf, n)
    }
}

/// An 8-wide hierarchy over a scene's primitives, with the scene's leaf code.
pub struct WideScene<'a, B> {
    /// The scene whose primitives are cast against.
    pub scene: &'a Scene,
    /// The hierarchy.
    pub bvh: B,
    /// Its leaf blocks.
    pub blocks: TriBlocks,
    /// Scene primitive of each position of this hierarchy's order.
    pub order: Vec<u32>,
}

impl<'a, B: Wide> WideScene<'a, B> {
    /// Builds the hierarchy over the scene's primitives.
    pub fn new(scene: &'a Scene) -> Self {
        let corners: Vec<[Vec3; 3]> = (0..scene.prims.len())
            .map(|i| scene.triangle(i).unwrap_or([Vec3::NAN; 3]))
            .collect();
        let bounds: Vec<Aabb> = (0..scene.prims.len())
            .map(|i| scene.prims[i].bounds(&corners[i], &scene.disks, &scene.shapes))
            .collect();
        let (mut bvh, order) = B::build(&bounds);
        let sorted: Vec<[Vec3; 3]> = order.iter().map(|&i| corners[i as usize]).collect();
        let blocks = TriBlocks::build(&mut bvh, &sorted);
        WideScene {
            scene,
            bvh,
            blocks,
            order,
        }
    }

    /// Closest hit, as a scene primitive.
    pub fn intersect_hit(&self, ray: &Ray, nodes: Option<&mut u64>) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let tri = TriRay::new(ray);
        let r4 = Ray4::new(&tri);
        let other = |i: usize, _: &[Vec3; 3], t: f32| {
            self.scene
                .intersect_prim(self.order[i] as usize, ray, &tri, t)
        };
        let leaf = |first, count, t_max| {
            self.blocks
                .closest(first, count, &r4, t_max, &mut best, other)
        };
        self.bvh.closest(ray, leaf, nodes);
        best.map(|h| Hit {
            prim: self.order[h.prim as usize],
            ..h
        })
    }

    /// Any hit.
    pub fn occluded(&self, ray: &Ray, nodes: Option<&mut u64>) -> bool {
        let mut hit = false;
        let tri = TriRay::new(ray);
        let r4 = Ray4::new(&tri);
        let other = |i: usize, _: &[Vec3; 3], t: f32| {
            self.scene
                .intersect_prim(self.order[i] as usize, ray, &tri, t)
        };
        self.bvh.any(
            ray,
            |first, count, t_max| {
                hit = self.blocks.any(first, count, &r4, t_max, other);
                hit
            },
            nodes,
        );
        hit
    }
}

/// Compares the 8-wide hierarchy `w8` (with its box test, counted and not) with brute force,
/// the greedily collapsed hierarchy, one with the portable box test and the scene's own casts;
/// returns (hits, rays that disagree). Exact ties may resolve to another primitive at the same distance; there must be
/// few of them.
pub fn compare(scene: &Scene, w8: &WideScene<Bvh8>, rays: &[Ray]) -> (usize, usize) {
    let g8 = WideScene::<Greedy8>::new(scene);
    let mut p8 = WideScene::<Bvh8>::new(scene);
    p8.bvh.use_portable();
    let (mut hits, mut ties, mut bad) = (0, 0, 0);
    let key = |h: Option<Hit>| h.map(|h| (h.t.to_bits(), h.prim));
    for ray in rays {
        let best = brute_closest(scene, ray);
        let h8 = w8.intersect_hit(ray, None);
        let any8 = w8.occluded(ray, None);
        let mut n = 0;
        let counted = (
            key(w8.intersect_hit(ray, Some(&mut n))),
            w8.occluded(ray, Some(&mut n)),
        );
        let portable = (key(p8.intersect_hit(ray, None)), p8.occluded(ray, None));
        let tg = g8.intersect_hit(ray, None).map(|h| h.t.to_bits());
        let anyg = g8.occluded(ray, None);
        // The scene's own casts: leaves inside the AVX2 walk, blocks in pairs, restartable.
        // (Its tree is built from the scene's reordered primitives: equal up to exact ties.)
        let cast = (
            scene.intersect_hit(ray).map(|h| h.t.to_bits()),
            scene.occluded(ray),
        );
        let same = match (best, h8) {
            (None, None) => true,
            (Some((t, i)), Some(h)) => {
                hits += 1;
                if i as u32 != h.prim && t == h.t {
                    ties += 1;
                }
                t == h.t && h.t.is_finite() && h.t > 0.0
            }
            _ => false,
        };
        if !same
            || tg != key(h8).map(|k| k.0)
            || any8 != best.is_some()
            || anyg != any8
            || cast != (key(h8).map(|k| k.0), any8)
            || portable != (key(h8), any8)
            || counted != (key(h8), any8)
            || n < 2
        {
            bad += 1;
        }
    }
    assert!(ties * 20 <= hits.max(1), "{ties} ties in {hits} hits");
    (hits, bad)
}
