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

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec::Vec;

    /// Every mask of two to eight hit lanes, with distances drawn from a few values (so ties are
    /// common): the nearest comes back and the stack, read from the top, holds the rest, in the
    /// order of a stable sort by distance (lane order on ties).
    #[test]
    fn orders_as_a_stable_sort_by_distance() {
        let mut state = 12345u32;
        let mut next = || {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            state >> 16
        };
        for mask in 0u32..256 {
            if mask.count_ones() < 2 {
                continue;
            }
            for _ in 0..50 {
                let t: Vec<f32> = (0..8).map(|_| (next() % 4) as f32 * 0.5).collect();
                let entry = |lane: usize| Entry {
                    child: lane as u32,
                    count: 0,
                    t_near: t[lane],
                };
                let mut want: Vec<usize> = (0..8).filter(|&l| mask & (1 << l) != 0).collect();
                want.sort_by(|&a, &b| t[a].total_cmp(&t[b]));
                let mut stack = [Entry::default(); 16];
                let mut sp = 3; // entries already on the stack stay untouched
                let near = nearest_first(mask, entry, &mut stack, &mut sp);
                let mut got = alloc::vec![near.child as usize];
                got.extend(stack[3..sp].iter().rev().map(|e| e.child as usize));
                assert_eq!(got, want, "mask {mask:08b}, distances {t:?}");
            }
        }
    }

    /// All distances equal: lane order throughout (both tests fail when the exchanges swap on
    /// ties, checked by hand with `<=` in `order`).
    #[test]
    fn ties_keep_lane_order() {
        let entry = |lane: usize| Entry {
            child: lane as u32,
            count: 0,
            t_near: 1.0,
        };
        for mask in [0b11u32, 0b1011, 0b1111_0000] {
            let mut stack = [Entry::default(); 8];
            let mut sp = 0;
            let near = nearest_first(mask, entry, &mut stack, &mut sp);
            assert_eq!(near.child, mask.trailing_zeros());
            assert!(stack[..sp].windows(2).all(|w| w[0].child > w[1].child));
        }
    }
}
