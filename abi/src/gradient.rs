//! A `gradient` parameter kept live (`--keep-params`): the layout of its
//! slots in the style uniform block, which the compiler declares, the
//! runner fills and [`crate::param_value`] packs a `--set`, studio or
//! host value into (docs/decisions/0040-a-gradient-is-a-constant-ramp.md).
//!
//! [`GRADIENT_SLOTS`] `vec4<f32>` slots, a WGSL `array<vec4<f32>, 21>`
//! (16-byte stride, so std140 and WGSL's uniform layout agree):
//!
//! - slot 0: `(stop count, 1 if constant else 0, 0, 0)`;
//! - slots 1..=16: the stops' straight-alpha colours, unused ones zero;
//! - slots 17..=20: the positions, four to a slot (stop `i` at slot
//!   `17 + i / 4`, component `i % 4`), unused ones zero.
//!
//! A parameter's value ([`crate::manifest::ParamManifest::default`]) is
//! these slots' 84 components in order.

/// The most stops a gradient has (E0404 in a declaration, E0206 in a value).
pub const MAX_STOPS: usize = 16;
/// The first slot of the colours.
pub const COLOUR_SLOT: usize = 1;
/// The first slot of the positions.
pub const POSITION_SLOT: usize = COLOUR_SLOT + MAX_STOPS;
/// The slots a gradient takes in the style uniform block.
pub const GRADIENT_SLOTS: usize = POSITION_SLOT + MAX_STOPS / 4;
/// The declared type of a gradient parameter, as the manifest writes it.
pub const GRADIENT_TYPE: &str = "gradient";

/// Stops of position (0..1, in order) and straight-alpha colour.
pub type Stops = Vec<(f64, [f64; 4])>;

/// The slots a parameter of declared type `ty` takes: [`GRADIENT_SLOTS`]
/// for a gradient, one `vec4` for every other type.
pub fn slots_of(ty: &str) -> usize {
    if ty == GRADIENT_TYPE {
        GRADIENT_SLOTS
    } else {
        1
    }
}

/// Why stops are no gradient: the label under the value (a position
/// outside 0..1, positions out of order, no stops or too many), or `None`.
pub fn check_stops(stops: &[(f64, [f64; 4])]) -> Option<String> {
    if stops.is_empty() || stops.len() > MAX_STOPS {
        return Some(format!("{} stops: a gradient has 1 to {MAX_STOPS} stops", stops.len()));
    }
    if let Some((p, _)) = stops.iter().find(|(p, _)| !(0.0..=1.0).contains(p)) {
        return Some(format!("the position {p} is outside 0..1"));
    }
    if let Some(w) = stops.windows(2).find(|w| w[1].0 < w[0].0) {
        return Some(format!(
            "the position {} comes after {}: positions must not decrease",
            w[1].0, w[0].0
        ));
    }
    None
}

/// The 84 components of the slots of `stops` (checked by [`check_stops`]).
pub fn pack(stops: &[(f64, [f64; 4])], constant: bool) -> Vec<f64> {
    let mut v = vec![0.0; GRADIENT_SLOTS * 4];
    v[0] = stops.len() as f64;
    v[1] = if constant { 1.0 } else { 0.0 };
    for (i, (p, c)) in stops.iter().take(MAX_STOPS).enumerate() {
        v[(COLOUR_SLOT + i) * 4..(COLOUR_SLOT + i + 1) * 4].copy_from_slice(c);
        v[POSITION_SLOT * 4 + i] = *p;
    }
    v
}

/// The stops and mode packed in `value` by [`pack`]; `None` if it is not
/// the slots of a gradient.
pub fn unpack(value: &[f64]) -> Option<(Stops, bool)> {
    if value.len() != GRADIENT_SLOTS * 4 {
        return None;
    }
    let n = value[0];
    if !(1.0..=MAX_STOPS as f64).contains(&n) || n.fract() != 0.0 {
        return None;
    }
    let stops = (0..n as usize)
        .map(|i| {
            let c = &value[(COLOUR_SLOT + i) * 4..(COLOUR_SLOT + i + 1) * 4];
            (value[POSITION_SLOT * 4 + i], [c[0], c[1], c[2], c[3]])
        })
        .collect();
    Some((stops, value[1] > 0.5))
}

/// The colour of the ramp at `t`, in f64: the rule `ramp(g, t)` follows,
/// folded or live (a reference for tests). `r = c0`, then per next stop
/// `r = mix(r, c_i, f)` with `f = step(p_i, t)` for a constant ramp or a
/// hard edge (two stops at one position), else `saturate((t - p_{i-1}) /
/// (p_i - p_{i-1}))`.
pub fn ramp(stops: &[(f64, [f64; 4])], constant: bool, t: f64) -> [f64; 4] {
    let mut r = stops[0].1;
    for w in stops.windows(2) {
        let ((p0, _), (p1, c1)) = (w[0], w[1]);
        let f = if constant || p1 == p0 {
            if t < p1 {
                0.0
            } else {
                1.0
            }
        } else {
            ((t - p0) / (p1 - p0)).clamp(0.0, 1.0)
        };
        for k in 0..4 {
            r[k] += (c1[k] - r[k]) * f;
        }
    }
    r
}

/// A colour as the language writes it: `#rrggbb`, or `#rrggbbaa` when not opaque.
pub fn colour_text(c: &[f64; 4]) -> String {
    let b = |v: f64| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    let mut s = format!("#{:02x}{:02x}{:02x}", b(c[0]), b(c[1]), b(c[2]));
    if c[3] < 1.0 {
        s.push_str(&format!("{:02x}", b(c[3])));
    }
    s
}

/// A number as short as it reads back exactly.
fn position_text(p: f64) -> String {
    format!("{p}")
}

/// The stops as `--set` takes them: `0:#000000, 0.5:#ff8800, 1:#ffffff`.
pub fn stops_text(stops: &[(f64, [f64; 4])]) -> String {
    stops
        .iter()
        .map(|(p, c)| format!("{}:{}", position_text(*p), colour_text(c)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The gradient as a style file writes it: `gradient(stop(0.0, #000000),
/// stop(1.0, #ffffff))`, with `mode: constant` when constant.
pub fn declaration_text(stops: &[(f64, [f64; 4])], constant: bool) -> String {
    let mut parts: Vec<String> = stops
        .iter()
        .map(|(p, c)| {
            let mut pos = position_text(*p);
            if !pos.contains('.') {
                pos.push_str(".0");
            }
            format!("stop({pos}, {})", colour_text(c))
        })
        .collect();
    if constant {
        parts.push("mode: constant".into());
    }
    format!("gradient({})", parts.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packing_round_trips_and_the_layout_is_21_slots() {
        assert_eq!(GRADIENT_SLOTS, 21);
        let stops = vec![
            (0.0, [0.0, 0.0, 0.0, 1.0]),
            (0.5, [1.0, 0.5, 0.0, 1.0]),
            (1.0, [1.0; 4]),
        ];
        let v = pack(&stops, true);
        assert_eq!(v.len(), 84);
        assert_eq!(&v[0..2], &[3.0, 1.0]);
        assert_eq!(&v[8..12], &[1.0, 0.5, 0.0, 1.0], "stop 1's colour is slot 2");
        assert_eq!(&v[68..71], &[0.0, 0.5, 1.0], "positions from slot 17");
        assert_eq!(unpack(&v), Some((stops, true)));
        assert_eq!(unpack(&v[..80]), None);
    }

    #[test]
    fn a_value_types_into_the_slots_in_the_declared_mode_or_is_e0206() {
        use crate::param_literal::{read_literal, SettingOrigin};
        use crate::param_value::{format_literal, type_value, ParamShape, ValueKind};
        let declared = vec![(0.0, [0.0, 0.0, 0.0, 1.0]), (1.0, [1.0; 4])];
        let shape = ParamShape {
            name: "g".into(),
            ty: GRADIENT_TYPE.into(),
            kind: ValueKind::of(GRADIENT_TYPE),
            components: 4,
            range: None,
            variants: Vec::new(),
            per_object: false,
            default: pack(&declared, true),
            default_percent_of_height: false,
        };
        let typed = |text: &str| type_value(&shape, &read_literal(text), text, &SettingOrigin::Host);
        let text = "0:#ff0000, 0.5:#00ff0080, 1:#0000ff";
        let v = typed(text).expect("stops").value;
        let (stops, constant) = unpack(&v).expect("slots");
        assert!(constant, "the declared mode stays");
        assert_eq!(stops[1], (0.5, [0.0, 1.0, 0.0, 128.0 / 255.0]));
        assert_eq!(
            format_literal(&shape, &v).as_deref(),
            Some(text),
            "written back as typed"
        );
        for bad in [
            "0.8:#000000, 0.2:#ffffff",
            "0:#000000, 1.5:#ffffff",
            "#ff0000",
            "0:#zz0000",
            "3",
        ] {
            let r = typed(bad).expect_err(bad);
            assert_eq!(r.code, "E0206", "{bad}: {r:?}");
            assert!(r.help.contains("position:#colour"), "{bad}: {r:?}");
        }
    }

    #[test]
    fn bad_stops_are_named() {
        assert!(check_stops(&[]).unwrap().contains("0 stops"));
        assert!(check_stops(&[(1.5, [0.0; 4])]).unwrap().contains("outside 0..1"));
        assert!(check_stops(&[(0.6, [0.0; 4]), (0.2, [0.0; 4])])
            .unwrap()
            .contains("must not decrease"));
        assert_eq!(check_stops(&[(0.5, [0.0; 4]), (0.5, [1.0; 4])]), None, "a hard edge");
    }

    #[test]
    fn the_ramp_mixes_within_a_segment_and_steps_at_a_hard_edge() {
        let stops = vec![(0.25, [0.0; 4]), (0.75, [1.0; 4]), (0.75, [0.5; 4])];
        assert_eq!(ramp(&stops, false, 0.0), [0.0; 4]);
        assert_eq!(ramp(&stops, false, 0.5), [0.5; 4]);
        assert_eq!(ramp(&stops, false, 0.75), [0.5; 4]);
        assert_eq!(ramp(&stops, true, 0.5), [0.0; 4]);
        assert_eq!(
            declaration_text(&stops[..2], true),
            "gradient(stop(0.25, #00000000), stop(0.75, #ffffff), mode: constant)"
        );
        assert_eq!(stops_text(&stops[..2]), "0.25:#00000000, 0.75:#ffffff");
    }
}
