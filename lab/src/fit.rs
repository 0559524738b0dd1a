//! Least-squares fits of a cost against a size, for benchmarks that ask
//! whether a cost is linear (issue 14: "cost linear in pixels from 128² to
//! 1024², with the slope reported"): a line t = a + b·n, whose slope b is
//! the cost of one more unit, and a power law t = c·n^k fitted as a line in
//! log–log, whose exponent k is 1 where the cost is linear with no fixed
//! part, under 1 where a fixed cost still shows, over 1 where each unit
//! gets dearer (a working set that leaves the caches).

/// t = intercept + slope · n, by ordinary least squares.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Line {
    pub slope: f64,
    pub intercept: f64,
}

/// Least-squares line through `points` (n, t); `None` with fewer than two
/// distinct n, or a value that is not finite.
pub fn line(points: &[(f64, f64)]) -> Option<Line> {
    if points.iter().any(|(n, t)| !n.is_finite() || !t.is_finite()) {
        return None;
    }
    let count = points.len() as f64;
    let mean_n = points.iter().map(|p| p.0).sum::<f64>() / count;
    let mean_t = points.iter().map(|p| p.1).sum::<f64>() / count;
    // Centred sums: the sizes here span 1.6·10⁴ to 10⁶ pixels, where
    // Σn² − (Σn)²/N would lose digits to cancellation.
    let snn: f64 = points.iter().map(|(n, _)| (n - mean_n) * (n - mean_n)).sum();
    let snt: f64 = points.iter().map(|(n, t)| (n - mean_n) * (t - mean_t)).sum();
    if points.len() < 2 || snn <= 0.0 {
        return None;
    }
    let slope = snt / snn;
    Some(Line {
        slope,
        intercept: mean_t - slope * mean_n,
    })
}

/// t = coefficient · n^exponent, fitted as a line through (ln n, ln t);
/// `None` with fewer than two distinct n or any n or t not positive.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PowerLaw {
    pub exponent: f64,
    pub coefficient: f64,
}

pub fn power_law(points: &[(f64, f64)]) -> Option<PowerLaw> {
    if points.iter().any(|(n, t)| !(*n > 0.0 && *t > 0.0)) {
        return None;
    }
    let logs: Vec<(f64, f64)> = points.iter().map(|(n, t)| (n.ln(), t.ln())).collect();
    let l = line(&logs)?;
    Some(PowerLaw {
        exponent: l.slope,
        coefficient: l.intercept.exp(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * b.abs().max(1e-300)
    }

    /// The benchmark's pixel counts, 128² to 1024².
    const PIXELS: [f64; 4] = [16384.0, 65536.0, 262144.0, 1048576.0];

    #[test]
    fn an_exact_line_is_recovered() {
        // 2 ms fixed plus 40 ns a pixel, in seconds.
        let points: Vec<(f64, f64)> = PIXELS.iter().map(|n| (*n, 2e-3 + 40e-9 * n)).collect();
        let l = line(&points).expect("a fit");
        assert!(close(l.slope, 40e-9, 1e-12), "{l:?}");
        assert!(close(l.intercept, 2e-3, 1e-10), "{l:?}");
        // A fixed cost makes the log–log exponent less than 1.
        let p = power_law(&points).expect("a fit");
        assert!(p.exponent > 0.5 && p.exponent < 1.0, "{p:?}");
    }

    #[test]
    fn a_line_through_the_origin_has_exponent_one() {
        let points: Vec<(f64, f64)> = PIXELS.iter().map(|n| (*n, 7e-9 * n)).collect();
        let p = power_law(&points).expect("a fit");
        assert!(close(p.exponent, 1.0, 1e-12), "{p:?}");
        assert!(close(p.coefficient, 7e-9, 1e-10), "{p:?}");
    }

    #[test]
    fn an_exact_power_law_is_recovered() {
        let points: Vec<(f64, f64)> = PIXELS.iter().map(|n| (*n, 3e-10 * n.powf(1.25))).collect();
        let p = power_law(&points).expect("a fit");
        assert!(close(p.exponent, 1.25, 1e-12), "{p:?}");
        assert!(close(p.coefficient, 3e-10, 1e-9), "{p:?}");
        // The line's slope is then the least-squares average: between the
        // local slopes at the ends, 1.25 · 3e-10 · n^0.25.
        let l = line(&points).expect("a fit");
        let local = |n: f64| 1.25 * 3e-10 * n.powf(0.25);
        assert!(l.slope > local(PIXELS[0]) && l.slope < local(PIXELS[3]), "{l:?}");
    }

    #[test]
    fn residuals_orthogonal_to_the_line_leave_it_unchanged() {
        // t = 1 + 2n with residuals +e, −e, −e, +e: they sum to 0 and to 0
        // weighted by n − n̄, so least squares gives the line back, where a
        // line through the end points would be off by e.
        let points = [(0.0, 1.1), (1.0, 2.9), (2.0, 4.9), (3.0, 7.1)];
        let l = line(&points).expect("a fit");
        assert!(close(l.slope, 2.0, 1e-12), "{l:?}");
        assert!(close(l.intercept, 1.0, 1e-12), "{l:?}");
    }

    #[test]
    fn too_few_or_bad_points_give_no_fit() {
        assert_eq!(line(&[]), None);
        assert_eq!(line(&[(1.0, 2.0)]), None);
        assert_eq!(line(&[(1.0, 2.0), (1.0, 3.0)]), None);
        assert_eq!(line(&[(1.0, 2.0), (2.0, f64::NAN)]), None);
        assert_eq!(power_law(&[(1.0, 2.0), (2.0, 0.0)]), None);
        assert_eq!(power_law(&[(0.0, 2.0), (2.0, 1.0)]), None);
    }
}
