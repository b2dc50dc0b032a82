//! The `format` of a `bitmap` texture: the precision Mitsuba 3.9.1 stores its pixels at.
//!
//! Mitsuba's choices and what each means here:
//! - `auto` (the default): 8-bit images as bytes decoded texel by texel on lookup, 16-bit images
//!   as half floats, others at full precision;
//! - `variant`: full precision;
//! - `uint8`: bytes;
//! - `float16` (also `fp16`): half floats.
//!
//! Tessera keeps 32-bit floats. An 8-bit image stored as bytes and decoded per texel reads the
//! same values as its decoded floats (checked against Mitsuba's own lookups), so `auto`,
//! `variant` and `uint8` on an 8-bit image change nothing. `float16` rounds every value (after
//! sRGB decoding) to the nearest half float, as Mitsuba stores it. `uint8` on a floating-point
//! image would quantize it to 8 bits by a rounding not reproduced here: it is refused.
use crate::plugin::Param;
use glam::Vec3;

/// `format`.
pub(crate) const FORMAT: Param = Param::choice(
    "format",
    "auto",
    &["auto", "variant", "float16", "fp16", "uint8"],
    "storage precision: `float16` rounds each value to a half float as Mitsuba 3 stores it; \
     the others keep the values (an 8-bit image reads the same either way); `uint8` is refused \
     for a floating-point image",
);

/// What a `format` does to the decoded pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Storage {
    /// The values as decoded.
    Full,
    /// Every value rounded to the nearest half float.
    Half,
    /// Bytes: only for 8-bit images, whose decoded values it keeps.
    Byte,
}

impl Storage {
    /// The storage a `format` choice names.
    pub(crate) fn of(choice: &str) -> Storage {
        match choice {
            "float16" | "fp16" => Storage::Half,
            "uint8" => Storage::Byte,
            _ => Storage::Full,
        }
    }
}

/// `v` rounded to the nearest half-precision value (ties to even), back in single precision.
pub(crate) fn round_to_half(v: Vec3) -> Vec3 {
    Vec3::from_array(v.to_array().map(|x| half::f16::from_f32(x).to_f32()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Values Mitsuba 3.9.1 returned for a 32-bit EXR texture read with `format="float16"`
    /// (`mi.load_dict({'type': 'bitmap', 'format': 'float16', ...}).eval(...)`), against the
    /// rounding here; the control, the values unrounded, differs from them.
    #[test]
    #[allow(clippy::excessive_precision)] // Mitsuba's half values, written out exactly.
    fn half_rounding_is_mitsubas() {
        let stored = Vec3::new(0.1234, 0.7, 0.003);
        let mitsuba = Vec3::new(
            0.123_413_085_937_5,
            0.700_195_312_5,
            0.003_000_259_399_414_062_5,
        );
        assert_eq!(round_to_half(stored), mitsuba);
        assert_eq!(
            round_to_half(Vec3::new(0.5, 2.0, 0.9999)),
            Vec3::new(0.5, 2.0, 1.0)
        );
        assert_ne!(stored, mitsuba);
    }
}
