//! What a BSDF is asked at, at a path vertex: the texture coordinates, and, for a model that
//! reads them (`bumpmap`, textures of `mesh_attribute`), the position's partials and the
//! geometric normal in the local shading frame, and the mesh triangle hit.
//!
//! The partials are not kept in every `Interaction`: computing and carrying them cost every
//! hit of every scene about 2% more instructions (measured with cachegrind on `cbox.xml`).
//! Instead a vertex whose BSDF reads them (`BsdfTraits::reads_geometry`) finds them again from
//! the ray that reached it (`Scene::surface_detail`, the same cast as the `aov` outputs'), so
//! only vertices of such models pay, one more cast each.
//!
//! Likewise a vertex keeps a memo of its image lookups (`LookupMemo`) only where its model reads
//! an image (`BsdfTraits::reads_images`).
use super::Scene;
use crate::geometry::{Interaction, LookupMemo, Partials};
use crate::math::Ray;
use glam::Vec3;

impl Scene {
    /// The partials BSDF number `bsdf` reads at `si`, which `ray` reached: `None` for a model
    /// that does not read them (then `ShadingPoint::from(si.uv)` is all it is asked with).
    #[inline(always)]
    pub fn partials(&self, bsdf: u32, si: &Interaction, ray: &Ray) -> Option<Partials<'_>> {
        if self.bsdf_traits(bsdf).reads_geometry {
            Some(self.partials_at(si, ray))
        } else {
            None
        }
    }

    /// An empty memo for the image lookups of BSDF number `bsdf` at one vertex (the shading
    /// point's `memo`): `None` for a model that reads no image.
    #[inline(always)]
    pub fn lookup_memo(&self, bsdf: u32) -> Option<LookupMemo> {
        self.bsdf_traits(bsdf)
            .reads_images
            .then(LookupMemo::default)
    }

    /// The partials at `si` (zero if the cast no longer finds the surface, which leaves a
    /// bump map's frame unperturbed), with the mesh triangle hit.
    #[inline(never)]
    pub fn partials_at(&self, si: &Interaction, ray: &Ray) -> Partials<'_> {
        let (dp_du, dp_dv, site) = self
            .surface_detail_and_site(ray)
            .map_or((Vec3::ZERO, Vec3::ZERO, None), |(d, site)| {
                (d.dp_du, d.dp_dv, site)
            });
        Partials {
            dp_du: si.frame.to_local(dp_du),
            dp_dv: si.frame.to_local(dp_dv),
            ng: si.frame.to_local(si.ng),
            site,
        }
    }
}
