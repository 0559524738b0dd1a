//! `Intrinsic`: the WGSL built-in functions and constructors the language
//! exposes directly, their spellings and arities.

use super::*;

/// WGSL built-in functions and constructors the language exposes directly.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
pub enum Intrinsic {
    /// `vec2(..)`, `vec3(..)`, `vec4(..)`: components flattened, or one scalar splatted.
    Construct(u32),
    /// Component-wise, same type in and out: abs, floor, sin, ...
    Map(&'static str),
    /// Same-typed operands, same type out: min, max, pow, step, atan2.
    Map2(&'static str),
    /// clamp(x, lo, hi), smoothstep(lo, hi, x), mix(a, b, t).
    Map3(&'static str),
    /// Vector to scalar: length.
    Length,
    Dot,
    Distance,
    Normalize,
    Cross,
    /// `project(p)`: world point → (screen u, screen v, NDC depth) in this eye.
    Project,
    /// `project_other_eye(p)`: the same in the other eye of a stereo frame.
    ProjectOtherEye,
    /// `project_previous(p)`: the same with the previous frame's camera.
    ProjectPrevious,
    /// `ramp(g, t)` of a gradient kept live: the colour of gradient param
    /// `g` (slots of the style block) at `t`, the one argument. Made by the
    /// resolver only (a folded gradient's `ramp` is a chain of `mix`), so
    /// not in [`Intrinsic::TABLE`].
    Ramp(ParamId),
}

impl Intrinsic {
    /// Every intrinsic a style can call, by spelling: the single source of
    /// both [`Intrinsic::lookup`] and [`Intrinsic::name`]'s spellings (a unit
    /// test checks that each entry's `name()` is its spelling).
    pub const TABLE: &'static [(&'static str, Intrinsic)] = &[
        ("vec2", Intrinsic::Construct(2)),
        ("vec3", Intrinsic::Construct(3)),
        ("vec4", Intrinsic::Construct(4)),
        ("abs", Intrinsic::Map("abs")),
        ("floor", Intrinsic::Map("floor")),
        ("ceil", Intrinsic::Map("ceil")),
        ("fract", Intrinsic::Map("fract")),
        ("round", Intrinsic::Map("round")),
        ("sqrt", Intrinsic::Map("sqrt")),
        ("exp", Intrinsic::Map("exp")),
        ("exp2", Intrinsic::Map("exp2")),
        ("log", Intrinsic::Map("log")),
        ("log2", Intrinsic::Map("log2")),
        ("sin", Intrinsic::Map("sin")),
        ("cos", Intrinsic::Map("cos")),
        ("tan", Intrinsic::Map("tan")),
        ("asin", Intrinsic::Map("asin")),
        ("acos", Intrinsic::Map("acos")),
        ("atan", Intrinsic::Map("atan")),
        ("sign", Intrinsic::Map("sign")),
        ("saturate", Intrinsic::Map("saturate")),
        ("min", Intrinsic::Map2("min")),
        ("max", Intrinsic::Map2("max")),
        ("pow", Intrinsic::Map2("pow")),
        ("step", Intrinsic::Map2("step")),
        ("atan2", Intrinsic::Map2("atan2")),
        ("clamp", Intrinsic::Map3("clamp")),
        ("smoothstep", Intrinsic::Map3("smoothstep")),
        ("mix", Intrinsic::Map3("mix")),
        ("length", Intrinsic::Length),
        ("dot", Intrinsic::Dot),
        ("distance", Intrinsic::Distance),
        ("normalize", Intrinsic::Normalize),
        ("cross", Intrinsic::Cross),
        ("project", Intrinsic::Project),
        ("project_other_eye", Intrinsic::ProjectOtherEye),
        ("project_previous", Intrinsic::ProjectPrevious),
    ];

    pub fn lookup(name: &str) -> Option<Intrinsic> {
        Self::TABLE.iter().find(|(n, _)| *n == name).map(|(_, i)| *i)
    }

    /// Every spelling, in table order (for "did you mean").
    pub fn names() -> impl Iterator<Item = &'static str> {
        Self::TABLE.iter().map(|(n, _)| *n)
    }

    pub fn name(self) -> &'static str {
        match self {
            Intrinsic::Construct(2) => "vec2",
            Intrinsic::Construct(3) => "vec3",
            Intrinsic::Construct(_) => "vec4",
            Intrinsic::Map(n) | Intrinsic::Map2(n) | Intrinsic::Map3(n) => n,
            Intrinsic::Length => "length",
            Intrinsic::Dot => "dot",
            Intrinsic::Distance => "distance",
            Intrinsic::Normalize => "normalize",
            Intrinsic::Cross => "cross",
            Intrinsic::Project => "project",
            Intrinsic::ProjectOtherEye => "project_other_eye",
            Intrinsic::ProjectPrevious => "project_previous",
            Intrinsic::Ramp(_) => "ramp",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_intrinsic_spelling_round_trips() {
        for (spelling, i) in Intrinsic::TABLE {
            assert_eq!(Intrinsic::lookup(spelling), Some(*i));
            assert_eq!(i.name(), *spelling, "{i:?} is spelled `{spelling}` in the table");
        }
        assert_eq!(Intrinsic::lookup("no_such_function"), None);
    }
}
