//! The one way from inputs to checked layouts, for the command line and library users alike:
//! sample with the generator (guidance during sampling), repair each sample ([`crate::repair`]),
//! `check` it ([`crate::sim`]) and, with `require_clean`, resample with new seeds until each input
//! has its layouts or the attempts are spent. An input whose people are in a wall or stand on
//! nothing (`check` fails it whatever the layout, [`people_in_walls`], [`people_off_the_floor`]) is
//! not resampled: its layouts are sampled once, and under `require_clean` none are kept.
//!
//! Inputs of several room types go through [`make_grouped_layouts`]: each type's inputs with its
//! own generator, seeds numbered within the type ([`room_groups`]), so the command line's folder
//! runs and Python's lists of inputs give the same layouts.
//!
//! This is the only module of the library that joins `generator`, `repair` and `sim`; it adds no
//! behaviour of its own beyond the resampling loop, and a tally of what each input's rejected
//! layouts hit ([`Rejections`]), so that an input without a clean layout is told why. For the
//! import of motion ([`crate::motion`]) it has [`import_placed`], which the command line and
//! Python share: the search for a placement that keeps a clip inside the room and apart from the
//! other people ([`place_to_fit`]), and the check's refusal of a body in a wall or the ceiling.

use crate::generator::{GenError, Generator, GuidanceConfig};
use crate::human::{ContactBox, inside_each_other_at_once, seats_in_the_way};
use crate::motion::{Clip, ImportOptions, ImportReport, MotionError, Placement, import_clip, import_clips};
use crate::physics::Physics;
use crate::repair::{RepairConfig, RepairReport, repair_scene};
use crate::scene::{FloorPlan, Human, RoomType, Scene};
use crate::sim::{
    CEILING, CheckConfig, CheckReport, FLOOR, SimPhysics, Violation, ViolationKind, check_scene, people_in_walls,
    people_off_the_floor,
};
use rayon::prelude::*;
use std::borrow::Borrow;
use std::path::PathBuf;
use std::sync::Arc;

/// How to make layouts.
#[derive(Debug, Clone)]
pub struct LayoutOptions {
    /// Layouts wanted per input.
    pub samples: usize,
    /// Run seed: the same seed gives the same layouts.
    pub seed: u64,
    /// Guidance during sampling.
    pub guidance: GuidanceConfig,
    /// Repair after sampling (`None`: the model's layouts as sampled).
    pub repair: Option<RepairConfig>,
    /// Keep only layouts that pass `check`, resampling with new seeds.
    pub require_clean: bool,
    /// Sampling rounds at most with `require_clean` (at least one).
    pub attempts: usize,
    /// The check's settings.
    pub check: CheckConfig,
}

impl Default for LayoutOptions {
    /// One sample, seed 0, all spatial guidance, the default repair, no resampling (what
    /// `shade-sim generate` does without flags).
    fn default() -> LayoutOptions {
        LayoutOptions {
            samples: 1,
            seed: 0,
            guidance: GuidanceConfig::all(),
            repair: Some(RepairConfig::default()),
            require_clean: false,
            attempts: 8,
            check: CheckConfig::default(),
        }
    }
}

/// One layout kept for an input.
#[derive(Debug, Clone)]
pub struct Layout {
    /// The scene: the input's floor plan and humans with the layout's objects.
    pub scene: Scene,
    /// What repair changed (`None` without repair).
    pub repair: Option<RepairReport>,
    /// The check's report (only under `require_clean`, where every kept layout passed it).
    pub check: Option<CheckReport>,
}

/// The layouts of a run.
#[derive(Debug, Clone, Default)]
pub struct Layouts {
    /// The layouts kept, per input in input order (fewer than asked where `require_clean` found
    /// no more clean ones).
    pub kept: Vec<Vec<Layout>>,
    /// Layouts sampled in all.
    pub sampled: usize,
    /// Layouts that passed the check (under `require_clean`).
    pub accepted: usize,
    /// Per input: its people's bones in the walls (under `require_clean`; empty for an input some
    /// layout could make pass).
    pub people_in_walls: Vec<Vec<Violation>>,
    /// Per input: why its layouts that failed the check failed (under `require_clean`).
    pub rejected: Vec<Rejections>,
}

/// One kind of trouble a rejected layout had: the check's kind, the person it concerns (if any)
/// and what they or the piece met — a category, or `"wall"`.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
pub struct Cause {
    /// The check's kind of violation.
    pub kind: ViolationKind,
    /// The human's id, for people in pieces and people without support.
    pub human: Option<String>,
    /// The category of the piece (the first of two that overlap), or `"wall"`.
    pub what: Option<String>,
}

/// Why an input's rejected layouts failed: how many there were, and in how many of them each
/// [`Cause`] occurs, most frequent first.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Rejections {
    /// Layouts sampled for the input that failed the check.
    pub layouts: usize,
    /// Each cause with the number of rejected layouts it occurs in.
    pub causes: Vec<(Cause, usize)>,
}

impl Rejections {
    /// Counts the causes in `report`, a check of `scene`, once each.
    fn add(&mut self, scene: &Scene, report: &CheckReport) {
        self.layouts += 1;
        let what = |id: &Option<String>| {
            id.as_ref().map(|id| match scene.objects.iter().find(|o| &o.id == id) {
                Some(o) => o.category.to_string(),
                None => "wall".to_string(),
            })
        };
        let mut seen: Vec<Cause> = report
            .violations
            .iter()
            .map(|v| Cause { kind: v.kind, human: v.human.clone(), what: what(&v.object) })
            .collect();
        seen.sort();
        seen.dedup();
        for cause in seen {
            match self.causes.iter_mut().find(|(c, _)| *c == cause) {
                Some((_, n)) => *n += 1,
                None => self.causes.push((cause, 1)),
            }
        }
        self.causes.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
    }
}

/// Why an input got no clean layout, from its [`Layouts::rejected`] (`None` when none was
/// rejected): its three most frequent causes, each with the share of rejected layouts it occurs in.
pub fn rejections_message(r: &Rejections) -> Option<String> {
    if r.layouts == 0 {
        return None;
    }
    let said: Vec<String> = r
        .causes
        .iter()
        .take(3)
        .map(|(c, n)| {
            let who = c.human.as_deref().unwrap_or("?");
            let what = c.what.as_deref().unwrap_or("?");
            let text = match c.kind {
                ViolationKind::Penetration if what == "wall" => format!("{who}'s bones in a wall"),
                ViolationKind::Penetration => format!("{who}'s bones in {}", with_article(what)),
                ViolationKind::Unsupported => format!("{who} without support"),
                ViolationKind::ObjectOverlap => format!("{} in another piece", with_article(what)),
                ViolationKind::ObjectWall => format!("{} in a wall", with_article(what)),
                ViolationKind::OutsideFloor => format!("{} outside the floor plan", with_article(what)),
                ViolationKind::Unstable => format!("{} unstable", with_article(what)),
            };
            format!("{text} ({n} of {})", r.layouts)
        })
        .collect();
    Some(format!("no clean layout in {} samples; most often: {}", r.layouts, said.join(", ")))
}

/// A category's name after "a", or "an" before a vowel: "an armchair", "a wardrobe".
fn with_article(name: &str) -> String {
    let vowel = name.starts_with(['a', 'e', 'i', 'o', 'u']);
    format!("{} {name}", if vowel { "an" } else { "a" })
}

/// What `generator` says of an input before sampling it, as the command line and Python warn it:
/// its contact spans beyond those the model conditions on ([`unseen_contacts_message`]), and a
/// floor whose area, width or length none of the model's training rooms has ([`Generator::unseen_floor`]).
pub fn input_notes(generator: &Generator, scene: &Scene) -> Vec<String> {
    let seen = generator.checkpoint.meta.model.max_contacts;
    let contacts = unseen_contacts_message(&generator.unseen_contacts(scene), seen);
    contacts.into_iter().chain(generator.unseen_floor(scene).map(|f| f.to_string())).collect()
}

/// What the model does not see of an input ([`Generator::unseen_contacts`]): its contact spans
/// beyond the `seen` the model conditions on, by person and action (`None` when it sees them all).
pub fn unseen_contacts_message(unseen: &[ContactBox], seen: usize) -> Option<String> {
    if unseen.is_empty() {
        return None;
    }
    let spans: Vec<String> = unseen.iter().map(|b| format!("{} {}", b.human, b.action)).collect();
    Some(format!(
        "{} contact spans beyond the {seen} the model conditions on ({}): their pieces come from guidance and repair alone",
        unseen.len(),
        spans.join(", ")
    ))
}

/// Why no layout of an input can pass the check, from its [`Layouts::people_in_walls`] (`None` when
/// some layout could): the deepest bone in a wall.
pub fn people_in_walls_message(walls: &[Violation]) -> Option<String> {
    let worst = walls.iter().max_by(|a, b| a.depth.total_cmp(&b.depth))?;
    Some(format!(
        "no layout can pass the check: {}'s {} is {:.3} m into {} at frame {} ({} such episodes); it was not resampled",
        worst.human.as_deref().unwrap_or("?"),
        worst.bone.as_deref().unwrap_or("?"),
        worst.depth,
        worst.object.as_deref().unwrap_or("a wall"),
        worst.frame.unwrap_or(0),
        walls.len()
    ))
}

/// The warnings for an input's people whose feet are off the floor ([`people_off_the_floor`]), as
/// the command line and Python give them ([`off_the_floor_message`]).
pub fn off_the_floor_warnings(scene: &Scene, cfg: &CheckConfig) -> Vec<String> {
    people_off_the_floor(scene, cfg).iter().map(|v| off_the_floor_message(scene, v)).collect()
}

/// One of [`people_off_the_floor`]'s violations of `scene` as a warning: who, which frames and
/// seconds, how high, what to do.
pub fn off_the_floor_message(scene: &Scene, v: &Violation) -> String {
    let fps = scene.humans.iter().find(|h| Some(&h.id) == v.human.as_ref()).map_or(30.0, |h| h.fps);
    let [start, end] = v.frames.unwrap_or([0, 0]);
    format!(
        "{}'s feet are off the floor at frames {start}–{end} ({:.2}–{:.2} s; {:.2} m up at frame {}): they stand on something, and no piece here is for standing on, so no layout passes the check; leave those frames out (--trim)",
        v.human.as_deref().unwrap_or("?"),
        start as f64 / fps,
        end as f64 / fps,
        v.depth,
        v.frame.unwrap_or(start)
    )
}

/// An input made from motion: the scene, what the import found in each clip, and where each clip
/// was placed (`None`: kept where captured).
#[derive(Debug, Clone)]
pub struct Imported {
    /// The generation input.
    pub scene: Scene,
    /// One per clip, in order.
    pub reports: Vec<ImportReport>,
    /// The placement each clip got, given or found.
    pub places: Vec<Option<Placement>>,
}

/// The import of motion as `import-motion` and Python's `import_motion` make it: clip `i` placed
/// by [`place_to_fit`] where `auto[i]` (in order, apart from the clips placed by hand, kept where
/// captured or found before it), then `motion::import_clips`, then the refusal of a body in a wall
/// ([`body_in_a_wall`]).
pub fn import_placed(clips: &[(PathBuf, Clip)], opts: &ImportOptions, auto: &[bool]) -> Result<Imported, MotionError> {
    let mut opts = opts.clone();
    let is_auto = |i: usize| auto.get(i) == Some(&true);
    // The people already where they will be; a clip that does not import is refused below.
    let mut placed: Vec<Human> = (0..clips.len())
        .filter(|&i| !is_auto(i))
        .filter_map(|i| import_clip(&clips[i].1, i, &opts).ok().map(|(human, _)| human))
        .collect();
    for (i, (file, clip)) in clips.iter().enumerate().filter(|(i, _)| is_auto(*i)) {
        let (found, human) = place_to_fit(clip, i, &opts, &placed).map_err(|m| MotionError::invalid(file, m))?;
        opts.places.resize(opts.places.len().max(i + 1), None);
        opts.places[i] = Some(found);
        placed.push(human);
    }
    let (scene, reports) = import_clips(clips, &opts)?;
    if let Some(error) = body_in_a_wall(&scene, &reports, opts.fps) {
        return Err(error);
    }
    let places = (0..clips.len()).map(|i| opts.places.get(i).copied().flatten()).collect();
    Ok(Imported { scene, reports, places })
}

/// The deepest place where a body of an imported `scene` reaches into a wall, the ceiling or the
/// floor, as `check` finds it, as an error naming its file (`reports[k]` made human k): the frame,
/// its time, the bone, the depth and the floor-plan edge (or the ceiling, or the floor). Such an
/// input fails `check` whatever the layout, although the pelvis and ankles that
/// `motion::import_clip` tests are inside the floor plan (an arm swung out, a shoulder along the
/// wall, a head above a low room's height, a knee lower than the lowest toe — or a clip read with
/// the wrong up axis, lying on its side through the floor, which the error then says).
fn body_in_a_wall(scene: &Scene, reports: &[ImportReport], fps: f64) -> Option<MotionError> {
    let walls = people_in_walls(scene, &CheckConfig::default());
    let v = walls.iter().max_by(|a, b| a.depth.total_cmp(&b.depth))?;
    let human = scene.humans.iter().position(|h| Some(&h.id) == v.human.as_ref()).unwrap_or(0);
    let frame = v.frame.unwrap_or(0);
    let bone = v.bone.as_deref().unwrap_or("body").replace('_', " ").replace('-', "–");
    let (inside, remedy) = match v.object.as_deref() {
        Some(CEILING) => (
            format!("the ceiling ({:.2} m high)", scene.floor_plan.height),
            "give the room a higher --height, or leave the frame out with --trim",
        ),
        Some(FLOOR) => {
            // A clip read with the wrong up axis lies on its side through the floor.
            let on_its_side = reports.get(human).is_some_and(|r| !r.ever_upright);
            let remedy = match on_its_side {
                true => {
                    "the trunk is never upright, so the up axis is likely wrong (--up); else leave the frame out with --trim"
                }
                false => "leave the frame out with --trim",
            };
            ("the floor".to_string(), remedy)
        }
        other => (
            format!("the wall of floor-plan edge {}", other.and_then(|o| o.strip_prefix("wall")).unwrap_or("?")),
            "place the clip with --place, or leave the frame out with --trim",
        ),
    };
    Some(MotionError::invalid(
        reports.get(human).map(|r| r.file.clone()).unwrap_or_default(),
        format!(
            "frame {frame} ({:.2} s): the {bone} is {:.2} m inside {inside}; {remedy}",
            frame as f64 / fps,
            v.depth
        ),
    ))
}

/// The placements [`place_to_fit`] tries, in order: the clip's first pelvis over the centre of the
/// floor plan's bounding box, then over the points of a 5 × 5 grid at 10 %, 30 %, … 90 % of the box
/// that lie inside the plan, nearest the centre first; at each, facing +y, −x, −y and +x.
pub fn fitting_placements(floor: &FloorPlan) -> Vec<Placement> {
    let polygon = floor.polygon();
    let (lo, hi) = polygon.bounds();
    let centre = (lo + hi) * 0.5;
    let mut spots: Vec<glam::DVec2> = (0..5)
        .flat_map(|i| (0..5).map(move |j| (i, j)))
        .map(|(i, j)| lo + (hi - lo) * glam::DVec2::new(0.1 + 0.2 * i as f64, 0.1 + 0.2 * j as f64))
        .filter(|&p| polygon.contains(p))
        .collect();
    spots.sort_by(|a, b| a.distance(centre).total_cmp(&b.distance(centre)));
    std::iter::once(centre)
        .filter(|&c| polygon.contains(c))
        .chain(spots)
        .flat_map(|at| [0.0, 90.0, 180.0, 270.0].map(|yaw_degrees| Placement { at, yaw_degrees }))
        .collect()
}

/// Where clip `i` (imported with `opts`, its own placement replaced) goes among the people
/// already placed (`others`), and the person it makes there: the first of [`fitting_placements`]
/// at which it stays inside the floor plan at every frame, its body out of the walls as `check`
/// tests them, and apart from every other person — never inside one at the same moment
/// ([`inside_each_other_at_once`]), never through where one sits or lies, nor one through where it
/// does ([`seats_in_the_way`]). Where no placement keeps it apart, the first that fits the room
/// (the command line and Python then warn about what meets). The error says none fits.
pub fn place_to_fit(
    clip: &Clip,
    i: usize,
    opts: &ImportOptions,
    others: &[Human],
) -> Result<(Placement, Human), String> {
    let candidates = fitting_placements(&opts.floor);
    let tolerance = CheckConfig::default().tolerance;
    let mut tried = opts.clone();
    tried.places.resize(tried.places.len().max(i + 1), None);
    let mut fitting = None;
    for &place in &candidates {
        tried.places[i] = Some(place);
        let Ok((human, _)) = import_clip(clip, i, &tried) else { continue };
        let alone = Scene { humans: vec![human.clone()], ..Scene::new(opts.room_type, opts.floor.clone()) };
        // No placement moves a head out of the ceiling or a knee out of the floor: that is
        // `import_placed`'s error to give.
        let in_walls = people_in_walls(&alone, &CheckConfig::default());
        if in_walls.iter().any(|v| !matches!(v.object.as_deref(), Some(CEILING | FLOOR))) {
            continue;
        }
        if others.iter().all(|o| apart(&human, o, &opts.floor, tolerance)) {
            return Ok((place, human));
        }
        fitting.get_or_insert((place, human));
    }
    fitting.ok_or_else(|| {
        format!(
            "no placement keeps the clip inside the floor plan and out of its walls ({} tried: the plan's centre and a 5 × 5 grid, each facing four ways); a larger --floor, or --trim",
            candidates.len()
        )
    })
}

/// Whether people `a` and `b` can share a room as placed: never inside each other at once, and
/// neither walking or standing through where the other sits or lies.
fn apart(a: &Human, b: &Human, floor: &FloorPlan, tolerance: f64) -> bool {
    if inside_each_other_at_once(a, b, tolerance) {
        return false;
    }
    let mut pair = Scene::new(RoomType::Living, floor.clone());
    pair.humans = vec![a.clone(), b.clone()];
    seats_in_the_way(&pair, tolerance).iter().all(|s| s.human == s.seated)
}

/// The seed of resampling round `round` for the run seed `seed` (round 0 is the seed itself, so a
/// clean first sample is the same as without `require_clean`).
pub fn round_seed(seed: u64, round: usize) -> u64 {
    seed.wrapping_add(round as u64 * 1_000_003)
}

/// Layouts for `inputs` (all of the generator's room type): sampled, repaired, checked and
/// resampled as `opts` says; `progress` gets the number of layouts sampled so far in the round
/// plus those accepted before it.
pub fn make_layouts(
    generator: &Generator,
    inputs: &[Scene],
    opts: &LayoutOptions,
    progress: &mut dyn FnMut(usize),
) -> Result<Layouts, GenError> {
    let physics: Arc<dyn Physics> = Arc::new(SimPhysics);
    let meta = generator.checkpoint.meta.clone();
    let guidance = opts.guidance.clone();
    let phys = physics.clone();
    let mut factory = move |scenes: &[&Scene]| guidance.for_batch(&meta.model, &meta.bounds, scenes, &phys);
    let rounds = if opts.require_clean { opts.attempts.max(1) } else { 1 };
    let people_in_walls: Vec<Vec<Violation>> = if opts.require_clean {
        inputs.par_iter().map(|s| people_in_walls(s, &opts.check)).collect()
    } else {
        vec![Vec::new(); inputs.len()]
    };
    // People standing on nothing: the free space under their feet keeps pieces away from there.
    let off_the_floor: Vec<bool> = match opts.require_clean {
        true => inputs.par_iter().map(|s| !people_off_the_floor(s, &opts.check).is_empty()).collect(),
        false => vec![false; inputs.len()],
    };
    let mut out = Layouts {
        kept: vec![Vec::new(); inputs.len()],
        sampled: 0,
        accepted: 0,
        people_in_walls,
        rejected: vec![Rejections::default(); inputs.len()],
    };
    for round in 0..rounds {
        // No round makes a layout pass for people in a wall or standing on nothing: they get the
        // first round's samples only.
        let hopeless = |i: usize| round > 0 && (!out.people_in_walls[i].is_empty() || off_the_floor[i]);
        let wanted: Vec<usize> =
            (0..inputs.len()).filter(|&i| out.kept[i].len() < opts.samples && !hopeless(i)).collect();
        if wanted.is_empty() {
            break;
        }
        let batch: Vec<Scene> = wanted.iter().map(|&i| inputs[i].clone()).collect();
        let accepted = out.accepted;
        let total = opts.samples * inputs.len();
        let sampled =
            generator.generate_with(&batch, opts.samples, round_seed(opts.seed, round), &mut factory, &mut |done| {
                progress(accepted + done.min(total))
            })?;
        let jobs: Vec<(usize, Scene)> =
            wanted.iter().zip(sampled).flat_map(|(&i, scenes)| scenes.into_iter().map(move |s| (i, s))).collect();
        let finished: Vec<(usize, Layout)> = jobs
            .into_par_iter()
            .map(|(i, mut scene)| {
                let repair = opts.repair.as_ref().map(|cfg| repair_scene(&mut scene, cfg, physics.as_ref()));
                let check = opts.require_clean.then(|| check_scene(&scene, &opts.check));
                (i, Layout { scene, repair, check })
            })
            .collect();
        for (i, layout) in finished {
            out.sampled += 1;
            if !opts.require_clean {
                out.kept[i].push(layout);
                continue;
            }
            let clean = layout.check.as_ref().is_some_and(CheckReport::is_clean);
            if let Some(report) = layout.check.as_ref().filter(|_| !clean) {
                out.rejected[i].add(&layout.scene, report);
            }
            if clean && out.kept[i].len() < opts.samples {
                out.accepted += 1;
                out.kept[i].push(layout);
            }
        }
    }
    Ok(out)
}

/// The room types of `inputs` in the order they first appear, each with the indices of its inputs.
pub fn room_groups(inputs: &[Scene]) -> Vec<(RoomType, Vec<usize>)> {
    let mut groups: Vec<(RoomType, Vec<usize>)> = Vec::new();
    for (i, s) in inputs.iter().enumerate() {
        match groups.iter_mut().find(|(room, _)| *room == s.room_type) {
            Some((_, members)) => members.push(i),
            None => groups.push((s.room_type, vec![i])),
        }
    }
    groups
}

/// [`make_layouts`] for inputs of several room types: each group of [`room_groups`] with its
/// generator (`generators[k]` for `groups[k]`) one after another, seeds numbered within the
/// group; the layouts come back in input order. `progress` counts the layouts sampled over all
/// groups.
pub fn make_grouped_layouts<G: Borrow<Generator>>(
    inputs: &[Scene],
    groups: &[(RoomType, Vec<usize>)],
    generators: &[G],
    opts: &LayoutOptions,
    progress: &mut dyn FnMut(usize),
) -> Result<Layouts, GenError> {
    assert_eq!(groups.len(), generators.len(), "one generator per group");
    let mut out = Layouts {
        kept: vec![Vec::new(); inputs.len()],
        sampled: 0,
        accepted: 0,
        people_in_walls: vec![Vec::new(); inputs.len()],
        rejected: vec![Rejections::default(); inputs.len()],
    };
    let mut offset = 0;
    for ((_, members), generator) in groups.iter().zip(generators) {
        let generator = generator.borrow();
        let group: Vec<Scene> = members.iter().map(|&i| inputs[i].clone()).collect();
        let layouts = make_layouts(generator, &group, opts, &mut |done| progress(offset + done))?;
        offset += members.len() * opts.samples;
        out.sampled += layouts.sampled;
        out.accepted += layouts.accepted;
        for (((&i, kept), walls), rejected) in
            members.iter().zip(layouts.kept).zip(layouts.people_in_walls).zip(layouts.rejected)
        {
            out.kept[i] = kept;
            out.people_in_walls[i] = walls;
            out.rejected[i] = rejected;
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::generate_room;
    use crate::scene::{Category, Object};

    fn violation(kind: ViolationKind, human: Option<&str>, object: &str) -> Violation {
        Violation {
            kind,
            human: human.map(Into::into),
            bone: None,
            object: Some(object.into()),
            other: None,
            frame: Some(0),
            frames: None,
            depth: 0.1,
        }
    }

    #[test]
    fn rejections_count_each_cause_once_per_layout_and_name_the_commonest() {
        let mut scene = generate_room(RoomType::Bedroom, 3, 0, false).scene;
        scene.objects = vec![
            Object::standing("o0", Category::Wardrobe, [1.0, 1.0], [1.0, 0.6, 2.0]),
            Object::standing("o1", Category::Armchair, [2.0, 1.0], [0.8, 0.8, 0.8]),
        ];
        let mut r = Rejections::default();
        assert_eq!(rejections_message(&r), None, "nothing rejected, nothing to say");
        // Two episodes of h1 in the wardrobe in one layout count once; the wall is named as such.
        let first = CheckReport {
            violations: vec![
                violation(ViolationKind::Penetration, Some("h1"), "o0"),
                violation(ViolationKind::Penetration, Some("h1"), "o0"),
                violation(ViolationKind::Penetration, Some("h0"), "wall2"),
            ],
            frames: 10,
        };
        let second =
            CheckReport { violations: vec![violation(ViolationKind::Penetration, Some("h1"), "o0")], frames: 10 };
        let third = CheckReport { violations: vec![violation(ViolationKind::ObjectWall, None, "o1")], frames: 10 };
        for report in [&first, &second, &third] {
            r.add(&scene, report);
        }
        assert_eq!(r.layouts, 3);
        assert_eq!(r.causes[0].1, 2, "{:?}", r.causes);
        assert_eq!(r.causes.iter().map(|(_, n)| n).sum::<usize>(), 4);
        assert_eq!(
            rejections_message(&r).unwrap(),
            "no clean layout in 3 samples; most often: h1's bones in a wardrobe (2 of 3), h0's bones in a wall (1 of 3), \
             an armchair in a wall (1 of 3)"
        );
    }

    #[test]
    fn placements_to_try_start_at_the_centre_and_stay_inside_the_plan() {
        use crate::scene::FloorPlan;
        let rect = FloorPlan { polygon: vec![[0.0, 0.0], [4.0, 0.0], [4.0, 2.0], [0.0, 2.0]], height: 2.8 };
        let tried = fitting_placements(&rect);
        assert_eq!(tried.len(), 4 * (1 + 25));
        let first: Vec<(f64, f64, f64)> = tried[..5].iter().map(|p| (p.at.x, p.at.y, p.yaw_degrees)).collect();
        assert_eq!(first[..4], [(2.0, 1.0, 0.0), (2.0, 1.0, 90.0), (2.0, 1.0, 180.0), (2.0, 1.0, 270.0)]);
        // Then the grid, nearest the centre first: (2.0, 1.0) again is the grid's middle point.
        assert_eq!((first[4].0, first[4].1), (2.0, 1.0));
        // An L whose bounding box's centre is outside it: only points inside are tried.
        let l = FloorPlan {
            polygon: vec![[0.0, 0.0], [4.0, 0.0], [4.0, 1.0], [1.0, 1.0], [1.0, 4.0], [0.0, 4.0]],
            height: 2.8,
        };
        let tried = fitting_placements(&l);
        assert!(tried.iter().all(|p| l.polygon().contains(p.at)));
        assert_eq!(tried.len(), 4 * 9, "the grid's first column and row: 5 + 5 − 1 points");
    }
}
