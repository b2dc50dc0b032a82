//! Roughness that varies over the surface: `alpha` (or `alpha_u` and `alpha_v`) given as
//! textures on `roughconductor` and `roughdielectric`, as Mitsuba 3 accepts them.
//!
//! Each texture is read as a scalar ([`Texture::eval_1`]: the luminance of a bitmap) at the
//! shading point and, as Mitsuba 3's microfacet distribution does, raised to at least `1e-4`.
//! A model without textured roughness keeps its fixed [`Microfacet`] untouched.
use super::microfacet::Microfacet;
use crate::geometry::ShadingPoint;
use crate::texture::Texture;

/// Roughness textures along the two tangents (the same texture twice when isotropic).
#[derive(Clone, Debug)]
pub struct RoughnessTexture {
    /// Roughness along the first tangent (`alpha_u`, or `alpha`).
    pub alpha_u: Texture,
    /// Roughness along the second tangent (`alpha_v`, or `alpha`).
    pub alpha_v: Texture,
}

/// The lowest roughness a texture can give (Mitsuba 3's bound).
const MIN_ALPHA: f32 = 1e-4;

fn alpha(t: &Texture, at: ShadingPoint) -> f32 {
    let a = t.eval_1(at);
    if a.is_finite() {
        a.max(MIN_ALPHA)
    } else {
        MIN_ALPHA
    }
}

impl RoughnessTexture {
    /// `base` with its roughness read at `at`.
    #[inline]
    pub fn at(&self, base: &Microfacet, at: ShadingPoint) -> Microfacet {
        Microfacet {
            alpha_u: alpha(&self.alpha_u, at),
            alpha_v: alpha(&self.alpha_v, at),
            ..*base
        }
    }
}

/// The distribution of a rough model at `at`: `base` itself without textures.
#[inline]
pub(crate) fn distribution_at(
    base: &Microfacet,
    textures: &Option<RoughnessTexture>,
    at: ShadingPoint,
) -> Microfacet {
    match textures {
        None => *base,
        Some(t) => t.at(base, at),
    }
}
