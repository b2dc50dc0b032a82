//! What a shading point remembers of the image lookups made at it.
//!
//! At one path vertex the same image is read at the same texture coordinates several times: a
//! diffuse surface's reflectance once for the emitter sample's BSDF value and again for the
//! BSDF sample's weight; a textured coating once per light weighed by light selection, then for
//! the emitter sample and for the BSDF sample. A bilinear lookup (the coordinate transform, the
//! wrap of four indices, four texel reads and their blend) is among the costliest parts of a
//! vertex, and each repeat gives the same bits. The path loop hands its vertex's shading point
//! a [`LookupMemo`]; an image lookup there returns the colour it already found for the same
//! image, or looks it up and keeps it.
//!
//! The memo is keyed by the image's address alone: every lookup through one shading point has
//! the same coordinates (a model that reads the surface in a tilted frame, `bumpmap` or
//! `normalmap`, passes the same coordinates on). Two slots, so that a model reading two images
//! (a textured reflectance and a textured roughness) keeps both.
use crate::Color;
use core::cell::Cell;

/// Up to two image lookups made at one shading point, each under the address of the image read.
#[derive(Debug, Default, PartialEq)]
pub struct LookupMemo {
    /// `(address, colour)`; address 0 marks an empty slot (no image lives at address 0).
    slots: [Cell<(usize, Color)>; 2],
    /// The slot the next new lookup replaces.
    next: Cell<u8>,
}

impl LookupMemo {
    /// The colour remembered for the image at address `key`, or `look()`'s, then remembered
    /// (replacing the older of the two slots).
    #[inline]
    pub fn get_or(&self, key: usize, look: impl FnOnce() -> Color) -> Color {
        for slot in &self.slots {
            let (k, c) = slot.get();
            if k == key {
                return c;
            }
        }
        let c = look();
        let i = usize::from(self.next.get() & 1);
        self.slots[i].set((key, c));
        self.next.set((i as u8) ^ 1);
        c
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A key seen before returns its colour without a lookup; a third key replaces the oldest.
    #[test]
    fn remembers_two_keys_and_replaces_the_oldest() {
        let memo = LookupMemo::default();
        let mut looked = 0;
        let mut get = |key: usize, v: f32| {
            memo.get_or(key, || {
                looked += 1;
                Color::splat(v)
            })
        };
        assert_eq!(get(8, 1.0), Color::splat(1.0));
        assert_eq!(get(16, 2.0), Color::splat(2.0));
        // Remembered: the value passed now is not looked up.
        assert_eq!(get(8, 9.0), Color::splat(1.0));
        assert_eq!(get(16, 9.0), Color::splat(2.0));
        // A third image replaces the first slot (key 8); key 16 stays.
        assert_eq!(get(24, 3.0), Color::splat(3.0));
        assert_eq!(get(16, 9.0), Color::splat(2.0));
        assert_eq!(get(8, 4.0), Color::splat(4.0));
        assert_eq!(looked, 4);
    }
}
