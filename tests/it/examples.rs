//! The example inputs (the demo's inputs) are valid and cover what the demo needs.

use crate::example_scenes;
use glam::DVec2;
use shade_sim::human::{Conditions, Gait, Motion, stand};
use shade_sim::scene::{Action, RoomType, Scene};
use std::collections::BTreeSet;

#[test]
fn at_least_six_examples_over_three_room_types_and_l_shapes() {
    let files = example_scenes();
    assert!(files.len() >= 6, "{} examples", files.len());
    let mut rooms = BTreeSet::new();
    let mut actions = BTreeSet::new();
    let mut non_rectangular = 0;
    for f in &files {
        let scene = Scene::load(f).unwrap_or_else(|e| panic!("{e}"));
        rooms.insert(scene.room_type);
        if scene.floor_plan.polygon.len() > 4 {
            non_rectangular += 1;
        }
        assert!(scene.objects.is_empty(), "{}: inputs have no objects", f.display());
        let walkers = scene.humans.iter().filter(|h| h.actions.iter().any(|s| s.action == Action::Walk)).count();
        let contact = scene.humans.iter().filter(|h| h.contact_spans().next().is_some()).count();
        assert!(walkers >= 1 && contact >= 2, "{}: {walkers} walkers, {contact} contact humans", f.display());
        actions.extend(scene.humans.iter().flat_map(|h| h.actions.iter().map(|s| s.action)));
    }
    assert_eq!(rooms.len(), 3);
    assert!(non_rectangular >= 2);
    for a in [Action::Walk, Action::Sit, Action::Lie, Action::Touch] {
        assert!(actions.contains(&a), "{a} missing");
    }
}

#[test]
fn walkers_stay_inside_their_rooms_and_off_the_contact_regions() {
    for f in example_scenes() {
        let scene = Scene::load(&f).unwrap();
        let floor = scene.floor_plan.polygon();
        let c = Conditions::of(&scene);
        for h in &scene.humans {
            for frame in 0..h.frames.len() {
                for p in h.frame(frame) {
                    assert!(
                        floor.contains(p.truncate()),
                        "{}: {} frame {frame} leaves the floor at {p}",
                        f.display(),
                        h.id
                    );
                }
            }
        }
        // Free-space pixels never fall inside a sit or lie support footprint.
        let mut support = shade_sim::geom::Mask::new();
        for b in c.contact_boxes.iter().filter(|b| b.action != Action::Touch) {
            support.fill_footprint(&c.window, &b.obox);
        }
        assert_eq!(c.free_space.overlap(&support), 0, "{}: walkers cross a seat or bed", f.display());
    }
}

#[test]
fn files_are_in_canonical_form() {
    // Loading and saving an example reproduces the committed bytes (stable key order, one frame per
    // line, fixed rounding): the examples are what the library writes.
    for f in example_scenes() {
        let text = std::fs::read_to_string(&f).unwrap();
        let scene = Scene::load(&f).unwrap();
        assert!(scene.to_json() == text, "{} is not in canonical form", f.display());
    }
}

#[test]
fn golden_digest_of_a_generated_motion() {
    // Pins the pose generators and the writer: any change to gait, poses or number formatting shows
    // up here. Regenerate the examples (see README) and update the digest when a change is meant.
    let body = shade_sim::human::Body::new(1.7);
    let path = shade_sim::geom::Polyline::new(vec![DVec2::ZERO, DVec2::new(2.0, 1.0)]).unwrap();
    let mut m = Motion::new(body, 30.0);
    m.walk(&path, 1.1).blend_to(&stand(&body, DVec2::new(2.0, 1.0), 0.3), 5);
    let mut scene = Scene::new(
        RoomType::Living,
        shade_sim::scene::FloorPlan { polygon: vec![[-1.0, -1.0], [3.0, -1.0], [3.0, 2.0]], height: 2.5 },
    );
    scene.humans.push(m.into_human("h0"));
    assert_eq!(scene.humans[0].frames.len(), Gait { speed: 1.1, fps: 30.0 }.frames(&path.clone()) + 5);
    let digest = fnv1a(scene.to_json().as_bytes());
    assert_eq!(format!("{digest:016x}"), GOLDEN);
}

const GOLDEN: &str = "7188693b5dbbe5df";

fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf29ce484222325, |h, &b| (h ^ b as u64).wrapping_mul(0x100000001b3))
}
