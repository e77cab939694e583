//! `narrow_off_paths` (ours): a standing piece a few centimetres over the walkers' feet (the
//! free-space mask the Col_mot metric counts) is narrowed off them, where cutting one side by at
//! most `narrowing` allows clears every covered pixel; a holder only as far as its
//! people stay on the part they must be on (a bed's foot end off a walkway beside its sleeper).

use super::config::{NarrowingConfig, RepairConfig, StepName};
use super::helpers::{keeps_its_people, narrow_by};
use super::pipeline::{RepairStep, StepReport, Workspace};
use crate::human::Conditions;
use crate::scene::{Object, Scene};
use glam::DVec2;

/// The `narrow_off_paths` step.
#[derive(Debug, Clone, Copy, Default)]
pub struct NarrowOffPaths;

impl RepairStep for NarrowOffPaths {
    fn name(&self) -> StepName {
        StepName::NarrowOffPaths
    }

    fn run(&self, scene: &mut Scene, work: &mut Workspace<'_>, config: &RepairConfig) -> StepReport {
        let people = &work.people;
        let narrowed = narrow_off_paths(scene, &people.cond, &config.narrowing, |i, o| {
            keeps_its_people(people, i, o, &config.holding)
        });
        StepReport::NarrowOffPaths { narrowed }
    }
}

/// Narrows every standing piece off the walkers' feet (the free-space mask the Col_mot metric
/// counts), where cutting one side by at most `narrowing` allows clears every
/// covered pixel and the narrowed piece `keeps` its people (`keeps(i, narrowed)`: a holder's
/// people still on the part they must be on). Returns how many it narrowed.
pub(super) fn narrow_off_paths(
    scene: &mut Scene,
    cond: &Conditions,
    limits: &NarrowingConfig,
    keeps: impl Fn(usize, &Object) -> bool,
) -> usize {
    let (window, free) = (&cond.window, &cond.free_space);
    let mut narrowed = 0;
    for (i, o) in scene.objects.iter_mut().enumerate() {
        if o.category.is_hanging() {
            continue;
        }
        let b = o.obox();
        let (lo, hi) = b.footprint_aabb();
        let (cols, rows) = window.pixel_ranges(lo, hi);
        let covered: Vec<DVec2> = rows
            .flat_map(|j| cols.clone().map(move |i| (i, j)))
            .filter(|&(i, j)| free.get(i, j) && b.footprint_contains(window.pixel_center(i, j)))
            .map(|(i, j)| b.to_local(window.pixel_center(i, j).extend(b.center.z)).truncate())
            .collect();
        if covered.is_empty() {
            continue;
        }
        // The cheapest side to cut: past the farthest covered pixel from that side, half a pixel more.
        let (ax, ay) = b.axes();
        let half = b.half().truncate();
        let margin = window.pixel() * 0.5;
        let (min, max) = covered.iter().fold((half, -half), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
        let cuts = [
            (half.x - min.x + margin, -ax),
            (max.x + half.x + margin, ax),
            (half.y - min.y + margin, -ay),
            (max.y + half.y + margin, ay),
        ];
        let (cut, dir) = cuts.into_iter().min_by(|a, b| a.0.total_cmp(&b.0)).expect("four sides");
        let mut cand = o.clone();
        if narrow_by(&mut cand, dir * cut, limits) && keeps(i, &cand) {
            *o = cand;
            narrowed += 1;
        }
    }
    narrowed
}
