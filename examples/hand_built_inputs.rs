//! Writes the hand-built generation inputs in `tests/inputs/` — rooms and motions made by hand,
//! unlike the procedural training data: a tight bedroom, a walker close behind a person seated at a
//! desk, a walker through the middle of a living room, three sitters side by side as on one sofa,
//! a dining room with sitters on both sides of one table; an L-shaped living room with two sitters
//! side by side and a walker round the corner, a bedroom with a sleeper, a person at a desk and a
//! walker between them, four diners with a walker behind one row, a reader and a person reaching
//! up to a wall shelf; a couple on one bed with a walker past its foot, six diners in an L-shaped
//! room, two walkers crossing a living room, a child on a 30 cm seat, a nap on the sofa, a living
//! room scanned at 25° to the axes, people sitting and lying on the floor; people who walk in, sit
//! down, get up and walk out again (on a sofa, and in a reading chair turned into a corner), their
//! actions labelled from the motion as `import-motion` labels a capture; four people in
//! conversation round a room's middle, two diners in a narrow dining room, two single beds with a
//! walker between them, a nap on a sofa facing a TV; an open-plan room 7 m long with a sofa facing
//! the TV from the middle of the room and four diners, four diners one to a side of a square table,
//! a bed standing off its wall with a walker behind its head, a living room 2.6 m wide and 6.5 m
//! long; the open-plan room's sofa pair alone in the middle of the room, a metre off a wall, and
//! with a walker behind them; and two inputs no layout can make pass (a sitter's feet in the wall; a walk through where
//! the person's chair must stand).
//!
//! ```sh
//! cargo run --release --example hand_built_inputs -- tests/inputs
//! ```
//!
//! The files are committed; this program is how they were made (deterministic).

use glam::{DVec2, DVec3};
use shade_sim::geom::Polyline;
use shade_sim::human::{Body, Joint, Motion, Side, lie, sit, stand, touch};
use shade_sim::motion::{LabelConfig, body_frames, label_frames, labels::runs};
use shade_sim::scene::{Action, FloorPlan, Human, RoomType, Scene};
use std::path::PathBuf;

const FPS: f64 = 10.0;

fn rect(w: f64, d: f64) -> FloorPlan {
    FloorPlan::rectangle(w, d, 2.6)
}

/// Yaws are the scene format's: 0° faces +y, 90° faces −x (counter-clockwise from +y).
fn sitter(id: &str, at: [f64; 2], seat: f64, yaw_deg: f64) -> Human {
    sitter_of(id, 1.72, at, seat, yaw_deg)
}

/// A sitter of `stature` (m).
fn sitter_of(id: &str, stature: f64, at: [f64; 2], seat: f64, yaw_deg: f64) -> Human {
    let body = Body::new(stature);
    let pose = sit(&body, DVec2::from(at), seat, yaw_deg.to_radians());
    let mut m = Motion::new(body, FPS);
    m.hold(pose, 20, Action::Sit);
    m.into_human(id)
}

fn walker(id: &str, path: &[[f64; 2]]) -> Human {
    let body = Body::new(1.75);
    let line = Polyline::new(path.iter().map(|&p| DVec2::from(p)).collect()).expect("a path of two points or more");
    let mut m = Motion::new(body, FPS);
    m.walk(&line, 1.1);
    m.into_human(id)
}

fn stander(id: &str, at: [f64; 2], yaw_deg: f64) -> Human {
    let body = Body::new(1.68);
    let mut m = Motion::new(body, FPS);
    m.hold(stand(&body, DVec2::from(at), yaw_deg.to_radians()), 20, Action::Stand);
    m.into_human(id)
}

fn lier(id: &str, at: [f64; 2], surface: f64, yaw_deg: f64) -> Human {
    let body = Body::new(1.7);
    let mut m = Motion::new(body, FPS);
    m.hold(lie(&body, DVec2::from(at), surface, yaw_deg.to_radians()), 20, Action::Lie);
    m.into_human(id)
}

fn toucher(id: &str, palm: [f64; 3], yaw_deg: f64) -> Human {
    let body = Body::new(1.7);
    let mut m = Motion::new(body, FPS);
    m.hold(touch(&body, DVec3::from(palm), yaw_deg.to_radians(), Side::Right), 20, Action::Touch);
    m.into_human(id)
}

/// A person who walks in from `door`, sits down on a seat of height `seat` at `at` facing
/// `yaw_deg`, stays, gets up and walks back to the door. They walk up to the seat from the front,
/// stop with their feet a little ahead of where they rest seated, turn, sit down and later stand
/// up there. The actions are labelled from the motion, frame by frame, as `import-motion` labels
/// a capture: the turns and the sitting down are walking or standing, not sitting.
fn visitor(id: &str, door: [f64; 2], at: [f64; 2], seat: f64, yaw_deg: f64) -> Human {
    let body = Body::new(1.74);
    let yaw = yaw_deg.to_radians();
    let seated = sit(&body, DVec2::from(at), seat, yaw);
    let facing = DVec2::new(-yaw.sin(), yaw.cos());
    let feet = (seated.get(Joint::LeftAnkle) + seated.get(Joint::RightAnkle)).truncate() * 0.5;
    let spot = feet + facing * 0.08;
    let (door, front) = (DVec2::from(door), spot + facing * 0.8);
    let standing = stand(&body, spot, yaw);
    let mut m = Motion::new(body, FPS);
    m.walk(&Polyline::new(vec![door, front, spot]).expect("three points"), 1.0);
    m.blend_to(&standing, 6).hold(standing, 4, Action::Stand).blend_to(&seated, 10);
    m.hold(seated, 40, Action::Sit).blend_to(&standing, 10).hold(standing, 4, Action::Stand);
    let away = stand(&body, spot, (-(door - spot).x).atan2((door - spot).y));
    m.blend_to(&away, 6);
    m.walk(&Polyline::new(vec![spot, front, door]).expect("three points"), 1.0);
    let mut human = m.into_human(id);
    let frames = body_frames(&human).expect("our own skeleton");
    human.actions = runs(&label_frames(&frames, FPS, body.stature, &LabelConfig::default()));
    human
}

/// A room whose walls run at `deg` to the axes, its first corner at `origin`: a scan's or a capture
/// space's own coordinates. `at` maps the room's coordinates to the world's.
struct Turned {
    deg: f64,
    origin: [f64; 2],
}

impl Turned {
    fn at(&self, p: [f64; 2]) -> [f64; 2] {
        (DVec2::from(self.origin) + DVec2::from_angle(self.deg.to_radians()).rotate(DVec2::from(p))).to_array()
    }

    fn plan(&self, w: f64, d: f64) -> FloorPlan {
        FloorPlan { polygon: rect(w, d).polygon.into_iter().map(|p| self.at(p)).collect(), height: 2.6 }
    }
}

/// Two people side by side on a sofa 2.6 m from the west wall, facing a TV touched on that wall
/// (the open-plan room's pair, and its cuts).
fn pair_facing_tv() -> Vec<Human> {
    vec![
        sitter("sofa_left", [2.6, 2.2], 0.43, 90.0),
        sitter("sofa_right", [2.6, 2.85], 0.43, 90.0),
        toucher("tv", [0.35, 2.5, 0.6], 90.0),
    ]
}

fn scene(room_type: RoomType, floor_plan: FloorPlan, humans: Vec<Human>) -> Scene {
    Scene { format: shade_sim::scene::FORMAT.into(), room_type, floor_plan, objects: Vec::new(), humans }
}

fn main() -> anyhow::Result<()> {
    let out = PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| "tests/inputs".into()));
    std::fs::create_dir_all(&out)?;
    let inputs = [
        // 2.6 × 2.8 m: a sleeper-less bedroom with one sitter facing the wall (a desk) and a walker
        // from the door to the window.
        (
            "tight_bedroom",
            scene(
                RoomType::Bedroom,
                rect(2.6, 2.8),
                vec![sitter("desk", [2.0, 2.05], 0.46, 0.0), walker("door", &[[0.4, 0.3], [0.6, 2.4]])],
            ),
        ),
        // A person seated facing a desk against the top wall, a walker passing about 30 cm behind them.
        (
            "walker_behind_sitter",
            scene(
                RoomType::Bedroom,
                rect(3.6, 3.4),
                vec![sitter("desk", [1.8, 2.75], 0.46, 0.0), walker("behind", &[[0.3, 1.95], [3.3, 1.95]])],
            ),
        ),
        // A living room crossed diagonally through its middle, with one sitter, back to a wall.
        (
            "walker_through_middle",
            scene(
                RoomType::Living,
                rect(5.0, 4.2),
                vec![sitter("reader", [0.55, 2.1], 0.44, -90.0), walker("cross", &[[1.2, 0.3], [4.6, 3.9]])],
            ),
        ),
        // Three sitters shoulder to shoulder, their backs to a wall (one sofa's worth), and a stander.
        (
            "three_on_a_sofa",
            scene(
                RoomType::Living,
                rect(4.8, 4.0),
                vec![
                    sitter("left", [1.75, 0.55], 0.43, 0.0),
                    sitter("middle", [2.4, 0.55], 0.43, 0.0),
                    sitter("right", [3.05, 0.55], 0.43, 0.0),
                    stander("host", [3.9, 2.8], 180.0),
                ],
            ),
        ),
        // Two sitters across from each other (1.3 m apart: their feet clear of each other) and one at
        // the head: one table between them.
        (
            "dinner_for_three",
            scene(
                RoomType::Dining,
                rect(4.2, 3.6),
                vec![
                    sitter("north", [2.1, 2.45], 0.46, 180.0),
                    sitter("south", [2.1, 1.15], 0.46, 0.0),
                    sitter("head", [1.2, 1.8], 0.46, -90.0),
                    walker("serve", &[[3.8, 0.4], [3.8, 3.2]]),
                ],
            ),
        ),
        // Four diners two a side of a table that runs east–west, and a person standing at its east
        // end with a hand on the top: a table touched at its end, where the data touched a table
        // only at its front, for most tables a long side (until `synth --touch-any-side`).
        (
            "dining_hand_at_the_head",
            scene(
                RoomType::Dining,
                rect(5.0, 4.0),
                vec![
                    sitter("north_west", [2.0, 2.75], 0.46, 180.0),
                    sitter("north_east", [2.7, 2.75], 0.46, 180.0),
                    sitter("south_west", [2.0, 1.25], 0.46, 0.0),
                    sitter("south_east", [2.7, 1.25], 0.46, 0.0),
                    toucher("head", [3.15, 2.0, 0.75], 90.0),
                    walker("serve", &[[0.4, 0.4], [4.6, 0.4]]),
                ],
            ),
        ),
        // An L-shaped living room: two sitters side by side against the far wall of the L's arm,
        // a walker coming round its inner corner.
        (
            "l_living_pair_and_walker",
            scene(
                RoomType::Living,
                FloorPlan {
                    polygon: vec![[0.0, 0.0], [6.0, 0.0], [6.0, 3.0], [3.5, 3.0], [3.5, 5.0], [0.0, 5.0]],
                    height: 2.7,
                },
                vec![
                    sitter("left", [1.2, 4.45], 0.43, 180.0),
                    sitter("right", [1.85, 4.45], 0.43, 180.0),
                    walker("round", &[[5.6, 1.5], [2.5, 1.5], [2.5, 3.0]]),
                ],
            ),
        ),
        // A sleeper, a person at a desk facing the bottom wall, and a walker from the door between them.
        (
            "bedroom_sleeper_desk_walker",
            scene(
                RoomType::Bedroom,
                rect(4.0, 3.6),
                vec![
                    lier("sleeper", [1.2, 2.4], 0.5, 0.0),
                    sitter("desk", [3.4, 0.95], 0.46, 180.0),
                    walker("door", &[[3.7, 3.3], [2.6, 1.6], [0.4, 0.4]]),
                ],
            ),
        ),
        // Four diners, two a side, and a walker 0.85 m behind the north row.
        (
            "dining_four_walker_behind",
            scene(
                RoomType::Dining,
                rect(4.5, 4.0),
                vec![
                    sitter("north_1", [1.9, 2.7], 0.46, 180.0),
                    sitter("north_2", [2.6, 2.7], 0.46, 180.0),
                    sitter("south_1", [1.9, 1.3], 0.46, 0.0),
                    sitter("south_2", [2.6, 1.3], 0.46, 0.0),
                    walker("behind", &[[0.3, 3.55], [4.2, 3.55]]),
                ],
            ),
        ),
        // A reader in the middle, a person reaching up to a shelf in a corner, a walker between.
        (
            "living_reader_and_shelf",
            scene(
                RoomType::Living,
                rect(5.0, 4.0),
                vec![
                    sitter("reader", [2.5, 1.0], 0.44, 0.0),
                    toucher("reach", [4.5, 3.6, 1.2], 0.0),
                    walker("cross", &[[0.4, 3.5], [3.0, 2.6]]),
                ],
            ),
        ),
        // A couple lying on one bed against the top wall, a walker 65 cm past its foot, and a
        // person reaching to a wardrobe's front on the right.
        (
            "bedroom_couple_walker_at_foot",
            scene(
                RoomType::Bedroom,
                rect(3.8, 4.0),
                vec![
                    lier("left", [1.5, 3.0], 0.5, 180.0),
                    lier("right", [2.2, 3.0], 0.5, 180.0),
                    walker("foot", &[[0.3, 1.3], [3.5, 1.3]]),
                    toucher("closet", [3.15, 2.6, 1.3], -90.0),
                ],
            ),
        ),
        // An L-shaped dining room: six diners, three a side of one table in the wide arm, and a
        // walker coming down the narrow arm and past the table's west end.
        (
            "l_dining_six",
            scene(
                RoomType::Dining,
                FloorPlan {
                    polygon: vec![[0.0, 0.0], [5.5, 0.0], [5.5, 3.2], [2.5, 3.2], [2.5, 5.0], [0.0, 5.0]],
                    height: 2.7,
                },
                vec![
                    sitter("north_1", [2.3, 2.25], 0.46, 180.0),
                    sitter("north_2", [3.0, 2.25], 0.46, 180.0),
                    sitter("north_3", [3.7, 2.25], 0.46, 180.0),
                    sitter("south_1", [2.3, 0.95], 0.46, 0.0),
                    sitter("south_2", [3.0, 0.95], 0.46, 0.0),
                    sitter("south_3", [3.7, 0.95], 0.46, 0.0),
                    walker("down", &[[1.2, 4.7], [1.2, 2.0], [0.4, 0.5]]),
                ],
            ),
        ),
        // Two walkers crossing a living room, a reader in a corner facing into it, and a hand
        // resting on a low piece by the east wall.
        (
            "living_crossing_walkers",
            scene(
                RoomType::Living,
                rect(5.5, 4.5),
                vec![
                    sitter("corner", [0.75, 0.6], 0.44, -45.0),
                    walker("a", &[[0.4, 1.6], [5.1, 3.8]]),
                    walker("b", &[[1.0, 4.1], [4.5, 0.4]]),
                    toucher("top", [5.2, 1.2, 0.9], -90.0),
                ],
            ),
        ),
        // A 1.15 m child on a 30 cm seat (lower than any seat in the furniture catalog) facing the
        // top wall, and a walker down the far side of the room.
        (
            "child_on_a_low_seat",
            scene(
                RoomType::Bedroom,
                rect(3.2, 3.4),
                vec![sitter_of("child", 1.15, [1.0, 2.7], 0.30, 0.0), walker("by", &[[2.8, 0.3], [2.8, 3.1]])],
            ),
        ),
        // A nap on the sofa against the bottom wall (lying along it, feet to the west), a walker
        // across the room and a viewer facing the sofa from across it.
        (
            "nap_on_the_sofa",
            scene(
                RoomType::Living,
                rect(4.6, 4.0),
                vec![
                    lier("nap", [2.3, 0.5], 0.42, 90.0),
                    walker("cross", &[[0.3, 2.4], [4.3, 2.4]]),
                    sitter("viewer", [3.8, 3.4], 0.44, 180.0),
                ],
            ),
        ),
        // A living room scanned at 25° to the axes: two sitters side by side against its bottom
        // wall, a walker across it and a hand on a shelf by its right wall.
        ("living_at_an_angle", {
            let room = Turned { deg: 25.0, origin: [2.0, -1.0] };
            scene(
                RoomType::Living,
                room.plan(5.0, 4.2),
                vec![
                    sitter("left", room.at([2.1, 0.55]), 0.44, 25.0),
                    sitter("right", room.at([2.75, 0.55]), 0.44, 25.0),
                    walker("cross", &[room.at([0.4, 2.4]), room.at([4.6, 3.0])]),
                    toucher(
                        "shelf",
                        {
                            let [x, y] = room.at([4.65, 1.8]);
                            [x, y, 1.2]
                        },
                        -65.0,
                    ),
                ],
            )
        }),
        // People on the floor: a child sitting on it, knees up, and a person lying on it by the
        // window wall, neither held by furniture; a walker between them and a reader on a seat.
        (
            "people_on_the_floor",
            scene(
                RoomType::Living,
                rect(5.0, 4.2),
                vec![
                    sitter_of("child", 1.2, [1.3, 3.2], 0.0, 180.0),
                    lier("floor", [3.2, 0.6], 0.0, 90.0),
                    walker("cross", &[[0.4, 1.9], [4.6, 2.1]]),
                    sitter("reader", [4.3, 3.5], 0.44, 180.0),
                ],
            ),
        ),
        // Someone walks in, sits down in the middle of the sofa against the back wall, gets up and
        // walks out; another reads in an armchair by the side wall.
        (
            "sofa_visit",
            scene(
                RoomType::Living,
                rect(5.0, 4.0),
                vec![
                    visitor("guest", [4.4, 0.5], [2.5, 3.45], 0.42, 180.0),
                    sitter("reader", [0.55, 1.6], 0.44, -90.0),
                ],
            ),
        ),
        // A reading chair turned into a bedroom's corner: walked to, sat in, left again; a sleeper.
        (
            "reading_chair_visit",
            scene(
                RoomType::Bedroom,
                rect(3.6, 3.4),
                vec![visitor("reader", [0.5, 0.5], [3.0, 2.8], 0.44, 135.0), lier("sleeper", [0.95, 2.2], 0.48, 0.0)],
            ),
        ),
        // A reading chair in the middle of a bedroom, walked to from the door behind it, straight
        // through where the chair must stand: no layout can pass the check (the warning
        // `human::seats_in_the_way` names it).
        (
            "walk_through_the_chair",
            scene(RoomType::Bedroom, rect(3.6, 4.6), vec![visitor("reader", [1.8, 0.5], [1.8, 2.3], 0.44, 0.0)]),
        ),
        // The person at the desk sits too close to the wall they face: their feet are in it, and
        // no layout can pass the check.
        (
            "sitter_feet_in_the_wall",
            scene(
                RoomType::Bedroom,
                rect(4.0, 3.6),
                vec![sitter("desk", [3.4, 0.55], 0.46, 180.0), walker("door", &[[3.7, 3.3], [0.4, 1.6]])],
            ),
        ),
        // Four people in conversation on four seats round the middle of a living room, facing
        // each other 2.2 m apart, and a walker along the wall behind two of them.
        (
            "conversation_circle",
            scene(
                RoomType::Living,
                rect(5.0, 4.6),
                vec![
                    sitter("north", [2.5, 3.4], 0.44, 180.0),
                    sitter("south", [2.5, 1.2], 0.44, 0.0),
                    sitter("east", [3.6, 2.3], 0.44, 90.0),
                    sitter("west", [1.4, 2.3], 0.44, -90.0),
                    walker("past", &[[0.4, 4.2], [4.6, 4.2]]),
                ],
            ),
        ),
        // Two diners face each other across where a small table must stand, in a dining room 2.8 m
        // deep, and someone walks past the table's end.
        (
            "dining_for_two_narrow",
            scene(
                RoomType::Dining,
                rect(3.6, 2.8),
                vec![
                    sitter("near", [1.4, 0.75], 0.46, 0.0),
                    sitter("far", [1.4, 2.05], 0.46, 180.0),
                    walker("past", &[[3.0, 0.3], [3.0, 2.5]]),
                ],
            ),
        ),
        // Two sleepers side by side, 1.6 m apart (two single beds), and someone walking between
        // the beds from their foot to the wall at their head.
        (
            "two_singles_walker_between",
            scene(
                RoomType::Bedroom,
                rect(3.6, 4.2),
                vec![
                    lier("left", [1.0, 2.6], 0.5, 0.0),
                    lier("right", [2.6, 2.6], 0.5, 0.0),
                    walker("between", &[[1.8, 0.3], [1.8, 3.7]]),
                ],
            ),
        ),
        // A person lying on a sofa, another in an armchair beside it, both facing a person who
        // touches the top of a TV stand on the far wall, and a walker between them and the TV.
        (
            "living_tv_and_nap",
            scene(
                RoomType::Living,
                rect(5.4, 4.2),
                vec![
                    lier("nap", [2.4, 0.55], 0.42, 90.0),
                    sitter("chair", [4.3, 1.0], 0.44, 30.0),
                    toucher("tv", [2.6, 3.75, 0.62], 0.0),
                    walker("cross", &[[0.4, 2.3], [5.0, 2.5]]),
                ],
            ),
        ),
        // An open-plan room 7 m long: two people on a sofa facing a TV on the west wall, four diners
        // two a side at the east end, and a walker from the door in the south wall to the north.
        (
            "open_plan_sofa_and_table",
            scene(
                RoomType::Living,
                rect(7.0, 5.0),
                [
                    pair_facing_tv(),
                    vec![
                        sitter("diner_nw", [5.1, 3.45], 0.46, 180.0),
                        sitter("diner_ne", [5.8, 3.45], 0.46, 180.0),
                        sitter("diner_sw", [5.1, 2.15], 0.46, 0.0),
                        sitter("diner_se", [5.8, 2.15], 0.46, 0.0),
                        walker("through", &[[3.8, 0.3], [3.9, 4.7]]),
                    ],
                ]
                .concat(),
            ),
        ),
        // Four diners, one at each side of a square table, and a hand on a sideboard by the wall.
        (
            "dining_square_four",
            scene(
                RoomType::Dining,
                rect(4.4, 4.0),
                vec![
                    sitter("north", [2.2, 2.85], 0.46, 180.0),
                    sitter("south", [2.2, 1.15], 0.46, 0.0),
                    sitter("east", [3.05, 2.0], 0.46, 90.0),
                    sitter("west", [1.35, 2.0], 0.46, -90.0),
                    toucher("sideboard", [4.05, 3.4, 0.8], -90.0),
                ],
            ),
        ),
        // A sleeper in the middle of the room, their head 1.2 m from the wall behind it, and someone
        // walking along that wall, between the bed's head and the wall, and up the room's east side.
        (
            "bed_off_the_wall",
            scene(
                RoomType::Bedroom,
                rect(4.6, 4.6),
                vec![lier("sleeper", [2.3, 2.0], 0.5, 0.0), walker("behind", &[[0.4, 0.35], [4.2, 0.35], [4.2, 4.2]])],
            ),
        ),
        // A living room 2.6 m wide and 6.5 m long: two people side by side at one end facing down
        // its length, a reader at the other end, and a walker along one long wall.
        (
            "long_narrow_living",
            scene(
                RoomType::Living,
                rect(2.6, 6.5),
                vec![
                    sitter("left", [1.0, 5.9], 0.43, 180.0),
                    sitter("right", [1.65, 5.9], 0.43, 180.0),
                    sitter("reader", [1.6, 0.6], 0.44, 0.0),
                    walker("along", &[[0.35, 0.4], [0.35, 6.1]]),
                ],
            ),
        ),
        // The open-plan room's sofa pair and TV alone: two people side by side in the middle of a
        // 7 × 5 m room, their backs 4 m from the east wall, facing the TV on the west wall.
        ("sofa_pair_in_the_open", scene(RoomType::Living, rect(7.0, 5.0), pair_facing_tv())),
        // The same pair in a room 4 m wide: their backs about a metre from the east wall.
        ("sofa_pair_a_metre_off_the_wall", scene(RoomType::Living, rect(4.0, 5.0), pair_facing_tv())),
        // The same pair in a room 4.6 m wide, with a walker crossing the room 1.2 m behind them.
        (
            "sofa_pair_walker_behind",
            scene(
                RoomType::Living,
                rect(4.6, 5.0),
                [pair_facing_tv(), vec![walker("through", &[[3.8, 0.3], [3.9, 4.7]])]].concat(),
            ),
        ),
    ];
    for (name, s) in inputs {
        if let Some(problem) = shade_sim::scene::validate(&s).first() {
            anyhow::bail!("{name}: {problem:?}");
        }
        let path = out.join(format!("{name}.json"));
        s.save(&path)?;
        println!("{}", path.display());
    }
    Ok(())
}
