//! The axes of a plot: linear or logarithmic, and the range each shows.
//!
//! The rules, which `docs/PERFORMANCE.md` states too:
//! - a speed-against-error axis is logarithmic when every value on it is
//!   positive and they span at least a decade (max ≥ 10 × min); otherwise
//!   linear, so a zero error (an exact method) is still drawn;
//! - a cost-against-size chart is log–log whatever its values, and a value
//!   ≤ 0 on it (a cost the table prints as "–") is left out, not clamped,
//!   and the chart says how many were;
//! - values that are not finite are never drawn.

/// How an axis maps its values.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scale {
    Linear,
    Log,
}

/// The scale of a speed-against-error axis over `values` (see the module).
pub fn auto_scale(values: &[f64]) -> Scale {
    let finite: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    let (lo, hi) = min_max(&finite);
    if finite.is_empty() || lo <= 0.0 || hi < 10.0 * lo {
        Scale::Linear
    } else {
        Scale::Log
    }
}

/// Whether `v` can be placed on an axis of `scale`.
pub fn drawable(v: f64, scale: Scale) -> bool {
    v.is_finite() && (scale == Scale::Linear || v > 0.0)
}

/// The range an axis of `scale` shows for `values` (those it cannot place
/// are ignored), padded so no point sits on the frame:
/// - linear: 5% of the span on each side; a single value (or equal ones)
///   gets ±10% of itself, or ±1 at zero;
/// - log: 0.05 decades (at least 0.1) above the largest, and below the
///   smallest down to (just under) a power of ten, so every log axis has
///   at least one labelled decade even when its values span less than one.
///
/// No drawable value at all gives a range that still draws: 0..1 or 1..10.
pub fn range(values: &[f64], scale: Scale) -> (f64, f64) {
    let placed: Vec<f64> = values.iter().copied().filter(|v| drawable(*v, scale)).collect();
    if placed.is_empty() {
        return match scale {
            Scale::Linear => (0.0, 1.0),
            Scale::Log => (1.0, 10.0),
        };
    }
    let (lo, hi) = min_max(&placed);
    match scale {
        Scale::Linear => {
            let pad = if hi > lo {
                0.05 * (hi - lo)
            } else if lo != 0.0 {
                0.1 * lo.abs()
            } else {
                1.0
            };
            (lo - pad, hi + pad)
        }
        Scale::Log => {
            let (l, h) = (lo.log10(), hi.log10());
            let pad = (0.05 * (h - l)).max(0.1);
            // Just under the power of ten: plotters finds the first
            // labelled decade with ceil(log10(lo)), which rounding can
            // push a decade up when lo is the power itself.
            (10f64.powf((l - pad).floor()) * (1.0 - 1e-9), 10f64.powf(h + pad))
        }
    }
}

/// A tick label on a log axis: plotters puts a tick at every 1…9 × 10^k
/// when the axis spans few decades, and nine labels per decade overlap;
/// only 1, 2 and 5 × 10^k are labelled (the others keep their grid line).
pub fn log_tick(v: f64) -> String {
    if v <= 0.0 || !v.is_finite() {
        return String::new();
    }
    let mantissa = v / 10f64.powf(v.log10().floor());
    if [1.0, 2.0, 5.0, 10.0].iter().any(|m| (mantissa - m).abs() < 1e-6 * m) {
        tick(v)
    } else {
        String::new()
    }
}

fn min_max(values: &[f64]) -> (f64, f64) {
    values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(*v), hi.max(*v))
    })
}

/// A tick label: short, with exponents only where plain decimals would be
/// long (1e-7, 1e4), and no trailing zeros (0.25, not 0.250000).
pub fn tick(v: f64) -> String {
    let a = v.abs();
    // Tick positions are computed in floating point: 0 comes out as
    // -2.8e-17 on an axis from -0.2 to 0.6. No axis here is that fine.
    if a < 1e-12 {
        return "0".into();
    }
    if !(1e-3..1e4).contains(&a) {
        let s = format!("{v:.1e}");
        // 1.0e-7 → 1e-7
        return s.replace(".0e", "e");
    }
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close((a, b): (f64, f64), (c, d): (f64, f64)) -> bool {
        (a - c).abs() < 1e-12 && (b - d).abs() < 1e-12
    }

    #[test]
    fn a_decade_of_positive_values_is_logarithmic() {
        assert_eq!(auto_scale(&[0.5, 5.0]), Scale::Log);
        assert_eq!(auto_scale(&[1e-8, 2e-7, 3.0]), Scale::Log);
        // Less than a decade stays linear.
        assert_eq!(auto_scale(&[1.0, 9.9]), Scale::Linear);
    }

    #[test]
    fn zero_or_negative_values_keep_the_axis_linear() {
        // An exact method (error 0) must still be drawn.
        assert_eq!(auto_scale(&[0.0, 0.1, 10.0]), Scale::Linear);
        assert_eq!(auto_scale(&[-1.0, 100.0]), Scale::Linear);
        assert_eq!(auto_scale(&[]), Scale::Linear);
        // Non-finite values are ignored, not a reason to go linear.
        assert_eq!(auto_scale(&[f64::NAN, 1.0, 100.0]), Scale::Log);
    }

    #[test]
    fn linear_ranges_pad_every_case() {
        assert!(close(range(&[0.0, 10.0], Scale::Linear), (-0.5, 10.5)));
        // One point, or equal values: ±10% of the value.
        assert!(close(range(&[2.0], Scale::Linear), (1.8, 2.2)));
        assert!(close(range(&[2.0, 2.0, 2.0], Scale::Linear), (1.8, 2.2)));
        assert!(close(range(&[-4.0], Scale::Linear), (-4.4, -3.6)));
        // At zero there is nothing to take 10% of.
        assert_eq!(range(&[0.0], Scale::Linear), (-1.0, 1.0));
        assert_eq!(range(&[f64::NAN], Scale::Linear), (0.0, 1.0));
    }

    #[test]
    fn log_ranges_start_at_a_power_of_ten_and_contain_every_point() {
        let decade = |lo: f64, p: f64| lo < p && lo > p * (1.0 - 1e-6);
        let (lo, hi) = range(&[16384.0, 65536.0], Scale::Log);
        assert!(decade(lo, 1e4), "{lo}");
        assert!(hi > 65536.0 && hi < 1e5, "{hi}");
        // One point, or equal values.
        let (lo, hi) = range(&[3.0], Scale::Log);
        assert!(decade(lo, 1.0), "{lo}");
        assert!((hi - 3.0 * 10f64.powf(0.1)).abs() < 1e-9, "{hi}");
        assert_eq!(range(&[3.0, 3.0], Scale::Log), range(&[3.0], Scale::Log));
        // A power of ten itself is not on the frame.
        let (lo, _) = range(&[10.0], Scale::Log);
        assert!(decade(lo, 1.0), "{lo}");
        // Values a log axis cannot place are ignored; none left draws 1..10.
        let (lo, hi) = range(&[0.0, -3.0, 0.02, 2.0], Scale::Log);
        assert!(decade(lo, 0.01) && hi > 2.0, "{lo}..{hi}");
        assert_eq!(range(&[0.0, -1.0], Scale::Log), (1.0, 10.0));
    }

    #[test]
    fn only_positive_finite_values_go_on_a_log_axis() {
        assert!(drawable(1e-9, Scale::Log));
        assert!(!drawable(0.0, Scale::Log));
        assert!(!drawable(-1.0, Scale::Log));
        assert!(drawable(0.0, Scale::Linear) && drawable(-1.0, Scale::Linear));
        assert!(!drawable(f64::INFINITY, Scale::Linear));
    }

    #[test]
    fn tick_labels_are_short() {
        assert_eq!(tick(0.0), "0");
        assert_eq!(tick(-2.8e-17), "0");
        assert_eq!(tick(0.25), "0.25");
        assert_eq!(tick(10.0), "10");
        assert_eq!(tick(1e-7), "1e-7");
        assert_eq!(tick(2.5e-8), "2.5e-8");
        assert_eq!(tick(1e5), "1e5");
        assert_eq!(tick(4096.0), "4096");
        assert_eq!(tick(65536.0), "6.6e4");
        assert_eq!(tick(-0.0001), "-1e-4");
    }

    #[test]
    fn a_log_axis_labels_one_two_and_five_of_each_decade() {
        let labelled: Vec<String> = [0.1, 0.2, 0.3, 0.5, 0.9, 1.0, 1.0000000000000002, 7.0, 20.0, 1e5]
            .iter()
            .map(|v| log_tick(*v))
            .collect();
        assert_eq!(labelled, ["0.1", "0.2", "", "0.5", "", "1", "1", "", "20", "1e5"]);
        assert_eq!(log_tick(0.0), "");
    }
}
