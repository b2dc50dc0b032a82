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
