//! Layout metrics of SHADE's Table 1, as the anchors' released code defines them.
//!
//! - Col_mot: free-space pixels covered by object footprints / free-space pixels (256², lamps
//!   excluded); over a set of scenes, the ratio of the sums.
//! - R_out: objects whose footprint has any 256² pixel outside the floor plan / all objects.
//! - Col_obj: objects whose 3D box intersects another object's / all objects.
//! - CKL: Σ_c p_c (log(p_c + 1e-6) − log(q_c + 1e-6)), p = reference frequencies, q = generated.

use crate::geom::{Mask, intersection_volume};
use crate::human::free_space_mask;
use crate::scene::{Category, RoomType, Scene};
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
    p.iter().zip(q).map(|(&a, &b)| ckl_term(a, b)).sum()
}

/// One category's term of [`category_kl`]: p (log(p + 1e-6) − log(q + 1e-6)).
fn ckl_term(p: f64, q: f64) -> f64 {
    p * ((p + 1e-6).ln() - (q + 1e-6).ln())
}

/// One category's share of the pieces in the reference and in a generated set, and its term of
/// CKL (positive where the set draws it less often than the reference).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CategoryShare {
    /// The category.
    pub category: Category,
    /// Its share of the reference's pieces.
    pub reference: f64,
    /// Its share of the generated pieces.
    pub generated: f64,
    /// Its term of CKL; the terms of a room type's categories sum to CKL.
    pub ckl_term: f64,
}

/// [`CategoryShare`] of every category of `room` that the reference (frequencies `p`) or the
/// generated set (`q`, both in the room type's one-hot order) has, largest CKL term first (ties
/// in the room type's order).
pub fn category_shares(p: &[f64], q: &[f64], room: RoomType) -> Vec<CategoryShare> {
    let mut shares: Vec<CategoryShare> = room
        .categories()
        .iter()
        .zip(p.iter().zip(q))
        .filter(|(_, (a, b))| **a > 0.0 || **b > 0.0)
        .map(|(&category, (&reference, &generated))| CategoryShare {
            category,
            reference,
            generated,
            ckl_term: ckl_term(reference, generated),
        })
        .collect();
    shares.sort_by(|a, b| b.ckl_term.total_cmp(&a.ckl_term));
    shares
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

    #[test]
    fn ckl_terms_by_category_sum_to_ckl_largest_first() {
        let room = RoomType::Dining;
        let n = room.categories().len();
        // The reference: half dining chairs, a quarter each dining tables and lamps (a category
        // the generated set never draws); the generated set: 3/4 chairs, 1/4 tables.
        let share = |pairs: &[(Category, f64)]| -> Vec<f64> {
            let mut v = vec![0.0; n];
            for &(c, f) in pairs {
                v[room.category_index(c).unwrap()] = f;
            }
            v
        };
        let (chair, table, lamp) = (Category::DiningChair, Category::DiningTable, Category::PendantLamp);
        let p = share(&[(chair, 0.5), (table, 0.25), (lamp, 0.25)]);
        let q = share(&[(chair, 0.75), (table, 0.25)]);
        let shares = category_shares(&p, &q, room);
        // Only the three categories either set has, the one never drawn first: 0.25 ln(0.25 / 1e-6)
        // by hand is 3.108 (the 1e-6 in both logs: 3.1073).
        let order: Vec<Category> = shares.iter().map(|s| s.category).collect();
        assert_eq!(order, vec![lamp, table, chair]);
        assert!((shares[0].ckl_term - 3.1073).abs() < 1e-3, "{}", shares[0].ckl_term);
        assert!(shares[1].ckl_term.abs() < 1e-12);
        assert!((shares[2].ckl_term - 0.5 * (0.5f64 / 0.75).ln()).abs() < 1e-5);
        assert_eq!((shares[2].reference, shares[2].generated), (0.5, 0.75));
        let sum: f64 = shares.iter().map(|s| s.ckl_term).sum();
        assert!((sum - category_kl(&p, &q)).abs() < 1e-12);
    }
}
