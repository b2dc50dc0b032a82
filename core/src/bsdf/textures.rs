//! Walks the textures a BSDF reads (nested models included), for reports of what a scene holds
//! and how much memory its images take, and to tell whether shading reads texture coordinates.
use super::roughness_texture::RoughnessTexture;
use super::Bsdf;
use crate::texture::Texture;

impl Bsdf {
    /// Whether some part of the model reads the shading point's texture coordinates: a texture
    /// that is not a constant, or a bump map.
    pub fn reads_uv(&self) -> bool {
        let mut varies = false;
        self.for_each_texture(&mut |t| varies |= !matches!(t, Texture::Constant(_)));
        varies || self.bumps()
    }

    /// Calls `f` with every texture this model reads, nested models' included, in a fixed
    /// order.
    pub fn for_each_texture(&self, f: &mut dyn FnMut(&Texture)) {
        match self {
            Bsdf::Diffuse(b) => f(&b.reflectance),
            Bsdf::TwoSided(b) => {
                b.front.for_each_texture(f);
                b.back.for_each_texture(f);
            }
            Bsdf::Conductor(b) => [&b.eta, &b.k, &b.specular_reflectance]
                .into_iter()
                .for_each(f),
            Bsdf::RoughConductor(b) => {
                [&b.eta, &b.k, &b.specular_reflectance]
                    .into_iter()
                    .for_each(&mut *f);
                roughness_textures(&b.roughness, f);
            }
            Bsdf::Dielectric(b) => [&b.specular_reflectance, &b.specular_transmittance]
                .into_iter()
                .for_each(f),
            Bsdf::RoughDielectric(b) => {
                [&b.specular_reflectance, &b.specular_transmittance]
                    .into_iter()
                    .for_each(&mut *f);
                roughness_textures(&b.roughness, f);
            }
            Bsdf::ThinDielectric(b) => [&b.specular_reflectance, &b.specular_transmittance]
                .into_iter()
                .for_each(f),
            Bsdf::Plastic(b) => [&b.diffuse, &b.specular].into_iter().for_each(f),
            Bsdf::RoughPlastic(b) => [&b.diffuse, &b.specular].into_iter().for_each(f),
            Bsdf::Mirror(_) | Bsdf::WakameMicrofacet(_) | Bsdf::Null(_) => {}
            Bsdf::BlinnPhong(b) => {
                if let Some(base) = &b.base {
                    base.for_each_texture(f);
                }
            }
            Bsdf::BlinnPhongMetal(b) => f(&b.color),
            Bsdf::Blend(b) => {
                f(&b.weight);
                b.first.for_each_texture(f);
                b.second.for_each_texture(f);
            }
            Bsdf::Mask(b) => {
                f(&b.opacity);
                b.nested.for_each_texture(f);
            }
            Bsdf::Principled(b) => b.for_each_texture(f),
            Bsdf::NormalMap(b) => {
                f(&b.normalmap);
                b.nested.for_each_texture(f);
            }
            Bsdf::PrincipledThin(b) => b.for_each_texture(f),
            Bsdf::PolarizedPlastic(b) => {
                [&b.diffuse, &b.specular, &b.eta]
                    .into_iter()
                    .for_each(&mut *f);
                roughness_textures(&b.roughness, f);
            }
            Bsdf::Polarizer(b) => f(&b.transmittance),
            Bsdf::BumpMap(b) => {
                f(&b.height);
                b.nested.for_each_texture(f);
            }
        }
    }
}

/// The roughness textures of a rough model (`alpha_u` then `alpha_v`), if it has them.
fn roughness_textures(r: &Option<RoughnessTexture>, f: &mut dyn FnMut(&Texture)) {
    if let Some(r) = r {
        f(&r.alpha_u);
        f(&r.alpha_v);
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Diffuse, TwoSided};
    use super::*;
    use crate::texture::{Bitmap, FilterType, UvTransform, WrapMode};
    use crate::Color;
    use alloc::boxed::Box;
    use alloc::vec;

    fn diffuse(reflectance: Texture) -> Bsdf {
        Bsdf::Diffuse(Diffuse { reflectance })
    }

    /// A model reads images when one of its textures, nested models' included, is an image;
    /// constant ones do not count.
    #[test]
    fn reads_images_finds_nested_images() {
        let image = Bitmap::new(
            1,
            1,
            vec![Color::ONE],
            FilterType::Bilinear,
            WrapMode::Repeat,
            UvTransform::default(),
        )
        .unwrap();
        let plain = diffuse(Texture::constant(0.5));
        let textured = diffuse(Texture::Bitmap(image));
        assert!(!plain.reads_images());
        assert!(textured.reads_images());
        let sides = |front: &Bsdf, back: &Bsdf| {
            Bsdf::TwoSided(TwoSided {
                front: Box::new(front.clone()),
                back: Box::new(back.clone()),
            })
        };
        assert!(!sides(&plain, &plain).reads_images());
        assert!(sides(&plain, &textured).reads_images());
    }
}
