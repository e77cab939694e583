//! J_t (ours): a diner's table reaches over their knees. Every real room of the data that seats a
//! person on a dining chair stands a dining table in front of them, its top over their knees (the
//! data places a dining table with its chairs around it, 4 cm off its edge); the sampled layouts
//! left about one diner in five at a table that stops short of them (docs/RESULTS.md, "Diners at
//! their table"). The term measures, for each person seated on such a seat, how far their knees
//! are from the footprint of the nearest table of the seat's kind, and draws that table towards
//! them and grows it.
//!
//! It knows which seats come with a table ([`table_of_seat`]) and where a sitter's knees are; not
//! what a table is for anyone else, and it never makes a table: a diner whose layout has none
//! within [`GuidanceConfig::table_reach`](super::GuidanceConfig::table_reach) (a lone dining
//! chair, as some real living rooms have) is left as they are.

use super::guidance::{GuidedObject, ObjectGradient, distance_outside, excess_outside};
use crate::human::ContactBox;
use crate::scene::{Category, Scene};
use glam::DVec2;

/// The table a seat of `category` stands at in the data, if it always stands at one: a dining
/// chair at a dining table (every diner of the val dining rooms, 272 of 272). A bedroom's chair is
/// not: none of the 20 people seated on one in the val bedrooms has a desk over their knees.
pub fn table_of_seat(category: Category) -> Option<Category> {
    match category {
        Category::DiningChair => Some(Category::DiningTable),
        _ => None,
    }
}

/// Where the sitter of a sit box has their knees on the floor plan ([`crate::human::knees_of`]).
pub fn knees_of(scene: &Scene, b: &ContactBox) -> Option<DVec2> {
    crate::human::knees_of(scene, b).map(|k| k.truncate())
}

/// J_t: Σ over pieces that seat someone at a table ([`table_of_seat`]) and over the knees of the
/// people they seat (`knees[i]`: those of the boxes piece i is anchored to) of the distance (m)
/// from the knees to the footprint of the nearest piece of the table's category, where that
/// distance is above 0 and at most `reach`, with its gradient on that table's centre and on its
/// width and depth (the edge facing the knees moves by half of what the size grows): a table
/// between two diners who sit farther apart than it is deep reaches both by growing.
pub fn tables_short_of_knees(objects: &[GuidedObject], knees: &[Vec<DVec2>], reach: f64) -> (f64, Vec<ObjectGradient>) {
    let mut total = 0.0;
    let mut grads = vec![[0.0; 7]; objects.len()];
    for (seat, points) in objects.iter().zip(knees) {
        let Some(table) = table_of_seat(seat.category) else { continue };
        for &p in points {
            let nearest = objects
                .iter()
                .enumerate()
                .filter(|(_, o)| o.category == table)
                .map(|(j, o)| (j, distance_outside(o, p)))
                .min_by(|a, b| a.1.0.total_cmp(&b.1.0));
            let Some((j, (d, toward))) = nearest else { continue };
            if d > 0.0 && d <= reach {
                total += d;
                let excess = excess_outside(&objects[j], p);
                grads[j][0] -= toward.x;
                grads[j][1] -= toward.y;
                grads[j][3] -= 0.5 * excess.x.abs() / d;
                grads[j][4] -= 0.5 * excess.y.abs() / d;
            }
        }
    }
    (total, grads)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chair(x: f64, y: f64) -> GuidedObject {
        GuidedObject::standing(Category::DiningChair, x, y, [0.5, 0.5, 0.9], 0.0)
    }

    fn table(x: f64, y: f64) -> GuidedObject {
        GuidedObject::standing(Category::DiningTable, x, y, [1.4, 0.9, 0.75], 0.0)
    }

    #[test]
    fn a_table_short_of_the_knees_is_pulled_towards_them_by_the_gap() {
        // The table's near edge is at y = 1.55; knees at y = 1.4 fall 15 cm short of it.
        let objects = [chair(2.0, 1.0), table(2.0, 2.0)];
        let knees = [vec![DVec2::new(2.0, 1.4)], vec![]];
        let (j, grads) = tables_short_of_knees(&objects, &knees, 0.5);
        assert!((j - 0.15).abs() < 1e-12, "{j}");
        assert_eq!(grads[0], [0.0; 7], "the seat itself is not moved");
        assert_eq!(grads[1][..2], [0.0, 1.0], "moving the table towards −y shortens the gap at rate 1");
        assert_eq!(grads[1][3..], [0.0, -0.5, 0.0, 0.0], "growing its depth, at half that rate");
        // Finite differences of the value agree, for the centre and for the depth.
        let moved = |dy: f64| tables_short_of_knees(&[objects[0], table(2.0, 2.0 + dy)], &knees, 0.5).0;
        assert!(((moved(1e-4) - moved(-1e-4)) / 2e-4 - 1.0).abs() < 1e-6);
        let deeper = |dd: f64| {
            let t = GuidedObject::standing(Category::DiningTable, 2.0, 2.0, [1.4, 0.9 + dd, 0.75], 0.0);
            tables_short_of_knees(&[objects[0], t], &knees, 0.5).0
        };
        assert!(((deeper(1e-4) - deeper(-1e-4)) / 2e-4 + 0.5).abs() < 1e-6);
    }

    #[test]
    fn covered_knees_far_tables_other_seats_and_no_table_cost_nothing() {
        let knees = [vec![DVec2::new(2.0, 1.4)], vec![]];
        let over = [chair(2.0, 1.0), table(2.0, 1.8)];
        assert_eq!(tables_short_of_knees(&over, &knees, 0.5).0, 0.0, "the top is over the knees");
        let far = [chair(2.0, 1.0), table(2.0, 2.5)];
        assert_eq!(tables_short_of_knees(&far, &knees, 0.5).0, 0.0, "65 cm short: beyond the reach");
        assert!(tables_short_of_knees(&far, &knees, 0.7).0 > 0.6);
        let sofa = GuidedObject::standing(Category::MultiSeatSofa, 2.0, 1.0, [2.0, 0.9, 0.8], 0.0);
        assert_eq!(tables_short_of_knees(&[sofa, table(2.0, 2.0)], &knees, 0.5).0, 0.0);
        assert_eq!(tables_short_of_knees(&[chair(2.0, 1.0)], &knees[..1], 0.5).0, 0.0);
    }

    #[test]
    fn only_the_nearest_table_is_pulled() {
        let objects = [chair(2.0, 1.0), table(2.0, 2.0), table(4.0, 1.2)];
        let (j, grads) = tables_short_of_knees(&objects, &[vec![DVec2::new(2.0, 1.4)], vec![], vec![]], 0.5);
        assert!((j - 0.15).abs() < 1e-12);
        assert_eq!(grads[2], [0.0; 7]);
    }
}
