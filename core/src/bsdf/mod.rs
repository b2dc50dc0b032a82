//! BSDFs: a closed enum, one variant per file, evaluated in the local shading frame.
//!
//! Conventions: `wi` points from the surface toward the previous path vertex (the viewer), `wo`
//! toward the next one (the light); both are unit vectors in the shading frame (normal = +z).
//! `eval` includes the cosine factor `|cos theta_o|` and covers the smooth components only;
//! delta components (mirrors, smooth glass) are reached only through `sample`, whose `pdf` for
//! them is the discrete probability of choosing that component. Radiance is transported: a
//! refraction from index `eta_i` into `eta_t` scales the weight by `(eta_i / eta_t)^2`.
mod blend;
mod blinnphong;
mod blinnphong_metal;
mod bumpmap;
mod conductor;
mod dielectric;
mod diffuse;
pub mod fresnel;
mod mask;
pub mod microfacet;
mod mirror;
mod model;
mod normalmap;
mod null;
pub mod perturbed;
mod plastic;
pub mod plastic_common;
mod polarizer;
mod pplastic;
mod principled;
pub mod principled_lobes;
mod principled_sample;
mod principled_thin;
mod roughconductor;
mod roughdielectric;
pub mod roughness_texture;
mod roughplastic;
mod sample;
mod textures;
mod thindielectric;
mod traits;
mod twosided;
mod wakame_microfacet;

pub use blend::Blend;
pub use blinnphong::BlinnPhong;
pub use blinnphong_metal::BlinnPhongMetal;
pub use bumpmap::BumpMap;
pub use conductor::Conductor;
pub use dielectric::Dielectric;
pub use diffuse::Diffuse;
pub use mask::Mask;
pub use mirror::Mirror;
pub use model::Model;
pub use normalmap::NormalMap;
pub use null::Null;
pub use plastic::Plastic;
pub use polarizer::Polarizer;
pub use pplastic::PolarizedPlastic;
pub use principled::{Principled, PrincipledIndex, PrincipledParams, SamplingRates};
pub use principled_thin::{PrincipledThin, PrincipledThinParams, ThinSamplingRates};
pub use roughconductor::RoughConductor;
pub use roughdielectric::RoughDielectric;
pub use roughplastic::RoughPlastic;
pub use sample::BsdfSample;
pub use thindielectric::ThinDielectric;
pub use traits::BsdfTraits;
pub use twosided::TwoSided;
pub use wakame_microfacet::WakameMicrofacet;

use crate::geometry::ShadingPoint;
use crate::sampling::Sampler;
use crate::Color;
use glam::{Vec2, Vec3};

impl BsdfTraits {
    /// The answers for `bsdf`.
    pub fn of(bsdf: &Bsdf) -> Self {
        let (uses_u1, uses_u2) = bsdf.sample_inputs();
        BsdfTraits {
            uses_u1,
            uses_u2,
            has_smooth: bsdf.has_smooth(),
            lambertian: bsdf.is_lambertian(),
            reads_geometry: bsdf.reads_geometry(),
            reads_images: bsdf.reads_images(),
            reads_uv: bsdf.reads_uv(),
        }
    }
}

/// Surface scattering models.
#[derive(Clone, Debug)]
pub enum Bsdf {
    /// Lambertian reflection (`diffuse`).
    Diffuse(Diffuse),
    /// A front and a back model on one surface (`twosided`).
    TwoSided(TwoSided<Bsdf>),
    /// Smooth metal with complex Fresnel (`conductor`).
    Conductor(Conductor),
    /// Rough metal, microfacet (`roughconductor`).
    RoughConductor(RoughConductor),
    /// Smooth glass: Fresnel reflection and refraction (`dielectric`).
    Dielectric(Dielectric),
    /// Rough glass, Walter et al. 2007 (`roughdielectric`).
    RoughDielectric(RoughDielectric),
    /// A thin glass sheet (`thindielectric`).
    ThinDielectric(ThinDielectric),
    /// Smooth coating over a diffuse base (`plastic`).
    Plastic(Plastic),
    /// Rough coating over a diffuse base (`roughplastic`).
    RoughPlastic(RoughPlastic),
    /// Nori's perfect mirror (`mirror`).
    Mirror(Mirror),
    /// Wakame's Beckmann microfacet over diffuse (`microfacet`).
    WakameMicrofacet(WakameMicrofacet),
    /// Chalmers' Blinn-Phong dielectric layer over a nested model (`blinnphong`).
    BlinnPhong(BlinnPhong<Bsdf>),
    /// Chalmers' tinted Blinn-Phong metal (`blinnphong_metal`).
    BlinnPhongMetal(BlinnPhongMetal),
    /// Linear blend of two models (`blendbsdf`, Chalmers' `blend`).
    Blend(Blend<Bsdf>),
    /// Opacity mask over a model (`mask`).
    Mask(Mask<Bsdf>),
    /// Burley's Disney model as Mitsuba 3 writes it (`principled`).
    Principled(Principled),
    /// A model seen through a tangent-space normal map (`normalmap`).
    NormalMap(NormalMap<Bsdf>),
    /// Burley's thin-sheet variant as Mitsuba 3 writes it (`principledthin`).
    PrincipledThin(PrincipledThin),
    /// Mitsuba 3's polarized plastic as unpolarized light sees it (`pplastic`).
    PolarizedPlastic(PolarizedPlastic),
    /// Mitsuba 3's linear polarizer as unpolarized light sees it: a pass-through (`polarizer`).
    Polarizer(Polarizer),
    /// A model seen through a height field (`bumpmap`).
    BumpMap(BumpMap<Bsdf>),
    /// A surface light passes through unchanged, bounding a medium (`null`).
    Null(Null),
}

macro_rules! dispatch {
    ($self:expr, $b:ident => $e:expr) => {
        match $self {
            Bsdf::Diffuse($b) => $e,
            Bsdf::TwoSided($b) => $e,
            Bsdf::Conductor($b) => $e,
            Bsdf::RoughConductor($b) => $e,
            Bsdf::Dielectric($b) => $e,
            Bsdf::RoughDielectric($b) => $e,
            Bsdf::ThinDielectric($b) => $e,
            Bsdf::Plastic($b) => $e,
            Bsdf::RoughPlastic($b) => $e,
            Bsdf::Mirror($b) => $e,
            Bsdf::WakameMicrofacet($b) => $e,
            Bsdf::BlinnPhong($b) => $e,
            Bsdf::BlinnPhongMetal($b) => $e,
            Bsdf::Blend($b) => $e,
            Bsdf::Mask($b) => $e,
            Bsdf::Principled($b) => $e,
            Bsdf::NormalMap($b) => $e,
            Bsdf::PrincipledThin($b) => $e,
            Bsdf::PolarizedPlastic($b) => $e,
            Bsdf::Polarizer($b) => $e,
            Bsdf::BumpMap($b) => $e,
            Bsdf::Null($b) => $e,
        }
    };
}

impl Bsdf {
    /// `f(wi, wo) |cos theta_o|` of the smooth components.
    #[inline]
    pub fn eval<'a>(&self, wi: Vec3, wo: Vec3, at: impl Into<ShadingPoint<'a>>) -> Color {
        let at = at.into();
        dispatch!(self, b => b.eval(wi, wo, at))
    }
    /// Solid-angle density with which `sample` produces `wo` (smooth components only).
    #[inline]
    pub fn pdf<'a>(&self, wi: Vec3, wo: Vec3, at: impl Into<ShadingPoint<'a>>) -> f32 {
        let at = at.into();
        dispatch!(self, b => b.pdf(wi, wo, at))
    }
    /// Samples `wo` for `wi` from three uniform numbers (`u1` chooses a component).
    #[inline]
    pub fn sample<'a>(
        &self,
        wi: Vec3,
        u1: f32,
        u2: Vec2,
        at: impl Into<ShadingPoint<'a>>,
    ) -> Option<BsdfSample> {
        let at = at.into();
        dispatch!(self, b => b.sample(wi, u1, u2, at))
    }
    /// Which random inputs [`Bsdf::sample`] reads: `(u1, u2)`. The integrators skip the draws
    /// of inputs a BSDF ignores (with [`crate::sampling::Sampler::skip_1d`], which leaves the
    /// sampler where the draw would have), so skipping changes no value, only the work.
    #[inline]
    pub fn sample_inputs(&self) -> (bool, bool) {
        match self {
            Bsdf::TwoSided(t) => {
                let (f, b) = (t.front.own_inputs(), t.back.own_inputs());
                (f.0 || b.0, f.1 || b.1)
            }
            b => b.own_inputs(),
        }
    }
    /// [`Bsdf::sample_inputs`] without recursion, so a two-sided model's sides inline (a
    /// two-sided model nested in a side answers through the out-of-line call).
    #[inline(always)]
    fn own_inputs(&self) -> (bool, bool) {
        match self {
            Bsdf::Diffuse(_) | Bsdf::RoughConductor(_) | Bsdf::BlinnPhongMetal(_) => (false, true),
            Bsdf::Conductor(_) | Bsdf::Mirror(_) | Bsdf::Polarizer(_) | Bsdf::Null(_) => {
                (false, false)
            }
            Bsdf::Dielectric(_) | Bsdf::ThinDielectric(_) => (true, false),
            Bsdf::TwoSided(_) => self.nested_inputs(),
            _ => (true, true),
        }
    }
    /// The recursive case, out of line so the common ones inline.
    #[inline(never)]
    fn nested_inputs(&self) -> (bool, bool) {
        self.sample_inputs()
    }
    /// Draws `(u1, u2)` for [`Bsdf::sample`] from the sampler's next three dimensions; inputs
    /// the BSDF ignores are skipped, not drawn, and given as 0.5.
    #[inline]
    pub fn draw_sample_inputs<S: Sampler>(&self, sampler: &mut S) -> (f32, Vec2) {
        let (uses_u1, uses_u2) = self.sample_inputs();
        traits::draw_inputs(uses_u1, uses_u2, sampler)
    }
    /// Whether some part of the model reads the shading point's partials (`bumpmap`) or the
    /// mesh triangle hit (a `mesh_attribute` texture).
    pub fn reads_geometry(&self) -> bool {
        let mut reads_mesh = false;
        self.for_each_texture(&mut |t| reads_mesh |= t.reads_mesh());
        reads_mesh || self.bumps()
    }
    /// Whether some texture of the model, nested models' included, is an image (what a shading
    /// point's [`LookupMemo`](crate::geometry::LookupMemo) remembers; an image inside a
    /// checkerboard is read without it).
    pub fn reads_images(&self) -> bool {
        let mut images = false;
        self.for_each_texture(&mut |t| images |= t.bitmap().is_some());
        images
    }
    /// Whether some part of the model is a bump map.
    fn bumps(&self) -> bool {
        match self {
            Bsdf::BumpMap(_) => true,
            Bsdf::TwoSided(b) => b.front.bumps() || b.back.bumps(),
            Bsdf::Blend(b) => b.first.bumps() || b.second.bumps(),
            Bsdf::Mask(b) => b.nested.bumps(),
            Bsdf::NormalMap(b) => b.nested.bumps(),
            Bsdf::BlinnPhong(b) => b.base.as_ref().is_some_and(|b| b.bumps()),
            _ => false,
        }
    }
    /// Whether any component is smooth (non-delta): emitter sampling is useful.
    #[inline]
    pub fn has_smooth(&self) -> bool {
        dispatch!(self, b => b.has_smooth())
    }
    /// Whether any component is a delta distribution.
    pub fn has_delta(&self) -> bool {
        dispatch!(self, b => b.has_delta())
    }
    /// Whether it is Lambertian on each side (`diffuse`, or `twosided` over two of them): the
    /// light it reflects toward a direction depends only on which side that direction is on.
    pub fn is_lambertian(&self) -> bool {
        match self {
            Bsdf::Diffuse(_) => true,
            Bsdf::TwoSided(t) => t.front.is_lambertian() && t.back.is_lambertian(),
            _ => false,
        }
    }
}

impl Model for Bsdf {
    #[inline]
    fn eval(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> Color {
        Bsdf::eval(self, wi, wo, at)
    }
    #[inline]
    fn pdf(&self, wi: Vec3, wo: Vec3, at: ShadingPoint) -> f32 {
        Bsdf::pdf(self, wi, wo, at)
    }
    #[inline]
    fn sample(&self, wi: Vec3, u1: f32, u2: Vec2, at: ShadingPoint) -> Option<BsdfSample> {
        Bsdf::sample(self, wi, u1, u2, at)
    }
    #[inline]
    fn has_smooth(&self) -> bool {
        Bsdf::has_smooth(self)
    }
    fn has_delta(&self) -> bool {
        Bsdf::has_delta(self)
    }
    #[inline]
    fn as_diffuse(&self) -> Option<&Diffuse> {
        match self {
            Bsdf::Diffuse(d) => Some(d),
            _ => None,
        }
    }
}
