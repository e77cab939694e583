//! Fourier features of the noisy tokens: sines and cosines of every continuous attribute at
//! octave-spaced frequencies, so that the denoiser's first layer sees centimetres.
//!
//! With `fourier_bands` > 0 (see [`ModelConfig::fourier_bands`]), every object token also gets a
//! learned embedding of sin(2ᵏπ x) and cos(2ᵏπ x), k = 1 … `fourier_bands`, of each of its
//! [`CLASS_OFFSET`] continuous attributes x (centre, size, yaw's cosine and sine, in the model's
//! frame). A token unit is the window's half side (2.8 to 5.2 m), so a 5 cm offset is about 0.01
//! of it: a linear layer on the raw token can hardly tell it from the noise it is denoising, which
//! is the spectral bias of small networks (Tancik et al. 2020). The highest band of 8 has a period of
//! 1/128 unit, 2.2 to 4.1 cm. Not here: the embedding itself (both engines); the class scores get
//! no features.

use super::ModelConfig;
use super::tokens::CLASS_OFFSET;

/// The most bands a config may ask for: beyond 2¹⁶π x, the phase is mostly the float rounding of x.
pub const MAX_BANDS: usize = 16;

/// Features per object slot.
pub fn features_per_slot(cfg: &ModelConfig) -> usize {
    CLASS_OFFSET * cfg.fourier_bands * 2
}

/// The Fourier features of one item's (or a batch's) object slots `tokens` (rows of
/// `token_dim`): per slot, per attribute, per band k the sine then the cosine of 2ᵏπ x.
pub fn slot_features(cfg: &ModelConfig, tokens: &[f32]) -> Vec<f32> {
    let dim = cfg.token_dim();
    let mut out = Vec::with_capacity(tokens.len() / dim * features_per_slot(cfg));
    for token in tokens.chunks_exact(dim) {
        for &x in &token[..CLASS_OFFSET] {
            for k in 1..=cfg.fourier_bands {
                let (s, c) = (std::f32::consts::PI * (1u32 << k) as f32 * x).sin_cos();
                out.push(s);
                out.push(c);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::RoomType;

    #[test]
    fn features_are_sines_and_cosines_of_each_attribute_by_octave() {
        let cfg = ModelConfig { fourier_bands: 2, ..ModelConfig::tiny(RoomType::Bedroom) };
        let dim = cfg.token_dim();
        let mut tokens = vec![0f32; 2 * dim];
        tokens[0] = 0.25; // slot 0, centre x
        tokens[dim + 7] = -0.125; // slot 1, sin yaw
        tokens[CLASS_OFFSET] = 0.9; // a class score: no features
        let f = slot_features(&cfg, &tokens);
        assert_eq!(f.len(), 2 * features_per_slot(&cfg));
        assert_eq!(features_per_slot(&cfg), 8 * 2 * 2);
        // Slot 0, attribute 0: sin(2π/4) = 1, cos = 0; sin(4π/4) = 0, cos = −1.
        let close = |a: f32, b: f32| (a - b).abs() < 1e-6;
        assert!(close(f[0], 1.0) && close(f[1], 0.0) && close(f[2], 0.0) && close(f[3], -1.0), "{:?}", &f[..4]);
        // Attributes at 0: sines 0, cosines 1.
        assert!(f[4..32].chunks(2).all(|sc| close(sc[0], 0.0) && close(sc[1], 1.0)));
        // Slot 1, attribute 7 = −1/8: sin(−π/4), cos(π/4); sin(−π/2) = −1, cos = 0.
        let g = &f[32 + 7 * 4..32 + 8 * 4];
        let h = std::f32::consts::FRAC_1_SQRT_2;
        assert!(close(g[0], -h) && close(g[1], h) && close(g[2], -1.0) && close(g[3], 0.0), "{g:?}");
    }
}
