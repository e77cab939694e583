//! One procedural room: floor plan, furniture counts drawn from 3D-FRONT's figures, arrangement,
//! humans, and (for the raw dataset) misplaced contact humans.

use super::Rng;
use super::floor_gen::sample_floor;
use super::layout::{Layout, placement_rank};
use super::people::{contact_humans, misplace, walkers};
use super::threedfront::{BEDROOM_COUNTS, BEDROOM_ROOMS, LIVING_COUNTS};
use crate::scene::{Category, Group, RoomType, Scene};

/// Mean objects per living and dining room (3D-FRONT's living rooms average about nine pieces).
const LIVING_MEAN_OBJECTS: f64 = 9.0;
const DINING_MEAN_OBJECTS: f64 = 11.0;

/// How a room's furniture counts are drawn: each category a Poisson count with its 3D-FRONT mean
/// per room, then the rules every room of the type follows (one bed per bedroom, at most two
/// nightstands, a dining table with 2–8 chairs in every dining room), within 3..=max objects.
pub fn sample_categories(room: RoomType, rng: &mut Rng) -> Vec<Category> {
    let (counts, per_room): (&[(Category, f64)], f64) = match room {
        RoomType::Bedroom => (&BEDROOM_COUNTS, 1.0 / BEDROOM_ROOMS),
        RoomType::Living => (&LIVING_COUNTS, LIVING_MEAN_OBJECTS / LIVING_COUNTS.iter().map(|c| c.1).sum::<f64>()),
        RoomType::Dining => (&LIVING_COUNTS, DINING_MEAN_OBJECTS / LIVING_COUNTS.iter().map(|c| c.1).sum::<f64>()),
    };
    let mut out = Vec::new();
    for &(c, n) in counts {
        let k = rng.poisson(n * per_room * dining_boost(room, c));
        out.extend(std::iter::repeat_n(c, k));
    }
    let count = |out: &Vec<Category>, c: Category| out.iter().filter(|&&x| x == c).count();
    match room {
        RoomType::Bedroom => {
            out.retain(|c| c.group() != Group::Bed);
            let beds = [(Category::DoubleBed, 3320.0), (Category::SingleBed, 411.0), (Category::KidsBed, 158.0)];
            out.insert(0, beds[rng.weighted(&beds.map(|b| b.1))].0);
            while count(&out, Category::Nightstand) > 2 {
                let i = out.iter().rposition(|&c| c == Category::Nightstand).expect("counted");
                out.remove(i);
            }
        }
        RoomType::Dining | RoomType::Living => {
            // Dining tables and their chairs come as a group: always in a dining room, in about
            // half of the living rooms (3D-FRONT: 3.7 dining chairs per dining table).
            out.retain(|&c| c != Category::DiningTable && c != Category::DiningChair);
            let p_group = if room == RoomType::Dining { 1.0 } else { 0.55 };
            if rng.chance(p_group) {
                out.insert(0, Category::DiningTable);
                let chairs = (2 + rng.poisson(if room == RoomType::Dining { 1.5 } else { 1.9 })).min(8);
                out.extend(std::iter::repeat_n(Category::DiningChair, chairs));
            } else if rng.chance(0.15) {
                out.push(Category::DiningChair);
            }
        }
    }
    while count(&out, Category::DiningChair) > 8 {
        let i = out.iter().rposition(|&c| c == Category::DiningChair).expect("counted");
        out.remove(i);
    }
    let freq: Vec<f64> = counts.iter().map(|c| c.1).collect();
    while out.len() < 3 {
        out.push(counts[rng.weighted(&freq)].0);
    }
    while out.len() > room.max_objects() {
        // Drop the least important: lamps and small pieces last in the placement order go first.
        let i = (0..out.len()).max_by_key(|&i| (placement_rank(out[i]), i)).expect("non-empty");
        out.remove(i);
    }
    out.sort_by_key(|&c| placement_rank(c));
    out
}

/// Dining rooms always hold a dining table and chairs, which crowds out the pieces that fit less
/// easily into the smaller rooms; these factors (fitted on 500 rooms, seed 1) draw those pieces more
/// often so that the placed furniture still follows the target frequencies.
fn dining_boost(room: RoomType, c: Category) -> f64 {
    match (room, c) {
        (RoomType::Dining, Category::CoffeeTable | Category::LoungeChair) => 1.8,
        (RoomType::Dining, Category::MultiSeatSofa | Category::LoveseatSofa | Category::Armchair) => 1.6,
        (RoomType::Dining, Category::CornerSideTable) => 1.3,
        (RoomType::Dining, Category::PendantLamp) => 0.9,
        _ => 1.0,
    }
}

/// Furnishes an empty `layout` with `wanted` (as drawn by [`sample_categories`]).
pub fn furnish(layout: &mut Layout, room: RoomType, mut wanted: Vec<Category>, rng: &mut Rng) {
    let take = |wanted: &mut Vec<Category>, pred: &dyn Fn(Category) -> bool| -> Option<Category> {
        let i = wanted.iter().position(|&c| pred(c))?;
        Some(wanted.remove(i))
    };
    let mut anchors = Vec::new();
    // Try a group up to three times; keep it only if every piece stays reachable.
    let group = |layout: &mut Layout, rng: &mut Rng, f: &mut dyn FnMut(&mut Layout, &mut Rng) -> Option<usize>| {
        for _ in 0..3 {
            let (n, r) = (layout.placed.len(), layout.reserved_len());
            match f(layout, rng) {
                Some(i) if layout.walkable() => return Some(i),
                Some(_) => layout.truncate(n, r),
                None => return None,
            }
        }
        None
    };
    if let Some(bed) = take(&mut wanted, &|c| c.group() == Group::Bed) {
        let ns = wanted.iter().filter(|&&c| c == Category::Nightstand).count();
        wanted.retain(|&c| c != Category::Nightstand);
        anchors.extend(group(layout, rng, &mut |l, r| l.place_bed(bed, ns, r)));
    }
    if let Some(table) = take(&mut wanted, &|c| c == Category::DiningTable) {
        let chair = if room == RoomType::Bedroom { Category::Chair } else { Category::DiningChair };
        let n = wanted.iter().filter(|&&c| c == chair).count();
        wanted.retain(|&c| c != chair);
        anchors.extend(group(layout, rng, &mut |l, r| l.place_table_with_chairs(table, chair, n.clamp(2, 8), r)));
    }
    if let Some(sofa) = take(&mut wanted, &|c| c.group() == Group::Sofa) {
        let before = wanted.clone();
        let mut extras = wanted.clone();
        let placed = group(layout, rng, &mut |l, r| {
            extras = before.clone();
            l.place_sofa_group(sofa, &mut extras, r)
        });
        if placed.is_some() {
            wanted = extras;
            anchors.extend(placed);
        }
    }
    for (main, seats) in [
        (Category::Desk, &[Category::Chair, Category::DiningChair][..]),
        (Category::DressingTable, &[Category::DressingChair, Category::Stool][..]),
    ] {
        while let Some(m) = take(&mut wanted, &|c| c == main) {
            let seat = take(&mut wanted, &|c| seats.contains(&c));
            group(layout, rng, &mut |l, r| l.place_with_seat(m, seat, r));
        }
    }
    let lamps: Vec<Category> = wanted.iter().copied().filter(|c| c.is_hanging()).collect();
    wanted.retain(|c| !c.is_hanging());
    for c in wanted {
        let against_wall = placed_against_wall(c);
        group(layout, rng, &mut |l, r| {
            let size = super::layout::real_size(c, r);
            if against_wall { l.place_on_wall(c, size, r, 30) } else { l.place_free(c, size, r, 40) }
        });
    }
    for (k, c) in lamps.into_iter().enumerate() {
        layout.place_lamp(c, anchors.get(k).copied(), rng);
    }
}

/// Whether the synthetic layouts stand a piece of `category` with its back against a wall, besides
/// beds (which go against one with their nightstands first).
pub fn placed_against_wall(category: Category) -> bool {
    matches!(category.group(), Group::Cabinet | Group::Shelf | Group::Sofa)
        || matches!(category, Category::ConsoleTable | Category::Desk | Category::DressingTable)
}

/// What the raw dataset records about a room besides the scene.
#[derive(Debug, Clone, PartialEq)]
pub struct RoomRecord {
    /// The scene (misplaced contact humans included when `raw`).
    pub scene: Scene,
    /// For each contact human (in scene order): the index of the object it was placed on.
    pub contact_objects: Vec<usize>,
}

/// Generates room `index` of a dataset seeded by `seed`. With `raw`, contact humans are misplaced
/// as in 3D-FRONT HUMAN; without, they rest exactly where they were placed.
pub fn generate_room(room: RoomType, seed: u64, index: u64, raw: bool) -> RoomRecord {
    let mut rng = super::Rng::for_item(seed, index);
    let plan = sample_floor(room, &mut rng);
    let mut layout = Layout::new(&plan);
    // Redraw until the room holds at least three pieces and its defining piece (a bed in a
    // bedroom, a dining table in a dining room).
    for _ in 0..20 {
        layout = Layout::new(&plan);
        let wanted = sample_categories(room, &mut rng);
        furnish(&mut layout, room, wanted, &mut rng);
        let has = |g: &dyn Fn(Category) -> bool| layout.placed.iter().any(|p| g(p.category));
        let defining = match room {
            RoomType::Bedroom => has(&|c| c.group() == Group::Bed),
            RoomType::Dining => has(&|c| c == Category::DiningTable),
            RoomType::Living => true,
        };
        if defining && layout.placed.len() >= 3 {
            break;
        }
    }
    let objects = layout.objects();
    let contact = contact_humans(&layout, &objects, &mut rng);
    let contact_bodies: Vec<_> = contact.iter().map(|(_, _, h)| h.clone()).collect();
    let n_walkers = rng.range(2, 4);
    let walking = walkers(&layout, &contact_bodies, n_walkers, &mut rng);
    let mut scene = Scene::new(room, plan);
    scene.objects = objects;
    let mut contact_objects = Vec::new();
    for (k, (action, object, mut human)) in contact.into_iter().enumerate() {
        if raw {
            let size = scene.objects[object].size;
            misplace(&mut human, action, size[0].max(size[1]), &mut rng);
        }
        human.id = format!("h{k}");
        contact_objects.push(object);
        scene.humans.push(human);
    }
    for mut w in walking {
        w.id = format!("h{}", scene.humans.len());
        scene.humans.push(w);
    }
    RoomRecord { scene, contact_objects }
}
