//! The `<sampler>` plugins ([`SAMPLERS`]): `independent` and Tessera's `zsobol` (Owen-scrambled
//! Sobol in Morton order, see `tessera_core::sampling::ZSobolSampler`; what a file that names
//! no sampler renders with, see `LoadedScene::sampler_named`).
//! Mitsuba's stratified low-discrepancy samplers (`ldsampler`, `stratified`, `multijitter`,
//! `orthogonal`) render with `zsobol`, the closest Tessera has (not Mitsuba's exact points), and
//! `correlated` with `independent`; a warning says so.
use crate::plugin::{self, Param, Plugin, Range};
use crate::util::Result;
use crate::xml::Object;
use tessera_core::sampling::SamplerKind;

/// What a `<sampler>` gives: `(sample_count, seed, which sampler)`.
pub(crate) type SamplerSettings = (u64, u64, SamplerKind);

/// A sampler plugin; the builder may add warnings.
pub(crate) type SamplerPlugin = Plugin<fn(&Object, &mut Vec<String>) -> Result<SamplerSettings>>;

/// Every `<sampler type=...>` Tessera knows.
pub static SAMPLERS: &[SamplerPlugin] = &[
    INDEPENDENT,
    ZSOBOL,
    to_zsobol("ldsampler"),
    to_zsobol("stratified"),
    to_zsobol("multijitter"),
    to_zsobol("orthogonal"),
    to_independent("correlated"),
];

/// Reads a sampler and reports unused parameters.
pub(crate) fn build_sampler(obj: &Object, warnings: &mut Vec<String>) -> Result<SamplerSettings> {
    let plugin = plugin::find(SAMPLERS, "sampler", obj)?;
    let s = (plugin.build)(obj, warnings)?;
    plugin.check_unused(obj)?;
    Ok(s)
}

const SAMPLE_COUNT: Param = Param::integer(
    "sample_count",
    4,
    Range::Note("between 1 and 2^40"),
    "samples per pixel",
);
const SEED: Param = Param::integer("seed", 0, Range::Any, "seed of every random stream");
const JITTER: Param = Param::boolean(
    "jitter",
    true,
    "Mitsuba's jitter within strata; has no effect (zsobol's points are scrambled)",
)
.ignored();

/// The settings every sampler reads, for the sampler `name`.
fn settings(obj: &Object, name: &str) -> Result<SamplerSettings> {
    let spp = SAMPLE_COUNT.read_i64_where(obj, |n| (1..=1 << 40).contains(&n))?;
    let seed = SEED.read_i64(obj)?;
    let kind = SamplerKind::from_name(name, spp as u64).unwrap_or_default();
    Ok((spp as u64, seed as u64, kind))
}

/// `independent`.
pub(crate) const INDEPENDENT: SamplerPlugin = Plugin {
    name: "independent",
    aliases: &[],
    doc: "Independent uniform random numbers: a PCG32 stream per pixel and sample.",
    params: &[SAMPLE_COUNT, SEED],
    nested: "",
    build: |obj, _| settings(obj, "independent"),
};

/// `zsobol`.
pub(crate) const ZSOBOL: SamplerPlugin = Plugin {
    name: "zsobol",
    aliases: &[],
    doc: "Tessera's low-discrepancy sampler: Owen-scrambled Sobol points in Morton order \
          (pbrt-v4's ZSobol); less noise than independent at equal samples.",
    params: &[SAMPLE_COUNT, SEED],
    nested: "",
    build: |obj, _| settings(obj, "zsobol"),
};

/// A Mitsuba sampler that renders with Tessera's `zsobol` (and a warning).
const fn to_zsobol(name: &'static str) -> SamplerPlugin {
    Plugin {
        name,
        aliases: &[],
        doc:
            "A Mitsuba 3 sampler that Tessera renders with its zsobol sampler (a warning says so).",
        params: &[SAMPLE_COUNT, SEED, JITTER],
        nested: "",
        build: |obj, warnings| substituted(obj, warnings, "zsobol"),
    }
}

/// A Mitsuba sampler that renders with Tessera's `independent` (and a warning).
const fn to_independent(name: &'static str) -> SamplerPlugin {
    Plugin {
        name,
        aliases: &[],
        doc: "A Mitsuba 3 sampler that Tessera renders with its independent sampler (a warning \
              says so).",
        params: &[SAMPLE_COUNT, SEED, JITTER],
        nested: "",
        build: |obj, warnings| substituted(obj, warnings, "independent"),
    }
}

fn substituted(obj: &Object, warnings: &mut Vec<String>, with: &str) -> Result<SamplerSettings> {
    warnings.push(format!(
        "{}: sampler \"{}\" renders with Tessera's {with} sampler",
        obj.loc, obj.plugin
    ));
    JITTER.read_bool(obj)?;
    settings(obj, with)
}

#[cfg(test)]
mod tests {
    #[test]
    fn declarations_match_what_the_builders_read() {
        crate::plugin::check::check_family(
            super::SAMPLERS,
            crate::xml::Kind::Sampler,
            |obj| super::build_sampler(obj, &mut Vec::new()),
            |_| String::new(),
            &[],
        );
    }
}
