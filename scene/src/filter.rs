//! The `<rfilter>` plugins ([`FILTERS`]): the pixel reconstruction filters `gaussian` (the
//! default), `box`, `tent`, and the filters with negative lobes `mitchell`, `catmullrom` and
//! `lanczos`. Their conventions are in `tessera_core::camera::filter`.
use crate::plugin::{self, Param, Plugin, Range};
use crate::util::Result;
use crate::xml::Object;
use tessera_core::camera::{Filter, GaussianFilter, LanczosFilter, MitchellFilter, TentFilter};

/// A reconstruction filter plugin.
pub(crate) type FilterPlugin = Plugin<fn(&Object) -> Result<Filter>>;

/// Every `<rfilter type=...>` Tessera knows.
pub static FILTERS: &[FilterPlugin] = &[GAUSSIAN, BOX, TENT, MITCHELL, CATMULLROM, LANCZOS];

/// Builds a filter and reports unused parameters.
pub(crate) fn build_filter(obj: &Object) -> Result<Filter> {
    let plugin = plugin::find(FILTERS, "rfilter", obj)?;
    let f = (plugin.build)(obj)?;
    plugin.check_unused(obj)?;
    Ok(f)
}

/// `box`.
pub(crate) const BOX: FilterPlugin = Plugin {
    name: "box",
    aliases: &[],
    doc: "Each sample counts for the pixel it falls in (radius 0.5 pixel).",
    params: &[],
    nested: "",
    build: |_| Ok(Filter::Box),
};

const STDDEV: Param = Param::float(
    "stddev",
    0.5,
    Range::open_closed(0.0, 64.0),
    "standard deviation in pixels (the support is 4 of them)",
);

/// `gaussian`.
pub(crate) const GAUSSIAN: FilterPlugin = Plugin {
    name: "gaussian",
    aliases: &[],
    doc: "A truncated Gaussian, Mitsuba 3's default. Like every filter but `box`, it is applied \
          as Mitsuba 3 applies it: each sample, placed uniformly in its pixel, is added with the \
          filter's weight (tabulated in 31 steps, as Mitsuba does) to every pixel within the \
          radius, and a pixel is its weighted sum over its summed weight. `--filter-sampling` \
          applies it by importance sampling instead (pbrt-v4's way), as it does any filter \
          reaching further than 4.5 pixels.",
    params: &[STDDEV],
    nested: "",
    build: |obj| Ok(Filter::Gaussian(GaussianFilter::new(STDDEV.read_f32(obj)?))),
};

const RADIUS: Param = Param::float(
    "radius",
    1.0,
    Range::open_closed(0.0, 64.0),
    "half width of the tent in pixels",
);

/// `tent`.
pub(crate) const TENT: FilterPlugin = Plugin {
    name: "tent",
    aliases: &[],
    doc: "A triangle, max(0, 1 - |x| / radius) along each axis: no ringing, less aliasing than \
          box. Applied as `gaussian` is.",
    params: &[RADIUS],
    nested: "",
    build: |obj| Ok(Filter::Tent(TentFilter::new(RADIUS.read_f32(obj)?))),
};

const B: Param = Param::float(
    "B",
    1.0 / 3.0,
    Range::Any,
    "the B parameter of Mitchell and Netravali's paper (blurring)",
);
const C: Param = Param::float(
    "C",
    1.0 / 3.0,
    Range::Any,
    "the C parameter of Mitchell and Netravali's paper (ringing)",
);

/// `mitchell`.
pub(crate) const MITCHELL: FilterPlugin = Plugin {
    name: "mitchell",
    aliases: &[],
    doc: "The Mitchell-Netravali cubic, radius 2 pixels along each axis: a compromise between \
          sharpness and ringing. Applied as `gaussian` is (negative weights included); with \
          `--filter-sampling`, sampled proportionally to the filter's absolute value, each \
          sample weighted by its sign times the ratio of the absolute to the signed integral, \
          which is the same image without the splatted quotient's bias at low sample counts.",
    params: &[B, C],
    nested: "",
    build: |obj| {
        let (b, c) = (B.read_f32(obj)?, C.read_f32(obj)?);
        MitchellFilter::new(b, c)
            .map(Filter::Mitchell)
            .ok_or_else(|| {
                B.out_of_range(obj, "such that with C the filter's integral is positive", b)
            })
    },
};

/// `catmullrom`.
pub(crate) const CATMULLROM: FilterPlugin = Plugin {
    name: "catmullrom",
    aliases: &[],
    doc: "The Catmull-Rom spline, the Mitchell-Netravali cubic with B = 0 and C = 1/2: sharper \
          than `mitchell`, with more ringing. Applied as `mitchell` is.",
    params: &[],
    nested: "",
    build: |_| Ok(Filter::Mitchell(MitchellFilter::catmull_rom())),
};

const LOBES: Param = Param::integer(
    "lobes",
    3,
    Range::closed(1.0, 64.0),
    "number of lobes on each side, which is also the radius in pixels",
);

/// `lanczos`.
pub(crate) const LANCZOS: FilterPlugin = Plugin {
    name: "lanczos",
    aliases: &[],
    doc: "The Lanczos-windowed sinc, sinc(x) sinc(x / lobes) along each axis: sharp, with strong \
          ringing at discontinuities. Applied as `mitchell` is.",
    params: &[LOBES],
    nested: "",
    build: |obj| {
        let lobes = LOBES.read_i64(obj)?;
        LanczosFilter::new(lobes as u32)
            .map(Filter::Lanczos)
            .ok_or_else(|| {
                LOBES.out_of_range(obj, "few enough for 31 steps to resolve them", lobes)
            })
    },
};

#[cfg(test)]
mod tests {
    /// The load error of a scene whose film has the filter `rfilter` (on line 3).
    fn error_of(rfilter: &str) -> String {
        let xml = format!(
            "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><film type=\"hdrfilm\">\n\
             {rfilter}\n</film></sensor></scene>"
        );
        match crate::load_scene_str(&xml, std::path::Path::new("/nowhere/f.xml"), &[]) {
            Ok(_) => panic!("{rfilter}: loaded"),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn bad_filter_parameters_are_located_errors() {
        let cases = [
            (
                r#"<rfilter type="lanczos"><integer name="lobes" value="0"/></rfilter>"#,
                "f.xml:3:25: \"lobes\" of rfilter \"lanczos\" must be in [1, 64], found 0",
            ),
            // B = 100 makes the tabulated cubic's integral negative (it falls by 1/6 per unit B
            // from 8.25 at B = 0, in steps).
            (
                r#"<rfilter type="mitchell"><float name="B" value="100"/></rfilter>"#,
                "f.xml:3:26: \"B\" of rfilter \"mitchell\" must be such that with C the \
                 filter's integral is positive, found 100",
            ),
            (
                r#"<rfilter type="mitchell"><float name="b" value="0.5"/></rfilter>"#,
                "unused parameter \"b\"",
            ),
        ];
        for (rfilter, want) in cases {
            let e = error_of(rfilter);
            assert!(e.contains(want), "{rfilter}: {e}");
            assert!(!e.contains('\n'), "{e}");
        }
        // Control: the same filters with good values load.
        for good in [
            r#"<rfilter type="lanczos"><integer name="lobes" value="2"/></rfilter>"#,
            r#"<rfilter type="mitchell"><float name="B" value="40"/></rfilter>"#,
        ] {
            let xml = format!(
                "<scene version=\"3.0.0\"><sensor type=\"perspective\"><film \
                 type=\"hdrfilm\">{good}</film></sensor></scene>"
            );
            crate::load_scene_str(&xml, std::path::Path::new("/nowhere/f.xml"), &[])
                .unwrap_or_else(|e| panic!("{good}: {e}"));
        }
    }

    #[test]
    fn declarations_match_what_the_builders_read() {
        crate::plugin::check::check_family(
            super::FILTERS,
            crate::xml::Kind::RFilter,
            super::build_filter,
            |_| String::new(),
            &[],
        );
    }
}
