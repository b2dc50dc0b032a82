//! The 8-wide walk's stack entries, and the order in which a node's hit children are visited for
//! a closest hit: nearest entry first, the others pushed so that the nearest of them is popped
//! first, equal distances in lane order (which `accel/root.rs` reproduces for one-node trees).
//!
//! Which child is nearer is a coin toss for the branch predictor on incoherent rays, so two and
//! three hit children (about 21% and 8% of the node visits of random rays on a 1k mesh) are
//! ordered with selects, not branches. Measured on those rays: each of the two cost about 5% of
//! a closest-hit cast as branches.

/// A postponed child: node index or first primitive, leaf count (0 for a node), entry distance.
#[derive(Clone, Copy, Default)]
pub(super) struct Entry {
    /// Interior child: its node index. Leaf: its first primitive.
    pub child: u32,
    /// Leaf: primitive count. Interior: 0.
    pub count: u32,
    /// Where the ray enters the child's box.
    pub t_near: f32,
}

/// Two entries nearest first, `a` first on equal distances (`a` was hit in the lower lane).
#[inline(always)]
fn order(a: Entry, b: Entry) -> (Entry, Entry) {
    core::hint::select_unpredictable(b.t_near < a.t_near, (b, a), (a, b))
}

/// Orders the children hit in `mask` (at least two bits) whose entries `entry(lane)` gives:
/// returns the nearest and pushes the others onto `stack` at `*sp`, farthest deepest. The caller
/// has checked that the stack has room for all of them.
#[inline(always)]
pub(super) fn nearest_first(
    mut mask: u32,
    entry: impl Fn(usize) -> Entry,
    stack: &mut [Entry],
    sp: &mut usize,
) -> Entry {
    let first = entry(mask.trailing_zeros() as usize);
    mask &= mask - 1;
    let second = entry(mask.trailing_zeros() as usize);
    let rest = mask & (mask - 1);
    if rest == 0 {
        let (near, far) = order(first, second);
        stack[*sp] = far;
        *sp += 1;
        return near;
    }
    if rest & (rest - 1) == 0 {
        // A sorting network of three exchanges of neighbours, each only when strictly out of
        // order, so equal distances keep lane order as the insertion sort below does.
        let third = entry(rest.trailing_zeros() as usize);
        let (a, b) = order(first, second);
        let (b, c) = order(b, third);
        let (a, b) = order(a, b);
        stack[*sp] = c;
        stack[*sp + 1] = b;
        *sp += 2;
        return a;
    }
    // Four or more (4% of the visits): an insertion sort in place on the top of the stack, then
    // pop the nearest.
    let base = *sp;
    stack[base] = first;
    let mut top = base + 1;
    while mask != 0 {
        let e = entry(mask.trailing_zeros() as usize);
        mask &= mask - 1;
        let mut j = top;
        while j > base && stack[j - 1].t_near <= e.t_near {
            stack[j] = stack[j - 1];
            j -= 1;
        }
        stack[j] = e;
        top += 1;
    }
    *sp = top - 1;
    stack[top - 1]
}
