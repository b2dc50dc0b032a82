//! How the path tracer finds light ([`Strategy`]), and the numbers its loop is compiled for,
//! one loop per strategy so that the strategy's tests fold away in each.

/// How a path finds light.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Strategy {
    /// BSDF sampling only.
    Bsdf,
    /// Emitter sampling only (implicit hits only where it could not reach).
    Emitter,
    /// Emitter and BSDF sampling, each weighted 1/2.
    Half,
    /// Emitter and BSDF sampling combined by the power heuristic.
    Mis,
}

/// [`Strategy::Bsdf`]'s number, the loop's const parameter `ST` (see [`Strategy::of`]).
pub(super) const BSDF: u8 = 0;
/// [`Strategy::Emitter`]'s number.
pub(super) const EMITTER: u8 = 1;
/// [`Strategy::Half`]'s number.
pub(super) const HALF: u8 = 2;
/// [`Strategy::Mis`]'s number.
pub(super) const MIS: u8 = 3;

impl Strategy {
    /// The strategy numbered `n` (a const parameter of the path loop).
    #[inline(always)]
    pub(super) const fn of(n: u8) -> Strategy {
        match n {
            BSDF => Strategy::Bsdf,
            EMITTER => Strategy::Emitter,
            HALF => Strategy::Half,
            _ => Strategy::Mis,
        }
    }
}
