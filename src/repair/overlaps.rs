//! `overlaps`, the last repair step (ours): overlaps the moves could not undo, because both pieces are
//! wedged between walls and neighbours, are resolved by narrowing or, failing that, removing a piece.
//!
//! - Narrowing: where the shortest footprint separation of a pair runs along one of the smaller
//!   piece's own axes and is at most 10 cm and a quarter of its size there, that piece loses the
//!   overlap (and 5 mm) on the side facing the other and keeps its far side where it was.
//! - Removing: a pair that still overlaps loses its smaller piece — never one in use (`in_use`: it
//!   holds a person's contact, someone sits at it, or it is the room's last bed, dining table or
//!   sofa; a pair both in use is left as it is). These are mostly the model's duplicates (two
//!   nightstands, two beds in one place) and pieces squeezed into a gap too small for them; a
//!   dining table that touches a bookshelf is not one of them.
//!
//! It does not move anything: placement is the rounds' job.

use super::config::LeftOutConfig;
use super::config::{RepairConfig, StepName};
use super::helpers::{footprint_separations, narrow_by};
use super::in_use::in_use;
use super::pipeline::{RepairStep, StepReport, Workspace};
use crate::geom::intersection_volume;
use crate::human::ContactBox;
use crate::scene::Scene;

/// What resolving overlaps changed.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct OverlapReport {
    /// Pieces narrowed.
    pub narrowed: usize,
    /// Pieces removed.
    pub removed: usize,
}

/// Narrows or removes pieces until no two overlap, sparing the pieces in use (`holds[i]` marks
/// those holding a person's contact; `contacts` are the people's boxes): they may only be narrowed.
fn resolve_overlaps(
    scene: &mut Scene,
    holds: &[bool],
    contacts: &[ContactBox],
    config: &RepairConfig,
) -> OverlapReport {
    let mut report = OverlapReport::default();
    let mut holds = holds.to_vec();
    for (i, j) in overlapping_pairs(scene) {
        if overlap(scene, i, j) && narrow_apart(scene, i, j, config) {
            report.narrowed += 1;
        }
    }
    while let Some(victim) = overlapping_pairs(scene)
        .into_iter()
        .find_map(|(i, j)| removable(scene, &holds, contacts, &config.left_out, i, j))
    {
        scene.objects.remove(victim);
        holds.remove(victim);
        report.removed += 1;
    }
    report
}

fn overlap(scene: &Scene, i: usize, j: usize) -> bool {
    intersection_volume(&scene.objects[i].obox(), &scene.objects[j].obox()) > 1e-9
}

/// Every overlapping pair (i < j), in index order.
fn overlapping_pairs(scene: &Scene) -> Vec<(usize, usize)> {
    let n = scene.objects.len();
    (0..n).flat_map(|i| (i + 1..n).map(move |j| (i, j))).filter(|&(i, j)| overlap(scene, i, j)).collect()
}

fn volume(scene: &Scene, i: usize) -> f64 {
    scene.objects[i].size.iter().product()
}

/// The smaller of the pair that is not in use (the other one if the smaller is).
fn removable(
    scene: &Scene,
    holds: &[bool],
    contacts: &[ContactBox],
    cfg: &LeftOutConfig,
    i: usize,
    j: usize,
) -> Option<usize> {
    let (small, large) = if volume(scene, i) <= volume(scene, j) { (i, j) } else { (j, i) };
    [small, large].into_iter().find(|&k| !in_use(scene, k, holds, contacts, cfg))
}

/// Narrows the smaller piece of an overlapping pair out of the other, if a small cut along one of
/// its own axes does it. Returns whether it did.
fn narrow_apart(scene: &mut Scene, i: usize, j: usize, config: &RepairConfig) -> bool {
    let (small, other) = if volume(scene, i) <= volume(scene, j) { (i, j) } else { (j, i) };
    let (a, b) = (scene.objects[small].obox(), scene.objects[other].obox());
    let Some(&m) = footprint_separations(&a, &b, config.gap).first() else { return false };
    let (ax, ay) = a.axes();
    // Only along its own axes (the separation already keeps `gap` between the two).
    let along_own = [ax, ay].iter().any(|axis| axis.dot(m).abs() > (1.0 - 1e-9) * m.length());
    along_own && narrow_by(&mut scene.objects[small], m, &config.narrowing) && !overlap(scene, small, other)
}

/// The `overlaps` step.
#[derive(Debug, Clone, Copy, Default)]
pub struct Overlaps;

impl RepairStep for Overlaps {
    fn name(&self) -> StepName {
        StepName::Overlaps
    }

    fn run(&self, scene: &mut Scene, work: &mut Workspace<'_>, config: &RepairConfig) -> StepReport {
        let (people, holds) = work.holds(scene.objects.len());
        let r = resolve_overlaps(scene, holds, &people.cond.contact_boxes, config);
        StepReport::Overlaps { narrowed: r.narrowed, removed: r.removed }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Category, Object, RoomType};

    fn scene(objects: Vec<Object>) -> Scene {
        let mut s = crate::data::generate_room(RoomType::Bedroom, 1, 0, false).scene;
        s.objects = objects;
        s
    }

    #[test]
    fn a_small_overlap_narrows_the_smaller_piece_on_its_near_side() {
        // A 0.5 m nightstand reaching 4 cm into a bed's side.
        let mut s = scene(vec![
            Object::standing("bed", Category::DoubleBed, [0.0, 0.0], [1.6, 2.0, 0.5]),
            Object::standing("n", Category::Nightstand, [1.01, 0.8], [0.5, 0.4, 0.5]),
        ]);
        let r = resolve_overlaps(&mut s, &[false, false], &[], &RepairConfig::default());
        assert_eq!(r, OverlapReport { narrowed: 1, removed: 0 });
        let n = &s.objects[1];
        // Its far side stays at x = 1.26; its near side moves to 0.805 (4.5 cm cut).
        assert!((n.center[0] + n.size[0] * 0.5 - 1.26).abs() < 1e-12);
        assert!((n.center[0] - n.size[0] * 0.5 - 0.805).abs() < 1e-12, "{n:?}");
        assert_eq!(s.objects[0], Object::standing("bed", Category::DoubleBed, [0.0, 0.0], [1.6, 2.0, 0.5]));
    }

    #[test]
    fn a_dining_room_keeps_its_only_table_and_loses_the_bookshelf_it_touches() {
        // The table (0.80 m³) is smaller than the tall bookshelf (0.83 m³) it overlaps by 20 cm.
        let mut s = crate::data::generate_room(RoomType::Dining, 1, 0, false).scene;
        s.objects = vec![
            Object::standing("table", Category::DiningTable, [0.0, 0.0], [1.22, 0.84, 0.78]),
            Object::standing("shelf", Category::Bookshelf, [0.0, 0.41], [1.16, 0.38, 1.89]),
        ];
        let r = resolve_overlaps(&mut s, &[false, false], &[], &RepairConfig::default());
        assert_eq!(r.removed, 1);
        assert_eq!(s.objects.iter().map(|o| o.id.as_str()).collect::<Vec<_>>(), ["table"]);
    }

    #[test]
    fn a_duplicate_goes_unless_it_holds_someone() {
        let twins = || {
            scene(vec![
                Object::standing("a", Category::Nightstand, [0.0, 0.0], [0.5, 0.4, 0.5]),
                Object::standing("b", Category::Nightstand, [0.05, 0.02], [0.45, 0.4, 0.5]),
                Object::standing("far", Category::Wardrobe, [3.0, 3.0], [1.0, 0.6, 2.0]),
            ])
        };
        let mut s = twins();
        assert_eq!(
            resolve_overlaps(&mut s, &[false, false, false], &[], &RepairConfig::default()),
            OverlapReport { narrowed: 0, removed: 1 }
        );
        assert_eq!(s.objects.iter().map(|o| o.id.as_str()).collect::<Vec<_>>(), ["a", "far"]);
        // The smaller one holds a contact: the larger goes.
        let mut s = twins();
        resolve_overlaps(&mut s, &[false, true, false], &[], &RepairConfig::default());
        assert_eq!(s.objects.iter().map(|o| o.id.as_str()).collect::<Vec<_>>(), ["b", "far"]);
        // Both hold contacts: both stay.
        let mut s = twins();
        assert_eq!(
            resolve_overlaps(&mut s, &[true, true, false], &[], &RepairConfig::default()),
            OverlapReport::default()
        );
        assert_eq!(s.objects.len(), 3);
    }
}
