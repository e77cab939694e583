//! Pearson's correlation of two samples, for the diagnostics that ask how closely one quantity
//! follows another (a nightstand's distance from its bed's centre line against the bed's half
//! width: `examples/pair_gaps.rs`, `examples/denoising_error.rs`).

/// Pearson's r of `a` against `b` (paired, same length); 0 where either has no spread.
pub fn pearson(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().max(1) as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    let cov: f64 = a.iter().zip(b).map(|(x, y)| (x - ma) * (y - mb)).sum();
    let (va, vb): (f64, f64) = (a.iter().map(|x| (x - ma).powi(2)).sum(), b.iter().map(|y| (y - mb).powi(2)).sum());
    cov / (va * vb).sqrt().max(1e-12)
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
}
