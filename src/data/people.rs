//! Humans for a furnished room, the way 3D-FRONT HUMAN has them: contact humans on the pieces that
//! afford them (MIME's mapping) and walkers whose paths cover the free floor.
//!
//! Contact humans are static poses (one frame), placed on the piece's template surface: sitters on
//! seats with their back clear of the backrest, sleepers on mattresses with the head at the
//! headboard, touchers with the palm on a top or a front face. Walkers follow shortest paths between
//! random points of the walkable floor (0.3 m clear of furniture, walls and contact humans), at
//! 1.0–1.4 m/s, recorded at 10 fps.

use super::Rng;
use super::layout::{FreeGrid, Layout, Placed};
use crate::furniture::template_of;
use crate::geom::{OBox, Polyline, facing, yaw_facing};
use crate::human::{Body, KNEE_OVERHANG, Motion, Pose, Side, lie, sit, touch};
use crate::measure::{FurnitureField, human_penetration};
use crate::scene::{Action, Category, Group, Human, Object};
use glam::{DVec2, DVec3};
use std::collections::VecDeque;

/// Frames per second of walkers in the dataset.
pub const WALK_FPS: f64 = 10.0;
/// Distance from a walker's path to furniture, walls and contact humans: half the shoulders, the
/// arm swing and the foot placement beside the path.
pub const WALKER_CLEARANCE: f64 = 0.45;
/// Largest E_pen a clean contact human may have against the furniture.
const CLEAN_PENETRATION: f64 = 0.5;

/// A sampled adult stature (m).
fn adult(rng: &mut Rng) -> f64 {
    (1.70 + 0.08 * rng.normal()).clamp(1.5, 1.95)
}

/// The pose of a person doing `action` on `piece`, or `None` if the piece has no room for it.
pub fn contact_pose(piece: &Placed, action: Action, slot: f64, rng: &mut Rng) -> Option<(Body, Pose)> {
    let b = &piece.obox;
    let surface = template_of(piece.category, b).surface?;
    let ext = surface.extent();
    let sofa_bed = action == Action::Lie && piece.category.group() == Group::Sofa;
    let stature = match piece.category {
        Category::KidsBed => rng.uniform(1.1, 1.5),
        _ if sofa_bed => adult(rng).min(ext.x - 0.02),
        _ => adult(rng),
    };
    if stature < 1.4 && sofa_bed {
        return None;
    }
    let body = Body::new(stature);
    let to_world = |l: DVec2| b.to_world(l.extend(0.0)).truncate();
    let pose = match (action, piece.category.group()) {
        (Action::Lie, Group::Sofa) => {
            // Along the seat, head at the local −x end, feet towards +x.
            let mid = (surface.min + surface.max) * 0.5;
            let at = to_world(DVec2::new(surface.min.x + 0.04 + 0.45 * stature, mid.y));
            let dir = b.to_world(DVec3::X).truncate() - b.center.truncate();
            lie(&body, at, surface.height, yaw_facing(dir))
        }
        (Action::Lie, _) => {
            let head_room = 0.12 + 0.45 * stature;
            if ext.y < head_room + 0.55 * stature - 0.05 || ext.x < 0.5 {
                return None;
            }
            let x = (slot * (ext.x * 0.5 - 0.35).max(0.0)).clamp(-ext.x * 0.5, ext.x * 0.5);
            let at = to_world(DVec2::new((surface.min.x + surface.max.x) * 0.5 + x, surface.min.y + head_room));
            lie(&body, at, surface.height, b.yaw)
        }
        (Action::Sit, Group::Bed) => {
            let side = if slot < 0.0 { -1.0 } else { 1.0 };
            let y = surface.min.y + ext.y * rng.uniform(0.35, 0.75);
            let at = to_world(DVec2::new(side * (ext.x * 0.5 - 0.2), y));
            let dir = b.to_world(DVec3::new(side, 0.0, 0.0)).truncate() - b.center.truncate();
            sit(&body, at, surface.height, yaw_facing(dir))
        }
        (Action::Sit, Group::Stool) => sit(&body, to_world((surface.min + surface.max) * 0.5), surface.height, b.yaw),
        (Action::Sit, _) => {
            if ext.x < 0.4 || ext.y < 0.3 {
                return None;
            }
            let x = (surface.min.x + surface.max.x) * 0.5 + slot * (ext.x * 0.5 - 0.3).max(0.0);
            // Back against the backrest, unless the seat is deeper than the thighs are long: then
            // forward until the knees clear the front edge (the lower legs hang in front of it);
            // and forward as far as keeps the leaning torso's capsules clear of the backrest.
            let y = (surface.min.y + 0.15).max(surface.max.y - body.thigh() + KNEE_OVERHANG);
            let seated = |y: f64| sit(&body, to_world(DVec2::new(x, y)), surface.height, b.yaw);
            let into_back = torso_behind(&body, &seated(y), b, surface.min.y - BACKREST_CLEARANCE);
            seated(y + into_back.max(0.0))
        }
        (Action::Touch, _) => {
            let x = rng.uniform(-0.3, 0.3) * b.size.x;
            let target = if b.size.z <= 1.0 {
                b.to_world(DVec3::new(x, b.size.y * 0.5 - 0.08, surface.height - b.center.z))
            } else {
                let z = rng.uniform(0.9, (b.size.z - 0.1).min(1.5));
                b.to_world(DVec3::new(x, b.size.y * 0.5, z - b.center.z))
            };
            let side = if rng.chance(0.5) { Side::Left } else { Side::Right };
            touch(&body, target, b.yaw + std::f64::consts::PI, side)
        }
        (Action::Walk | Action::Stand, _) => return None,
    };
    Some((body, pose))
}

/// Clearance between a sitter's torso and the backrest, which starts at the seat surface's back
/// edge (m): the check allows 2 cm, the exact capsule reaches past where the pose's joints say.
const BACKREST_CLEARANCE: f64 = 0.01;

/// How far the torso capsules (pelvis to neck) of `pose` reach behind local y = `limit` of piece
/// `b` (m; negative when they stay in front of it).
fn torso_behind(body: &Body, pose: &Pose, b: &OBox, limit: f64) -> f64 {
    use crate::human::Joint;
    let torso = [(Joint::Pelvis, Joint::Spine), (Joint::Spine, Joint::Chest), (Joint::Chest, Joint::Neck)];
    let mut reach = f64::NEG_INFINITY;
    for (a, c) in torso {
        let radius = body.bone_radius(a, c).unwrap_or(0.0);
        for j in [a, c] {
            reach = reach.max(limit - (b.to_local(pose.get(j)).y - radius));
        }
    }
    reach
}

/// How many people a piece seats side by side.
fn sitters(piece: &Placed, rng: &mut Rng) -> usize {
    match piece.category.group() {
        Group::Sofa => {
            let fit = ((piece.obox.size.x - 0.3) / 0.65).floor().max(1.0) as usize;
            rng.range(1, fit.min(3))
        }
        _ => 1,
    }
}

/// Contact humans on the pieces of `layout` (each piece that affords an action gets one with a
/// probability; at least one per room where any piece affords one).
pub fn contact_humans(layout: &Layout, objects: &[Object], rng: &mut Rng) -> Vec<(Action, usize, Human)> {
    let field = FurnitureField::new(objects);
    let polygon = layout.polygon();
    let mut out: Vec<(Action, usize, Human)> = Vec::new();
    let candidates: Vec<usize> =
        (0..layout.placed.len()).filter(|&i| !layout.placed[i].category.affordances().is_empty()).collect();
    let probability = |i: usize| contact_probability(layout.placed[i].category, layout.spacing().touch_chance);
    let mut chosen: Vec<usize> = candidates.iter().copied().filter(|&i| rng.chance(probability(i))).collect();
    if chosen.is_empty() && !candidates.is_empty() {
        // At least one contact human per room, preferably sitting or lying.
        let weights: Vec<f64> = candidates.iter().map(|&i| probability(i)).collect();
        chosen.push(candidates[rng.weighted(&weights)]);
    }
    for i in chosen {
        let piece = &layout.placed[i];
        let weights: Vec<f64> =
            piece.category.affordances().iter().map(|&a| piece.category.affordance_probability(a)).collect();
        let action = piece.category.affordances()[rng.weighted(&weights)];
        let n = if action == Action::Sit { sitters(piece, rng) } else { 1 };
        let turned;
        let piece = if action == Action::Touch
            && layout.spacing().touch_any_side
            && !super::rooms::stands_against_wall(piece.category)
        {
            turned = quarter_turned(piece, rng.range(0, 3));
            &turned
        } else {
            piece
        };
        for k in 0..n {
            let slot = if n == 1 { rng.uniform(-0.3, 0.3) } else { -1.0 + 2.0 * k as f64 / (n - 1) as f64 };
            let slot = if piece.category.group() == Group::Bed && action == Action::Sit {
                rng.uniform(-1.0, 1.0)
            } else {
                slot
            };
            let Some((body, pose)) = contact_pose(piece, action, slot, rng) else { continue };
            let mut m = Motion::new(body, 30.0);
            m.hold(pose, 1, action);
            let human = m.into_human(String::new());
            let inside = human.frames[0].iter().all(|p| polygon.signed_distance(DVec2::new(p[0], p[1])) < -0.02);
            let apart = out.iter().all(|(_, _, o)| bodies_apart(o, &human));
            if inside && apart && human_penetration(&human, &field) < CLEAN_PENETRATION {
                out.push((action, i, human));
            }
        }
    }
    out
}

/// `piece` with its box turned by `quarters` quarter turns about its centre and its width and
/// depth swapped each time: the same footprint, whose front is another of its sides (one quarter:
/// the side that was its −x end).
fn quarter_turned(piece: &Placed, quarters: usize) -> Placed {
    let mut obox = piece.obox;
    for _ in 0..quarters {
        obox = OBox::new(
            obox.center,
            DVec3::new(obox.size.y, obox.size.x, obox.size.z),
            obox.yaw + std::f64::consts::FRAC_PI_2,
        );
    }
    Placed { obox, ..piece.clone() }
}

/// The chance that a piece people touch rather than sit or lie on gets a contact person in the
/// data by default: touching humans are the minority in 3D-FRONT HUMAN, whose contact humans
/// mostly sit and lie (`synth --touch-chance` draws rooms with another).
pub const TOUCH_CHANCE: f64 = 0.06;

/// The chance that the data puts a contact person on a piece of `category` (before choosing the
/// action among its affordances), a piece people only touch getting one with `touch_chance`
/// ([`TOUCH_CHANCE`] in the data the shipped models learnt from).
pub fn contact_probability(category: Category, touch_chance: f64) -> f64 {
    match category.group() {
        Group::Bed => 0.85,
        Group::Sofa => 0.7,
        Group::Chair | Group::Stool => 0.45,
        _ => touch_chance,
    }
}

/// Whether two single-frame bodies keep 5 cm between their capsules (checked joint to joint).
fn bodies_apart(a: &Human, b: &Human) -> bool {
    let reach = |h: &Human| h.skeleton.bones.iter().map(|x| x.radius).fold(0.0, f64::max);
    let limit = reach(a) + reach(b) + 0.05;
    a.frames[0].iter().all(|p| b.frames[0].iter().all(|q| DVec3::from(*p).distance(DVec3::from(*q)) > limit))
}

/// Footprint of a single-frame body as a box around its joints (for walkers to avoid).
fn body_box(h: &Human) -> OBox {
    let pts: Vec<DVec2> = h.frames[0].iter().map(|p| DVec2::new(p[0], p[1])).collect();
    let lo = pts.iter().fold(DVec2::splat(f64::INFINITY), |m, &p| m.min(p)) - 0.12;
    let hi = pts.iter().fold(DVec2::splat(f64::NEG_INFINITY), |m, &p| m.max(p)) + 0.12;
    OBox::new(((lo + hi) * 0.5).extend(1.0), (hi - lo).extend(2.0), 0.0)
}

/// `count` walkers over the free floor, avoiding furniture and the given contact humans.
pub fn walkers(layout: &Layout, contact: &[Human], count: usize, rng: &mut Rng) -> Vec<Human> {
    let bodies: Vec<OBox> = contact.iter().map(body_box).collect();
    let obstacles = layout.placed.iter().filter(|p| !p.category.is_hanging()).map(|p| &p.obox).chain(bodies.iter());
    // Walkers keep their whole swinging body clear (WALKER_CLEARANCE from the path to anything);
    // in cramped rooms a little less, down to the narrowest walkway.
    let obstacles: Vec<&OBox> = obstacles.collect();
    let mut found = None;
    for clearance in [WALKER_CLEARANCE, 0.38, super::layout::WALKWAY_HALF] {
        let grid = FreeGrid::with_clearance(layout.polygon(), obstacles.iter().copied(), clearance);
        let Some(main) = grid.main_component() else { continue };
        let (nx, ny, _) = grid.shape();
        let cells: Vec<(usize, usize)> =
            (0..ny).flat_map(|j| (0..nx).map(move |i| (i, j))).filter(|&(i, j)| grid.label(i, j) == main).collect();
        if cells.len() >= 10 {
            found = Some((grid, main, cells));
            break;
        }
    }
    let Some((grid, main, cells)) = found else { return Vec::new() };
    let mut out = Vec::new();
    for attempt in 0..count * 15 {
        if out.len() == count {
            break;
        }
        // Prefer paths of at least 2 m; accept shorter ones in cramped rooms.
        let min_length = if attempt < count * 8 { 2.0 } else { 0.5 };
        let a = cells[rng.index(cells.len())];
        let b = cells[rng.index(cells.len())];
        let Some(path) = shortest_path(&grid, main, a, b) else { continue };
        let points = simplify(&grid, main, &path);
        let Some(line) = Polyline::new(points) else { continue };
        if line.length() < min_length {
            continue;
        }
        let body = Body::new(adult(rng));
        let mut m = Motion::new(body, WALK_FPS);
        m.walk(&line, rng.uniform(1.0, 1.4));
        out.push(m.into_human(String::new()));
    }
    if out.is_empty() {
        // Too cramped to walk: someone stands in the free floor instead (their feet still mark it).
        let (i, j) = cells[rng.index(cells.len())];
        let body = Body::new(adult(rng));
        let yaw = std::f64::consts::FRAC_PI_2 * rng.index(4) as f64;
        let mut m = Motion::new(body, WALK_FPS);
        m.hold(crate::human::stand(&body, grid.center(i, j), yaw), 10, Action::Stand);
        out.push(m.into_human(String::new()));
    }
    out
}

/// 4-connected BFS between two cells of one component; cell centres of the path.
fn shortest_path(grid: &FreeGrid, label: u32, a: (usize, usize), b: (usize, usize)) -> Option<Vec<DVec2>> {
    let (nx, ny, _) = grid.shape();
    let mut prev = vec![usize::MAX; nx * ny];
    let start = a.1 * nx + a.0;
    let goal = b.1 * nx + b.0;
    prev[start] = start;
    let mut queue = VecDeque::from([start]);
    while let Some(c) = queue.pop_front() {
        if c == goal {
            break;
        }
        let (i, j) = (c % nx, c / nx);
        let neighbours = [(i.wrapping_sub(1), j), (i + 1, j), (i, j.wrapping_sub(1)), (i, j + 1)];
        for (x, y) in neighbours {
            if x < nx && y < ny && grid.label(x, y) == label && prev[y * nx + x] == usize::MAX {
                prev[y * nx + x] = c;
                queue.push_back(y * nx + x);
            }
        }
    }
    if prev[goal] == usize::MAX {
        return None;
    }
    let mut cells = vec![goal];
    while *cells.last().expect("non-empty") != start {
        cells.push(prev[*cells.last().expect("non-empty")]);
    }
    cells.reverse();
    Some(cells.into_iter().map(|c| grid.center(c % nx, c / nx)).collect())
}

/// String pulling: keeps a point only where the straight line from the last kept one would leave
/// the walkable component.
fn simplify(grid: &FreeGrid, label: u32, path: &[DVec2]) -> Vec<DVec2> {
    let visible = |a: DVec2, b: DVec2| {
        let n = (a.distance(b) / 0.04).ceil().max(1.0) as usize;
        (0..=n).all(|k| grid.component_at(a.lerp(b, k as f64 / n as f64), &label))
    };
    let mut out = vec![path[0]];
    let mut i = 0;
    while i + 1 < path.len() {
        let mut j = path.len() - 1;
        while j > i + 1 && !visible(path[i], path[j]) {
            j -= 1;
        }
        out.push(path[j]);
        i = j;
    }
    out
}

/// Moves a contact human off its ideal placement the way 3D-FRONT HUMAN's contact humans are off:
/// sunk into furniture or floating beside it. Returns the applied translation.
///
/// `extent` is the larger side of the piece's footprint: on a big piece the misplacement is larger,
/// as a small offset would leave the contact box on the piece.
pub fn misplace(human: &mut Human, action: Action, extent: f64, rng: &mut Rng) -> DVec3 {
    if !rng.chance(0.9) {
        return DVec3::ZERO;
    }
    let yaw = crate::human::body_yaw(human, 0);
    let f = facing(yaw);
    let side = DVec2::new(f.y, -f.x);
    let t = match action {
        Action::Sit | Action::Lie => {
            let reach = 0.15 + 0.3 * extent;
            let angle = rng.uniform(0.0, std::f64::consts::TAU);
            let xy = (f * angle.cos() + side * angle.sin()) * rng.uniform(0.0, reach);
            xy.extend(rng.uniform(-0.18, 0.03))
        }
        _ => {
            let xy = f * rng.uniform(-0.1, 0.14) + side * (0.05 * rng.normal());
            xy.extend(0.05 * rng.normal())
        }
    };
    translate(human, t);
    t
}

/// Moves every frame of `human` by `t`.
pub fn translate(human: &mut Human, t: DVec3) {
    for frame in &mut human.frames {
        for p in frame.iter_mut() {
            *p = (DVec3::from(*p) + t).to_array().map(crate::human::round_mm);
        }
    }
}
