//! The DDPM noise schedule: ᾱ over T steps and the posterior coefficients.
//!
//! Linear: betas run linearly from `1000/T · 1e-4` to `1000/T · 0.02` (DDPM's range rescaled to T
//! steps, so T = 200 still ends at pure noise: ᾱ_T ≈ 5e-5). Log-SNR: log(ᾱ / (1 − ᾱ)) linear in
//! t from a small least noise to the same end. Everything is computed once, in f64.

use super::ModelConfig;
use super::config::{COSINE_OFFSET, LOG_SNR_SIGMA_MIN, NoiseSchedule};

/// Precomputed schedule of one model.
#[derive(Debug, Clone, PartialEq)]
pub struct Schedule {
    /// β_t for t = 0..T.
    pub betas: Vec<f64>,
    /// ᾱ_t = Π_{s ≤ t} (1 − β_s).
    pub alpha_bars: Vec<f64>,
}

impl Schedule {
    /// The schedule a model's config names.
    pub fn of(cfg: &ModelConfig) -> Schedule {
        match cfg.schedule {
            NoiseSchedule::Linear => Schedule::linear(cfg.diffusion_steps),
            NoiseSchedule::LogSnr => Schedule::log_snr(cfg.diffusion_steps),
            NoiseSchedule::Cosine => Schedule::cosine(cfg.diffusion_steps),
        }
    }

    /// The cosine schedule with `steps` steps: ᾱ_t = f(t + 1) / f(0), β_t = 1 − ᾱ_t / ᾱ_{t−1}
    /// clipped to 0.999 (the last step, where f reaches 0).
    pub fn cosine(steps: usize) -> Schedule {
        let f = |t: f64| {
            ((t / steps as f64 + COSINE_OFFSET) / (1.0 + COSINE_OFFSET) * std::f64::consts::FRAC_PI_2).cos().powi(2)
        };
        let mut betas = Vec::with_capacity(steps);
        let mut alpha_bars = Vec::with_capacity(steps);
        let mut product = 1.0;
        for t in 0..steps {
            let beta = (1.0 - f(t as f64 + 1.0) / f(t as f64)).min(0.999);
            product *= 1.0 - beta;
            betas.push(beta);
            alpha_bars.push(product);
        }
        Schedule { betas, alpha_bars }
    }

    /// log-SNR linear in t, from σ = [`LOG_SNR_SIGMA_MIN`] at step 0 to the linear schedule's last
    /// ᾱ at step T − 1.
    pub fn log_snr(steps: usize) -> Schedule {
        let first = ((1.0 - LOG_SNR_SIGMA_MIN.powi(2)) / LOG_SNR_SIGMA_MIN.powi(2)).ln();
        let end = *Schedule::linear(steps).alpha_bars.last().expect("at least one step");
        let last = (end / (1.0 - end)).ln();
        let alpha_bars: Vec<f64> = (0..steps)
            .map(|t| {
                let l = if steps == 1 { first } else { first + (last - first) * t as f64 / (steps - 1) as f64 };
                1.0 / (1.0 + (-l).exp())
            })
            .collect();
        let betas = (0..steps).map(|t| 1.0 - alpha_bars[t] / if t == 0 { 1.0 } else { alpha_bars[t - 1] }).collect();
        Schedule { betas, alpha_bars }
    }

    /// The linear schedule with `steps` steps.
    pub fn linear(steps: usize) -> Schedule {
        let scale = 1000.0 / steps as f64;
        let (start, end) = (scale * 1e-4, scale * 0.02);
        let betas: Vec<f64> = (0..steps)
            .map(|t| if steps == 1 { start } else { start + (end - start) * t as f64 / (steps - 1) as f64 })
            .collect();
        let mut product = 1.0;
        let alpha_bars = betas
            .iter()
            .map(|b| {
                product *= 1.0 - b;
                product
            })
            .collect();
        Schedule { betas, alpha_bars }
    }

    /// How many of this schedule's steps carry less noise than `other`'s step `t` (more signal:
    /// ᾱ greater): `t` itself when `other` is this schedule.
    pub fn steps_below(&self, other: &Schedule, t: usize) -> usize {
        let level = other.alpha_bars[t.min(other.steps() - 1)];
        self.alpha_bars.iter().filter(|&&ab| ab > level).count()
    }

    /// How many of this schedule's steps carry less noise than the linear schedule's (of the same
    /// length) step `t`: where a window set in linear steps (the guidance's last 20) begins here.
    pub fn at_linear_noise(&self, t: usize) -> usize {
        self.steps_below(&Schedule::linear(self.steps()), t)
    }

    /// Number of steps T.
    pub fn steps(&self) -> usize {
        self.betas.len()
    }

    /// Coefficients (of x̂0, of x_t) of the posterior mean q(x_{t−1} | x_t, x̂0), and its variance.
    pub fn posterior(&self, t: usize) -> (f64, f64, f64) {
        self.posterior_to(t, t.checked_sub(1))
    }

    /// Like [`posterior`](Self::posterior) for a jump from step `t` to the earlier step `s` (`None`:
    /// the clean data, ᾱ = 1): the posterior q(x_s | x_t, x̂0) of the chain that visits only the
    /// steps a [`respaced`](Self::respaced) sampler visits (Nichol & Dhariwal's respacing), whose
    /// β for the jump is 1 − ᾱ_t / ᾱ_s. With `s = t − 1` it is the full chain's.
    pub fn posterior_to(&self, t: usize, s: Option<usize>) -> (f64, f64, f64) {
        let ab = self.alpha_bars[t];
        let ab_prev = s.map_or(1.0, |s| self.alpha_bars[s]);
        // The full chain's own β where the jump is one step (bit-identical to it; the cosine
        // schedule clips its last β).
        let beta = if s == t.checked_sub(1) { self.betas[t] } else { 1.0 - ab / ab_prev };
        let c0 = beta * ab_prev.sqrt() / (1.0 - ab);
        let ct = (1.0 - ab_prev) * (1.0 - beta).sqrt() / (1.0 - ab);
        let var = beta * (1.0 - ab_prev) / (1.0 - ab);
        (c0, ct, var)
    }

    /// The jump from step `t` to the earlier step `s` (`None`: the clean data) of DDIM's family
    /// (Song et al. 2021, eq. 12) with fresh noise `eta`: x_s = c0 x̂0 + ct x_t + √var z, var =
    /// η² times DDPM's posterior variance, and the rest of the noise step s needs taken from x_t's
    /// own. `eta` 0 is the deterministic DDIM sampler; `eta` 1 is DDPM's posterior, returned as
    /// [`posterior_to`](Self::posterior_to) computes it, so a DDPM chain is unchanged to the bit;
    /// above 1 more noise is drawn anew, at most all of step s's (x̂0 noised afresh, ct 0).
    pub fn jump(&self, t: usize, s: Option<usize>, eta: f64) -> (f64, f64, f64) {
        if eta == 1.0 {
            return self.posterior_to(t, s);
        }
        let ab = self.alpha_bars[t];
        let ab_s = s.map_or(1.0, |s| self.alpha_bars[s]);
        let var = (eta * eta * (1.0 - ab_s) / (1.0 - ab) * (1.0 - ab / ab_s)).min(1.0 - ab_s);
        let ct = (1.0 - ab_s - var).max(0.0).sqrt() / (1.0 - ab).sqrt();
        let c0 = ab_s.sqrt() - ct * ab.sqrt();
        (c0, ct, var)
    }

    /// The steps a sampler with `n` model calls visits, ascending: `n` steps evenly spaced from 0
    /// to T − 1 (every step when `n` ≥ T; at least 0 and T − 1, so the chain still starts at pure
    /// noise and ends at the least noise).
    pub fn respaced(&self, n: usize) -> Vec<usize> {
        let last = self.steps() - 1;
        if n >= self.steps() {
            return (0..self.steps()).collect();
        }
        let n = n.max(2);
        let mut visited: Vec<usize> = (0..n).map(|i| ((i * last) as f64 / (n - 1) as f64).round() as usize).collect();
        visited.dedup();
        visited
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn alpha_bars_match_hand_computed_values() {
        let s = Schedule::linear(200);
        let b0 = 5e-4;
        let b1 = 5e-4 + (0.1 - 5e-4) / 199.0;
        assert!((s.betas[0] - b0).abs() < 1e-15);
        assert!((s.betas[199] - 0.1).abs() < 1e-15);
        assert!((s.alpha_bars[0] - (1.0 - b0)).abs() < 1e-15);
        assert!((s.alpha_bars[1] - (1.0 - b0) * (1.0 - b1)).abs() < 1e-15);
        // Σβ = 200 · (5e-4 + 0.1) / 2 = 10.05, so ᾱ_T ≈ exp(−10.05 − Σβ²/2) ≈ 2.0e-5 … 4.4e-5.
        assert!(s.alpha_bars[199] > 1e-5 && s.alpha_bars[199] < 5e-5, "{}", s.alpha_bars[199]);
    }

    #[test]
    fn log_snr_runs_from_the_least_noise_to_the_linear_end_in_equal_log_steps() {
        let s = Schedule::log_snr(200);
        let snr = |t: usize| (s.alpha_bars[t] / (1.0 - s.alpha_bars[t])).ln();
        assert!(((1.0 - s.alpha_bars[0]).sqrt() - LOG_SNR_SIGMA_MIN).abs() < 1e-12);
        assert!((s.alpha_bars[199] - Schedule::linear(200).alpha_bars[199]).abs() < 1e-12);
        for t in 1..200 {
            assert!((snr(t) - snr(t - 1) - (snr(199) - snr(0)) / 199.0).abs() < 1e-9);
            // ᾱ is the product of the (1 − β) so far.
            assert!((s.alpha_bars[t] - s.alpha_bars[t - 1] * (1.0 - s.betas[t])).abs() < 1e-12);
        }
    }

    #[test]
    fn cosine_matches_its_closed_form_and_ends_in_noise() {
        let s = Schedule::cosine(200);
        let f = |t: f64| ((t / 200.0 + 0.008) / 1.008 * std::f64::consts::FRAC_PI_2).cos().powi(2);
        // ᾱ_t = f(t + 1) / f(0) wherever no β was clipped; σ at step 0 ≈ 0.016 (hand-computed).
        for t in [0, 1, 50, 100, 150, 198] {
            assert!((s.alpha_bars[t] - f(t as f64 + 1.0) / f(0.0)).abs() < 1e-12, "step {t}");
        }
        assert!(((1.0 - s.alpha_bars[0]).sqrt() - 0.0157).abs() < 5e-4, "{}", (1.0 - s.alpha_bars[0]).sqrt());
        assert!(s.betas[199] <= 0.999 && s.alpha_bars[199] < 1e-3);
        assert!(s.betas.windows(2).all(|w| w[1] >= w[0]), "betas rise");
        // Between linear and log-SNR at low noise: more steps below the linear step 20's noise.
        let (linear, log_snr) = (Schedule::linear(200), Schedule::log_snr(200));
        let n = s.steps_below(&linear, 20);
        assert!(n > 20 && n < log_snr.steps_below(&linear, 20), "{n}");
    }

    #[test]
    fn steps_below_a_noise_level_are_counted_in_either_schedule() {
        let (linear, log_snr) = (Schedule::linear(200), Schedule::log_snr(200));
        assert_eq!(linear.steps_below(&linear, 80), 80);
        let n = log_snr.steps_below(&linear, 80);
        // Every counted log-SNR step has more signal than linear step 80, the next one not.
        assert!(log_snr.alpha_bars[n - 1] > linear.alpha_bars[80] && log_snr.alpha_bars[n] <= linear.alpha_bars[80]);
        assert!(n > 80, "log-SNR spends more steps at low noise: {n}");
    }

    #[test]
    fn posterior_at_the_first_step_returns_the_clean_estimate() {
        let s = Schedule::linear(200);
        let (c0, ct, var) = s.posterior(0);
        assert!((c0 - 1.0).abs() < 1e-12 && ct.abs() < 1e-12 && var.abs() < 1e-12);
        // Posterior mean of x0 = x_t = 1 must be 1 at every t when x_t is the noiseless image scaled.
        for t in [1, 50, 199] {
            let (c0, ct, _) = s.posterior(t);
            let x0 = 1.0;
            let xt = s.alpha_bars[t].sqrt() * x0;
            let mean = c0 * x0 + ct * xt;
            assert!((mean - s.alpha_bars[t - 1].sqrt() * x0).abs() < 1e-12);
        }
    }

    #[test]
    fn a_ddim_jump_is_ddpm_at_eta_one_and_follows_the_noise_at_eta_zero() {
        for s in [Schedule::linear(200), Schedule::log_snr(200), Schedule::cosine(200)] {
            for (t, to) in [(199, Some(150)), (150, Some(50)), (60, Some(59)), (3, None)] {
                // η 1 is DDPM's posterior: the general formula agrees with it.
                let (ab, ab_s) = (s.alpha_bars[t], to.map_or(1.0, |k| s.alpha_bars[k]));
                let (c0, ct, var) = s.posterior_to(t, to);
                let var1 = (1.0 - ab_s) / (1.0 - ab) * (1.0 - ab / ab_s);
                let ct1 = (1.0 - ab_s - var1).max(0.0).sqrt() / (1.0 - ab).sqrt();
                let c01 = ab_s.sqrt() - ct1 * ab.sqrt();
                assert!((c0 - c01).abs() < 1e-9 && (ct - ct1).abs() < 1e-9 && (var - var1).abs() < 1e-12, "{t}");
                assert_eq!(s.jump(t, to, 1.0), (c0, ct, var));
                // η 0: no fresh noise, and x_t = √ᾱ_t x0 + √(1 − ᾱ_t) ε with x̂0 = x0 lands on
                // x_s = √ᾱ_s x0 + √(1 − ᾱ_s) ε, the same ε (x0 = 0.7, ε = −1.3).
                let (c0, ct, var) = s.jump(t, to, 0.0);
                assert_eq!(var, 0.0);
                let xt = ab.sqrt() * 0.7 + (1.0 - ab).sqrt() * -1.3;
                let want = ab_s.sqrt() * 0.7 + (1.0 - ab_s).sqrt() * -1.3;
                assert!((c0 * 0.7 + ct * xt - want).abs() < 1e-9, "{t}: {} vs {want}", c0 * 0.7 + ct * xt);
                // The variance grows as η², up to all the noise of step s, where nothing of x_t
                // is kept.
                let (_, _, half) = s.jump(t, to, 0.5);
                assert!((half - 0.25 * var1).abs() < 1e-12);
                let (c0, ct, most) = s.jump(t, to, 1e3);
                assert!((most - (1.0 - ab_s)).abs() < 1e-12 && ct == 0.0 && (c0 - ab_s.sqrt()).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn a_respaced_chain_visits_evenly_spaced_steps_from_pure_noise_to_the_least() {
        let s = Schedule::log_snr(200);
        // i · 199 / 4 rounded: 0, 49.75, 99.5, 149.25, 199.
        assert_eq!(s.respaced(5), vec![0, 50, 100, 149, 199]);
        assert_eq!(s.respaced(2), vec![0, 199]);
        assert_eq!(s.respaced(0), vec![0, 199]);
        assert_eq!(s.respaced(200), (0..200).collect::<Vec<_>>());
        assert_eq!(s.respaced(500).len(), 200);
    }

    #[test]
    fn a_jump_keeps_the_clean_signal_and_one_step_is_the_full_chain() {
        for s in [Schedule::linear(200), Schedule::log_snr(200), Schedule::cosine(200)] {
            for t in [1, 60, 199] {
                assert_eq!(s.posterior_to(t, Some(t - 1)), s.posterior(t));
            }
            // From t 150 to s 50: the mean of a noiseless x_t = √ᾱ_t x0 with x̂0 = x0 is √ᾱ_s x0,
            // and the variance is β' (1 − ᾱ_s) / (1 − ᾱ_t) with β' = 1 − ᾱ_t / ᾱ_s.
            let (ab_t, ab_s) = (s.alpha_bars[150], s.alpha_bars[50]);
            let (c0, ct, var) = s.posterior_to(150, Some(50));
            assert!((c0 + ct * ab_t.sqrt() - ab_s.sqrt()).abs() < 1e-12);
            assert!((var - (1.0 - ab_t / ab_s) * (1.0 - ab_s) / (1.0 - ab_t)).abs() < 1e-12);
            // To the clean data: the estimate itself.
            let (c0, ct, var) = s.posterior_to(150, None);
            assert!((c0 - 1.0).abs() < 1e-9 && ct.abs() < 1e-9 && var.abs() < 1e-9, "{c0} {ct} {var}");
        }
    }
}
