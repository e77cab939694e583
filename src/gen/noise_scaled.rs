//! Noise-scaled features of the noisy tokens: every continuous attribute divided by the step's
//! noise, squashed, so that the denoiser reads how far a piece is from its token origin in units
//! of the noise it is removing.
//!
//! With `noise_scaled_features` (see [`ModelConfig::noise_scaled_features`]), every object token
//! also gets a learned embedding of tanh(x_t / (k σ_t)), k = [`SPREAD`], of each of its
//! [`CLASS_OFFSET`] continuous attributes x_t, where σ_t = √(1 − ᾱ_t) is the noise on it. A value
//! whose clean attribute is 0 — a free piece at the floor's centre (the token origin), an anchored
//! piece at its contact box's own place — then reads as its noise ε/k, at every step; a value far
//! from 0 saturates at its sign. Near the data the ideal correction of such a value is ε itself,
//! a gain of 1/σ_t on the raw token that the network would otherwise build from the time
//! embedding (a hanging lamp at the centre's one-step estimate is off by the noise itself:
//! docs/RESULTS.md, "Pendant lamps the model never hangs at the centre"). Measured on the living
//! rooms: it helps below 5 cm of noise only, and is not used by the shipped models
//! (docs/RESULTS.md, "Noise-scaled features"). Not here: the embedding itself (both engines); the
//! class scores get no features.

use super::ModelConfig;
use super::schedule::Schedule;
use super::tokens::CLASS_OFFSET;

/// The noise multiple at which a value saturates: within ±k σ_t of 0, tanh is nearly linear, so
/// two standard deviations of noise read as themselves.
pub const SPREAD: f32 = 3.0;

/// Features per object slot.
pub fn features_per_slot() -> usize {
    CLASS_OFFSET
}

/// The features of a batch's object slots `tokens` (rows of `token_dim`, `cfg.slots()` per item)
/// at steps `t` (one per item): per slot, per continuous attribute, tanh(x / (k σ_t)).
pub fn slot_features(cfg: &ModelConfig, t: &[usize], tokens: &[f32]) -> Vec<f32> {
    let schedule = Schedule::of(cfg);
    let (dim, slots) = (cfg.token_dim(), cfg.slots());
    let mut out = Vec::with_capacity(tokens.len() / dim * CLASS_OFFSET);
    for (item, rows) in tokens.chunks_exact(dim * slots).enumerate() {
        let sigma = (1.0 - schedule.alpha_bars[t[item]]).sqrt() as f32;
        let scale = 1.0 / (SPREAD * sigma);
        for token in rows.chunks_exact(dim) {
            out.extend(token[..CLASS_OFFSET].iter().map(|&x| (x * scale).tanh()));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::RoomType;

    #[test]
    fn features_are_the_attributes_in_units_of_the_noise_squashed() {
        let cfg = ModelConfig { noise_scaled_features: true, ..ModelConfig::tiny(RoomType::Bedroom) };
        let schedule = Schedule::of(&cfg);
        let (dim, slots) = (cfg.token_dim(), cfg.slots());
        let mut tokens = vec![0f32; 2 * slots * dim];
        let sigma = |t: usize| (1.0 - schedule.alpha_bars[t]).sqrt() as f32;
        let (quiet, loud) = (0, cfg.diffusion_steps - 1);
        tokens[0] = sigma(quiet); // item 0, slot 0, centre x: one σ off the origin
        tokens[1] = 0.5; // item 0, slot 0, centre y: far off at the least noise
        tokens[CLASS_OFFSET] = 0.9; // a class score: no feature
        tokens[slots * dim + 2] = 0.5; // item 1, slot 0, centre z, at the most noise
        let f = slot_features(&cfg, &[quiet, loud], &tokens);
        assert_eq!(f.len(), 2 * slots * CLASS_OFFSET);
        let close = |a: f32, b: f32| (a - b).abs() < 1e-5;
        assert!(close(f[0], (1.0 / SPREAD).tanh()), "{}", f[0]);
        assert!(f[1] > 0.999, "saturates: {}", f[1]);
        assert!(f[2..slots * CLASS_OFFSET].iter().all(|&v| v == 0.0), "zeros stay zero; no class feature");
        let expected = (0.5 / (SPREAD * sigma(loud))).tanh();
        assert!(close(f[slots * CLASS_OFFSET + 2], expected) && expected < 0.2, "{expected}");
    }
}
