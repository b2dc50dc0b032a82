//! The `<rfilter>` plugins ([`FILTERS`]): the pixel reconstruction filters `gaussian` (the
//! default), `box` and `tent`. Their conventions are in `tessera_core::camera::filter`.
use crate::plugin::{self, Param, Plugin, Range};
use crate::util::Result;
use crate::xml::Object;
use tessera_core::camera::{Filter, GaussianFilter, TentFilter};

/// A reconstruction filter plugin.
pub type FilterPlugin = Plugin<fn(&Object) -> Result<Filter>>;

/// Every `<rfilter type=...>` Tessera knows.
pub static FILTERS: &[FilterPlugin] = &[GAUSSIAN, BOX, TENT];

/// Builds a filter and reports unused parameters.
pub fn build_filter(obj: &Object) -> Result<Filter> {
    let plugin = plugin::find(FILTERS, "rfilter", obj)?;
    let f = (plugin.build)(obj)?;
    plugin.check_unused(obj)?;
    Ok(f)
}

/// `box`.
pub const BOX: FilterPlugin = Plugin {
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
pub const GAUSSIAN: FilterPlugin = Plugin {
    name: "gaussian",
    aliases: &[],
    doc: "A truncated Gaussian, as Mitsuba 3's default; sampled exactly, so every sample weighs 1.",
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
pub const TENT: FilterPlugin = Plugin {
    name: "tent",
    aliases: &[],
    doc: "A triangle, max(0, 1 - |x| / radius) along each axis: no ringing, less aliasing than \
          box.",
    params: &[RADIUS],
    nested: "",
    build: |obj| Ok(Filter::Tent(TentFilter::new(RADIUS.read_f32(obj)?))),
};

#[cfg(test)]
mod tests {
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
