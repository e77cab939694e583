//! Layout metrics of SHADE's Table 1, as the anchors' released code defines them.
//!
//! - Col_mot: free-space pixels covered by object footprints / free-space pixels (256², lamps
//!   excluded); over a set of scenes, the ratio of the sums.
//! - R_out: objects whose footprint has any 256² pixel outside the floor plan / all objects.
//! - Col_obj: objects whose 3D box intersects another object's / all objects.
//! - CKL: Σ_c p_c (log(p_c + 1e-6) − log(q_c + 1e-6)), p = reference frequencies, q = generated.

use crate::geom::{Mask, intersection_volume};
use crate::human::free_space_mask;
use crate::scene::Scene;
use serde::{Deserialize, Serialize};

/// Counts of one scene, to be summed over a set.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct LayoutCounts {
    /// Free-space pixels.
    pub free_pixels: usize,
    /// Free-space pixels under a non-hanging object's footprint.
    pub covered_pixels: usize,
    /// Objects.
    pub objects: usize,
    /// Objects with a footprint pixel outside the floor plan.
    pub outside: usize,
    /// Objects whose box intersects another's.
    pub colliding: usize,
}

impl LayoutCounts {
    /// The counts of one scene.
    pub fn of(scene: &Scene) -> LayoutCounts {
        let polygon = scene.floor_plan.polygon();
        let window = scene.room_window();
        let free = free_space_mask(scene, &window);
        let outside_floor = Mask::of_polygon(&window, &polygon).inverted();
        let mut covered = Mask::new();
        let mut outside = 0;
        for o in &scene.objects {
            let fp = Mask::of_footprint(&window, &o.obox());
            if !o.category.is_hanging() {
                covered.fill_footprint(&window, &o.obox());
            }
            outside += (fp.overlap(&outside_floor) > 0) as usize;
        }
        let boxes: Vec<_> = scene.objects.iter().map(|o| o.obox()).collect();
        let colliding = (0..boxes.len())
            .filter(|&i| (0..boxes.len()).any(|j| j != i && intersection_volume(&boxes[i], &boxes[j]) > 1e-9))
            .count();
        LayoutCounts {
            free_pixels: free.count(),
            covered_pixels: free.overlap(&covered),
            objects: scene.objects.len(),
            outside,
            colliding,
        }
    }

    /// Adds another scene's counts.
    pub fn add(&mut self, o: &LayoutCounts) {
        self.free_pixels += o.free_pixels;
        self.covered_pixels += o.covered_pixels;
        self.objects += o.objects;
        self.outside += o.outside;
        self.colliding += o.colliding;
    }

    /// Col_mot.
    pub fn col_mot(&self) -> f64 {
        ratio(self.covered_pixels, self.free_pixels)
    }

    /// R_out.
    pub fn r_out(&self) -> f64 {
        ratio(self.outside, self.objects)
    }

    /// Col_obj.
    pub fn col_obj(&self) -> f64 {
        ratio(self.colliding, self.objects)
    }
}

fn ratio(a: usize, b: usize) -> f64 {
    if b == 0 { 0.0 } else { a as f64 / b as f64 }
}

/// CKL between reference frequencies `p` and generated frequencies `q`.
pub fn category_kl(p: &[f64], q: &[f64]) -> f64 {
    p.iter().zip(q).map(|(&a, &b)| a * ((a + 1e-6).ln() - (b + 1e-6).ln())).sum()
}

/// Category frequencies of a set of scenes in the room type's one-hot order.
pub fn category_frequencies<'a>(scenes: impl Iterator<Item = &'a Scene>, room: crate::scene::RoomType) -> Vec<f64> {
    frequencies_of(scenes.flat_map(|s| s.objects.iter().map(|o| o.category)), room)
}

/// Frequencies of a list of categories in the room type's one-hot order (categories of other room
/// types left out).
pub fn frequencies_of(
    categories: impl Iterator<Item = crate::scene::Category>,
    room: crate::scene::RoomType,
) -> Vec<f64> {
    let mut counts = vec![0usize; room.categories().len()];
    for i in categories.filter_map(|c| room.category_index(c)) {
        counts[i] += 1;
    }
    let total: usize = counts.iter().sum();
    counts.iter().map(|&c| ratio(c, total)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::human::{Body, Motion, stand};
    use crate::scene::{Action, Category, FloorPlan, Object, RoomType};
    use glam::DVec2;

    #[test]
    fn hand_computed_counts() {
        let mut s = Scene::new(
            RoomType::Bedroom,
            FloorPlan { polygon: vec![[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]], height: 2.7 },
        );
        let obj = |id: &str, c: Category, x: f64, y: f64| Object {
            id: id.into(),
            category: c,
            center: [x, y, 0.4],
            size: [1.0, 1.0, 0.8],
            yaw: 0.0,
        };
        // Two overlapping cabinets, one half outside the floor, one lamp over a standing person.
        s.objects.push(obj("o0", Category::Cabinet, 1.0, 1.0));
        s.objects.push(obj("o1", Category::Cabinet, 1.5, 1.0));
        s.objects.push(obj("o2", Category::Wardrobe, 4.0, 3.0));
        let mut lamp = obj("o3", Category::PendantLamp, 3.0, 1.0);
        lamp.center[2] = 2.3;
        s.objects.push(lamp);
        let body = Body::default();
        let mut m = Motion::new(body, 30.0);
        m.hold(stand(&body, DVec2::new(3.0, 1.0), 0.0), 3, Action::Stand);
        s.humans.push(m.into_human("h0"));
        let c = LayoutCounts::of(&s);
        assert_eq!((c.objects, c.outside, c.colliding), (4, 1, 2));
        assert_eq!(c.r_out(), 0.25);
        assert_eq!(c.col_obj(), 0.5);
        // The person stands under the lamp only: lamps do not count.
        assert!(c.free_pixels > 0);
        assert_eq!(c.col_mot(), 0.0);
        // A cabinet on the person's feet covers all of them.
        s.objects.push(obj("o4", Category::Cabinet, 3.0, 1.1));
        let c = LayoutCounts::of(&s);
        assert_eq!(c.covered_pixels, c.free_pixels);
        assert_eq!(c.col_mot(), 1.0);
        assert!((category_kl(&[0.5, 0.5], &[0.5, 0.5])).abs() < 1e-12);
        // By hand: 0.5 ln(0.5/0.25) + 0.5 ln(0.5/0.75) = 0.1438.
        assert!((category_kl(&[0.5, 0.5], &[0.25, 0.75]) - 0.143841).abs() < 1e-5);
    }
}
