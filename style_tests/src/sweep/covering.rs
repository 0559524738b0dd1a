//! A strength-2 covering array (issue 49): rows of parameter settings in
//! which every pair of parameters meets at every pair of their levels (a
//! range's two ends, each bool or enum value). Built in parameter order
//! as IPOG does (Lei et al. 2007, "IPOG: A General Strategy for T-Way
//! Software Testing"): the first two parameters' levels crossed, then each
//! next parameter grown horizontally (each row takes the level covering
//! most pairs still missing) and vertically (rows added, or a row's free
//! cell filled, for the pairs still missing). For parameters of two levels
//! the rows grow as O(log n), not as the n² pairs.

/// A row: each parameter's level index, `None` where any level will do
/// (the sweep leaves that parameter at its default).
pub type Row = Vec<Option<usize>>;

/// A covering array for parameters with `levels[i]` levels each.
pub fn covering_array(levels: &[usize]) -> Vec<Row> {
    let n = levels.len();
    if n == 0 {
        return Vec::new();
    }
    if n == 1 {
        return (0..levels[0]).map(|v| vec![Some(v)]).collect();
    }
    let mut rows: Vec<Row> = Vec::new();
    for a in 0..levels[0] {
        for b in 0..levels[1] {
            let mut r = vec![None; n];
            r[0] = Some(a);
            r[1] = Some(b);
            rows.push(r);
        }
    }
    for i in 2..n {
        // The pairs of parameter i with each earlier one still missing.
        let mut missing: Vec<Vec<Vec<bool>>> = (0..i).map(|j| vec![vec![true; levels[j]]; levels[i]]).collect();
        // Horizontal growth: each row takes the level of i covering most.
        for r in rows.iter_mut() {
            let gain = |v: usize| (0..i).filter(|&j| r[j].is_some_and(|w| missing[j][v][w])).count();
            let best = (0..levels[i])
                .max_by_key(|&v| (gain(v), std::cmp::Reverse(v)))
                .unwrap_or(0);
            r[i] = Some(best);
            for j in 0..i {
                if let Some(w) = r[j] {
                    missing[j][best][w] = false;
                }
            }
        }
        // Vertical growth: each pair still missing, in a row with i at its
        // level and j free, or in a new row.
        for (j, of_j) in missing.iter_mut().enumerate() {
            for (v, of_v) in of_j.iter_mut().enumerate() {
                for (w, m) in of_v.iter_mut().enumerate() {
                    if !*m {
                        continue;
                    }
                    match rows.iter_mut().find(|r| r[i] == Some(v) && r[j].is_none()) {
                        Some(r) => r[j] = Some(w),
                        None => {
                            let mut r = vec![None; n];
                            r[i] = Some(v);
                            r[j] = Some(w);
                            rows.push(r);
                        }
                    }
                    *m = false;
                }
            }
        }
    }
    rows
}

/// How many pairs of (parameter, level) a covering array must cover.
pub fn pair_count(levels: &[usize]) -> usize {
    let mut total = 0;
    for i in 0..levels.len() {
        for j in 0..i {
            total += levels[i] * levels[j];
        }
    }
    total
}

/// The pairs `rows` cover (a free cell covers none).
pub fn covered_pairs(levels: &[usize], rows: &[Row]) -> usize {
    let mut seen = std::collections::HashSet::new();
    for r in rows {
        for i in 0..levels.len() {
            for j in 0..i {
                if let (Some(v), Some(w)) = (r[i], r[j]) {
                    seen.insert((i, v, j, w));
                }
            }
        }
    }
    seen.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_pair_is_covered_for_several_sizes_and_levels() {
        for levels in [
            vec![2],
            vec![2, 2],
            vec![2, 2, 2],
            vec![2; 5],
            vec![2; 10],
            vec![2; 40],
            vec![3, 2, 4, 2, 2, 5],
            vec![2, 3, 2, 3, 2, 3, 2, 3],
        ] {
            let rows = covering_array(&levels);
            assert!(rows.iter().all(|r| r.len() == levels.len()));
            assert!(
                rows.iter()
                    .all(|r| r.iter().zip(&levels).all(|(c, l)| c.is_none_or(|v| v < *l))),
                "a level out of range for {levels:?}"
            );
            if levels.len() > 1 {
                assert_eq!(
                    covered_pairs(&levels, &rows),
                    pair_count(&levels),
                    "{levels:?}: {} rows miss a pair",
                    rows.len()
                );
            }
        }
    }

    #[test]
    fn rows_grow_slowly_with_the_number_of_two_level_params() {
        // Every pair of n two-level params is 4·n(n−1)/2 pairs; the rows
        // grow as log n (this greedy gives 7, 11, 14, 17, 21 for n = 5, 10,
        // 20, 40, 80; a minimal array has 6 for 10 params, 8 for 40).
        for n in [5, 10, 20, 40, 80] {
            let rows = covering_array(&vec![2; n]).len();
            let bound = 4.0 * (n as f64).log2() + 3.0;
            assert!((rows as f64) <= bound, "{n} params: {rows} rows, past 4·log2(n) + 3");
            assert!(rows < pair_count(&vec![2; n]) / 4);
        }
    }
}
