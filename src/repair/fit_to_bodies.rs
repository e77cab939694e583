//! `fit_to_bodies` (ours): pieces that bones still enter reshaped, a few centimetres at a time,
//! until the bodies around them stop entering them.
//!
//! `settle` keeps pieces off people's paths by a height map and fits seats, beds and tables under
//! the people they hold, but a piece a little too shallow, too narrow, too tall or in the wrong
//! place for the bodies around it — a sitter's back in a loveseat's backrest and their shins in
//! its front, a walker's hip through the end of the sofa they pass, a diner's thigh under a table
//! top wedged between two others, a cabinet's front in the person standing before it — is only
//! found by replaying the bodies against the pieces' parts. This step searches, for each piece a bone still enters deeper than
//! the check's tolerance, the small changes of its box: moving it along its own axes, moving one
//! of its four sides or its top in or out, or turning it about its centre so that its corners
//! move, by each of [`FitToBodiesConfig::steps`](super::config::FitToBodiesConfig::steps). It
//! takes the change that takes the bones furthest out of it (the check's exact capsule depths,
//! [`Physics::piece_fit`]) and repeats while some change helps. A change is allowed only where
//! every person the check found supported stays supported (its own support test), the piece
//! goes no further out of the floor plan or into any other piece, and each of its sizes stays
//! within its category's real sizes (or no further outside them). Where no shape of a piece that
//! holds people is clear of the bodies, the same search runs from each other category that affords
//! what they do on it (a sofa whose sitter sits 30 cm from a wall becomes a stool): started where
//! the piece stands and, where none of those ends clear, under its people and as tall as their
//! seat (within the 15 cm of real heights that guidance and `eval` allow; a kids' bed under a child
//! on a 30 cm seat becomes a low chair), each start moved inside the floor plan first and ending
//! no further out of it than the piece (a loveseat in a corner does not become a wider sofa
//! through the wall). A piece that holds nobody keeps its category. One
//! mechanism for every way a piece can meet a body; it knows nothing of what the piece or the body
//! is.
//!
//! Nothing changes when no change helps; hanging pieces are left alone.

use super::completion::height_for_surface;
use super::config::{RepairConfig, StepName};
use super::helpers::{inside_push, shift, worst_offence};
use super::occupancy::Occupancy;
use super::pipeline::{RepairStep, StepReport, Workspace};
use crate::furniture::{REAL_SIZE_MARGIN, beyond_real, height_range, size_range};
use crate::geom::{Polygon, intersection_volume};
use crate::physics::{EngineContact, Owner, PHYS_TOLERANCE, Physics};
use crate::scene::{Action, Category, Object, Scene};
use glam::DVec2;

/// The changes of `o` one round tries: for each step length, a move along each local axis both
/// ways, each side of its footprint out and in, a turn each way that moves its corners by that
/// much, and its top up and down.
fn changes(o: &Object, steps: &[f64]) -> Vec<Object> {
    let (ax, ay) = o.obox().axes();
    let axes = [ax, ay];
    let mut out = Vec::with_capacity(steps.len() * 16);
    for &s in steps {
        for (k, axis) in axes.iter().enumerate() {
            for sign in [-1.0, 1.0] {
                // Moved along the axis.
                let mut moved = o.clone();
                let m: DVec2 = *axis * (sign * s);
                moved.center[0] += m.x;
                moved.center[1] += m.y;
                out.push(moved);
                // The side on `sign`'s end out (grow) and in (shrink), the other side staying.
                for grow in [-1.0, 1.0] {
                    let mut sided = o.clone();
                    sided.size[k] += grow * s;
                    let m: DVec2 = *axis * (sign * grow * s * 0.5);
                    sided.center[0] += m.x;
                    sided.center[1] += m.y;
                    out.push(sided);
                }
            }
        }
        // Turned about its centre so that its corners move by s.
        let half_diagonal = (o.size[0].hypot(o.size[1]) * 0.5).max(1e-3);
        for sign in [-1.0, 1.0] {
            let mut turned = o.clone();
            turned.yaw += sign * s / half_diagonal;
            out.push(turned);
        }
        for grow in [-1.0, 1.0] {
            let mut topped = o.clone();
            topped.size[2] += grow * s;
            topped.center[2] += grow * s * 0.5;
            out.push(topped);
        }
    }
    out
}

/// Whether `c`'s sizes are within its category's real ones, or no further outside them than
/// `before`'s.
fn real_enough(c: &Object, before: &Object) -> bool {
    (0..3).all(|k| {
        let outside = |v: f64| beyond_real(c.category, k, v);
        c.size[k] > 0.05 && outside(c.size[k]) <= outside(before.size[k]) + 1e-9
    })
}

/// What a piece may not do while it changes: go further out of the floor plan or further into
/// another piece than it is.
struct Room<'a> {
    polygon: Polygon,
    gap: f64,
    others: &'a [Object],
    /// How far piece `i` pokes out of the floor plan now (m, [`worst_offence`]).
    outside: f64,
    /// How far piece `i` overlaps each other piece now (m³).
    overlap: Vec<f64>,
}

impl<'a> Room<'a> {
    /// Piece `i` of `objects` as it is.
    fn of(scene: &Scene, objects: &'a [Object], i: usize, gap: f64) -> Room<'a> {
        let polygon = scene.floor_plan.polygon();
        let b = objects[i].obox();
        let outside = worst_offence(&b, &polygon, gap).map_or(0.0, |w| w.0);
        let overlap = objects.iter().map(|o| intersection_volume(&b, &o.obox())).collect();
        Room { polygon, gap, others: objects, outside, overlap }
    }

    /// Whether `c` pokes out of the floor plan no further than piece `i` does.
    fn keeps_inside(&self, c: &Object) -> bool {
        worst_offence(&c.obox(), &self.polygon, self.gap).map_or(0.0, |w| w.0) <= self.outside + 1e-9
    }

    /// Whether `c` goes no further out of the floor plan or into another piece than piece `i`.
    fn allows(&self, i: usize, c: &Object) -> bool {
        let b = c.obox();
        self.keeps_inside(c)
            && self
                .others
                .iter()
                .enumerate()
                .all(|(j, other)| j == i || intersection_volume(&b, &other.obox()) <= self.overlap[j] + 1e-9)
    }
}

/// The search's fixed terms for one piece: who must stay supported, the depth tolerance.
struct Search<'a> {
    i: usize,
    physics: &'a dyn Physics,
    config: &'a RepairConfig,
    tolerance: f64,
    /// The people the check found unsupported before the piece changed (nobody else may join them).
    unsupported: Vec<usize>,
    /// Shapes judged so far, against
    /// [`FitToBodiesConfig::max_tries`](super::config::FitToBodiesConfig::max_tries).
    tries: std::cell::Cell<usize>,
}

impl Search<'_> {
    /// How deep the bones are in `o` put in place of the piece, where everybody supported before
    /// stays supported; `None` otherwise.
    fn depth(&self, scene: &mut Scene, o: &Object) -> Option<f64> {
        if self.spent() {
            return None;
        }
        self.tries.set(self.tries.get() + 1);
        let kept = std::mem::replace(&mut scene.objects[self.i], o.clone());
        let fit = self.physics.piece_fit(scene, self.i, self.tolerance);
        scene.objects[self.i] = kept;
        fit.unsupported.iter().all(|h| self.unsupported.contains(h)).then_some(fit.depth)
    }

    /// Whether the piece's budget of shapes to judge is spent.
    fn spent(&self) -> bool {
        self.tries.get() >= self.config.fit_to_bodies.max_tries
    }

    /// The piece reshaped from `from` ([`changes`], the best change each round, while one helps)
    /// and the depth it ends with (infinite where it ends further out of the floor plan than the
    /// piece); sizes no further outside the real ones than `from`'s.
    fn run(&self, scene: &mut Scene, from: Object, depth: f64) -> (Object, f64) {
        let cfg = &self.config.fit_to_bodies;
        let others = scene.objects.clone();
        let room = Room::of(scene, &others, self.i, self.config.gap);
        // A start further out of the floor plan than the piece (another category's shape that no
        // push fits inside) is no answer: the first change the room allows beats it. A start's
        // overlaps with other pieces are left to `overlaps`, as the piece's own are.
        let start_depth = if room.keeps_inside(&from) { depth } else { f64::INFINITY };
        let mut best = (from.clone(), start_depth);
        for _ in 0..cfg.rounds {
            if best.1 <= 0.0 || self.spent() {
                break;
            }
            let mut round_best: Option<(Object, f64)> = None;
            for c in changes(&best.0, &cfg.steps) {
                if !real_enough(&c, &from) || !room.allows(self.i, &c) {
                    continue;
                }
                let bar = round_best.as_ref().map_or(best.1 - cfg.min_gain, |r| r.1);
                if let Some(d) = self.depth(scene, &c).filter(|&d| d < bar) {
                    round_best = Some((c, d));
                }
            }
            match round_best {
                Some(r) => best = r,
                None => break,
            }
        }
        best
    }
}

/// `o` as a piece of `category`: each size brought into that category's real sizes, its centre
/// kept.
fn as_category(o: &Object, category: Category) -> Object {
    let mut c = o.clone();
    c.category = category;
    for k in 0..3 {
        let (lo, hi) = size_range(category, k);
        c.size[k] = c.size[k].clamp(lo, hi);
    }
    c.center[2] = c.size[2] * 0.5 + (o.center[2] - o.size[2] * 0.5);
    c
}

/// `o` as its people need it: unturned, centred under them (world xy) and as tall as puts its
/// sitting or lying surface at `surface` (the top of their contact boxes), standing on the floor —
/// within its category's real heights widened by [`REAL_SIZE_MARGIN`], as far as guidance and
/// `eval` count a piece real.
fn under_people(o: &Object, held: &Held) -> Object {
    let mut c = o.clone();
    c.center[0] = held.under.x;
    c.center[1] = held.under.y;
    let (lo, hi) = height_range(c.category);
    c.size[2] =
        height_for_surface(c.category, c.size, held.surface).clamp(lo - REAL_SIZE_MARGIN, hi + REAL_SIZE_MARGIN);
    c.center[2] = c.size[2] * 0.5;
    c
}

/// What a piece must hold, for the search under other categories: the actions its people do on
/// it, the middle of their contact boxes (world xy) and the highest of their tops (m). No actions
/// when it holds nobody.
struct Held {
    affords: Vec<Action>,
    under: DVec2,
    surface: f64,
}

/// Reshapes object `i` of `scene` while that takes bones out of it ([`changes`]); where that
/// leaves bones in it, tries it as each other category that affords what its people do
/// (`held`; none when it holds nobody) — the few whose starting shape the bones enter least —
/// reshaped the same way, and takes the one nearest its size that leaves no bone in it. The other
/// categories start where the piece stands, moved inside the floor plan where their shape pokes
/// out of it, and end no further out of it than the piece was; where none of those ends clean,
/// they start again under its people, as tall as their seat ([`under_people`]: a bed under a child
/// on a 30 cm seat, whose stool must stand beneath the child and that low). Returns whether it
/// changed.
fn fit_piece(scene: &mut Scene, i: usize, held: &Held, physics: &dyn Physics, config: &RepairConfig) -> bool {
    let tolerance = PHYS_TOLERANCE - config.fit_to_bodies.margin;
    let given = scene.objects[i].clone();
    let start = physics.piece_fit(scene, i, tolerance);
    let search = Search { i, physics, config, tolerance, unsupported: start.unsupported, tries: Default::default() };
    let mut best = search.run(scene, given.clone(), start.depth);
    if best.1 > 0.0 && config.fit_to_bodies.other_categories && !held.affords.is_empty() {
        let others: Vec<Category> = scene
            .room_type
            .categories()
            .iter()
            .copied()
            .filter(|&c| c != given.category && !c.is_hanging() && held.affords.iter().all(|&a| c.affords(a)))
            .collect();
        let size_change = |o: &Object| (0..3).map(|k| (o.size[k] - given.size[k]).abs()).sum::<f64>();
        let polygon = scene.floor_plan.polygon();
        // From each start, the categories whose starting shape the bones enter least are searched.
        let mut search_from = |place: &dyn Fn(Object) -> Object| -> Option<Object> {
            let mut starts: Vec<(Object, f64)> = others
                .iter()
                .filter_map(|&category| {
                    let mut from = place(as_category(&given, category));
                    let push = inside_push(&from.obox(), &polygon, config.gap);
                    shift(&mut from, push);
                    search.depth(scene, &from).map(|d| (from, d))
                })
                .collect();
            starts.sort_by(|a, b| a.1.total_cmp(&b.1));
            starts.truncate(config.fit_to_bodies.categories_searched);
            let mut clean: Option<Object> = None;
            for (from, depth) in starts {
                let (o, d) = search.run(scene, from, depth);
                if d <= 0.0 && clean.as_ref().is_none_or(|c| size_change(&o) < size_change(c)) {
                    clean = Some(o);
                }
            }
            clean
        };
        let clean = search_from(&|o| o).or_else(|| search_from(&|o| under_people(&o, held)));
        if let Some(o) = clean {
            best = (o, 0.0);
        }
    }
    scene.objects[i] = best.0;
    scene.objects[i] != given
}

/// Reshapes every standing piece that a bone of `contacts` (the scene's exact contacts deeper than
/// the check's tolerance) enters. Returns how many changed.
fn fit_to_bodies(
    scene: &mut Scene,
    contacts: &[EngineContact],
    people: &Occupancy,
    physics: &dyn Physics,
    config: &RepairConfig,
) -> usize {
    let mut entered: Vec<usize> = contacts
        .iter()
        .filter_map(|c| match c.owner {
            Owner::Object(i) if !scene.objects[i].category.is_hanging() => Some(i),
            _ => None,
        })
        .collect();
    entered.sort_unstable();
    entered.dedup();
    let mut fitted = 0;
    for i in entered {
        let boxes = people.held_by(i);
        let under = boxes.iter().map(|(c, _)| c.obox.center.truncate()).sum::<DVec2>() / boxes.len().max(1) as f64;
        let surface = boxes.iter().map(|(c, _)| c.obox.z_range().1).fold(0.0, f64::max);
        let held = Held { affords: boxes.iter().map(|(c, _)| c.action).collect(), under, surface };
        fitted += usize::from(fit_piece(scene, i, &held, physics, config));
    }
    fitted
}

/// The `fit_to_bodies` step.
#[derive(Debug, Clone, Copy, Default)]
pub struct FitToBodies;

impl RepairStep for FitToBodies {
    fn name(&self) -> StepName {
        StepName::FitToBodies
    }

    fn run(&self, scene: &mut Scene, work: &mut Workspace<'_>, config: &RepairConfig) -> StepReport {
        let physics = work.physics;
        let contacts = match work.bones.take() {
            Some(bones) => bones,
            None => physics.exact_contacts(scene, PHYS_TOLERANCE),
        };
        let fitted = fit_to_bodies(scene, &contacts, &work.people, physics, config);
        // What `left_out` sees: the bones where the pieces are now.
        work.bones = Some(if fitted > 0 { physics.exact_contacts(scene, PHYS_TOLERANCE) } else { contacts });
        StepReport::FitToBodies { fitted }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::generate_room;
    use crate::physics::PieceFit;
    use crate::repair::helpers::fits_inside;
    use crate::scene::{Group, RoomType};
    use crate::sim::{SimPhysics, check_scene, exact_contacts};
    use glam::DVec2;

    /// The first generated living room with a sofa a sitter sits on, squarely turned, and its index.
    fn sofa_with_sitter() -> (Scene, usize) {
        for index in 0..20 {
            let scene = generate_room(RoomType::Living, 3, index, false).scene;
            let people = occupancy(&scene);
            let found = (0..scene.objects.len()).find(|&i| {
                let o = &scene.objects[i];
                o.category.group() == Group::Sofa
                    && (o.yaw / std::f64::consts::FRAC_PI_2).fract().abs() < 1e-6
                    && people.held_by(i).iter().any(|(c, _)| c.action == Action::Sit)
            });
            if let Some(i) = found.filter(|&i| deepest_in(&scene, i) <= PHYS_TOLERANCE) {
                return (scene, i);
            }
        }
        panic!("no sofa with a sitter");
    }

    /// Who holds whom in `scene`, as the pipeline's workspace finds it.
    fn occupancy(scene: &Scene) -> Occupancy {
        let config = RepairConfig::default();
        let mut people = Occupancy::of(scene, &config.holding);
        people.assign(scene, &config.settle);
        people
    }

    /// The deepest bone in object `i` (m).
    fn deepest_in(scene: &Scene, i: usize) -> f64 {
        exact_contacts(scene, 0.0).iter().filter(|c| c.owner == Owner::Object(i)).map(|c| c.depth).fold(0.0, f64::max)
    }

    /// Runs the step on `scene` with `config` and `sim`'s physics; the pieces it changed.
    fn fit(scene: &mut Scene, config: &RepairConfig) -> usize {
        let mut work = Workspace::new(scene, config, &SimPhysics);
        match FitToBodies.run(scene, &mut work, config) {
            StepReport::FitToBodies { fitted } => fitted,
            other => panic!("{other:?}"),
        }
    }

    /// Moves object `i` by `forward` (m) along its own front axis.
    fn push_forward(scene: &mut Scene, i: usize, forward: f64) {
        let (_, ay) = scene.objects[i].obox().axes();
        let m = ay * forward;
        scene.objects[i].center[0] += m.x;
        scene.objects[i].center[1] += m.y;
    }

    #[test]
    fn a_sofa_pushed_into_its_sitters_back_comes_back_off_it() {
        let (mut scene, i) = sofa_with_sitter();
        let clean = scene.objects[i].clone();
        push_forward(&mut scene, i, 0.08);
        assert!(deepest_in(&scene, i) > 0.04, "the backrest is in the sitter: {}", deepest_in(&scene, i));
        let mut config = RepairConfig::default();
        config.fit_to_bodies.other_categories = false;
        assert_eq!(fit(&mut scene, &config), 1);
        let o = &scene.objects[i];
        assert!(deepest_in(&scene, i) <= PHYS_TOLERANCE, "{}", deepest_in(&scene, i));
        assert_eq!(o.category, clean.category);
        // Back by about the push (a change of size may take some of it), its sitter still on it.
        let back = DVec2::new(o.center[0] - clean.center[0], o.center[1] - clean.center[1]).length();
        assert!(back < 0.08 + 1e-9, "{back}");
        let report = check_scene(&scene, &Default::default());
        assert_eq!(report.count(crate::sim::ViolationKind::Unsupported), 0, "{:?}", report.violations);
    }

    #[test]
    fn pieces_nobody_enters_stay_and_a_piece_that_holds_nobody_keeps_its_category() {
        let (mut scene, i) = sofa_with_sitter();
        let before = scene.objects.clone();
        assert_eq!(fit(&mut scene, &RepairConfig::default()), 0);
        assert_eq!(scene.objects, before);
        // The sofa in its sitter, but nobody assigned to anything: reshaped out of the bones, a
        // sofa still.
        push_forward(&mut scene, i, 0.08);
        let nobody = Occupancy::of(&scene, &RepairConfig::default().holding);
        assert!(nobody.held_by(i).is_empty());
        let contacts = exact_contacts(&scene, PHYS_TOLERANCE);
        assert_eq!(fit_to_bodies(&mut scene, &contacts, &nobody, &SimPhysics, &RepairConfig::default()), 1);
        assert_eq!(scene.objects[i].category, before[i].category);
        assert!(deepest_in(&scene, i) <= PHYS_TOLERANCE, "{}", deepest_in(&scene, i));
    }

    #[test]
    fn a_sofa_that_cannot_hold_its_sitter_against_a_wall_becomes_a_seat_that_can() {
        let (mut scene, i) = sofa_with_sitter();
        // Nothing else in the room; the sofa pushed 20 cm into its sitter and the floor plan cut
        // at its back, so that no sofa fits between the wall and the sitter's back.
        scene.objects = vec![scene.objects[i].clone()];
        push_forward(&mut scene, 0, 0.20);
        let o = scene.objects[0].obox();
        let (_, ay) = o.axes();
        let back = o.center.truncate() - ay * (o.size.y * 0.5);
        let along = |p: DVec2| p.dot(ay);
        let (lo, hi) = scene.floor_plan.polygon().bounds();
        let corners = [lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)];
        let cut: Vec<[f64; 2]> = corners
            .iter()
            .map(|&c| {
                let d = along(c) - along(back);
                let p = if d < 0.0 { c - ay * d } else { c };
                [p.x, p.y]
            })
            .collect();
        scene.floor_plan.polygon = cut;
        assert!(deepest_in(&scene, 0) > 0.04);
        // The other people's pieces are gone: they lack support before and after.
        let unsupported = SimPhysics.piece_fit(&scene, 0, PHYS_TOLERANCE).unsupported;
        let sitters: Vec<usize> = occupancy(&scene)
            .held_by(0)
            .iter()
            .map(|(c, _)| scene.humans.iter().position(|h| h.id == c.human).unwrap())
            .collect();
        assert!(!sitters.is_empty() && sitters.iter().all(|h| !unsupported.contains(h)), "{sitters:?} {unsupported:?}");
        let mut config = RepairConfig::default();
        config.fit_to_bodies.other_categories = false;
        let mut kept = scene.clone();
        fit(&mut kept, &config);
        assert!(deepest_in(&kept, 0) > PHYS_TOLERANCE, "reshaping alone cannot mend it");
        assert_eq!(fit(&mut scene, &RepairConfig::default()), 1);
        let o = &scene.objects[0];
        assert_ne!(o.category, kept.objects[0].category);
        assert!(o.category.affords(Action::Sit), "{}", o.category);
        assert!(deepest_in(&scene, 0) <= PHYS_TOLERANCE, "{}: {}", o.category, deepest_in(&scene, 0));
        for k in 0..3 {
            let (lo, hi) = size_range(o.category, k);
            assert!(o.size[k] >= lo - 1e-9 && o.size[k] <= hi + 1e-9, "{} {:?}", o.category, o.size);
        }
        let fit = SimPhysics.piece_fit(&scene, 0, PHYS_TOLERANCE);
        assert_eq!(fit, PieceFit { depth: 0.0, unsupported });
    }

    /// Physics in which bones enter every piece but a multi-seat sofa, and nobody lacks support.
    struct OnlyMultiSeatSofasFit;

    impl Physics for OnlyMultiSeatSofasFit {
        fn passes_check(&self, _: &Scene) -> bool {
            false
        }
        fn exact_contacts(&self, _: &Scene, _: f64) -> Vec<EngineContact> {
            Vec::new()
        }
        fn pushes(&self, _: &Scene, _: f64) -> Vec<(usize, DVec2)> {
            Vec::new()
        }
        fn piece_fit(&self, scene: &Scene, object: usize, _: f64) -> PieceFit {
            let depth = if scene.objects[object].category == Category::MultiSeatSofa { 0.0 } else { 0.1 };
            PieceFit { depth, unsupported: Vec::new() }
        }
    }

    /// A loveseat 15 cm narrower than any multi-seat sofa, 2 cm from the west and south walls of a
    /// room `width` m wide and 4 m deep, holding one sitter; it and what `fit_piece` makes of it.
    fn loveseat_in_a_corner(width: f64) -> (Object, Object, Polygon) {
        let (mut scene, _) = sofa_with_sitter();
        let narrowest_multi = size_range(Category::MultiSeatSofa, 0).0;
        let (lo, _) = size_range(Category::LoveseatSofa, 0);
        assert!(lo < narrowest_multi - 0.1, "{lo} {narrowest_multi}");
        let w = (narrowest_multi - 0.15).max(lo);
        let given = Object::standing("o0", Category::LoveseatSofa, [0.02 + w * 0.5, 0.42], [w, 0.8, 0.85]);
        scene.floor_plan.polygon = vec![[0.0, 0.0], [width, 0.0], [width, 4.0], [0.0, 4.0]];
        scene.objects = vec![given.clone()];
        let held = Held { affords: vec![Action::Sit], under: DVec2::new(given.center[0], 0.6), surface: 0.45 };
        fit_piece(&mut scene, 0, &held, &OnlyMultiSeatSofasFit, &RepairConfig::default());
        (given, scene.objects[0].clone(), scene.floor_plan.polygon())
    }

    #[test]
    fn another_category_starts_inside_the_floor_plan_and_never_ends_through_a_wall() {
        let gap = RepairConfig::default().gap;
        // Room to spare east of the loveseat: the multi-seat sofa, 7.5 cm wider on each side,
        // starts pushed off the west wall and ends inside.
        let (_, o, polygon) = loveseat_in_a_corner(4.0);
        assert_eq!(o.category, Category::MultiSeatSofa);
        assert!(fits_inside(&o.obox(), &polygon, gap), "{o:?}");
        // A room 3 cm narrower than the narrowest multi-seat sofa (the loveseat 10 cm off its east
        // wall): none fits, so none is drawn through a wall; the loveseat stays as it was.
        let (given, o, _) = loveseat_in_a_corner(size_range(Category::MultiSeatSofa, 0).0 - 0.03);
        assert!(given.center[0] + given.size[0] * 0.5 < size_range(Category::MultiSeatSofa, 0).0 - 0.03 - gap);
        assert_eq!(o, given);
    }

    /// A room from y = `south` to 3 m, 4 m wide, a person standing at (2, 1.5) and a real-sized
    /// cabinet (holding nobody) south of them, its north face as far into them as makes the deepest bone
    /// 5–6 cm deep.
    fn cabinet_into_a_stander(south: f64) -> Scene {
        use crate::human::{Body, Motion, stand};
        let mut scene = generate_room(RoomType::Living, 3, 0, false).scene;
        scene.floor_plan.polygon = vec![[0.0, south], [4.0, south], [4.0, 3.0], [0.0, 3.0]];
        let body = Body::default();
        let mut m = Motion::new(body, 30.0);
        m.hold(stand(&body, DVec2::new(2.0, 1.5), 0.0), 3, Action::Stand);
        scene.humans = vec![m.into_human("h0")];
        for k in 0..200 {
            let north = 1.2 + 0.002 * k as f64;
            let size = [1.0, 0.55, 0.8];
            let center = [2.0, north - size[1] * 0.5, size[2] * 0.5];
            scene.objects = vec![Object { id: "o0".into(), category: Category::Cabinet, center, size, yaw: 0.0 }];
            if deepest_in(&scene, 0) > 0.05 {
                return scene;
            }
        }
        panic!("the cabinet never reaches the person");
    }

    #[test]
    fn a_cabinet_in_a_standing_person_comes_out_of_them_and_against_its_wall_loses_depth_instead() {
        // Free to move: it comes out of the person, a cabinet still, no bigger.
        let mut scene = cabinet_into_a_stander(0.0);
        let before = scene.objects[0].clone();
        assert_eq!(fit(&mut scene, &RepairConfig::default()), 1);
        let o = &scene.objects[0];
        assert!(deepest_in(&scene, 0) <= PHYS_TOLERANCE, "{}", deepest_in(&scene, 0));
        assert_eq!(o.category, Category::Cabinet);
        assert!((0..3).all(|k| o.size[k] <= before.size[k] + 1e-9), "{o:?}");
        // Its back on the south wall: it cannot move back, so its front comes in.
        let back = before.center[1] - before.size[1] * 0.5;
        let mut scene = cabinet_into_a_stander(back);
        assert_eq!(scene.objects[0], before);
        assert_eq!(fit(&mut scene, &RepairConfig::default()), 1);
        let o = &scene.objects[0];
        assert!(deepest_in(&scene, 0) <= PHYS_TOLERANCE, "{}", deepest_in(&scene, 0));
        assert!(o.center[1] - o.size[1] * 0.5 >= back - 1e-9, "{o:?}");
        assert!(o.size[1] < before.size[1] - 0.02 && o.size[1] >= size_range(Category::Cabinet, 1).0 - 1e-9, "{o:?}");
    }
}
