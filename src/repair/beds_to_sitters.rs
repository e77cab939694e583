//! `beds_to_sitters` (ours): a bed whose sitter's knees do not pass the edge they face by 7 cm
//! (its other side at a wall, so `settle` could not move it out from under their lower legs) is
//! narrowed on their side, keeping everyone it holds on it (a sitter's box over that edge by no
//! more than repair allows) and no narrower than the category's narrowest real piece. Nothing moves.

use super::config::{HoldingConfig, RepairConfig, StepName};
use super::helpers::{bed_edge_faced, local_extent, shift};
use super::occupancy::Occupancy;
use super::pipeline::{RepairStep, StepReport, Workspace};
use crate::furniture::size_range;
use crate::human::KNEE_OVERHANG;
use crate::scene::{Action, Group, Scene};
use glam::DVec2;

/// Narrows every bed whose sitters' knees do not pass the edge they face by [`KNEE_OVERHANG`]
/// (a bed that could not move out from under their lower legs: its other side at a wall), on that
/// side, as far as keeps its other people on it and no narrower than its category's narrowest
/// real piece. Returns how many it narrowed.
fn trim_beds_to_sitters(scene: &mut Scene, people: &Occupancy, rules: &HoldingConfig) -> usize {
    let mut trimmed = 0;
    for i in 0..scene.objects.len() {
        let o = &scene.objects[i];
        let held = people.held_by(i);
        if o.category.group() != Group::Bed || !held.iter().any(|(c, _)| c.action == Action::Sit) {
            continue;
        }
        let b = o.obox();
        let half = DVec2::new(o.size[0], o.size[1]) * 0.5;
        // Per side (axis k, sign s): the cut its sitters need and the edge its people need kept.
        let mut cuts = [[0.0f64; 2]; 2];
        let mut keep = [[f64::NEG_INFINITY; 2]; 2];
        for (c, gaps) in &held {
            let (lo, hi) = local_extent(&c.obox, &b);
            // The side a sitter faces: their box may overhang its edge as repair lets it.
            let (k, ahead) = bed_edge_faced(o, c);
            let (s, sign) = if ahead { (1, 1.0) } else { (0, -1.0) };
            let sits = c.action == Action::Sit;
            for k2 in 0..2 {
                let overhang = |s2: usize| if sits && (k2, s2) == (k, s) { rules.bed_edge_overhang } else { 0.0 };
                keep[k2][0] = keep[k2][0].max(-lo[k2] - overhang(0));
                keep[k2][1] = keep[k2][1].max(hi[k2] - overhang(1));
            }
            if !sits || gaps.knees.is_empty() {
                continue;
            }
            let reach = gaps.knees.iter().map(|p| sign * b.to_local(p.extend(b.center.z)).truncate()[k]);
            let reach = reach.fold(f64::INFINITY, f64::min);
            cuts[k][s] = cuts[k][s].max(half[k] - (reach - KNEE_OVERHANG));
        }
        let o = &mut scene.objects[i];
        let mut any = false;
        for k in 0..2 {
            for s in 0..2 {
                let narrowest = size_range(o.category, k).0;
                let edge = o.size[k] * 0.5;
                let cut = cuts[k][s].min(edge - keep[k][s]).min(o.size[k] - narrowest);
                if cut > 1e-3 {
                    let (ax, ay) = o.obox().axes();
                    let axis = if k == 0 { ax } else { ay };
                    let sign = if s == 1 { 1.0 } else { -1.0 };
                    o.size[k] -= cut;
                    shift(o, -axis * (sign * cut * 0.5));
                    any = true;
                }
            }
        }
        trimmed += usize::from(any);
    }
    trimmed
}

/// The `beds_to_sitters` step.
#[derive(Debug, Clone, Copy, Default)]
pub struct BedsToSitters;

impl RepairStep for BedsToSitters {
    fn name(&self) -> StepName {
        StepName::BedsToSitters
    }

    fn run(&self, scene: &mut Scene, work: &mut Workspace<'_>, config: &RepairConfig) -> StepReport {
        StepReport::BedsToSitters { trimmed: trim_beds_to_sitters(scene, &work.people, &config.holding) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::generate_room;
    use crate::furniture::template;
    use crate::human::KNEE_OVERHANG;
    use crate::scene::RoomType;
    use crate::scene::{Category, Object};

    /// A 1.8 m double bed against the west wall of a 5 × 4 m bedroom, and a person sitting on its
    /// east side `inset` (m) in from the edge, facing east; the bed holds them.
    fn bed_with_side_sitter(inset: f64) -> (Scene, Occupancy) {
        use crate::human::{Body, Motion, sit};
        let mut scene = generate_room(RoomType::Bedroom, 3, 0, false).scene;
        scene.floor_plan.polygon = vec![[1.09, 0.0], [6.0, 0.0], [6.0, 4.0], [1.09, 4.0]];
        let bed = Object::standing("o0", Category::DoubleBed, [2.0, 1.5], [1.8, 2.1, 0.9]);
        let top = template(&bed).surface.unwrap().height;
        let body = Body::default();
        let mut m = Motion::new(body, 30.0);
        m.hold(sit(&body, DVec2::new(2.9 - inset, 1.5), top, -std::f64::consts::FRAC_PI_2), 3, Action::Sit);
        scene.humans = vec![m.into_human("h0")];
        scene.objects = vec![bed];
        let mut people = Occupancy::of(&scene, &Default::default());
        people.holders = vec![(0, 0)];
        assert_eq!(people.cond.contact_boxes.len(), 1);
        (scene, people)
    }

    #[test]
    fn a_bed_under_its_sitters_lower_legs_is_narrowed_on_their_side() {
        let (mut scene, people) = bed_with_side_sitter(0.5);
        let knee = people.gaps[0].knees.iter().map(|k| k.x).fold(f64::INFINITY, f64::min);
        assert!(knee < 2.9, "the knees are over the bed: {knee}");
        assert_eq!(trim_beds_to_sitters(&mut scene, &people, &HoldingConfig::default()), 1);
        let o = &scene.objects[0];
        let (west, east) = (o.center[0] - o.size[0] * 0.5, o.center[0] + o.size[0] * 0.5);
        assert!((east - (knee - KNEE_OVERHANG)).abs() < 1e-9, "east edge {east}, knees {knee}");
        assert!((west - 1.1).abs() < 1e-9 && o.size[1] == 2.1 && o.size[0] >= size_range(Category::DoubleBed, 0).0);
        // Still on the mattress: the support box overhangs the edge by no more than repair allows.
        let b = &people.cond.contact_boxes[0].obox;
        assert!(b.center.x + b.size.x * 0.5 - east <= HoldingConfig::default().bed_edge_overhang + 1e-9);
    }

    #[test]
    fn a_bed_whose_sitter_sits_at_its_edge_stays_as_it_is() {
        let (mut scene, people) = bed_with_side_sitter(0.15);
        let before = scene.objects.clone();
        assert_eq!(trim_beds_to_sitters(&mut scene, &people, &HoldingConfig::default()), 0);
        assert_eq!(scene.objects, before);
    }
}
