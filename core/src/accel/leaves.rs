//! What a BVH traversal does at its leaves (`Bvh8::cast`): the trait the
//! traversal calls for each leaf a ray reaches, so the leaf tests compile into the traversal's
//! own (possibly AVX2-enabled) function. The triangle blocks' implementations are
//! `ClosestLeaves` and `AnyLeaves`.
use super::slab_simd::Hit8;

/// The leaves of a traversal (`Bvh8::cast`).
pub trait Leaves {
    /// Whether a traversal may stop early and start again from the root with a larger stack
    /// (when a small one overflows), calling [`Leaves::test`] again for the same leaves: true
    /// when the effect of the last, complete traversal is all that counts (the closest hit, as
    /// each improvement overwrites the last; whether any hit was found, since a hit stops the
    /// traversal). Then most rays need only a small stack, which is cheaper to set up.
    const RESTARTABLE: bool = false;

    /// Tests the leaf of `count` primitives at `first` within `(0, t_max)` with the SIMD tests
    /// of `simd`: `Some(new t_max)` to go on, `None` to stop the traversal.
    fn test<H: Hit8>(&mut self, simd: H, first: usize, count: usize, t_max: f32) -> Option<f32>;

    /// A hint that the leaf of `count` primitives at `first` will probably be tested soon (its
    /// box is hit): implementations may prefetch its data. No effect on results.
    #[inline(always)]
    fn prefetch(&self, first: usize, count: usize) {
        let _ = (first, count);
    }
}

impl<L: Leaves> Leaves for &mut L {
    const RESTARTABLE: bool = L::RESTARTABLE;

    #[inline(always)]
    fn test<H: Hit8>(&mut self, simd: H, first: usize, count: usize, t_max: f32) -> Option<f32> {
        (**self).test(simd, first, count, t_max)
    }

    #[inline(always)]
    fn prefetch(&self, first: usize, count: usize) {
        (**self).prefetch(first, count)
    }
}

/// A closure as leaves (it does not use the SIMD token).
pub(super) struct FnLeaves<F>(pub(super) F);

impl<F: FnMut(usize, usize, f32) -> Option<f32>> Leaves for FnLeaves<F> {
    #[inline(always)]
    fn test<H: Hit8>(&mut self, _: H, first: usize, count: usize, t_max: f32) -> Option<f32> {
        (self.0)(first, count, t_max)
    }
}
