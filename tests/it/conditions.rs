//! Conditioning on hand-built scenes with known answers.

use glam::{DVec2, DVec3};
use shade_sim::geom::{Mask, RoomWindow};
use shade_sim::human::{Body, Conditions, Motion, SUPPORT_DEPTH, Side, TOUCH_SIDE, sit, stand, touch};
use shade_sim::scene::{Action, FloorPlan, RoomType, Scene};

fn room() -> Scene {
    Scene::new(
        RoomType::Bedroom,
        FloorPlan { polygon: vec![[0.0, 0.0], [5.0, 0.0], [5.0, 4.0], [0.0, 4.0]], height: 2.7 },
    )
}

fn one(pose: shade_sim::human::Pose, action: Action, id: &str) -> shade_sim::scene::Human {
    let mut m = Motion::new(Body::default(), 30.0);
    m.hold(pose, 10, action);
    m.into_human(id)
}

#[test]
fn sitting_box_is_the_support_volume_under_pelvis_and_thighs() {
    let body = Body::default();
    let mut scene = room();
    let yaw = 0.7;
    scene.humans.push(one(sit(&body, DVec2::new(2.0, 2.0), 0.45, yaw), Action::Sit, "h0"));
    let c = Conditions::of(&scene);
    assert_eq!(c.contact_boxes.len(), 1);
    let b = &c.contact_boxes[0];
    assert_eq!((b.human.as_str(), b.action, b.frames), ("h0", Action::Sit, [0, 10]));
    assert!((b.obox.yaw - yaw).abs() < 1e-3);
    let (z0, z1) = b.obox.z_range();
    assert!((z1 - 0.45).abs() < 1e-3, "top at the seat: {z1}");
    assert!((z1 - z0 - SUPPORT_DEPTH).abs() < 1e-9);
    // By hand for 1.75 m: the pelvis–hip capsules (r = 0.0875) bound it; the pelvis sits 1.75 cm
    // behind the hips, the knees 0.4284 m ahead and 1.75 cm wider, a third of the thigh counts:
    // depth 0.0175 + 0.0875 + 0.35 × 0.4284 + 0.0875 = 0.3424, width 2 × (0.0875 + 0.35 × 0.0175
    // + 0.0875) = 0.3623, centre 0.0662 ahead of the hips.
    assert!((b.obox.size.x - 0.3623).abs() < 0.003, "{}", b.obox.size.x);
    assert!((b.obox.size.y - 0.3424).abs() < 0.003, "{}", b.obox.size.y);
    let facing = DVec2::new(-yaw.sin(), yaw.cos());
    let ahead = (b.obox.center.truncate() - DVec2::new(2.0, 2.0)).dot(facing);
    assert!((ahead - 0.0662).abs() < 0.003, "{ahead}");
    // No walking or standing frames: no free space.
    assert_eq!(c.free_space.count(), 0);
}

#[test]
fn a_seat_sat_on_again_is_one_support_and_the_next_place_on_a_sofa_another() {
    // One person sits, stands, sits again 10 cm further along the same seat, stands, and sits on
    // the place 55 cm along (a sofa's next seat); then touches the same spot twice.
    let body = Body::default();
    let seat = |x: f64| sit(&body, DVec2::new(x, 2.0), 0.45, 0.0);
    let up = |x: f64| stand(&body, DVec2::new(x, 1.6), 0.0);
    let palm = DVec3::new(4.0, 2.8, 0.9);
    let mut m = Motion::new(body, 30.0);
    m.hold(seat(2.0), 10, Action::Sit).hold(up(2.0), 10, Action::Stand).hold(seat(2.1), 10, Action::Sit);
    m.hold(up(2.1), 10, Action::Stand).hold(seat(2.65), 10, Action::Sit).hold(up(2.65), 10, Action::Stand);
    let reach = touch(&body, palm, 0.0, Side::Right);
    m.hold(reach, 10, Action::Touch).hold(up(3.6), 10, Action::Stand).hold(reach, 10, Action::Touch);
    let mut scene = room();
    scene.humans.push(m.into_human("h0"));
    let boxes = Conditions::contact_boxes_of(&scene);
    let summary: Vec<(Action, [usize; 2])> = boxes.iter().map(|b| (b.action, b.frames)).collect();
    assert_eq!(
        summary,
        [(Action::Sit, [0, 30]), (Action::Sit, [40, 50]), (Action::Touch, [60, 70]), (Action::Touch, [80, 90])]
    );
    // The merged box holds both sittings' boxes: 10 cm wider than one, as deep, at the seat.
    let mut alone = room();
    alone.humans.push(one(seat(2.0), Action::Sit, "h0"));
    let single = Conditions::contact_boxes_of(&alone)[0].obox;
    let both = boxes[0].obox;
    assert!((both.size.x - single.size.x - 0.1).abs() < 1e-6, "{} vs {}", both.size.x, single.size.x);
    assert!((both.size.y - single.size.y).abs() < 1e-6 && (both.size.z - single.size.z).abs() < 1e-6);
    assert!((both.center.x - single.center.x - 0.05).abs() < 1e-6 && (both.center.z - single.center.z).abs() < 1e-6);
}

#[test]
fn touch_box_is_a_cube_on_the_palm() {
    let body = Body::default();
    let mut scene = room();
    let target = DVec3::new(3.0, 1.0, 0.75);
    scene.humans.push(one(touch(&body, target, 1.2, Side::Left), Action::Touch, "h0"));
    let c = Conditions::of(&scene);
    let b = &c.contact_boxes[0];
    // Half a box past the palm, along the forearm.
    let h = &scene.humans[0];
    let (elbow, wrist) = (h.joint_at(0, 14), h.joint_at(0, 15));
    let dir = (wrist - elbow).normalize();
    let expected = target + dir * (TOUCH_SIDE * 0.5);
    assert!(b.obox.center.distance(expected) < 2e-3, "{:?} vs {expected:?}", b.obox.center);
    assert_eq!(b.obox.size, DVec3::splat(TOUCH_SIDE));
}

#[test]
fn free_space_marks_the_feet_of_a_standing_human_only() {
    let body = Body::default();
    let mut scene = room();
    let at = DVec2::new(1.5, 2.5);
    scene.humans.push(one(stand(&body, at, 0.0), Action::Stand, "h0"));
    let c = Conditions::of(&scene);
    let n = c.free_space.count();
    // Two feet of ≈ 0.19 × 0.077 m plus round ends, at 2.42 cm pixels: ≈ 2 × 33 pixels.
    assert!((40..110).contains(&n), "{n}");
    for (j, row) in c.free_space.rows().enumerate() {
        for (i, &set) in row.iter().enumerate() {
            if set {
                let p = c.window.pixel_center(i, j);
                assert!(p.distance(at + DVec2::new(0.0, 0.1)) < 0.25, "pixel {p} far from the feet");
            }
        }
    }
    assert!(c.contact_boxes.is_empty());
}

#[test]
fn floor_mask_and_points_follow_the_plan() {
    let c = Conditions::of(&room());
    let w = RoomWindow { center: DVec2::new(2.5, 2.0), side: 6.2 };
    assert_eq!(c.window, w);
    let expected = 20.0 / w.pixel_area();
    assert!((c.floor.count() as f64 - expected).abs() < 18.0 / w.pixel() * 1.0, "{} vs {expected}", c.floor.count());
    assert_eq!(c.floor_points.len(), 256);
    // Boundary points lie on the walls (relative to the window centre), interior points inside.
    for p in &c.floor_points[..128] {
        let q = DVec2::from(p.position) + w.center;
        let on_wall = q.x.abs() < 1e-9 || (q.x - 5.0).abs() < 1e-9 || q.y.abs() < 1e-9 || (q.y - 4.0).abs() < 1e-9;
        assert!(on_wall, "{q}");
        assert!((DVec2::from(p.normal).length() - 1.0).abs() < 1e-12);
    }
    for p in &c.floor_points[128..] {
        let q = DVec2::from(p.position) + w.center;
        assert!(q.x > 0.0 && q.x < 5.0 && q.y > 0.0 && q.y < 4.0 && p.normal == [0.0, 0.0]);
    }
    assert_eq!(c.free_space, Mask::new());
}

#[test]
fn people_at_the_end_of_a_hall_wider_than_the_window_stay_in_view() {
    // Two walkers crossing a 5.5 × 4.5 m living room; the same people at the west end of a 20 m
    // hall, three times the living rooms' 12.4 m window. The window follows them along the hall,
    // so they are conditioned on as in the small room: every joint in view, the same walked floor.
    let small = Scene::load(crate::root().join("tests/inputs/living_crossing_walkers.json")).unwrap();
    let mut hall = small.clone();
    hall.floor_plan.polygon = vec![[0.0, 0.0], [20.0, 0.0], [20.0, 4.5], [0.0, 4.5]];
    let (a, b) = (Conditions::of(&small), Conditions::of(&hall));
    assert_eq!(a.window.center, DVec2::new(2.75, 2.25));
    // As far west as the hall allows (6.2), then as far again as keeps the reader, seated in the
    // west corner, within the living rooms' reach.
    let (seated, _) = hall.contact_pelvis_bounds().unwrap();
    let west = seated.x + RoomType::Living.reach();
    assert!(west < 6.2, "{west}");
    assert!((b.window.center - DVec2::new(west, 2.25)).length() < 1e-12, "{}", b.window.center);
    let (lo, hi) = hall.people_bounds().unwrap();
    for p in [lo, hi] {
        assert!((p - b.window.center).abs().max_element() < b.window.side / 2.0, "{p} out of view");
    }
    let (fa, fb) = (a.free_space.count() as f64, b.free_space.count() as f64);
    assert!((fa - fb).abs() <= 0.1 * fa, "walked floor {fa} pixels in the room, {fb} in the hall");
    // A walker down the whole hall: everyone spans more than the window, and the people in
    // contact (the reader in the west corner, the hand by the east wall of the small room) keep it.
    let mut walked = hall.clone();
    let mut m = Motion::new(Body::default(), 10.0);
    m.walk(&shade_sim::geom::Polyline::new(vec![DVec2::new(0.5, 4.0), DVec2::new(19.5, 4.0)]).unwrap(), 1.2);
    walked.humans.push(m.into_human("long"));
    assert_eq!(walked.room_window(), b.window);
    // (Within a tenth: the pixel grid falls differently.) Centred on the hall (x 3.8 to 16.2), the
    // window would leave most of the first walk out.
    let centred = RoomWindow::around(hall.room_type.window_side(), &hall.floor_plan.polygon());
    let cut = shade_sim::human::free_space_mask(&hall, &centred).count() as f64;
    assert!(cut < 0.8 * fa, "{cut} of {fa}");
}

#[test]
fn the_window_keeps_people_in_contact_within_reach_and_the_training_rooms_as_they_were() {
    // In the procedural rooms the window is the plan's, whatever the room type: the reach moves it
    // in none of them, so the models see their training rooms' windows.
    for room in RoomType::ALL {
        for index in 0..150 {
            let scene = shade_sim::data::generate_room(room, 3, index, false).scene;
            let plain = RoomWindow::around(room.window_side(), &scene.floor_plan.polygon());
            assert_eq!(scene.room_window(), plain, "{room} room {index}");
        }
    }
    // A reader 0.6 m from the west wall of a 13 m living room: centred on the plan's west part as
    // far as the plan allows, the window left the reader 5.6 m from its centre, beyond the 5.24 m
    // any piece's centre reaches; now the reader is within reach.
    let mut long = Scene::load(crate::root().join("tests/inputs/sofa_visit.json")).unwrap();
    long.floor_plan.polygon = vec![[0.0, 0.0], [13.0, 0.0], [13.0, 4.0], [0.0, 4.0]];
    let w = long.room_window();
    let (lo, hi) = long.contact_pelvis_bounds().unwrap();
    for p in [lo, hi] {
        assert!((p - w.center).abs().max_element() <= RoomType::Living.reach() + 1e-12, "{p} from {}", w.center);
    }
    assert!(w.center.x < 6.2, "{}", w.center);
}

#[test]
fn every_shipped_model_reaches_as_far_as_its_room_type_says() {
    // The window keeps people within `RoomType::reach` of its centre on the promise that the model
    // can put a piece's centre that far; each shipped model's centre bounds keep it (to the cm).
    for room in shade_sim::generator::shipped_rooms() {
        let bounds = shade_sim::generator::shipped_model(room).unwrap().meta.bounds;
        for k in 0..2 {
            let reach = bounds.center_max[k].min(-bounds.center_min[k]);
            assert!(reach >= room.reach() && reach < room.reach() + 0.01, "{room}: {reach} against {}", room.reach());
        }
    }
}

#[test]
fn a_body_resting_on_the_floor_needs_no_piece_and_keeps_its_floor_free() {
    let body = Body::default();
    let lying = |surface: f64| {
        let mut scene = room();
        scene.humans.push(one(shade_sim::human::lie(&body, DVec2::new(2.5, 2.0), surface, 1.2), Action::Lie, "h0"));
        Conditions::of(&scene)
    };
    // On a 42 cm sofa: a support volume under the body, and no free floor (nobody walks).
    let sofa = lying(0.42);
    assert_eq!(sofa.contact_boxes.len(), 1);
    assert_eq!(sofa.free_space.count(), 0);
    // On the floor: no box, and the floor under the whole body is kept free, about its shadow's
    // area (a 1.7 m body: 0.3–0.6 m² at 2.4 cm pixels).
    let floor = lying(0.0);
    assert!(floor.contact_boxes.is_empty());
    let area = floor.free_space.count() as f64 * floor.window.pixel_area();
    assert!((0.3..0.6).contains(&area), "{area} m²");
    // Sitting on the floor with the knees up: the same.
    let mut scene = room();
    scene.humans.push(one(sit(&body, DVec2::new(2.5, 2.0), 0.0, 0.0), Action::Sit, "h0"));
    let c = Conditions::of(&scene);
    assert!(c.contact_boxes.is_empty() && c.free_space.count() > 0);
}
