//! [`Unit`]: the physical dimension of a quantity (px, m, s, Hz, radians),
//! which the stdlib's signatures, the typechecker and the typing of
//! parameter values share.

use serde::Serialize;

/// The physical dimension of a quantity, in its canonical unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
pub enum Unit {
    /// A plain number.
    None,
    /// Screen pixels (a `%` of the image height converts to px at run time).
    Px,
    /// Metres (`mm` converts at compile time).
    Meters,
    Seconds,
    Hertz,
    /// Angles: written in `deg`, passed in radians.
    Radians,
}

impl Unit {
    pub fn name(self) -> &'static str {
        match self {
            Unit::None => "a plain number",
            Unit::Px => "px",
            Unit::Meters => "m",
            Unit::Seconds => "s",
            Unit::Hertz => "Hz",
            Unit::Radians => "deg",
        }
    }
}
