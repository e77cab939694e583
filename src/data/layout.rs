//! Furniture arrangement by the rules real rooms follow.
//!
//! Large pieces stand against walls (5 cm gap) facing into the room; a bed has nightstands beside its
//! headboard; a desk or dressing table has its chair in front; a dining table stands free with 2–8
//! chairs around it; a sofa faces a tv stand across a coffee table, with armchairs and end tables
//! beside; lamps hang from the ceiling. No two footprints overlap (lamps excepted, which clear every
//! piece below them), everything stays inside the floor plan, and every piece stays reachable over
//! walkways at least 0.6 m wide (checked on a 10 cm grid after each group).
//!
//! The gaps the rules leave (a piece's back from its wall, a nightstand from its bed, a chair from
//! its table, …) are exact by default; with a [`Spacing`] spread each one is drawn afresh for every
//! piece, as a room furnished by hand keeps them only roughly. A [`Spacing`] may also stand a share
//! of the sofas out in the room, their backs [`FREE_SOFA_BACK`] off the wall behind them with a
//! walkway there, as open-plan rooms have them; by default every sofa stands at a wall. Its last
//! two settings are read when people are put in the room (`data::people`): at which sides of a
//! table a person touching it may stand, and how often a piece people touch gets one.

use super::Rng;
use super::people::TOUCH_CHANCE;
use crate::furniture::{SIZE_JITTER, catalog_items};
use crate::geom::{OBox, Polygon, Wall, facing, footprint_intersection_area, intersection_volume, yaw_facing};
use crate::scene::{Category, FloorPlan, Group, Object};
use glam::{DVec2, DVec3};
use std::collections::VecDeque;

/// Gap between a wall and the back of a piece against it.
pub const WALL_GAP: f64 = 0.05;
/// The clearance a piece placed beside another keeps from every other footprint (m); no gap the
/// rules leave is drawn below it.
const BESIDE_CLEARANCE: f64 = 0.02;
/// Half the narrowest walkway kept free.
pub const WALKWAY_HALF: f64 = 0.3;
const GRID: f64 = 0.1;
/// Distance in front of a piece where a person reaches it.
const ACCESS: f64 = 0.45;

/// How far a piece's back stands off its wall: drawn from the layout's spacing and the stream.
type Back = fn(&Spacing, &mut Rng) -> f64;

/// A piece placed in the room.
#[derive(Debug, Clone, PartialEq)]
pub struct Placed {
    /// Its category.
    pub category: Category,
    /// Its box.
    pub obox: OBox,
    /// Points (any one suffices) from which a person reaches it.
    pub access: Vec<DVec2>,
    /// Index of the piece it belongs to (a chair's table, a nightstand's bed), if any.
    pub anchor: Option<usize>,
}

/// How exactly the rules' gaps are kept, and what else the draw loosens from the exact rules.
///
/// With `spread` 0 (the default) every gap is the rule's own ([`WALL_GAP`] from a wall, 4 cm
/// between a nightstand and its bed or a chair and its table, …) and nothing is drawn for it, so
/// the rooms are those of the exact rules draw for draw. With a spread `s`, each gap `g` is drawn
/// uniformly from `[max(g − s, 2 cm), g + s]` for every piece (2 cm: the clearance a piece placed
/// beside another keeps from the rest).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Spacing {
    /// Half the width of the range each gap is drawn from (m; 0 = the rules' gaps exactly).
    pub spread: f64,
    /// The share of sofa groups whose sofa stands out in the room, its back [`FREE_SOFA_BACK`]
    /// off the wall behind it (0 = every sofa at a wall, the rooms of the exact rules draw for
    /// draw; a room too small for it gets its sofa at a wall).
    pub free_sofas: f64,
    /// Whether a person touching a piece that stands free of the walls (a table, not a cabinet)
    /// may stand at any of its four sides, drawn for each toucher (false = at its front only, the
    /// rooms of the exact rules draw for draw). A side with no room for them drops the toucher,
    /// as a blocked front does.
    pub touch_any_side: bool,
    /// The chance that a piece people touch rather than sit or lie on (a table, a cabinet, a
    /// wardrobe) gets a person touching it ([`TOUCH_CHANCE`] = the rooms of the exact rules draw
    /// for draw: the chance is drawn against either way, so only who touches changes).
    pub touch_chance: f64,
}

/// How far (m) the back of a sofa that stands out in the room is from the wall behind it: a
/// walkway's width at least ([`WALKWAY_HALF`] twice, and a little), at most what open-plan rooms
/// leave behind a sofa that faces away from a dining table or a door.
pub const FREE_SOFA_BACK: (f64, f64) = (0.8, 1.4);

impl Spacing {
    /// The rules' gaps exactly, every sofa at a wall, a person touching a piece at its front, and
    /// pieces touched as often as in 3D-FRONT HUMAN.
    pub const EXACT: Spacing =
        Spacing { spread: 0.0, free_sofas: 0.0, touch_any_side: false, touch_chance: TOUCH_CHANCE };

    /// The gap for a rule whose own is `rule` (m): `rule` itself when exact, else a draw.
    pub fn gap(&self, rule: f64, rng: &mut Rng) -> f64 {
        if self.spread <= 0.0 {
            return rule;
        }
        let lo = (rule - self.spread).max(BESIDE_CLEARANCE + 1e-3).min(rule);
        rng.uniform(lo, rule + self.spread)
    }
}

/// A room being furnished.
#[derive(Debug, Clone)]
pub struct Layout {
    polygon: Polygon,
    height: f64,
    spacing: Spacing,
    /// The pieces, in placement order.
    pub placed: Vec<Placed>,
    reserved: Vec<OBox>,
}

/// A real size for a piece of `category`: a catalog item, jittered by a few per cent, in cm steps.
pub fn real_size(category: Category, rng: &mut Rng) -> DVec3 {
    let items = catalog_items(category);
    let s = items[rng.index(items.len())].size;
    let j = |x: f64, r: &mut Rng, a: f64| ((x * r.uniform(1.0 - a, 1.0 + a)) * 100.0).round() / 100.0;
    DVec3::new(j(s[0], rng, SIZE_JITTER[0]), j(s[1], rng, SIZE_JITTER[1]), j(s[2], rng, SIZE_JITTER[2]))
}

fn local_to_world(obox: &OBox, local: DVec2) -> DVec2 {
    obox.to_world(local.extend(0.0)).truncate()
}

impl Layout {
    /// An empty room, furnished with the rules' gaps exactly.
    pub fn new(plan: &FloorPlan) -> Layout {
        Layout::with_spacing(plan, Spacing::EXACT)
    }

    /// An empty room whose gaps are kept as `spacing` says.
    pub fn with_spacing(plan: &FloorPlan, spacing: Spacing) -> Layout {
        Layout { polygon: plan.polygon(), height: plan.height, spacing, placed: Vec::new(), reserved: Vec::new() }
    }

    /// How the rules' gaps are kept, and what else the draw loosens.
    pub fn spacing(&self) -> Spacing {
        self.spacing
    }

    /// The floor polygon.
    pub fn polygon(&self) -> &Polygon {
        &self.polygon
    }

    /// The pieces as scene objects (ids `o0`, `o1`, … in placement order).
    pub fn objects(&self) -> Vec<Object> {
        self.placed
            .iter()
            .enumerate()
            .map(|(i, p)| Object {
                id: format!("o{i}"),
                category: p.category,
                center: p.obox.center.to_array().map(round_mm),
                size: p.obox.size.to_array(),
                yaw: round_angle(p.obox.yaw),
            })
            .collect()
    }

    /// Whether a floor-standing box fits: inside the floor plan, clear of placed footprints (by at
    /// least `gap`) and of reserved zones.
    pub fn fits(&self, b: &OBox, gap: f64) -> bool {
        let inside = b.footprint().iter().all(|&c| self.polygon.signed_distance(c) < -0.005)
            && !self.polygon.points.iter().any(|&v| b.footprint_signed_distance(v) < 0.0);
        if !inside {
            return false;
        }
        let grown = OBox::new(b.center, b.size + DVec3::new(2.0 * gap, 2.0 * gap, 0.0), b.yaw);
        let clear = |o: &OBox| footprint_intersection_area(&grown, o) < 1e-9;
        self.placed.iter().filter(|p| !p.category.is_hanging()).all(|p| clear(&p.obox))
            && self.reserved.iter().all(|r| footprint_intersection_area(b, r) < 1e-9)
    }

    fn push(&mut self, category: Category, obox: OBox, access: Vec<DVec2>, anchor: Option<usize>) -> usize {
        self.placed.push(Placed { category, obox, access, anchor });
        self.placed.len() - 1
    }

    fn reserve_front(&mut self, b: &OBox, depth: f64) {
        let f = facing(b.yaw);
        let c = b.center.truncate() + f * (b.size.y * 0.5 + depth * 0.5);
        self.reserved.push(OBox::new(c.extend(0.0), DVec3::new(b.size.x, depth, 1.0), b.yaw));
    }

    /// A pose against a wall: (centre, yaw) for a footprint `w` × `d`, or `None` if no wall fits.
    fn wall_spot(&self, w: f64, d: f64, rng: &mut Rng) -> Option<(DVec2, f64)> {
        self.spot_facing_in(w, d, rng, |spacing, rng| spacing.gap(WALL_GAP, rng))
    }

    /// A pose facing into the room from a wall (drawn by length) for a footprint `w` × `d`, its
    /// back `back` off the wall (drawn after the place along it), or `None` if no wall fits.
    fn spot_facing_in(&self, w: f64, d: f64, rng: &mut Rng, back: Back) -> Option<(DVec2, f64)> {
        let walls: Vec<Wall> = self.polygon.walls().collect();
        let weights: Vec<f64> =
            walls.iter().map(|wall| if wall.length > w + 0.1 { wall.length } else { 0.0 }).collect();
        if weights.iter().all(|&x| x == 0.0) {
            return None;
        }
        let wall = walls[rng.weighted(&weights)];
        let t = rng.uniform(w * 0.5 + 0.02, wall.length - w * 0.5 - 0.02);
        let gap = back(&self.spacing, rng);
        Some((wall.point(t, d * 0.5 + gap), yaw_facing(wall.inward)))
    }

    /// Places a piece of `size` against a wall; `None` after `tries` failures.
    pub fn place_on_wall(&mut self, category: Category, size: DVec3, rng: &mut Rng, tries: usize) -> Option<usize> {
        self.place_facing_in(category, size, rng, tries, |spacing, rng| spacing.gap(WALL_GAP, rng))
    }

    /// Places a piece of `size` facing into the room from a wall, its back [`FREE_SOFA_BACK`] off
    /// it (drawn); `None` after `tries` failures.
    fn place_off_wall(&mut self, category: Category, size: DVec3, rng: &mut Rng, tries: usize) -> Option<usize> {
        self.place_facing_in(category, size, rng, tries, |_, rng| rng.uniform(FREE_SOFA_BACK.0, FREE_SOFA_BACK.1))
    }

    /// Places a piece of `size` facing into the room from a wall, its back `back` off it; `None`
    /// after `tries` failures.
    fn place_facing_in(
        &mut self,
        category: Category,
        size: DVec3,
        rng: &mut Rng,
        tries: usize,
        back: Back,
    ) -> Option<usize> {
        for _ in 0..tries {
            let (c, yaw) = self.spot_facing_in(size.x, size.y, rng, back)?;
            let b = OBox::new(c.extend(size.z * 0.5), size, yaw);
            if self.fits(&b, 0.02) {
                let access = vec![local_to_world(&b, DVec2::new(0.0, size.y * 0.5 + ACCESS))];
                return Some(self.push(category, b, access, None));
            }
        }
        None
    }

    /// Places a piece of `size` anywhere on the floor, aligned with the walls.
    pub fn place_free(&mut self, category: Category, size: DVec3, rng: &mut Rng, tries: usize) -> Option<usize> {
        let (min, max) = self.polygon.bounds();
        for _ in 0..tries {
            let c = DVec2::new(rng.uniform(min.x, max.x), rng.uniform(min.y, max.y));
            let yaw = std::f64::consts::FRAC_PI_2 * rng.index(4) as f64;
            let b = OBox::new(c.extend(size.z * 0.5), size, yaw);
            if self.fits(&b, 0.05) {
                let access = vec![local_to_world(&b, DVec2::new(0.0, size.y * 0.5 + ACCESS))];
                return Some(self.push(category, b, access, None));
            }
        }
        None
    }

    /// Places a piece at a given pose relative to another one, if it fits.
    pub fn place_at(
        &mut self,
        category: Category,
        size: DVec3,
        center: DVec2,
        yaw: f64,
        anchor: usize,
        access_local: &[DVec2],
    ) -> Option<usize> {
        let b = OBox::new(center.extend(size.z * 0.5), size, yaw);
        if !self.fits(&b, BESIDE_CLEARANCE) {
            return None;
        }
        let access = access_local.iter().map(|&l| local_to_world(&b, l)).collect();
        Some(self.push(category, b, access, Some(anchor)))
    }

    /// Removes every piece from index `from` on (a group that did not work out).
    pub fn truncate(&mut self, from: usize, reserved_from: usize) {
        self.placed.truncate(from);
        self.reserved.truncate(reserved_from);
    }

    /// Number of reserved zones (to roll a group back).
    pub fn reserved_len(&self) -> usize {
        self.reserved.len()
    }

    /// A bed against a wall with up to `nightstands` nightstands beside its headboard.
    pub fn place_bed(&mut self, category: Category, nightstands: usize, rng: &mut Rng) -> Option<usize> {
        let size = real_size(category, rng);
        // Look for a wall stretch wide enough for the bed and its nightstands, then put the bed
        // in its middle.
        let room = DVec3::new(size.x + nightstands.min(2) as f64 * 0.6, size.y, size.z);
        let bed = (0..30).find_map(|_| {
            let (c, yaw) = self.wall_spot(room.x, room.y, rng)?;
            let b = OBox::new(c.extend(size.z * 0.5), size, yaw);
            self.fits(&b, 0.02).then(|| self.push(category, b, Vec::new(), None))
        });
        let bed = match bed {
            Some(b) => b,
            None => self.place_on_wall(category, size, rng, 30)?,
        };
        let b = self.placed[bed].obox;
        let (w, d) = (size.x, size.y);
        self.placed[bed].access =
            [DVec2::new(0.0, d * 0.5 + ACCESS), DVec2::new(w * 0.5 + ACCESS, 0.0), DVec2::new(-w * 0.5 - ACCESS, 0.0)]
                .iter()
                .map(|&l| local_to_world(&b, l))
                .collect();
        let mut sides = [-1.0, 1.0];
        rng.shuffle(&mut sides);
        let mut placed = 0;
        for s in sides {
            if placed >= nightstands {
                break;
            }
            let ns = real_size(Category::Nightstand, rng);
            let gap = self.spacing.gap(0.04, rng);
            let local = DVec2::new(s * (w * 0.5 + ns.x * 0.5 + gap), -d * 0.5 + ns.y * 0.5);
            let c = local_to_world(&b, local);
            // Reached from the bed: no walkway needed in front of it.
            if self.place_at(Category::Nightstand, ns, c, b.yaw, bed, &[]).is_some() {
                placed += 1;
            }
        }
        self.reserve_front(&b, 0.5);
        Some(bed)
    }

    /// A piece against a wall with a seat in front of it facing it (desk + chair, dressing table +
    /// stool).
    pub fn place_with_seat(&mut self, category: Category, seat: Option<Category>, rng: &mut Rng) -> Option<usize> {
        let size = real_size(category, rng);
        let main = self.place_on_wall(category, size, rng, 30)?;
        let b = self.placed[main].obox;
        if let Some(seat) = seat {
            let s = real_size(seat, rng);
            let along = rng.uniform(-0.15, 0.15) * size.x;
            let gap = self.spacing.gap(0.04, rng);
            let c = local_to_world(&b, DVec2::new(along, size.y * 0.5 + s.y * 0.5 + gap));
            let yaw = b.yaw + std::f64::consts::PI;
            self.place_at(seat, s, c, yaw, main, &[DVec2::new(0.0, -s.y * 0.5 - ACCESS)]);
        }
        Some(main)
    }

    /// A free-standing table with `chairs` chairs of `chair` around it.
    pub fn place_table_with_chairs(
        &mut self,
        table: Category,
        chair: Category,
        chairs: usize,
        rng: &mut Rng,
    ) -> Option<usize> {
        let (min, max) = self.polygon.bounds();
        let start = self.placed.len();
        let reserved = self.reserved_len();
        let mut size = real_size(table, rng);
        let mut chair_size = real_size(chair, rng);
        for attempt in 0..60 {
            if attempt % 15 == 14 {
                // Another real table and chair, maybe smaller.
                size = real_size(table, rng);
                chair_size = real_size(chair, rng);
            }
            let margin = chair_size.y + 0.3;
            let c =
                DVec2::new(rng.uniform(min.x + margin, max.x - margin), rng.uniform(min.y + margin, max.y - margin));
            let yaw = std::f64::consts::FRAC_PI_2 * rng.index(2) as f64;
            let b = OBox::new(c.extend(size.z * 0.5), size, yaw);
            if !self.fits(&b, 0.6) {
                continue;
            }
            let t = self.push(table, b, Vec::new(), None);
            let mut seats = chair_slots(&size, &chair_size, chairs);
            seats.truncate(chairs);
            let mut n = 0;
            for (local, facing_local) in seats {
                // The slots stand CHAIR_GAP from the table; a chair faces the table, so it backs
                // away from it along its own facing.
                let back = self.spacing.gap(CHAIR_GAP, rng) - CHAIR_GAP;
                let at = local_to_world(&b, local - facing_local * back);
                let yaw = b.yaw + yaw_facing(facing_local);
                if self
                    .place_at(chair, chair_size, at, yaw, t, &[DVec2::new(0.0, -chair_size.y * 0.5 - ACCESS)])
                    .is_some()
                {
                    n += 1;
                }
            }
            if n >= 2.min(chairs) {
                return Some(t);
            }
            self.truncate(start, reserved);
        }
        None
    }

    /// A sofa against a wall, then what faces it: coffee table, tv stand on the opposite wall,
    /// armchairs beside the coffee table, end tables beside the sofa.
    pub fn place_sofa_group(&mut self, sofa: Category, extras: &mut Vec<Category>, rng: &mut Rng) -> Option<usize> {
        let size = real_size(sofa, rng);
        // The share is drawn only when asked for: with none, the rooms are those drawn before it.
        let free = self.spacing.free_sofas > 0.0 && rng.uniform(0.0, 1.0) < self.spacing.free_sofas;
        let off_wall = if free { self.place_off_wall(sofa, size, rng, 30) } else { None };
        let s = match off_wall {
            Some(s) => s,
            None => self.place_on_wall(sofa, size, rng, 30)?,
        };
        let b = self.placed[s].obox;
        let (w, d) = (size.x, size.y);
        self.placed[s].access = [-1.0, 1.0]
            .iter()
            .map(|&k| local_to_world(&b, DVec2::new(k * (w * 0.5 - 0.25), d * 0.5 + ACCESS)))
            .collect();
        let take = |extras: &mut Vec<Category>, c: Category| -> bool {
            match extras.iter().position(|&x| x == c) {
                Some(i) => {
                    extras.remove(i);
                    true
                }
                None => false,
            }
        };
        let mut coffee = None;
        if take(extras, Category::CoffeeTable) {
            let ct = real_size(Category::CoffeeTable, rng);
            let gap = self.spacing.gap(0.4, rng);
            let c = local_to_world(&b, DVec2::new(0.0, d * 0.5 + gap + ct.y * 0.5));
            coffee = self.place_at(Category::CoffeeTable, ct, c, b.yaw, s, &[]);
            if coffee.is_none() {
                extras.push(Category::CoffeeTable);
            }
        }
        if take(extras, Category::TvStand) && self.place_opposite(Category::TvStand, &b, rng).is_none() {
            extras.push(Category::TvStand);
        }
        for chair in [Category::Armchair, Category::LoungeChair] {
            for side in [-1.0, 1.0] {
                let Some(ct) = coffee.map(|i| self.placed[i].obox) else { break };
                if !extras.contains(&chair) {
                    break;
                }
                let a = real_size(chair, rng);
                let gap = self.spacing.gap(0.3, rng);
                let local = DVec2::new(side * (ct.size.x * 0.5 + gap + a.y * 0.5), 0.0);
                let at = local_to_world(&ct, local);
                let yaw = ct.yaw + yaw_facing(DVec2::new(-side, 0.0));
                if self.place_at(chair, a, at, yaw, s, &[DVec2::new(0.0, a.y * 0.5 + 0.3)]).is_some() {
                    take(extras, chair);
                }
            }
        }
        for end in [Category::CornerSideTable, Category::RoundEndTable] {
            for side in [-1.0, 1.0] {
                if !extras.contains(&end) {
                    break;
                }
                let e = real_size(end, rng);
                let gap = self.spacing.gap(0.05, rng);
                let at = local_to_world(&b, DVec2::new(side * (w * 0.5 + e.x * 0.5 + gap), -d * 0.5 + e.y * 0.5));
                if self.place_at(end, e, at, b.yaw, s, &[DVec2::new(0.0, e.y * 0.5 + ACCESS)]).is_some() {
                    take(extras, end);
                }
            }
        }
        Some(s)
    }

    /// A piece on the wall that the front of `from` looks at, facing back at it.
    fn place_opposite(&mut self, category: Category, from: &OBox, rng: &mut Rng) -> Option<usize> {
        let origin = from.center.truncate();
        let dir = facing(from.yaw);
        let hit = self
            .polygon
            .edges()
            .filter_map(|(a, b)| ray_segment(origin, dir, a, b).map(|t| (t, a, b)))
            .min_by(|x, y| x.0.total_cmp(&y.0))?;
        let (t, a, b) = hit;
        if t < 1.8 {
            return None;
        }
        let size = real_size(category, rng);
        let along = (b - a).normalize();
        let inward = DVec2::new(-along.y, along.x);
        let gap = self.spacing.gap(WALL_GAP, rng);
        let c = origin + dir * t + inward * (size.y * 0.5 + gap);
        let ob = OBox::new(c.extend(size.z * 0.5), size, yaw_facing(inward));
        if !self.fits(&ob, 0.02) {
            return None;
        }
        let access = vec![local_to_world(&ob, DVec2::new(0.0, size.y * 0.5 + ACCESS))];
        Some(self.push(category, ob, access, None))
    }

    /// A lamp hanging from the ceiling above `over` (or the room's middle), clear of everything below.
    pub fn place_lamp(&mut self, category: Category, over: Option<usize>, rng: &mut Rng) -> Option<usize> {
        let size = real_size(category, rng);
        let (min, max) = self.polygon.bounds();
        let mut spots: Vec<DVec2> = over.map(|i| self.placed[i].obox.center.truncate()).into_iter().collect();
        spots.push((min + max) * 0.5);
        for _ in 0..20 {
            spots.push(DVec2::new(rng.uniform(min.x, max.x), rng.uniform(min.y, max.y)));
        }
        for c in spots {
            let b = OBox::new(c.extend(self.height - size.z * 0.5), size, 0.0);
            let inside = b.footprint().iter().all(|&p| self.polygon.signed_distance(p) < -0.05);
            let clear = self.placed.iter().all(|p| intersection_volume(&b, &p.obox) < 1e-9);
            if inside && clear {
                return Some(self.push(category, b, Vec::new(), None));
            }
        }
        None
    }

    /// Whether every placed floor piece can be reached over walkways at least 0.6 m wide.
    pub fn walkable(&self) -> bool {
        let grid =
            FreeGrid::new(&self.polygon, self.placed.iter().filter(|p| !p.category.is_hanging()).map(|p| &p.obox));
        let Some(main) = grid.main_component() else { return self.placed.is_empty() };
        self.placed
            .iter()
            .filter(|p| !p.access.is_empty())
            .all(|p| p.access.iter().any(|&a| grid.component_at(a, &main)))
    }
}

/// Gap between a table's edge and the front of a chair at it, by the rule.
const CHAIR_GAP: f64 = 0.04;

/// Chair places around a table (table-local position, direction the chair faces), long sides first.
fn chair_slots(table: &DVec3, chair: &DVec3, wanted: usize) -> Vec<(DVec2, DVec2)> {
    let per_side = ((table.x / (chair.x + 0.1)).floor() as usize).max(1);
    let off = table.y * 0.5 + chair.y * 0.5 + CHAIR_GAP;
    let mut slots = Vec::new();
    let long = |k: usize, n: usize| (k as f64 + 0.5) / n as f64 * table.x - table.x * 0.5;
    let n_long = wanted.min(2 * per_side);
    let front = n_long.div_ceil(2);
    let back = n_long / 2;
    for k in 0..front {
        slots.push((DVec2::new(long(k, front), off), DVec2::new(0.0, -1.0)));
    }
    for k in 0..back {
        slots.push((DVec2::new(long(k, back), -off), DVec2::new(0.0, 1.0)));
    }
    let end_off = table.x * 0.5 + chair.y * 0.5 + CHAIR_GAP;
    slots.push((DVec2::new(end_off, 0.0), DVec2::new(-1.0, 0.0)));
    slots.push((DVec2::new(-end_off, 0.0), DVec2::new(1.0, 0.0)));
    slots
}

/// Distance along the ray `o + t·dir` to the segment `a`–`b`, if it hits.
fn ray_segment(o: DVec2, dir: DVec2, a: DVec2, b: DVec2) -> Option<f64> {
    let e = b - a;
    let denom = dir.perp_dot(e);
    if denom.abs() < 1e-12 {
        return None;
    }
    let t = (a - o).perp_dot(e) / denom;
    let u = (a - o).perp_dot(dir) / denom;
    (t > 1e-9 && (0.0..=1.0).contains(&u)).then_some(t)
}

fn round_mm(x: f64) -> f64 {
    (x * 1000.0).round() / 1000.0
}

fn round_angle(a: f64) -> f64 {
    (crate::geom::wrap_angle(a) * 1e6).round() / 1e6
}

/// The floor on a 10 cm grid: which cells are at least half a walkway from walls and furniture,
/// and how they connect.
pub struct FreeGrid {
    origin: DVec2,
    nx: usize,
    ny: usize,
    /// Component label per cell (`u32::MAX` = not walkable).
    label: Vec<u32>,
}

impl FreeGrid {
    /// The grid of `polygon` with `obstacles` as footprints, walkable where at least half a
    /// walkway ([`WALKWAY_HALF`]) from both.
    pub fn new<'a>(polygon: &Polygon, obstacles: impl Iterator<Item = &'a OBox>) -> FreeGrid {
        FreeGrid::with_clearance(polygon, obstacles, WALKWAY_HALF)
    }

    /// As [`FreeGrid::new`], walkable where at least `clearance` from walls and obstacles.
    pub fn with_clearance<'a>(
        polygon: &Polygon,
        obstacles: impl Iterator<Item = &'a OBox>,
        clearance: f64,
    ) -> FreeGrid {
        let (min, max) = polygon.bounds();
        let origin = min;
        let nx = ((max.x - min.x) / GRID).ceil() as usize;
        let ny = ((max.y - min.y) / GRID).ceil() as usize;
        let center = |i: usize, j: usize| origin + DVec2::new((i as f64 + 0.5) * GRID, (j as f64 + 0.5) * GRID);
        let obstacles: Vec<&OBox> = obstacles.collect();
        // Clearance of each cell: distance to the walls, then to each footprint near it.
        let mut clear = vec![0.0f64; nx * ny];
        for j in 0..ny {
            for i in 0..nx {
                let p = center(i, j);
                let mut d = -polygon.signed_distance(p);
                if d >= clearance {
                    for o in &obstacles {
                        let (lo, hi) = o.footprint_aabb();
                        if p.x < lo.x - clearance
                            || p.x > hi.x + clearance
                            || p.y < lo.y - clearance
                            || p.y > hi.y + clearance
                        {
                            continue;
                        }
                        d = d.min(o.footprint_signed_distance(p));
                        if d < clearance {
                            break;
                        }
                    }
                }
                clear[j * nx + i] = d;
            }
        }
        let mut label = vec![u32::MAX; nx * ny];
        let mut next = 0u32;
        let mut queue = VecDeque::new();
        for start in 0..nx * ny {
            if label[start] != u32::MAX || clear[start] < clearance {
                continue;
            }
            label[start] = next;
            queue.push_back(start);
            while let Some(c) = queue.pop_front() {
                let (i, j) = (c % nx, c / nx);
                let mut visit = |n: usize| {
                    if label[n] == u32::MAX && clear[n] >= clearance {
                        label[n] = next;
                        queue.push_back(n);
                    }
                };
                if i > 0 {
                    visit(c - 1);
                }
                if i + 1 < nx {
                    visit(c + 1);
                }
                if j > 0 {
                    visit(c - nx);
                }
                if j + 1 < ny {
                    visit(c + nx);
                }
            }
            next += 1;
        }
        FreeGrid { origin, nx, ny, label }
    }

    /// The label of the largest walkable component.
    pub fn main_component(&self) -> Option<u32> {
        let mut sizes = std::collections::HashMap::new();
        for &l in self.label.iter().filter(|&&l| l != u32::MAX) {
            *sizes.entry(l).or_insert(0usize) += 1;
        }
        sizes.into_iter().max_by_key(|&(l, n)| (n, std::cmp::Reverse(l))).map(|(l, _)| l)
    }

    /// The cell containing `p`, if inside the grid.
    pub fn cell(&self, p: DVec2) -> Option<(usize, usize)> {
        let q = (p - self.origin) / GRID;
        (q.x >= 0.0 && q.y >= 0.0 && (q.x as usize) < self.nx && (q.y as usize) < self.ny)
            .then_some((q.x as usize, q.y as usize))
    }

    /// Whether `p` lies in component `label`.
    pub fn component_at(&self, p: DVec2, label: &u32) -> bool {
        self.cell(p).is_some_and(|(i, j)| self.label[j * self.nx + i] == *label)
    }

    /// Grid size (columns, rows) and cell side.
    pub fn shape(&self) -> (usize, usize, f64) {
        (self.nx, self.ny, GRID)
    }

    /// Centre of cell (i, j).
    pub fn center(&self, i: usize, j: usize) -> DVec2 {
        self.origin + DVec2::new((i as f64 + 0.5) * GRID, (j as f64 + 0.5) * GRID)
    }

    /// Label of cell (i, j) (`u32::MAX` = not walkable).
    pub fn label(&self, i: usize, j: usize) -> u32 {
        self.label[j * self.nx + i]
    }
}

/// Categories in the order the layout places them.
pub fn placement_rank(c: Category) -> u8 {
    match c.group() {
        Group::Bed => 0,
        Group::Sofa => 1,
        _ if c == Category::DiningTable => 2,
        _ if matches!(c, Category::Desk | Category::DressingTable) => 3,
        Group::Cabinet | Group::Shelf => 4,
        Group::Table => 5,
        Group::Chair | Group::Stool => 6,
        Group::Lamp => 7,
    }
}
