//! Stepping a style parameter from the keyboard: `[` and `]` choose one of
//! the style's scalar parameters (numbers, ints, booleans, enums, values
//! with a unit), `-` and `=` step it. A step is a twentieth of the
//! declared range (one for an int or enum, a flip for a boolean), clamped
//! to the range; the new value is written as `--set` takes it and handed
//! to the runtime's `set_param`, which types and range-checks it.
//!
//! Values are kept here (canonical units, as the manifest gives them),
//! starting at the style's defaults, so a step needs no read back.

use npr_abi::manifest::{ParamBinding, ParamManifest};

/// Steps across a declared range.
const STEPS_PER_RANGE: f64 = 20.0;

#[derive(Debug, Clone, PartialEq)]
enum Kind {
    /// A number, in canonical units; `suffix` is what `--set` writes after
    /// it (`px`, `m`, `s`, `Hz`; radians are written in `deg`).
    Number {
        int: bool,
        suffix: &'static str,
    },
    Bool,
    Enum(Vec<String>),
}

#[derive(Debug, Clone, PartialEq)]
struct Steppable {
    name: String,
    kind: Kind,
    value: f64,
    range: Option<(f64, f64)>,
}

impl Steppable {
    fn of(p: &ParamManifest) -> Option<Steppable> {
        if p.binding == ParamBinding::PerObject || p.components != 1 || p.default.len() != 1 {
            return None;
        }
        let kind = if !p.enum_variants.is_empty() {
            Kind::Enum(p.enum_variants.clone())
        } else if p.ty == "bool" {
            Kind::Bool
        } else if p.ty == "int" || p.ty == "float" || !p.unit.is_empty() {
            let suffix = match p.unit.as_str() {
                "px" => "px",
                "m" => "m",
                "s" => "s",
                "Hz" => "Hz",
                "deg" => "deg",
                _ => "",
            };
            Kind::Number {
                int: p.ty == "int",
                suffix,
            }
        } else {
            return None;
        };
        Some(Steppable {
            name: p.name.clone(),
            kind,
            value: p.default[0],
            range: p.range,
        })
    }

    fn step(&mut self, direction: i32) {
        let dir = f64::from(direction.signum());
        self.value = match &self.kind {
            Kind::Bool => {
                if self.value != 0.0 {
                    0.0
                } else {
                    1.0
                }
            }
            Kind::Enum(variants) => (self.value + dir).clamp(0.0, (variants.len().max(1) - 1) as f64),
            Kind::Number { int, .. } => {
                let step = match self.range {
                    Some((lo, hi)) if hi > lo => (hi - lo) / STEPS_PER_RANGE,
                    _ if self.value != 0.0 => self.value.abs() / 10.0,
                    _ => 0.1,
                };
                let step = if *int { step.round().max(1.0) } else { step };
                let next = self.value + dir * step;
                let next = if *int { next.round() } else { next };
                match self.range {
                    Some((lo, hi)) => next.clamp(lo, hi),
                    None => next,
                }
            }
        };
    }

    /// The value as `--set` takes it.
    fn literal(&self) -> String {
        match &self.kind {
            Kind::Bool => (self.value != 0.0).to_string(),
            Kind::Enum(variants) => variants.get(self.value as usize).cloned().unwrap_or_default(),
            Kind::Number { int: true, .. } => format!("{}", self.value.round() as i64),
            Kind::Number { suffix: "deg", .. } => format!("{}deg", trim(self.value.to_degrees())),
            Kind::Number { suffix, .. } => format!("{}{suffix}", trim(self.value)),
        }
    }
}

/// A float written short: six significant decimals at most.
fn trim(v: f64) -> String {
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}

/// The style's steppable parameters and which one the keys step.
#[derive(Debug, Clone, Default)]
pub struct Stepper {
    params: Vec<Steppable>,
    chosen: usize,
    /// Names of the parameters stepped since the style's defaults.
    changed: Vec<String>,
}

impl Stepper {
    /// From the manifest's parameters, at their defaults (a `--set`
    /// value is the default of the style compiled with it).
    pub fn new(params: &[ParamManifest]) -> Stepper {
        Stepper {
            params: params.iter().filter_map(Steppable::of).collect(),
            chosen: 0,
            changed: Vec::new(),
        }
    }

    /// Keep the choice and the stepped values across a rebuild where the
    /// parameters still exist (a save of the style); `(name, literal)` of
    /// each value this stepper changed, to set on the new runtime.
    pub fn carry_over(&mut self, before: &Stepper) -> Vec<(String, String)> {
        let mut set = Vec::new();
        for p in &mut self.params {
            if let Some(old) = before.params.iter().find(|o| o.name == p.name && o.kind == p.kind) {
                let changed = before.changed.contains(&p.name);
                if changed {
                    p.value = old.value;
                    set.push((p.name.clone(), p.literal()));
                }
            }
        }
        self.changed = set.iter().map(|(n, _)| n.clone()).collect();
        if let Some(name) = before.params.get(before.chosen).map(|p| &p.name) {
            if let Some(i) = self.params.iter().position(|p| &p.name == name) {
                self.chosen = i;
            }
        }
        set
    }

    /// Choose the next (`+1`) or previous (`-1`) parameter, wrapping.
    pub fn choose(&mut self, direction: i32) {
        let n = self.params.len();
        if n > 0 {
            self.chosen = (self.chosen as i64 + i64::from(direction)).rem_euclid(n as i64) as usize;
        }
    }

    /// Step the chosen parameter; its name and new value as `--set` writes it.
    pub fn step(&mut self, direction: i32) -> Option<(String, String)> {
        let p = self.params.get_mut(self.chosen)?;
        p.step(direction);
        let name = p.name.clone();
        if !self.changed.contains(&name) {
            self.changed.push(name.clone());
        }
        Some((name, p.literal()))
    }

    /// `name = value` of the chosen parameter, for the title and the log.
    pub fn describe(&self) -> Option<String> {
        self.params
            .get(self.chosen)
            .map(|p| format!("{} = {}", p.name, p.literal()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn param(name: &str, ty: &str, unit: &str, default: f64, range: Option<(f64, f64)>) -> ParamManifest {
        ParamManifest {
            name: name.into(),
            doc: String::new(),
            ty: ty.into(),
            unit: unit.into(),
            components: 1,
            default: vec![default],
            default_percent_of_height: false,
            range,
            enum_variants: Vec::new(),
            keyframes: Vec::new(),
            interpolation: String::new(),
            binding: ParamBinding::Uniform,
            offset: Some(0),
        }
    }

    #[test]
    fn steps_are_a_twentieth_of_the_range_and_stop_at_its_ends() {
        let mut s = Stepper::new(&[param("rim", "float", "a plain number", 0.3, Some((0.0, 1.0)))]);
        assert_eq!(s.step(1), Some(("rim".into(), "0.35".into())));
        for _ in 0..40 {
            s.step(1);
        }
        assert_eq!(s.describe().as_deref(), Some("rim = 1"));
    }

    #[test]
    fn ints_step_by_whole_numbers_and_units_are_written_as_set_takes_them() {
        let mut s = Stepper::new(&[
            param("bands", "int", "a plain number", 3.0, Some((1.0, 8.0))),
            param("width", "px", "px", 2.0, None),
            param(
                "angle",
                "deg",
                "deg",
                std::f64::consts::FRAC_PI_2,
                Some((0.0, std::f64::consts::PI)),
            ),
        ]);
        assert_eq!(s.step(-1), Some(("bands".into(), "2".into())));
        s.choose(1);
        assert_eq!(s.step(1), Some(("width".into(), "2.2px".into())));
        s.choose(1);
        // π/20 above 90°: 99°.
        assert_eq!(s.step(1), Some(("angle".into(), "99deg".into())));
        s.choose(1);
        assert_eq!(s.describe().as_deref(), Some("bands = 2"), "wraps round");
    }

    #[test]
    fn booleans_flip_enums_walk_their_variants_and_others_are_not_steppable() {
        let mut flag = param("on", "bool", "a plain number", 1.0, None);
        flag.ty = "bool".into();
        let mut mode = param("mode", "enum(a|b|c)", "a plain number", 1.0, None);
        mode.enum_variants = vec!["a".into(), "b".into(), "c".into()];
        let mut colour = param("base", "color", "a plain number", 0.0, None);
        colour.components = 4;
        colour.default = vec![0.0; 4];
        let mut tint = param("tint", "float", "a plain number", 1.0, None);
        tint.binding = ParamBinding::PerObject;
        let mut s = Stepper::new(&[colour, tint, flag, mode]);
        assert_eq!(s.step(1), Some(("on".into(), "false".into())));
        s.choose(1);
        assert_eq!(s.step(1), Some(("mode".into(), "c".into())));
        assert_eq!(s.step(1), Some(("mode".into(), "c".into())));
        s.choose(1);
        assert_eq!(s.describe().as_deref(), Some("on = false"));
    }

    #[test]
    fn a_rebuild_keeps_the_choice_and_the_stepped_values() {
        let params = [
            param("a", "float", "a plain number", 0.0, Some((0.0, 1.0))),
            param("b", "float", "a plain number", 0.5, Some((0.0, 1.0))),
        ];
        let mut before = Stepper::new(&params);
        before.choose(1);
        before.step(1);
        let mut after = Stepper::new(&params);
        assert_eq!(after.carry_over(&before), vec![("b".to_string(), "0.55".to_string())]);
        assert_eq!(after.describe().as_deref(), Some("b = 0.55"));
    }
}
