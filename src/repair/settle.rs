//! `settle`, the first repair step (ours): rounds of small, exact geometric corrections of what
//! the model's few-centimetre imprecision leaves undone.
//!
//! Each contact box (sit, lie, touch) is given to an object that affords its action: best covered
//! pairs first, then nearest within 2 m; a chair or stool holds one person, a sofa or bed one per
//! 55 cm of its length, tables and cabinets any number of touches. A box no object can hold gets a
//! new piece of real furniture (`completion`). A chair, stool or sofa is turned to face like the
//! first sitter it holds (its front the way they face), a sofa to lie along its sleeper, a bed a
//! quarter turn where its sitter faces along it (the data seats people on a bed's side, against the
//! edge they face); then every piece is turned square to the walls (the longest wall's direction
//! plus quarter turns; every piece of the data stands so, and a diagonal wardrobe or bed was what
//! most walkers walked into), and every piece the data stands against a wall (beds, cabinets,
//! shelves, sofas, desks, dressing and console tables) is put back against the nearest wall behind
//! or in front of it, its back to it (`walls`; a piece holding people only backwards, within what
//! its people allow). A seat's or bed's surface goes to the top of its person's support
//! volume (within the heights of the category's real pieces, give or take 15 cm; a bed up to
//! 0.7 m tall has no headboard and its mattress is its top, so a high sitter gets a low bed where
//! a tall one cannot reach them), a low table's or cabinet's top comes down to a palm resting on it
//! where real pieces of its category are that low, other holders grow to the top of their box (at
//! most 15 cm), and width and depth grow by at most 20 cm where the box needs it. A piece taller
//! than a metre is touched on its front: the toucher's pressed volume must lie just behind its
//! front face. Every round then (1) moves each holder by the smallest shift that puts its boxes'
//! footprints on the part they must be on (a seat's surface clear of its backrest and near enough
//! its front edge for the knees to pass it by 7 cm, as in the data; a mattress; else the footprint)
//! and pushes pieces out of people's way (where footprint and height meet a walking or standing
//! body, or a sitter's or toucher's shins and feet for a piece solid to the floor, `Clearance`; a
//! holder only as far as its people stay on it), (2) separates overlapping pairs along the shortest
//! separating axis that keeps both inside the walls, and (3) moves every footprint inside the floor
//! plan (corners inside, and off an L-shaped room's inner corner). Holders move a fifth as much for
//! overlaps and paths; the last third of the rounds leaves contacts alone and the last five paths,
//! so the layout ends separated and inside. Rounds stop when nothing moves a millimetre. A box
//! still less than half covered by pieces that can hold it (a table top over a sitter's seat does
//! not count) after that gets a new piece and a second pass of rounds.
//!
//! The numbers above are [`SettleConfig`]'s defaults. The later steps (each in its own file)
//! finish what the rounds leave.

use super::clearance::Clearance;
use super::completion::{SeatGaps, height_within, support_for};
use super::config::{HoldingConfig, RepairConfig, StepName};
use super::helpers::{
    containment_shift, footprint_separations, holding_region, inside_push, is_solid, local_extent, shift, within_slack,
};
use super::occupancy::Occupancy;
use super::pipeline::{RepairStep, SettleReport, StepReport, Workspace};
use super::walls::{stands_against_wall, to_wall_behind, wall_poses};
use crate::furniture::{height_range, template};
use crate::geom::{OBox, intersection_volume, iou_3d, wrap_angle};
use crate::human::{Conditions, ContactBox};
use crate::measure::contact_iou;
use crate::scene::{Action, Group, Object, Scene};
use glam::DVec2;

/// The `settle` step.
#[derive(Debug, Clone, Copy, Default)]
pub struct Settle;

impl RepairStep for Settle {
    fn name(&self) -> StepName {
        StepName::Settle
    }

    /// At most `rounds` rounds per pass: a first pass, with a new piece for every contact box no
    /// object can hold, and a second one only if some box is still uncovered and a new piece can be
    /// added for it.
    fn run(&self, scene: &mut Scene, work: &mut Workspace<'_>, config: &RepairConfig) -> StepReport {
        let cfg = &config.settle;
        let people = &mut work.people;
        let mut report = SettleReport::default();
        let start: Vec<DVec2> = scene.objects.iter().map(|o| DVec2::new(o.center[0], o.center[1])).collect();
        for pass in 0..2 {
            people.assign(scene, cfg);
            let missing: Vec<usize> = (0..people.cond.contact_boxes.len())
                .filter(|k| match pass {
                    0 => !people.holders.iter().any(|(b, _)| b == k),
                    // Covered by what can hold it: a table top over a sitter's seat does not count.
                    _ => {
                        let b = &people.cond.contact_boxes[*k];
                        let holders: Vec<Object> =
                            scene.objects.iter().filter(|o| o.category.affords(b.action)).cloned().collect();
                        contact_iou(&b.obox, &holders) < cfg.covered
                    }
                })
                .collect();
            let added = if cfg.complete {
                complete_supports(scene, &people.cond, &missing, &mut people.holders, config)
            } else {
                0
            };
            if pass > 0 && added == 0 {
                break;
            }
            report.added += added;
            settle_rounds(scene, people, config, &mut report);
        }
        report.max_move = scene
            .objects
            .iter()
            .zip(&start)
            .map(|(o, s)| DVec2::new(o.center[0], o.center[1]).distance(*s))
            .fold(0.0, f64::max);
        work.reassigned();
        StepReport::Settle(report)
    }
}

/// One pass: turning and fitting the holders, then up to `rounds` rounds of moves.
fn settle_rounds(scene: &mut Scene, people: &Occupancy, config: &RepairConfig, report: &mut SettleReport) {
    let (cfg, rules, gap) = (&config.settle, &config.holding, config.gap);
    let rounds = cfg.rounds;
    let Occupancy { cond, gaps, clearance, holders } = people;
    let polygon = scene.floor_plan.polygon();
    let start_yaw: Vec<f64> = scene.objects.iter().map(|o| o.yaw).collect();
    // A bed with a sleeper keeps its orientation whatever its sitters face (beds are not turned to
    // sleepers: that made more bedrooms penetrate).
    let mut turned: Vec<bool> = (0..scene.objects.len())
        .map(|i| {
            scene.objects[i].category.group() == Group::Bed
                && holders.iter().any(|(b, h)| *h == i && cond.contact_boxes[*b].action == Action::Lie)
        })
        .collect();
    let kept = turned.clone();
    for (b, i) in holders {
        let contact = &cond.contact_boxes[*b];
        if let Some(yaw) = facing_yaw(&scene.objects[*i], contact).filter(|_| !turned[*i]) {
            scene.objects[*i].yaw = yaw;
            turned[*i] = true;
        }
        report.resized += fit_size(&mut scene.objects[*i], contact, &gaps[*b], config) as usize;
    }
    report.turned += turned.iter().zip(&kept).filter(|(t, k)| **t && !**k).count();
    // The data's pieces all stand square to the walls; so do ours (seats the quarter turn nearest
    // their sitter).
    if let Some(wall) = polygon.longest_edge_direction().filter(|_| cfg.square) {
        for (o, start) in scene.objects.iter_mut().zip(&start_yaw) {
            o.yaw = square_yaw(o.yaw, wall);
            report.squared += (wrap_angle(o.yaw - start).abs() > 1e-3) as usize;
        }
    }
    if cfg.walls {
        report.walled += back_to_walls(scene, people, config);
    }
    let mobility: Vec<f64> =
        (0..scene.objects.len()).map(|i| if people.holds(i) { cfg.anchored_mobility } else { 1.0 }).collect();
    for round in 0..rounds {
        let before: Vec<[f64; 3]> = scene.objects.iter().map(|o| o.center).collect();
        // The last third of the rounds leaves the contacts where they are, the last five the paths.
        let mut moves = vec![DVec2::ZERO; scene.objects.len()];
        let mut counts = vec![0usize; scene.objects.len()];
        if (round as f64) < rounds as f64 * cfg.contact_rounds {
            for (b, i) in holders {
                moves[*i] += containment_shift(&cond.contact_boxes[*b], &gaps[*b], &scene.objects[*i], rules);
                counts[*i] += 1;
            }
        }
        for (i, o) in scene.objects.iter_mut().enumerate() {
            shift(o, (moves[i] / counts[i].max(1) as f64).clamp_length_max(cfg.max_step));
            if round + cfg.pathless_rounds < rounds {
                // A holder gives way to walkers only as far as its people stay on it.
                let push = within_slack(o, &people.held_by(i), path_push(o, clearance, cfg.max_step), rules);
                shift(o, push.clamp_length_max(cfg.max_step));
            }
        }
        for i in 0..scene.objects.len() {
            for j in i + 1..scene.objects.len() {
                let (a, b) = (scene.objects[i].obox(), scene.objects[j].obox());
                if intersection_volume(&a, &b) <= 1e-9 {
                    continue;
                }
                let (wi, wj) = (mobility[i], mobility[j]);
                let (si, sj) = (wi / (wi + wj), wj / (wi + wj));
                // The shortest separation that keeps both inside the walls, else the shortest.
                let fits = |m: DVec2| {
                    let moved = |o: &OBox, d: DVec2| OBox::new(o.center + d.extend(0.0), o.size, o.yaw);
                    inside_push(&moved(&a, m * si), &polygon, gap).length() < 1e-6
                        && inside_push(&moved(&b, -m * sj), &polygon, gap).length() < 1e-6
                };
                let separations = footprint_separations(&a, &b, gap);
                let Some(&mtv) = separations.iter().find(|m| fits(**m)).or(separations.first()) else { continue };
                shift(&mut scene.objects[i], mtv * si);
                shift(&mut scene.objects[j], -mtv * sj);
            }
        }
        for o in &mut scene.objects {
            let w = inside_push(&o.obox(), &polygon, gap);
            shift(o, w);
        }
        report.rounds += 1;
        let moved = scene
            .objects
            .iter()
            .zip(&before)
            .map(|(o, c)| DVec2::new(o.center[0] - c[0], o.center[1] - c[1]).length())
            .fold(0.0, f64::max);
        if moved < 1e-3 {
            break;
        }
    }
}

/// Puts every piece the data stands against a wall back against one (`walls`): a piece holding
/// nobody against the first of [`wall_poses`] (behind, in front, beside) least in people's way; a
/// holder towards the wall behind it as far as its people stay on it. Returns how many pieces moved
/// or turned.
fn back_to_walls(scene: &mut Scene, people: &Occupancy, config: &RepairConfig) -> usize {
    let walls = &config.walls;
    let polygon = scene.floor_plan.polygon();
    let mut walled = 0;
    for i in 0..scene.objects.len() {
        if !stands_against_wall(scene.objects[i].category) {
            continue;
        }
        let held = people.held_by(i);
        let o = &mut scene.objects[i];
        let (yaw, m) = if held.is_empty() {
            let in_the_way = |&(yaw, m): &(f64, DVec2)| {
                let b = o.obox();
                people.clearance.blocked(&OBox::new(b.center + m.extend(0.0), b.size, yaw), true).len()
            };
            // `min_by_key` keeps the first of equals: the nearer wall.
            let Some(pose) = wall_poses(&o.obox(), &polygon, walls).into_iter().min_by_key(in_the_way) else {
                continue;
            };
            pose
        } else {
            let Some(m) = to_wall_behind(&o.obox(), &polygon, walls) else { continue };
            (o.yaw, within_slack(o, &held, m, &config.holding))
        };
        if m.length() > 1e-3 || wrap_angle(yaw - o.yaw).abs() > 1e-3 {
            walled += 1;
        }
        o.yaw = yaw;
        shift(o, m);
    }
    walled
}

/// The yaw nearest `yaw` among `wall` plus quarter turns, in (−π, π].
fn square_yaw(yaw: f64, wall: f64) -> f64 {
    let quarter = std::f64::consts::FRAC_PI_2;
    wrap_angle(wall + ((yaw - wall) / quarter).round() * quarter)
}

/// Adds a piece of furniture for each of the `missing` contact boxes (boxes at one place share
/// one), within the room type's object limit, and makes it their holder. Returns how many were added.
fn complete_supports(
    scene: &mut Scene,
    cond: &Conditions,
    missing: &[usize],
    holders: &mut Vec<(usize, usize)>,
    config: &RepairConfig,
) -> usize {
    let mut added: Vec<(usize, usize)> = Vec::new();
    for &k in missing {
        let contact = &cond.contact_boxes[k];
        let shared = added.iter().find(|(b, _)| iou_3d(&cond.contact_boxes[*b].obox, &contact.obox) >= 0.5);
        let holder = match shared {
            Some(&(_, i)) => i,
            None if scene.objects.len() < scene.room_type.max_objects() => {
                let Some(o) = support_for(scene, contact, &config.holding, &config.completion) else { continue };
                scene.objects.push(o);
                scene.objects.len() - 1
            }
            None => break,
        };
        added.push((k, holder));
    }
    holders.retain(|(b, _)| !added.iter().any(|(k, _)| k == b));
    let count = added.iter().map(|(_, i)| *i).collect::<std::collections::BTreeSet<_>>().len();
    holders.extend(added);
    holders.sort_unstable();
    count
}

/// The yaw `o` takes for the person of `contact`: a chair, stool or sofa faces like its sitter (its
/// front the way they face), a sofa lies along its sleeper (the body along its local x, as the data
/// lays people on sofas), a bed a quarter turn where its sitter faces along it, a touched table,
/// cabinet or shelf presents a side to its toucher: its front where it stands against a wall (the
/// only side a wall piece has), else the side nearest the way it stands (a dining table touched
/// at its end keeps its diners; `synth --touch-any-side` touches free pieces so). Beds are not
/// turned to their sleepers (that made penetrating bedrooms more frequent: 0.886 → 0.909 of the
/// test split).
fn facing_yaw(o: &Object, contact: &ContactBox) -> Option<f64> {
    match (o.category.group(), contact.action) {
        (Group::Table | Group::Cabinet | Group::Shelf, Action::Touch) => {
            let front = contact.obox.yaw + std::f64::consts::PI;
            Some(if stands_against_wall(o.category) { front } else { square_yaw(o.yaw, front) })
        }
        (Group::Chair | Group::Stool | Group::Sofa, Action::Sit) => Some(contact.obox.yaw),
        (Group::Sofa, Action::Lie) => Some(contact.obox.yaw + std::f64::consts::FRAC_PI_2),
        // A quarter turn where the sitter faces along the bed: the data seats people on its sides.
        (Group::Bed, Action::Sit) => {
            let f = super::helpers::bed_local_facing(o, contact);
            (f.y.abs() > f.x.abs()).then_some(o.yaw + std::f64::consts::FRAC_PI_2)
        }
        _ => None,
    }
}

/// Fits a floor-standing object to `contact`: a seat's or bed's surface goes to the top of a sitter's
/// or sleeper's support volume (up or down), a low piece's top down to a palm resting on it
/// ([`rests_palm_on_top`]; only where the category's real pieces, less 15 cm, are that low),
/// anything else grows to the top of the box; width and
/// depth grow until the box fits the part it must be on ([`holding_region`]). A surface's height
/// stays within the category's real pieces' (± 15 cm), any other height changes by at most 15 cm,
/// width and depth by at most 20 cm. Returns whether it changed.
fn fit_size(o: &mut Object, contact: &ContactBox, gaps: &SeatGaps, config: &RepairConfig) -> bool {
    let (cfg, rules) = (&config.settle, &config.holding);
    if o.category.is_hanging() {
        return false;
    }
    let before = o.size;
    let top = contact.obox.z_range().1;
    let surface = template(o).surface.filter(|_| matches!(contact.action, Action::Sit | Action::Lie));
    let height = match surface {
        // Any height real pieces of the category have, give or take cfg.max_grow_height.
        // A top above a resting palm comes down to it where the category's real pieces (give or
        // take cfg.max_grow_height) are that low; part of the way would only put it in the forearm.
        _ if rests_palm_on_top(o, contact, rules) && o.size[2] > top => {
            Some(top).filter(|&h| h >= height_range(o.category).0 - cfg.max_grow_height)
        }
        Some(_) => {
            let (lo, hi) = height_range(o.category);
            Some(height_within(o.category, o.size, top, (lo - cfg.max_grow_height, hi + cfg.max_grow_height)))
        }
        None => Some(o.size[2].max(top)).filter(|h| h - o.size[2] <= cfg.max_grow_height),
    };
    if let Some(height) = height {
        o.size[2] = height;
        o.center[2] = height * 0.5;
    }
    let (lo, hi) = local_extent(&contact.obox, &o.obox());
    let (region_lo, region_hi) = holding_region(o, contact, gaps, rules);
    for k in 0..2 {
        let need = (hi[k] - lo[k]) + (o.size[k] - (region_hi[k] - region_lo[k]));
        if need > o.size[k] && need - o.size[k] <= cfg.max_grow_extent {
            o.size[k] = need;
        }
    }
    o.size != before
}

/// Whether `contact` is a palm resting on `o`'s top: a touch at most `rules.top_touch_height`
/// high on a table, cabinet or shelf no taller than that (the data rests the palm on the top of
/// such a piece, the top at the touch box's top, and touches a taller one's front).
pub(super) fn rests_palm_on_top(o: &Object, contact: &ContactBox, rules: &HoldingConfig) -> bool {
    contact.action == Action::Touch
        && contact.obox.center.z <= rules.top_touch_height
        && o.size[2] <= rules.top_touch_height
        && matches!(o.category.group(), Group::Table | Group::Cabinet | Group::Shelf)
}

/// A push of `o` out of people's way (walkers' bodies; for a solid piece also sitters' and
/// touchers' shins and feet): away from the centroid of the pixels where it meets them, by their
/// area over its longer side.
fn path_push(o: &Object, clearance: &Clearance, max_step: f64) -> DVec2 {
    let b = o.obox();
    // A piece without legs is solid to the floor: a sitter's feet cannot go under it.
    let blocked = clearance.blocked(&b, is_solid(o));
    if blocked.is_empty() {
        return DVec2::ZERO;
    }
    let w = clearance.window();
    let centroid = blocked.iter().sum::<DVec2>() / blocked.len() as f64;
    let dir = (b.center.truncate() - centroid).try_normalize().unwrap_or(DVec2::X);
    let depth = blocked.len() as f64 * w.pixel_area() / b.size.x.max(b.size.y);
    dir * depth.clamp(w.pixel(), max_step)
}
