//! A bitmap's pixel storage: linear floats, or, for images stored with 8 bits per channel, the
//! codes themselves beside each channel's 256 values. Codes take a quarter of the memory (a 2k
//! texture: 12 MiB instead of 48) and a lookup reads the same values through the table, so
//! images do not change by a bit whichever storage holds them.
use crate::Color;
use alloc::sync::Arc;
use alloc::vec::Vec;

/// Each channel's value for each of the 256 codes.
pub type CodeTable = [[f32; 256]; 3];

/// Pixel storage, row-major; cheap to clone (shared).
#[derive(Clone, Debug)]
pub enum Texels {
    /// Linear values.
    Float(Arc<[Color]>),
    /// 8-bit codes, and the value of each code in each channel.
    Codes(Arc<[[u8; 3]]>, Arc<CodeTable>),
}

impl Texels {
    /// Number of pixels.
    pub fn len(&self) -> usize {
        match self {
            Texels::Float(p) => p.len(),
            Texels::Codes(c, _) => c.len(),
        }
    }

    /// Whether there are no pixels.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Pixel `i`.
    #[inline(always)]
    pub fn get(&self, i: usize) -> Color {
        match self {
            Texels::Float(p) => p[i],
            Texels::Codes(c, t) => decode(&c[i], t),
        }
    }

    /// Pixels `i`: four at once, the storage matched once.
    #[inline(always)]
    pub fn get4(&self, i: [usize; 4]) -> [Color; 4] {
        match self {
            Texels::Float(p) => i.map(|i| p[i]),
            Texels::Codes(c, t) => i.map(|i| decode(&c[i], t)),
        }
    }

    /// Bytes of the pixels (and the code table).
    pub fn memory_bytes(&self) -> usize {
        match self {
            Texels::Float(p) => core::mem::size_of_val(&**p),
            Texels::Codes(c, t) => core::mem::size_of_val(&**c) + core::mem::size_of_val(&**t),
        }
    }

    /// Identifies the storage: equal for clones.
    pub fn storage_id(&self) -> usize {
        match self {
            Texels::Float(p) => Arc::as_ptr(p) as *const Color as usize,
            Texels::Codes(c, _) => Arc::as_ptr(c) as *const [u8; 3] as usize,
        }
    }

    /// Every pixel, in order.
    pub fn iter(&self) -> impl Iterator<Item = Color> + '_ {
        (0..self.len()).map(|i| self.get(i))
    }

    /// The largest channel value of any pixel (0 for none; values are not negative).
    pub fn max_value(&self) -> f32 {
        match self {
            Texels::Float(p) => p.iter().fold(0.0f32, |m, p| m.max(p.max_element())),
            Texels::Codes(c, t) => {
                // The codes each channel uses, then the largest of their values.
                let mut used = [[false; 256]; 3];
                for px in c.iter() {
                    for ch in 0..3 {
                        used[ch][usize::from(px[ch])] = true;
                    }
                }
                let mut m = 0.0f32;
                for ch in 0..3 {
                    for k in 0..256 {
                        if used[ch][k] {
                            m = m.max(t[ch][k]);
                        }
                    }
                }
                m
            }
        }
    }
}

/// The value of the pixel with codes `c`.
#[inline(always)]
fn decode(c: &[u8; 3], t: &CodeTable) -> Color {
    Color::new(
        t[0][usize::from(c[0])],
        t[1][usize::from(c[1])],
        t[2][usize::from(c[2])],
    )
}

impl From<Arc<[Color]>> for Texels {
    fn from(p: Arc<[Color]>) -> Self {
        Texels::Float(p)
    }
}

impl From<Vec<Color>> for Texels {
    fn from(p: Vec<Color>) -> Self {
        Texels::Float(p.into())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::texture::{Bitmap, FilterType, UvTransform, WrapMode};
    use glam::Vec2;

    /// A bitmap stored as codes looks up exactly what the same image stored as the codes'
    /// values does, bilinear and nearest, in every wrap mode; its memory is a quarter's plus
    /// the table. Control: a table with one value changed gives other lookups.
    #[test]
    fn codes_look_up_as_their_values() {
        let (w, h) = (5usize, 3usize);
        let codes: Vec<[u8; 3]> = (0..w * h)
            .map(|i| {
                [
                    (i * 37 % 256) as u8,
                    (i * 91 % 256) as u8,
                    (255 - i * 13) as u8,
                ]
            })
            .collect();
        let table: CodeTable = core::array::from_fn(|ch| {
            core::array::from_fn(|k| libm::powf(k as f32 / 255.0, 2.2) * (1.0 + ch as f32))
        });
        let values: Vec<Color> = codes.iter().map(|c| decode(c, &table)).collect();
        let mut other = table;
        other[1][usize::from(codes[7][1])] += 0.25;
        let make = |t: Texels, filter, wrap| {
            Bitmap::new(w, h, t, filter, wrap, UvTransform::default()).unwrap()
        };
        let coded = Texels::Codes(codes.clone().into(), Arc::new(table));
        let changed = Texels::Codes(codes.clone().into(), Arc::new(other));
        let (mut same, mut differ) = (0, 0);
        for filter in [FilterType::Bilinear, FilterType::Nearest] {
            for wrap in [WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror] {
                let a = make(coded.clone(), filter, wrap);
                let b = make(values.clone().into(), filter, wrap);
                let c = make(changed.clone(), filter, wrap);
                assert_eq!(a.max_value(), b.max_value());
                for i in -20..40 {
                    for j in -20..40 {
                        let uv = Vec2::new(i as f32 * 0.071, j as f32 * 0.113);
                        assert_eq!(a.eval(uv).to_array(), b.eval(uv).to_array(), "{uv}");
                        same += 1;
                        differ += (a.eval(uv) != c.eval(uv)) as u32;
                    }
                }
            }
        }
        assert!(same > 0 && differ > 100, "control: {differ} lookups differ");
        assert_eq!(
            coded.memory_bytes(),
            3 * w * h + core::mem::size_of::<CodeTable>()
        );
    }
}
