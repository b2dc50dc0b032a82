//! The camera a scene is seen through: a film of `width` x `height` pixels, a placement
//! (`to_world`) and one of Mitsuba 3's projections ([`Projection`]). Only the thin lens draws
//! sample values of its own (the point on its aperture); the others map a film position to one
//! ray, so a pinhole image does not depend on whether lenses exist.
use super::orthographic::Orthographic;
use super::perspective::{FovAxis, Perspective};
use super::thin_lens::ThinLens;
use crate::math::{Norm, Ray, Transform};
use crate::sampling::{Sampler, LENS_DIMENSION};
use glam::{Vec2, Vec3};

/// How film positions become rays, in camera space.
#[derive(Clone, Debug)]
pub enum Projection {
    /// A pinhole (`perspective`).
    Perspective(Perspective),
    /// A pinhole seen through a thin lens (`thinlens`).
    ThinLens(ThinLens),
    /// Parallel rays (`orthographic`).
    Orthographic(Orthographic),
}

impl Projection {
    /// The sensor plugin's name in a scene file.
    pub fn name(&self) -> &'static str {
        match self {
            Projection::Perspective(_) => "perspective",
            Projection::ThinLens(_) => "thinlens",
            Projection::Orthographic(_) => "orthographic",
        }
    }
}

/// A camera producing rays through continuous film positions.
#[derive(Clone, Debug)]
pub struct Camera {
    /// Camera to world (a perspective camera uses its rigid part: scale is ignored).
    pub to_world: Transform,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// The projection.
    pub projection: Projection,
    /// Where the image lies on a larger film (Mitsuba 3's crop window), if it does.
    pub crop: Option<Crop>,
}

/// A crop window: the camera's `width` x `height` image is the window at (`x`, `y`) (pixels,
/// top-left corner) of a `film_width` x `film_height` film, and sees what that window of the
/// whole film's image sees.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Crop {
    /// Left edge of the window on the film, in pixels.
    pub x: u32,
    /// Top edge of the window on the film, in pixels.
    pub y: u32,
    /// The whole film's width in pixels.
    pub film_width: u32,
    /// The whole film's height in pixels.
    pub film_height: u32,
}

impl Camera {
    /// A pinhole camera with field of view `fov_deg` along `axis`.
    pub fn perspective(
        to_world: Transform,
        width: u32,
        height: u32,
        fov_deg: f32,
        axis: FovAxis,
        near: f32,
        far: f32,
    ) -> Self {
        let p = Perspective::new(width, height, fov_deg, axis, near, far);
        Camera {
            to_world,
            width,
            height,
            projection: Projection::Perspective(p),
            crop: None,
        }
    }

    /// Film position `pos` of the image as a position on the whole film, and the film's size
    /// (the image's own without a crop window, `pos` then unchanged).
    #[inline]
    fn on_film(&self, pos: Vec2) -> (Vec2, (u32, u32)) {
        match self.crop {
            None => (pos, (self.width, self.height)),
            Some(c) => (
                pos + Vec2::new(c.x as f32, c.y as f32),
                (c.film_width, c.film_height),
            ),
        }
    }

    /// Whether the camera draws a 2D sample of its own for each ray (a thin lens's aperture).
    #[inline]
    pub fn has_lens(&self) -> bool {
        matches!(self.projection, Projection::ThinLens(_))
    }

    /// The camera ray through film position `pos` (pixels, continuous; `(0,0)` is the top-left
    /// corner). A thin lens reads its aperture sample from `sampler`, at dimension
    /// [`LENS_DIMENSION`]; the other projections draw nothing.
    #[inline]
    pub fn sample_ray<S: Sampler>(&self, pos: Vec2, sampler: &mut S) -> Ray {
        match &self.projection {
            Projection::ThinLens(lens) => {
                sampler.start_dimension(LENS_DIMENSION);
                let u = sampler.next_2d();
                let (pos, size) = self.on_film(pos);
                lens.generate_ray(&self.to_world, pos, size, u)
            }
            _ => self.generate_ray(pos),
        }
    }

    /// The ray through film position `pos` and, for a thin lens, the aperture point `lens`
    /// (in `[0,1)^2`) maps to; the other projections ignore `lens`.
    #[inline]
    pub fn generate_ray_through(&self, pos: Vec2, lens: Vec2) -> Ray {
        match &self.projection {
            Projection::ThinLens(l) => {
                let (pos, size) = self.on_film(pos);
                l.generate_ray(&self.to_world, pos, size, lens)
            }
            _ => self.generate_ray(pos),
        }
    }

    /// The ray through film position `pos`, through the centre of a thin lens's aperture.
    #[inline]
    pub fn generate_ray(&self, pos: Vec2) -> Ray {
        let (pos, size) = self.on_film(pos);
        match &self.projection {
            Projection::Perspective(p) => pinhole_ray(p, &self.to_world, pos, size),
            Projection::ThinLens(l) => pinhole_ray(&l.pinhole, &self.to_world, pos, size),
            Projection::Orthographic(o) => o.generate_ray(&self.to_world, pos, size),
        }
    }
}

/// The pinhole ray through film position `pos`, clipped to the near and far planes.
#[inline]
fn pinhole_ray(p: &Perspective, to_world: &Transform, pos: Vec2, (w, h): (u32, u32)) -> Ray {
    let local = p.image_point(pos, w, h);
    // Distance along the unit direction to the clip planes z = near and z = far.
    let len = local.norm();
    let d = to_world.vector(local / len).unit();
    let o = to_world.point(Vec3::ZERO);
    let (near_t, far_t) = (p.near * len, p.far * len);
    Ray {
        o: o + d * near_t,
        d,
        t_max: far_t - near_t,
    }
}
