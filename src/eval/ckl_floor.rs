//! The CKL an ideal generator would score: real layouts drawn from a pool (the training split), as
//! many as the generated set has, scored against the reference frequencies like any row.
//!
//! CKL compares two finite samples, so it is not 0 even for the data itself; rare categories
//! (0.1–0.3 % of objects) are missing from some draws and each missing one adds p·ln(p / 10⁻⁶).
//! This says how low a row's CKL can be expected to go; it does not score a generator.

use super::{category_frequencies, category_kl};
use crate::data::Rng;
use crate::scene::{RoomType, Scene};
use serde::{Deserialize, Serialize};

/// The spread of CKL over random draws of real layouts.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CklFloor {
    /// Layouts per draw.
    pub layouts: usize,
    /// Draws.
    pub draws: usize,
    /// Mean CKL over the draws.
    pub mean: f64,
    /// 10th percentile.
    pub p10: f64,
    /// 90th percentile.
    pub p90: f64,
}

/// CKL of `draws` random sets of `layouts` scenes from `pool` (without replacement within a set)
/// against `reference`; deterministic for `seed`. `None` when the pool is smaller than a set or
/// nothing is drawn.
pub fn ckl_floor(
    pool: &[Scene],
    room: RoomType,
    reference: &[f64],
    layouts: usize,
    draws: usize,
    seed: u64,
) -> Option<CklFloor> {
    if layouts == 0 || draws == 0 || pool.len() < layouts {
        return None;
    }
    let mut rng = Rng::new(seed);
    let mut order: Vec<usize> = (0..pool.len()).collect();
    let mut kls: Vec<f64> = (0..draws)
        .map(|_| {
            // Partial Fisher–Yates: the first `layouts` entries are a uniform draw.
            for i in 0..layouts {
                let j = rng.range(i, pool.len() - 1);
                order.swap(i, j);
            }
            let q = category_frequencies(order[..layouts].iter().map(|&i| &pool[i]), room);
            category_kl(reference, &q)
        })
        .collect();
    kls.sort_by(f64::total_cmp);
    let at = |f: f64| kls[((draws - 1) as f64 * f).round() as usize];
    Some(CklFloor { layouts, draws, mean: kls.iter().sum::<f64>() / draws as f64, p10: at(0.1), p90: at(0.9) })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::generate_room;

    #[test]
    fn drawing_the_whole_pool_scores_the_pools_own_ckl() {
        let pool: Vec<Scene> = (0..30).map(|i| generate_room(RoomType::Living, 5, i, false).scene).collect();
        let reference: Vec<Scene> = (30..60).map(|i| generate_room(RoomType::Living, 5, i, false).scene).collect();
        let p = category_frequencies(reference.iter(), RoomType::Living);
        let whole = category_kl(&p, &category_frequencies(pool.iter(), RoomType::Living));
        let f = ckl_floor(&pool, RoomType::Living, &p, 30, 5, 1).expect("pool is large enough");
        // Every draw is the whole pool in some order.
        assert!((f.mean - whole).abs() < 1e-12 && (f.p10 - whole).abs() < 1e-12 && (f.p90 - whole).abs() < 1e-12);
        assert!(whole > 0.0, "two different samples differ");
    }

    #[test]
    fn smaller_draws_score_worse_on_average_and_are_deterministic() {
        let pool: Vec<Scene> = (0..200).map(|i| generate_room(RoomType::Bedroom, 5, i, false).scene).collect();
        let p = category_frequencies(pool.iter(), RoomType::Bedroom);
        let small = ckl_floor(&pool, RoomType::Bedroom, &p, 20, 50, 7).unwrap();
        let large = ckl_floor(&pool, RoomType::Bedroom, &p, 150, 50, 7).unwrap();
        assert!(small.mean > large.mean, "{small:?} vs {large:?}");
        assert!(small.p10 <= small.mean && small.mean <= small.p90);
        assert_eq!(small, ckl_floor(&pool, RoomType::Bedroom, &p, 20, 50, 7).unwrap());
        assert_eq!(ckl_floor(&pool, RoomType::Bedroom, &p, 201, 5, 7), None);
    }
}
