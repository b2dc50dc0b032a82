//! The `<medium>` and `<phase>` plugins and the scene's media: each medium built once however
//! often it is referenced, the media on each shape's sides, and the camera's medium.
//!
//! - `phase`: the `<phase>` plugins ([`PHASES`]): `isotropic`, `hg`;
//! - `homogeneous`: the `<medium>` plugins ([`MEDIA`]): `homogeneous`;
//! - `interfaces`: a shape's `interior` / `exterior` and a sensor's medium, read into indices.
pub(crate) mod homogeneous;
pub(crate) mod interfaces;
pub(crate) mod phase;

pub use homogeneous::MEDIA;
pub use phase::PHASES;

#[cfg(test)]
mod tests {
    use crate::xml::Kind;

    #[test]
    fn declarations_match_what_the_builders_read() {
        crate::plugin::check::check_family(
            super::MEDIA,
            Kind::Medium,
            super::homogeneous::build_medium,
            |_| String::new(),
            &[],
        );
        crate::plugin::check::check_family(
            super::PHASES,
            Kind::Phase,
            super::phase::build_phase,
            |_| String::new(),
            &[],
        );
    }
}
