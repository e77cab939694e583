//! Pieces no real piece of their category resembles: the share of rooms holding a piece whose
//! width, depth or height lies further than [`REAL_SIZE_MARGIN`] outside the range of its
//! category's real pieces (`furniture::size_range`, the catalog the data is drawn from). A 5 cm
//! dining table scores well on every layout metric and passes the physics check; this is what
//! sees it. It judges sizes only, not places.
//!
//! The margin is wide, and the guidance's own bound (`GuidanceConfig::real_sizes`) is as wide, so
//! a piece the guidance resized as far as it may is not counted there. `odd_pieces` is the finer
//! measure: the share of all pieces with a size the procedural data never draws for their category
//! (`furniture::drawn_range`: the real range widened by the data's few per cent of jitter), 0 for
//! the data itself.

use crate::furniture::{REAL_SIZE_MARGIN, beyond_real, drawn_range};
use crate::scene::{Category, Scene};
use serde::{Deserialize, Serialize};

/// A category and axis on which generated pieces left the real range, and in how many rooms.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UnrealSize {
    /// The category.
    pub category: Category,
    /// `width`, `depth` or `height`.
    pub axis: String,
    /// Rooms with such a piece.
    pub rooms: usize,
}

/// The size statistics of a set of generated rooms.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SizeReport {
    /// Share of the rooms with a piece beyond its category's real sizes by more than the margin.
    pub unreal_rooms: f64,
    /// The (category, axis) pairs behind it, most rooms first (ties by category, then axis).
    pub unreal: Vec<UnrealSize>,
    /// Share of all pieces with a width, depth or height outside the sizes the data draws for
    /// their category (`furniture::drawn_range`); 0 without pieces.
    #[serde(default)]
    pub odd_pieces: f64,
}

const AXES: [&str; 3] = ["width", "depth", "height"];

/// A piece at the margin's edge is not beyond it: sampled sizes pass through single-precision
/// tokens, which move them by up to a fraction of a millimetre (m).
const DECODING_SLACK: f64 = 0.001;

/// The size statistics of `scenes`.
pub fn size_report(scenes: &[Scene]) -> SizeReport {
    let mut unreal: Vec<UnrealSize> = Vec::new();
    let (mut unreal_rooms, mut pieces, mut odd_pieces) = (0usize, 0usize, 0usize);
    for s in scenes {
        let mut seen: Vec<(Category, usize)> = Vec::new();
        for o in &s.objects {
            let mut odd = false;
            for axis in 0..3 {
                let (lo, hi) = drawn_range(o.category, axis);
                odd |= o.size[axis] < lo - DECODING_SLACK || o.size[axis] > hi + DECODING_SLACK;
                let unreal = beyond_real(o.category, axis, o.size[axis]) > REAL_SIZE_MARGIN + DECODING_SLACK;
                if unreal && !seen.contains(&(o.category, axis)) {
                    seen.push((o.category, axis));
                }
            }
            pieces += 1;
            odd_pieces += usize::from(odd);
        }
        unreal_rooms += usize::from(!seen.is_empty());
        for (category, axis) in seen {
            match unreal.iter_mut().find(|u| u.category == category && u.axis == AXES[axis]) {
                Some(u) => u.rooms += 1,
                None => unreal.push(UnrealSize { category, axis: AXES[axis].into(), rooms: 1 }),
            }
        }
    }
    unreal.sort_by(|a, b| b.rooms.cmp(&a.rooms).then(a.category.cmp(&b.category)).then(a.axis.cmp(&b.axis)));
    let share = |n: usize, of: usize| if of == 0 { 0.0 } else { n as f64 / of as f64 };
    SizeReport { unreal_rooms: share(unreal_rooms, scenes.len()), unreal, odd_pieces: share(odd_pieces, pieces) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::furniture::size_range;
    use crate::scene::{FloorPlan, Object, RoomType};

    #[test]
    fn a_flat_dining_table_is_unreal_and_real_pieces_are_not() {
        let floor = FloorPlan { polygon: vec![[0.0, 0.0], [6.0, 0.0], [6.0, 5.0], [0.0, 5.0]], height: 2.7 };
        let (lo, hi) = size_range(Category::DiningTable, 2);
        let table = |h: f64| {
            let mut s = Scene::new(RoomType::Dining, floor.clone());
            s.objects.push(Object::standing("o0", Category::DiningTable, [3.0, 2.5], [1.6, 0.9, h]));
            s
        };
        // Real, at the margin's edge, and a 5 cm table.
        let scenes = [table((lo + hi) * 0.5), table(lo - REAL_SIZE_MARGIN + 0.01), table(0.05)];
        let r = size_report(&scenes);
        assert!((r.unreal_rooms - 1.0 / 3.0).abs() < 1e-12, "{r:?}");
        assert_eq!(r.unreal, vec![UnrealSize { category: Category::DiningTable, axis: "height".into(), rooms: 1 }]);
        assert!((beyond_real(Category::DiningTable, 2, 0.05) - (lo - 0.05)).abs() < 1e-12);
        assert_eq!(size_report(&[]).unreal_rooms, 0.0);
        // The table at the margin's edge and the flat one have sizes the data never draws.
        assert!((r.odd_pieces - 2.0 / 3.0).abs() < 1e-12, "{r:?}");
        assert_eq!(size_report(&[]).odd_pieces, 0.0);
    }

    #[test]
    fn the_sizes_the_data_draws_are_not_odd_and_just_beyond_them_are() {
        let floor = FloorPlan { polygon: vec![[0.0, 0.0], [6.0, 0.0], [6.0, 5.0], [0.0, 5.0]], height: 2.7 };
        let mut rng = crate::data::Rng::new(3);
        let mut drawn = Scene::new(RoomType::Bedroom, floor.clone());
        for i in 0..400 {
            let category = [Category::Wardrobe, Category::Nightstand, Category::DoubleBed, Category::Cabinet][i % 4];
            let size = crate::data::layout::real_size(category, &mut rng);
            drawn.objects.push(Object::standing(format!("o{i}"), category, [3.0, 2.5], size.to_array()));
        }
        assert_eq!(size_report(std::slice::from_ref(&drawn)).odd_pieces, 0.0);
        // A wardrobe 3 cm shallower than the shallowest the data draws.
        let (lo, _) = drawn_range(Category::Wardrobe, 1);
        let (wlo, _) = size_range(Category::Wardrobe, 1);
        assert!((lo - (wlo * 0.93 - 0.005)).abs() < 1e-12);
        let mut odd = Scene::new(RoomType::Bedroom, floor);
        odd.objects.push(Object::standing("o0", Category::Wardrobe, [3.0, 2.5], [1.2, lo - 0.03, 2.0]));
        odd.objects.push(Object::standing("o1", Category::Wardrobe, [1.0, 2.5], [1.2, lo + 0.03, 2.0]));
        let r = size_report(&[odd]);
        assert!((r.odd_pieces - 0.5).abs() < 1e-12 && r.unreal_rooms == 0.0, "{r:?}");
    }
}
