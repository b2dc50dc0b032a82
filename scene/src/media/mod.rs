//! The `<medium>` and `<phase>` plugins and the scene's media: each medium built once however
//! often it is referenced, the media on each shape's sides, and the camera's medium.
//!
//! - `phase`: the `<phase>` plugins ([`PHASES`]): `isotropic`, `hg`;
//! - `table`: the `<medium>` plugins ([`MEDIA`]): `homogeneous` and `heterogeneous`, each in its
//!   own file, with what they share in `common`;
//! - `volumes`: the `<volume>` plugins ([`VOLUMES`]): `gridvolume`, `constvolume`, read from
//!   `.vol` files by `vol_file`;
//! - `interfaces`: a shape's `interior` / `exterior` and a sensor's medium, read into indices.
pub(crate) mod common;
pub(crate) mod heterogeneous;
pub(crate) mod homogeneous;
pub(crate) mod interfaces;
pub(crate) mod phase;
pub(crate) mod table;
pub(crate) mod vol_file;
pub(crate) mod volumes;

pub use phase::PHASES;
pub use table::MEDIA;
pub(crate) use volumes::build_volume;
pub use volumes::VOLUMES;

#[cfg(test)]
mod tests {
    use crate::xml::Kind;

    #[test]
    fn declarations_match_what_the_builders_read() {
        crate::plugin::check::check_family(
            super::MEDIA,
            Kind::Medium,
            super::table::build_medium,
            |_| String::new(),
            &[],
        );
        crate::plugin::check::check_family(
            super::VOLUMES,
            Kind::Volume,
            super::volumes::build_volume,
            |name| {
                if name == "gridvolume" {
                    format!(
                        "<string name=\"filename\" value=\"{}\"/>",
                        concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/media/smoke.vol")
                    )
                } else {
                    String::new()
                }
            },
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
