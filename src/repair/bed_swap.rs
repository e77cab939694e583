//! Swapping a double bed that stands in people's way for a single bed, or narrowing it to the
//! narrowest real double bed where that is enough (ours, the `bed_swap` repair step).
//!
//! The models put double beds where the data has narrower ones, and a double bed across a walkway
//! was the commonest way a walker walked into a bed. This step only swaps, after `settle`'s rounds, and keeps
//! everything else.

use super::completion::median_size;
use super::config::{BedSwapConfig, RepairConfig, StepName};
use super::helpers::shift;
use super::occupancy::Occupancy;
use super::pipeline::{RepairStep, StepReport, Workspace};
use crate::furniture::size_range;
use crate::measure::contact_iou;
use crate::scene::{Category, Object, Scene};

/// Swaps each double bed still in people's way (at least `cfg.blocked_area`; below that, swapping bought few clean
/// rooms and cost CKL: more single beds than the data has) after the rounds
/// (`Clearance`) for a single bed of the median real width, cut from the side where it is in the
/// way, where that clears part of the way (or narrows it to the narrowest real double bed, where
/// that clears all of it), keeps what it holds as covered (at least `cfg.keep_cover` of it) and
/// it holds at most one person. Returns how many it swapped.
fn single_beds_off_paths(scene: &mut Scene, people: &Occupancy, cfg: &BedSwapConfig) -> usize {
    let width = median_size(Category::SingleBed)[0];
    let mut swapped = 0;
    for i in 0..scene.objects.len() {
        let o = &scene.objects[i];
        if o.category != Category::DoubleBed || o.size[0] <= width {
            continue;
        }
        let held = people.held_by(i);
        if held.len() > 1 {
            continue;
        }
        let b = o.obox();
        let blocked = people.clearance.blocked(&b, true);
        if (blocked.len() as f64) * people.clearance.window().pixel_area() < cfg.blocked_area {
            continue;
        }
        // Cut from the side the blocked pixels are on (local x).
        let (ax, _) = b.axes();
        let side = blocked.iter().map(|p| (*p - b.center.truncate()).dot(ax)).sum::<f64>().signum();
        let cut_to = |category: Category, width: f64| {
            let mut cut = o.clone();
            cut.category = category;
            cut.size[0] = width;
            shift(&mut cut, -ax * side * (o.size[0] - width) * 0.5);
            cut
        };
        let covered = |x: &Object| held.iter().map(|(c, _)| contact_iou(&c.obox, std::slice::from_ref(x))).sum::<f64>();
        let keeps_covered = |x: &Object| covered(x) >= cfg.keep_cover * covered(o);
        // A double bed as narrow as the narrowest real one, where that clears the whole way: the
        // data's share of double beds stays.
        let narrowest = cut_to(Category::DoubleBed, size_range(Category::DoubleBed, 0).0.min(o.size[0]));
        if people.clearance.blocked(&narrowest.obox(), true).is_empty() && keeps_covered(&narrowest) {
            scene.objects[i] = narrowest;
            swapped += 1;
            continue;
        }
        let single = cut_to(Category::SingleBed, width);
        let clears = people.clearance.blocked(&single.obox(), true).len() < blocked.len();
        if clears && keeps_covered(&single) {
            scene.objects[i] = single;
            swapped += 1;
        }
    }
    swapped
}

/// The `bed_swap` step.
#[derive(Debug, Clone, Copy, Default)]
pub struct BedSwap;

impl RepairStep for BedSwap {
    fn name(&self) -> StepName {
        StepName::BedSwap
    }

    fn run(&self, scene: &mut Scene, work: &mut Workspace<'_>, config: &RepairConfig) -> StepReport {
        StepReport::BedSwap { swapped: single_beds_off_paths(scene, &work.people, &config.bed_swap) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::generate_room;
    use crate::scene::{Action, RoomType};

    #[test]
    fn a_double_bed_across_a_walkway_becomes_a_single_bed_cut_from_that_side() {
        let mut scene = generate_room(RoomType::Bedroom, 3, 0, false).scene;
        scene.humans.retain(|h| h.actions.iter().all(|a| a.action == Action::Walk));
        let h = &scene.humans[0];
        let p = h.joint_at(h.frames.len() / 2, h.skeleton.joint("pelvis").unwrap()).truncate();
        // 1.8 m wide, its +x side 0.3 m past a walker's pelvis.
        let bed = Object {
            id: "o0".into(),
            category: Category::DoubleBed,
            center: [p.x + 0.3 - 0.9, p.y, 0.25],
            size: [1.8, 2.0, 0.5],
            yaw: 0.0,
        };
        scene.objects = vec![bed.clone()];
        let people = Occupancy::of(&scene, &Default::default());
        let clearance = &people.clearance;
        let before = clearance.blocked(&bed.obox(), true).len();
        assert_eq!(single_beds_off_paths(&mut scene, &people, &BedSwapConfig::default()), 1);
        let o = &scene.objects[0];
        assert_eq!((o.category, o.size[0]), (Category::SingleBed, median_size(Category::SingleBed)[0]));
        assert!((o.center[0] - o.size[0] * 0.5 - (bed.center[0] - 0.9)).abs() < 1e-9, "the −x side stays: {o:?}");
        assert!(clearance.blocked(&o.obox(), true).len() < before);
    }

    #[test]
    fn a_double_bed_a_little_in_the_way_is_narrowed_and_stays_a_double_bed() {
        let mut scene = generate_room(RoomType::Bedroom, 3, 0, false).scene;
        scene.humans.retain(|h| h.actions.iter().all(|a| a.action == Action::Walk));
        let h = &scene.humans[0];
        let p = h.joint_at(h.frames.len() / 2, h.skeleton.joint("pelvis").unwrap()).truncate();
        scene.objects.clear();
        let people = Occupancy::of(&scene, &Default::default());
        let clearance = &people.clearance;
        // A 1.8 m wide bed west of a walker: moved west until clear of the way, then back by 0.25 m,
        // into it by less than the 0.483 m that cutting it to the narrowest real double bed
        // (1.317 m) takes off its +x side.
        let bed_at = |side: f64| Object {
            id: "o0".into(),
            category: Category::DoubleBed,
            center: [side - 0.9, p.y, 0.25],
            size: [1.8, 2.0, 0.5],
            yaw: 0.0,
        };
        let clear =
            (0..100).map(|k| p.x - 0.05 * k as f64).find(|&x| clearance.blocked(&bed_at(x).obox(), true).is_empty());
        let bed = bed_at(clear.unwrap() + 0.25);
        let blocked = clearance.blocked(&bed.obox(), true).len() as f64 * clearance.window().pixel_area();
        assert!(blocked >= BedSwapConfig::default().blocked_area, "{blocked}");
        scene.objects = vec![bed.clone()];
        assert_eq!(single_beds_off_paths(&mut scene, &people, &BedSwapConfig::default()), 1);
        let o = &scene.objects[0];
        let narrowest = size_range(Category::DoubleBed, 0).0;
        assert!((narrowest - 1.317).abs() < 1e-9, "catalog.csv's narrowest double bed: {narrowest}");
        assert_eq!((o.category, o.size[0]), (Category::DoubleBed, narrowest));
        assert!((o.center[0] - o.size[0] * 0.5 - (bed.center[0] - 0.9)).abs() < 1e-9, "the −x side stays: {o:?}");
        assert!(clearance.blocked(&o.obox(), true).is_empty());
    }
}
