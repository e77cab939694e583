//! The CKL an ideal generator would score: real layouts drawn from a pool (the training split), as
//! many as the generated set has, scored against the reference frequencies like any row.
//!
//! CKL compares two finite samples, so it is not 0 even for the data itself; rare categories
//! (0.1–0.3 % of objects) are missing from some draws and each missing one adds p·ln(p / 10⁻⁶).
//! This says how low a row's CKL can be expected to go; it does not score a generator.
//!
//! A second floor (`contact_floor`) credits a generator with what the conditioning tells it: every
//! test scene keeps its own contact pieces (the piece that covers most of each sit, lie or touch
//! box), and only the rest is drawn from the pool.

use super::{category_frequencies, category_kl, contact_iou, frequencies_of};
use crate::data::Rng;
use crate::human::Conditions;
use crate::scene::{Category, RoomType, Scene};
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
    let kls: Vec<f64> = (0..draws)
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
    Some(CklFloor::of(layouts, kls))
}

/// Whether each of `scene`'s objects holds one of its people: for every sit, lie or touch box, the
/// object that covers most of it (none where nothing covers it).
pub fn contact_pieces(scene: &Scene) -> Vec<bool> {
    let mut holds = vec![false; scene.objects.len()];
    for b in Conditions::contact_boxes_of(scene) {
        let cover = |o| contact_iou(&b.obox, std::slice::from_ref(o));
        let best = scene.objects.iter().enumerate().map(|(i, o)| (cover(o), i)).max_by(|x, y| x.0.total_cmp(&y.0));
        if let Some((_, i)) = best.filter(|(c, _)| *c > 0.0) {
            holds[i] = true;
        }
    }
    holds
}

/// CKL of `draws` sets that each keep every scene of `inputs` with its own contact pieces
/// ([`contact_pieces`]) and give it the other pieces of a random scene of `pool` (with replacement)
/// against `reference`; deterministic for `seed`. `None` for an empty input, pool or draw count.
pub fn contact_floor(
    inputs: &[Scene],
    pool: &[Scene],
    room: RoomType,
    reference: &[f64],
    draws: usize,
    seed: u64,
) -> Option<CklFloor> {
    if inputs.is_empty() || pool.is_empty() || draws == 0 {
        return None;
    }
    let split = |s: &Scene, held: bool| -> Vec<Category> {
        let holds = contact_pieces(s);
        s.objects.iter().zip(holds).filter(|(_, h)| *h == held).map(|(o, _)| o.category).collect()
    };
    let kept: Vec<Category> = inputs.iter().flat_map(|s| split(s, true)).collect();
    let rest: Vec<Vec<Category>> = pool.iter().map(|s| split(s, false)).collect();
    let mut rng = Rng::new(seed);
    let kls = (0..draws)
        .map(|_| {
            let mut drawn = kept.clone();
            for _ in inputs {
                drawn.extend(&rest[rng.range(0, pool.len() - 1)]);
            }
            category_kl(reference, &frequencies_of(drawn.into_iter(), room))
        })
        .collect();
    Some(CklFloor::of(inputs.len(), kls))
}

impl CklFloor {
    /// The spread of `kls`, one per draw of `layouts` layouts.
    fn of(layouts: usize, mut kls: Vec<f64>) -> CklFloor {
        let draws = kls.len();
        kls.sort_by(f64::total_cmp);
        let at = |f: f64| kls[((draws - 1) as f64 * f).round() as usize];
        CklFloor { layouts, draws, mean: kls.iter().sum::<f64>() / draws as f64, p10: at(0.1), p90: at(0.9) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::generate_room;
    use crate::scene::Action;

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
    fn the_contact_floor_keeps_the_inputs_contact_pieces_and_draws_the_rest() {
        let scenes: Vec<Scene> = (0..40).map(|i| generate_room(RoomType::Dining, 5, i, false).scene).collect();
        let (inputs, pool) = scenes.split_at(20);
        // The data's seats and beds are its contact pieces: every contact box is covered by one.
        let held: usize = inputs.iter().map(|s| contact_pieces(s).iter().filter(|h| **h).count()).sum();
        assert!(held >= 20, "{held}");
        for s in inputs {
            for (o, h) in s.objects.iter().zip(contact_pieces(s)) {
                let affords = [Action::Sit, Action::Lie, Action::Touch].iter().any(|a| o.category.affords(*a));
                assert!(!h || affords, "{:?} holds nobody's action", o.category);
            }
        }
        let p = category_frequencies(inputs.iter(), RoomType::Dining);
        // The inputs as their own pool: draws differ, deterministically for a seed.
        let f = contact_floor(inputs, inputs, RoomType::Dining, &p, 50, 3).unwrap();
        assert!(f.p10 <= f.mean && f.mean <= f.p90 && f.mean > 0.0);
        assert_eq!(f.layouts, 20);
        assert_eq!(f, contact_floor(inputs, inputs, RoomType::Dining, &p, 50, 3).unwrap());
        // A pool of empty rooms: a draw is exactly the kept pieces.
        let empty: Vec<Scene> = inputs.iter().map(|s| Scene { objects: Vec::new(), ..s.clone() }).collect();
        let only_kept = contact_floor(inputs, &empty, RoomType::Dining, &p, 1, 0).unwrap();
        let kept: Vec<Scene> = inputs
            .iter()
            .map(|s| {
                let holds = contact_pieces(s);
                let objects = s.objects.iter().zip(&holds).filter(|(_, h)| **h).map(|(o, _)| o.clone()).collect();
                Scene { objects, ..s.clone() }
            })
            .collect();
        let direct = category_kl(&p, &category_frequencies(kept.iter(), RoomType::Dining));
        assert!((only_kept.mean - direct).abs() < 1e-12, "{} vs {direct}", only_kept.mean);
        assert_eq!(contact_floor(&[], pool, RoomType::Dining, &p, 5, 0), None);
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
