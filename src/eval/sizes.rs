//! Pieces no real piece of their category resembles: the share of rooms holding a piece whose
//! width, depth or height lies further than [`REAL_SIZE_MARGIN`] outside the range of its
//! category's real pieces (`furniture::size_range`, the catalog the data is drawn from). A 5 cm
//! dining table scores well on every layout metric and passes the physics check; this is what
//! sees it. It judges sizes only, not places.

use crate::furniture::{REAL_SIZE_MARGIN, beyond_real};
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
}

const AXES: [&str; 3] = ["width", "depth", "height"];

/// A piece at the margin's edge is not beyond it: sampled sizes pass through single-precision
/// tokens, which move them by up to a fraction of a millimetre (m).
const DECODING_SLACK: f64 = 0.001;

/// The size statistics of `scenes`.
pub fn size_report(scenes: &[Scene]) -> SizeReport {
    let mut unreal: Vec<UnrealSize> = Vec::new();
    let mut odd_rooms = 0;
    for s in scenes {
        let mut seen: Vec<(Category, usize)> = Vec::new();
        for o in &s.objects {
            for axis in 0..3 {
                let unreal = beyond_real(o.category, axis, o.size[axis]) > REAL_SIZE_MARGIN + DECODING_SLACK;
                if unreal && !seen.contains(&(o.category, axis)) {
                    seen.push((o.category, axis));
                }
            }
        }
        odd_rooms += usize::from(!seen.is_empty());
        for (category, axis) in seen {
            match unreal.iter_mut().find(|u| u.category == category && u.axis == AXES[axis]) {
                Some(u) => u.rooms += 1,
                None => unreal.push(UnrealSize { category, axis: AXES[axis].into(), rooms: 1 }),
            }
        }
    }
    unreal.sort_by(|a, b| b.rooms.cmp(&a.rooms).then(a.category.cmp(&b.category)).then(a.axis.cmp(&b.axis)));
    SizeReport { unreal_rooms: if scenes.is_empty() { 0.0 } else { odd_rooms as f64 / scenes.len() as f64 }, unreal }
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
    }
}
