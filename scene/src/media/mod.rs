//! The `<medium>` and `<phase>` plugins and the scene's media: each medium built once however
//! often it is referenced, the media on each shape's sides, and the camera's medium.
//!
//! - `phases`: the `<phase>` plugins ([`PHASES`]): `isotropic`, `hg`, `rayleigh` (in `phase`),
//!   `tabphase`, `blendphase` and `sggx` (in files of their own);
//! - `table`: the `<medium>` plugins ([`MEDIA`]): `homogeneous` and `heterogeneous`, each in its
//!   own file, with what they share in `common`;
//! - `volumes`: the `<volume>` plugins ([`VOLUMES`]): `gridvolume`, `constvolume`, read from
//!   `.vol` files by `vol_file`;
//! - `interfaces`: a shape's `interior` / `exterior` and a sensor's medium, read into indices.
pub(crate) mod blendphase;
pub(crate) mod common;
pub(crate) mod heterogeneous;
pub(crate) mod homogeneous;
pub(crate) mod interfaces;
pub(crate) mod phase;
pub(crate) mod phases;
pub(crate) mod sggx;
pub(crate) mod table;
pub(crate) mod tabphase;
pub(crate) mod vol_file;
pub(crate) mod volumes;

pub use phases::PHASES;
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
            super::phases::build_phase,
            |name| match name {
                "tabphase" => "<string name=\"values\" value=\"0.5, 1, 2\"/>".to_string(),
                "sggx" => format!(
                    "<volume type=\"gridvolume\" name=\"S\"><string name=\"filename\" \
                     value=\"{}\"/></volume>",
                    concat!(
                        env!("CARGO_MANIFEST_DIR"),
                        "/../scenes/media/flakes_uniform.vol"
                    )
                ),
                "blendphase" => "<float name=\"weight\" value=\"0.3\"/><phase type=\"isotropic\"/>\
                                 <phase type=\"rayleigh\"/>"
                    .to_string(),
                _ => String::new(),
            },
            &[],
        );
    }
}
