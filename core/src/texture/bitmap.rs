//! Image textures (`bitmap`), looked up as Mitsuba 3 does (measured against it by
//! `scripts/mitsuba_texture_eval.py`).
//!
//! Scene parameters (`<texture type="bitmap">`, read by the driver): `filename` (string,
//! required: PNG, JPEG, BMP, TGA, EXR, PFM or RGBE `.hdr`, relative to the scene file), `raw`
//! (boolean, default false: when false, 8-bit values are sRGB-decoded to linear; EXR, PFM and
//! `.hdr` are linear already), `filter_type` (`bilinear` (default) | `nearest`), `wrap_mode` (`repeat` (default) |
//! `mirror` | `clamp`), `to_uv` (transform, see [`UvTransform`]).
//!
//! Conventions: the first (top) image row is at `v = 0`; pixel `(i, j)` covers
//! `[i/W, (i+1)/W) x [j/H, (j+1)/H)` with its value at the centre, so bilinear filtering
//! interpolates between centres at `((i + 1/2)/W, (j + 1/2)/H)` and `nearest` takes the pixel
//! the point falls in. The wrap mode applies to pixel indices: `repeat` tiles, `mirror`
//! reflects at every edge (a period of `2W`), `clamp` repeats the edge pixels. A scalar lookup
//! ([`Bitmap::eval_1`]) is the luminance of the colour, as in Mitsuba 3.
use super::texels::Texels;
use super::to_uv::UvTransform;
use crate::geometry::LookupMemo;
use crate::Color;
use glam::Vec2;

/// How pixel values are reconstructed between pixel centres.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FilterType {
    /// The value of the pixel the point falls in.
    Nearest,
    /// Bilinear interpolation of the four nearest pixel centres.
    Bilinear,
}

/// How pixel indices outside the image are mapped back in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WrapMode {
    /// Tile the image.
    Repeat,
    /// Tile the image, mirrored every other time.
    Mirror,
    /// Extend the edge pixels.
    Clamp,
}

/// A pixel index from a floored coordinate, kept far from integer overflow.
#[inline]
fn index(v: f32) -> i64 {
    const LIMIT: f32 = (1u64 << 40) as f32;
    v.clamp(-LIMIT, LIMIT) as i64
}

/// Rec. 709 luminance weights (Mitsuba 3's `luminance`).
const LUMINANCE: Color = Color::new(0.212_671, 0.715_160, 0.072_169);

/// An RGB image (linear values, top row first) with its lookup settings.
#[derive(Clone, Debug)]
pub struct Bitmap {
    width: usize,
    height: usize,
    pixels: Texels,
    filter: FilterType,
    wrap: WrapMode,
    to_uv: UvTransform,
    max: f32,
}

impl Bitmap {
    /// A texture from `width * height` pixels, top row first (a `Vec` of linear values, or
    /// [`Texels`] shared with other textures of the same image); `None` when the size is zero
    /// or does not match.
    pub fn new(
        width: usize,
        height: usize,
        pixels: impl Into<Texels>,
        filter: FilterType,
        wrap: WrapMode,
        to_uv: UvTransform,
    ) -> Option<Self> {
        let pixels: Texels = pixels.into();
        if width == 0 || height == 0 || width.checked_mul(height)? != pixels.len() {
            return None;
        }
        let max = pixels.max_value();
        Some(Bitmap {
            width,
            height,
            pixels,
            filter,
            wrap,
            to_uv,
            max,
        })
    }

    /// Image size in pixels `(width, height)`.
    pub fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }

    /// Bytes of the pixels (shared with every texture made from the same image).
    pub fn memory_bytes(&self) -> usize {
        self.pixels.memory_bytes()
    }

    /// Identifies the pixel storage: equal for textures that share one image.
    pub fn storage_id(&self) -> usize {
        self.pixels.storage_id()
    }

    fn wrap_index(&self, i: i64, n: usize) -> usize {
        let n = n as i64;
        let k = match self.wrap {
            WrapMode::Repeat => i.rem_euclid(n),
            WrapMode::Clamp => i.clamp(0, n - 1),
            WrapMode::Mirror => {
                let p = i.rem_euclid(2 * n);
                if p < n {
                    p
                } else {
                    2 * n - 1 - p
                }
            }
        };
        k as usize
    }

    /// The wrapped indices of `i` and `i + 1` along an axis of `n` texels, with one division
    /// (a 64-bit remainder costs tens of cycles, and a bilinear lookup needs four indices).
    fn wrap_pair(&self, i: i64, n: usize) -> (usize, usize) {
        let k = self.wrap_index(i, n);
        let next = match self.wrap {
            // One past the last texel is the first, as `(i + 1) mod n`.
            WrapMode::Repeat => {
                if k + 1 == n {
                    0
                } else {
                    k + 1
                }
            }
            _ => self.wrap_index(i.saturating_add(1), n),
        };
        (k, next)
    }

    fn texel(&self, x: i64, y: i64) -> Color {
        let (x, y) = (
            self.wrap_index(x, self.width),
            self.wrap_index(y, self.height),
        );
        self.pixels.get(y * self.width + x)
    }

    /// The four texels `(x0, y0)`, `(x0 + 1, y0)`, `(x0, y0 + 1)`, `(x0 + 1, y0 + 1)`.
    fn quad(&self, x0: i64, y0: i64) -> [Color; 4] {
        let (xa, xb) = self.wrap_pair(x0, self.width);
        let (ya, yb) = self.wrap_pair(y0, self.height);
        let (ra, rb) = (ya * self.width, yb * self.width);
        self.pixels.get4([ra + xa, ra + xb, rb + xa, rb + xb])
    }

    /// The colour at surface coordinates `uv` (a non-finite `uv` reads as `(0, 0)`, a huge one
    /// as if clamped to +-1e9). Always inlined: once the compiler stopped inlining it into
    /// emitter sampling's BSDF evaluation (after an unrelated change elsewhere), the material
    /// scene took 2-3% longer (`scripts/ab_bench.py`).
    #[inline(always)]
    pub fn eval(&self, uv: Vec2) -> Color {
        let uv = self.to_uv.apply(uv);
        let uv = if uv.is_finite() {
            // Beyond 2^30 an f32 has no fractional digits left: nothing is lost.
            uv.clamp(Vec2::splat(-1.0e9), Vec2::splat(1.0e9))
        } else {
            Vec2::ZERO
        };
        let (w, h) = (self.width as f32, self.height as f32);
        match self.filter {
            FilterType::Nearest => {
                let x = index(libm::floorf(uv.x * w));
                let y = index(libm::floorf(uv.y * h));
                self.texel(x, y)
            }
            FilterType::Bilinear => {
                let (x, y) = (uv.x * w - 0.5, uv.y * h - 0.5);
                let (xf, yf) = (libm::floorf(x), libm::floorf(y));
                let (fx, fy) = (x - xf, y - yf);
                let (x0, y0) = (index(xf), index(yf));
                let [t00, t10, t01, t11] = self.quad(x0, y0);
                let top = t00 * (1.0 - fx) + t10 * fx;
                let bottom = t01 * (1.0 - fx) + t11 * fx;
                top * (1.0 - fy) + bottom * fy
            }
        }
    }

    /// The luminance at `uv` (what Mitsuba 3 uses for scalar parameters such as weights).
    pub fn eval_1(&self, uv: Vec2) -> f32 {
        Self::luminance(self.eval(uv))
    }

    /// The luminance of a colour [`Bitmap::eval`] gave, as [`Bitmap::eval_1`] takes it.
    #[inline]
    pub fn luminance(c: Color) -> f32 {
        c.dot(LUMINANCE)
    }

    /// [`Bitmap::eval`] at `uv`, remembered in `memo` (a shading point's, whose lookups all
    /// have coordinates `uv`) under this image's address: read from there when it holds this
    /// image's value already (an image does not move while a render reads it).
    pub fn eval_remembered(&self, uv: Vec2, memo: Option<&LookupMemo>) -> Color {
        match memo {
            Some(memo) => memo.get_or(core::ptr::from_ref(self) as usize, || self.eval(uv)),
            None => self.eval(uv),
        }
    }

    /// The gradient of [`Bitmap::eval_1`] with respect to `(u, v)`, as Mitsuba 3.9.1's
    /// `eval_1_grad` gives it: the derivative of the bilinear interpolation of the four
    /// luminances around `uv` along the pixel axes, carried back through `to_uv` by its
    /// transpose and multiplied by the resolution `(W, H)` (exact for a `to_uv` that does not
    /// mix `u` and `v`, or for a square image). Zero with `nearest` filtering (the lookup is
    /// piecewise constant) and where `uv` is not finite.
    pub fn eval_1_grad(&self, uv: Vec2) -> Vec2 {
        if self.filter == FilterType::Nearest {
            return Vec2::ZERO;
        }
        let uv = self.to_uv.apply(uv);
        if !uv.is_finite() {
            return Vec2::ZERO;
        }
        let uv = uv.clamp(Vec2::splat(-1.0e9), Vec2::splat(1.0e9));
        let (w, h) = (self.width as f32, self.height as f32);
        let (x, y) = (uv.x * w - 0.5, uv.y * h - 0.5);
        let (xf, yf) = (libm::floorf(x), libm::floorf(y));
        let (fx, fy) = (x - xf, y - yf);
        let (x0, y0) = (index(xf), index(yf));
        let [f00, f10, f01, f11] = self.quad(x0, y0).map(|t| t.dot(LUMINANCE));
        let d_x = (1.0 - fy) * (f10 - f00) + fy * (f11 - f01);
        let d_y = (1.0 - fx) * (f01 - f00) + fx * (f11 - f10);
        let [a, b, _] = self.to_uv.row_u;
        let [d, e, _] = self.to_uv.row_v;
        Vec2::new(w * (a * d_x + d * d_y), h * (b * d_x + e * d_y))
    }

    /// The mean of the pixels.
    pub(crate) fn mean_value(&self) -> Color {
        let sum = self
            .pixels
            .iter()
            .fold(glam::DVec3::ZERO, |s, p| s + p.as_dvec3());
        (sum / self.pixels.len() as f64).as_vec3()
    }

    /// The largest channel value of any pixel.
    pub fn max_value(&self) -> f32 {
        self.max
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec::Vec;

    /// The texel index a wrap mode gives on an axis of `n`, written from the modes' definitions
    /// (repeat: periodic; clamp: the edge texel; mirror: reflected at each edge, period `2n`).
    fn wrapped(mode: WrapMode, i: i64, n: i64) -> usize {
        let k = match mode {
            WrapMode::Repeat => ((i % n) + n) % n,
            WrapMode::Clamp => i.max(0).min(n - 1),
            WrapMode::Mirror => {
                let p = ((i % (2 * n)) + 2 * n) % (2 * n);
                if p < n {
                    p
                } else {
                    2 * n - 1 - p
                }
            }
        };
        k as usize
    }

    /// A bilinear lookup blends the four texels around it, each found by the wrap mode on its
    /// own: checked on a 3x2 image at coordinates inside, on the edges, far outside and
    /// negative, for every mode; the control, the repeat image read with clamping, differs.
    #[test]
    fn bilinear_lookups_wrap_each_texel() {
        let (w, h) = (3usize, 2usize);
        let pixels: Vec<Color> = (0..w * h)
            .map(|i| Color::new(i as f32, (i * i) as f32, 1.0 + i as f32 * 0.5))
            .collect();
        let coords = [
            -7.3f32, -1.0, -0.49, 0.0, 0.1, 0.5, 0.99, 1.0, 1.26, 4.75, 1000.3,
        ];
        for mode in [WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror] {
            let t = Bitmap::new(
                w,
                h,
                pixels.clone(),
                FilterType::Bilinear,
                mode,
                UvTransform::default(),
            )
            .unwrap();
            for &u in &coords {
                for &v in &coords {
                    let (x, y) = (u * w as f32 - 0.5, v * h as f32 - 0.5);
                    let (xf, yf) = (libm::floorf(x), libm::floorf(y));
                    let (fx, fy) = (x - xf, y - yf);
                    let at = |dx: i64, dy: i64| {
                        let px = wrapped(mode, xf as i64 + dx, w as i64);
                        let py = wrapped(mode, yf as i64 + dy, h as i64);
                        pixels[py * w + px]
                    };
                    let top = at(0, 0) * (1.0 - fx) + at(1, 0) * fx;
                    let bottom = at(0, 1) * (1.0 - fx) + at(1, 1) * fx;
                    let expected = top * (1.0 - fy) + bottom * fy;
                    assert_eq!(t.eval(Vec2::new(u, v)), expected, "{mode:?} at ({u}, {v})");
                }
            }
        }
        let repeat = |mode| {
            Bitmap::new(
                w,
                h,
                pixels.clone(),
                FilterType::Bilinear,
                mode,
                UvTransform::default(),
            )
            .unwrap()
            .eval(Vec2::new(-0.49, 1.26))
        };
        assert_ne!(repeat(WrapMode::Repeat), repeat(WrapMode::Clamp));
    }
}
