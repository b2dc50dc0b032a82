//! The threads the scene build lends to the BVH build ([`tessera_core::accel::Fork`]): a
//! pair of large subtrees runs on a new thread while one is free (as many as the machine has
//! cores, the calling thread included), else in turn. Which ran where changes nothing: the
//! core joins the halves in a fixed order.
use std::sync::atomic::{AtomicUsize, Ordering};
use tessera_core::accel::Fork;

/// Lends up to `free` extra threads at a time.
#[derive(Debug)]
pub(crate) struct Threads {
    free: AtomicUsize,
}

impl Threads {
    /// As many threads as the machine runs at once, the caller's included.
    pub(crate) fn of_machine() -> Threads {
        let n = std::thread::available_parallelism().map_or(1, |n| n.get());
        Threads {
            free: AtomicUsize::new(n.saturating_sub(1)),
        }
    }
}

impl Fork for Threads {
    fn join(&self, a: &mut (dyn FnMut() + Send), b: &mut (dyn FnMut() + Send)) {
        let took = self
            .free
            .fetch_update(Ordering::AcqRel, Ordering::Acquire, |n| n.checked_sub(1))
            .is_ok();
        if !took {
            a();
            b();
            return;
        }
        // A panic in either is re-raised here once both are done (`scope` joins the thread).
        std::thread::scope(|s| {
            s.spawn(a);
            b();
        });
        self.free.fetch_add(1, Ordering::AcqRel);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tessera_core::accel::{Bvh, Bvh8, InTurn};
    use tessera_core::glam::Vec3;
    use tessera_core::math::Aabb;

    /// On real threads, the BVH is the one built in turn (node for node, primitive order
    /// too), and every thread lent is given back. (That the build's result does not depend on
    /// the order the halves run in, with a control that the fork is used, is the core's test.)
    #[test]
    fn threads_build_the_same_bvh() {
        let bounds: Vec<Aabb> = (0..30_000u32)
            .map(|i| {
                let h = i.wrapping_mul(2_654_435_761);
                let c = Vec3::new((h % 1000) as f32, (h / 1000 % 997) as f32, (i % 89) as f32);
                Aabb::EMPTY.grow(c).grow(c + Vec3::splat(0.5))
            })
            .collect();
        let threads = Threads {
            free: AtomicUsize::new(3),
        };
        let (a, order_a) = Bvh::build_forked(&bounds, Bvh8::PARAMS, &threads);
        let (b, order_b) = Bvh::build_forked(&bounds, Bvh8::PARAMS, &InTurn);
        assert_eq!(order_a, order_b);
        assert_eq!(format!("{:?}", a.nodes), format!("{:?}", b.nodes));
        assert_eq!(
            threads.free.load(Ordering::Acquire),
            3,
            "a thread was not given back"
        );
    }
}
