//! Which sample dimensions each draw of a path reads: a fixed budget per bounce, so that bounce
//! `d` of every path of a pixel reads the same dimensions whatever was skipped before it (no
//! emitter sampling at a delta vertex, an emitter selection that found nothing, a path that
//! ended early). With a stratified sampler (`zsobol`) the pixel's samples then stay one
//! stratified set per quantity; without it, a path that skipped its emitter draws at a mirror
//! would read its later bounces from dimensions its siblings used for something else. Same
//! layout as pbrt-v4: camera dimensions first, then per bounce emitter selection (1), emitter
//! position (2), BSDF component (1), BSDF direction (2) and Russian roulette (1).
//!
//! A thin lens draws its aperture point from its own 2D dimension, [`LENS_DIMENSION`], far past
//! the camera's and the first bounces': the pinhole cameras draw nothing there, so adding the
//! lens left every dimension a pinhole image reads where it was.
//!
//! The integrators call `Sampler::start_stage` before each stage;
//! a stage that draws fewer values than its budget leaves the rest unused, one that would draw
//! more runs into the next stage's dimensions (still unbiased, only less stratified).

/// Dimensions the camera reads before the first bounce: the filter's 2D offset.
pub const CAMERA_DIMENSIONS: u32 = 2;

/// First of the two dimensions a thin lens reads its aperture point from (after the filter's
/// offset, before the integrator's first stage). A path would only reach it at a depth of
/// about 3 * 10^8; it is the 1D emitter selection of that bounce, so it is never paired with
/// another draw.
pub const LENS_DIMENSION: u32 = 1 << 31;

/// Dimensions reserved for one bounce.
pub const BOUNCE_DIMENSIONS: u32 = 7;

/// The parts of a bounce that draw sample values, in path order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Emitter selection (1D) and a point on the emitter (2D).
    Light,
    /// BSDF component (1D) and direction (2D).
    Bsdf,
    /// Russian roulette after the bounce (1D).
    Roulette,
}

impl Stage {
    /// First dimension of the stage within its bounce.
    #[inline]
    const fn offset(self) -> u32 {
        match self {
            Stage::Light => 0,
            Stage::Bsdf => 3,
            Stage::Roulette => 6,
        }
    }
}

/// First dimension of `stage` at bounce `depth` (0 = the vertex the camera ray found). Wraps
/// for absurd depths (dimensions are only hashed, never indexed).
#[inline]
pub const fn dimension_of(depth: u32, stage: Stage) -> u32 {
    CAMERA_DIMENSIONS
        .wrapping_add(depth.wrapping_mul(BOUNCE_DIMENSIONS))
        .wrapping_add(stage.offset())
}

/// The 2D draw whose sequence index the 2D draw starting at `dim` shares, if any: the point on
/// the emitter at bounce 0 shares the camera's (dimension 0), the point on the emitter at bounce
/// `d + 1` shares the BSDF direction's of bounce `d`. A stratified sampler can then make each
/// such couple one 4D point of a net (see `zsobol`): the pixel footprint with
/// the light seen from the first vertex, and each bounce's direction with the light sampled
/// where it lands, which is what one-bounce lighting integrates over.
#[inline]
pub const fn paired_dimension(dim: u32) -> Option<u32> {
    // The emitter position follows the 1D emitter choice.
    let position = Stage::Light.offset() + 1;
    if dim < CAMERA_DIMENSIONS || (dim - CAMERA_DIMENSIONS) % BOUNCE_DIMENSIONS != position {
        return None;
    }
    let depth = (dim - CAMERA_DIMENSIONS) / BOUNCE_DIMENSIONS;
    if depth == 0 {
        Some(0)
    } else {
        // The BSDF direction follows the 1D component choice.
        Some(dimension_of(depth - 1, Stage::Bsdf) + 1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Camera with the first emitter position; each BSDF direction with the next bounce's
    /// emitter position; nothing else.
    #[test]
    fn pairs_light_positions_with_what_came_before() {
        assert_eq!(paired_dimension(3), Some(0));
        assert_eq!(paired_dimension(10), Some(6));
        assert_eq!(paired_dimension(17), Some(13));
        let paired = (0..200).filter(|&d| paired_dimension(d).is_some()).count();
        assert_eq!(paired, (200u32 - 3).div_ceil(7) as usize);
        for d in 0..200 {
            if let Some(p) = paired_dimension(d) {
                assert!(p < d && paired_dimension(p).is_none());
            }
        }
    }

    /// The lens's 2D draw is not paired with anything, and no bounce before a depth of
    /// 10^8 reads it.
    #[test]
    fn lens_dimension_is_apart() {
        assert_eq!(paired_dimension(LENS_DIMENSION), None);
        assert!(dimension_of(100_000_000, Stage::Roulette) < LENS_DIMENSION);
    }

    /// Stages of consecutive bounces tile the dimensions after the camera's without overlap.
    #[test]
    fn stages_tile_the_dimensions() {
        let mut next = CAMERA_DIMENSIONS;
        for depth in 0..10 {
            for (stage, width) in [(Stage::Light, 3), (Stage::Bsdf, 3), (Stage::Roulette, 1)] {
                assert_eq!(dimension_of(depth, stage), next);
                next += width;
            }
        }
    }
}
