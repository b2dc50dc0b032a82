//! How a caller lends threads to the BVH build: the core has no threads of its own (it is
//! `no_std`), so the build hands each pair of large subtrees to a [`Fork`], which may run them
//! at once. Each subtree is built into its own node list and the lists are joined in a fixed
//! order, so the hierarchy is the same, bit for bit, whether or not they ran at once.

/// Runs two pieces of work, perhaps at the same time.
pub trait Fork: Sync {
    /// Runs `a` and `b`, in either order or at once, and returns when both are done.
    fn join(&self, a: &mut (dyn FnMut() + Send), b: &mut (dyn FnMut() + Send));
}

/// Runs the two one after the other (the core's default).
#[derive(Clone, Copy, Debug, Default)]
pub struct InTurn;

impl Fork for InTurn {
    fn join(&self, a: &mut (dyn FnMut() + Send), b: &mut (dyn FnMut() + Send)) {
        a();
        b();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::{BuildParams, Bvh};
    use crate::math::Aabb;
    use alloc::vec::Vec;
    use core::sync::atomic::{AtomicUsize, Ordering};
    use glam::Vec3;

    /// Runs the second piece of work first, and counts the calls.
    struct Reversed(AtomicUsize);

    impl Fork for Reversed {
        fn join(&self, a: &mut (dyn FnMut() + Send), b: &mut (dyn FnMut() + Send)) {
            self.0.fetch_add(1, Ordering::Relaxed);
            b();
            a();
        }
    }

    /// The node list as plain numbers, to compare bit for bit.
    fn words(bvh: &Bvh) -> Vec<[u32; 9]> {
        bvh.nodes
            .iter()
            .map(|n| {
                let (a, b) = (n.bounds.min.to_array(), n.bounds.max.to_array());
                [
                    a[0].to_bits(),
                    a[1].to_bits(),
                    a[2].to_bits(),
                    b[0].to_bits(),
                    b[1].to_bits(),
                    b[2].to_bits(),
                    n.offset,
                    u32::from(n.count),
                    u32::from(n.axis),
                ]
            })
            .collect()
    }

    /// Halves built in another order (each into its own list, joined after) give the same
    /// hierarchy and primitive order as one depth-first build. Control: the fork was used, so
    /// the comparison is not between two plain builds.
    #[test]
    fn forked_halves_make_the_same_tree() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        let bounds: Vec<Aabb> = (0..40_000)
            .map(|_| {
                let c = Vec3::new(next(), next() * 0.3, next()) * 100.0;
                let e = Vec3::new(next(), next(), next());
                Aabb::EMPTY.grow(c).grow(c + e)
            })
            .collect();
        let params = BuildParams::BINARY;
        let (plain, order) = Bvh::build_with(&bounds, params);
        let fork = Reversed(AtomicUsize::new(0));
        let (forked, forked_order) = Bvh::build_forked(&bounds, params, &fork);
        assert!(fork.0.load(Ordering::Relaxed) >= 7, "the fork was not used");
        assert_eq!(order, forked_order);
        assert!(words(&plain) == words(&forked), "forked build differs");
    }
}
