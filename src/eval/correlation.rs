//! Two statistics for the diagnostics: Pearson's correlation, for how closely one quantity
//! follows another (a nightstand's distance from its bed's centre line against the bed's half
//! width: `examples/pair_gaps.rs`, `examples/denoising_error.rs`), and the rank AUC, for how well
//! one value tells two sets apart (`examples/judge_features.rs`).

use std::cmp::Ordering;

/// Pearson's r of `a` against `b` (paired, same length); 0 where either has no spread.
pub fn pearson(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().max(1) as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    let cov: f64 = a.iter().zip(b).map(|(x, y)| (x - ma) * (y - mb)).sum();
    let (va, vb): (f64, f64) = (a.iter().map(|x| (x - ma).powi(2)).sum(), b.iter().map(|y| (y - mb).powi(2)).sum());
    cov / (va * vb).sqrt().max(1e-12)
}

/// The Mann–Whitney AUC of `a` over `b`: P(x > y) + ½ P(x = y) over every pair of an x of `a`
/// and a y of `b` (0.5: the value alone does not tell the sets apart; 0 or 1: it always does).
/// −0 and 0 are equal; 0.5 where either set is empty.
pub fn rank_auc(a: &[f64], b: &[f64]) -> f64 {
    if a.is_empty() || b.is_empty() {
        return 0.5;
    }
    let wins: f64 = a
        .iter()
        .flat_map(|x| b.iter().map(move |y| (x, y)))
        .map(|(x, y)| match x.partial_cmp(y).unwrap_or(Ordering::Equal) {
            Ordering::Greater => 1.0,
            Ordering::Equal => 0.5,
            Ordering::Less => 0.0,
        })
        .sum();
    wins / (a.len() * b.len()) as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hand_computed_correlations() {
        // Exactly linear, either way up.
        assert!((pearson(&[1.0, 2.0, 3.0], &[2.0, 4.0, 6.0]) - 1.0).abs() < 1e-12);
        assert!((pearson(&[1.0, 2.0, 3.0], &[3.0, 2.0, 1.0]) + 1.0).abs() < 1e-12);
        // (1, 1), (2, 3), (3, 2): cov 1, variances 2 and 2, r 0.5.
        assert!((pearson(&[1.0, 2.0, 3.0], &[1.0, 3.0, 2.0]) - 0.5).abs() < 1e-12);
        // No spread: 0, not NaN.
        assert_eq!(pearson(&[1.0, 1.0], &[2.0, 5.0]), 0.0);
    }

    #[test]
    fn hand_computed_rank_aucs() {
        // Every x above every y, and the other way.
        assert_eq!(rank_auc(&[3.0, 4.0], &[1.0, 2.0]), 1.0);
        assert_eq!(rank_auc(&[1.0, 2.0], &[3.0, 4.0]), 0.0);
        // {1, 3} over {2, 3}: (1,2) 0, (1,3) 0, (3,2) 1, (3,3) ½ → 1.5 / 4.
        assert_eq!(rank_auc(&[1.0, 3.0], &[2.0, 3.0]), 0.375);
        // −0 is 0; an empty set tells nothing.
        assert_eq!(rank_auc(&[-0.0], &[0.0]), 0.5);
        assert_eq!(rank_auc(&[], &[1.0]), 0.5);
    }
}
