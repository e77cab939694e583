//! Builds the demo's inputs in `scenes/examples/`: hand-placed people in six rooms (three room
//! types, rectangular and L-shaped floors), each with walkers and at least two contact humans.
//! The furniture they imply (a bed under a lying person, a chair under a sitter) is left for the
//! generator to place. Deterministic: running it again rewrites identical files.
//!
//! Run: `cargo run --example build_example_scenes -- scenes/examples`

use glam::{DVec2, DVec3};
use shade_sim::geom::Polyline;
use shade_sim::human::{Body, Motion, Pose, Side, lie, sit, stand, touch};
use shade_sim::scene::{Action, FloorPlan, RoomType, Scene};
use std::path::Path;

const FPS: f64 = 30.0;
const SPEED: f64 = 1.2;
const BLEND: usize = 20;
const HOLD: usize = 45;

/// What one person does, in order.
enum Step {
    Walk(&'static [[f64; 2]]),
    Stand { facing: [f64; 2] },
    Sit { at: [f64; 2], seat: f64, facing: [f64; 2] },
    Lie { at: [f64; 2], surface: f64, facing: [f64; 2] },
    Touch { target: [f64; 3], facing: [f64; 2], side: Side },
}

struct Person {
    stature: f64,
    steps: &'static [Step],
}

struct Room {
    name: &'static str,
    room: RoomType,
    polygon: &'static [[f64; 2]],
    height: f64,
    people: &'static [Person],
}

/// Yaw that faces the direction (dx, dy).
fn yaw(facing: [f64; 2]) -> f64 {
    (-facing[0]).atan2(facing[1])
}

use Step::*;

const ROOMS: &[Room] = &[
    Room {
        name: "bedroom_rect",
        room: RoomType::Bedroom,
        polygon: &[[0.0, 0.0], [4.2, 0.0], [4.2, 3.8], [0.0, 3.8]],
        height: 2.7,
        people: &[
            Person { stature: 1.72, steps: &[Lie { at: [1.8, 2.75], surface: 0.5, facing: [0.0, -1.0] }] },
            Person { stature: 1.64, steps: &[Sit { at: [2.55, 1.95], seat: 0.5, facing: [0.0, -1.0] }] },
            Person {
                stature: 1.80,
                steps: &[
                    Walk(&[[3.9, 0.4], [2.6, 0.7], [1.4, 0.8]]),
                    Touch { target: [0.62, 0.9, 1.2], facing: [-1.0, 0.0], side: Side::Right },
                ],
            },
            Person {
                stature: 1.68,
                steps: &[Walk(&[[3.9, 0.5], [3.55, 1.3], [3.55, 3.2]]), Stand { facing: [-1.0, 0.0] }],
            },
            Person {
                stature: 1.25,
                steps: &[Walk(&[[0.6, 3.4], [0.8, 2.6], [0.9, 1.9]]), Stand { facing: [0.0, -1.0] }],
            },
        ],
    },
    Room {
        name: "bedroom_l",
        room: RoomType::Bedroom,
        polygon: &[[0.0, 0.0], [5.0, 0.0], [5.0, 2.5], [3.0, 2.5], [3.0, 4.5], [0.0, 4.5]],
        height: 2.8,
        people: &[
            Person { stature: 1.78, steps: &[Lie { at: [0.6, 3.25], surface: 0.45, facing: [0.0, -1.0] }] },
            Person {
                stature: 1.70,
                steps: &[
                    Walk(&[[2.6, 1.2], [3.9, 1.35], [4.3, 1.25]]),
                    Stand { facing: [0.0, 1.0] },
                    Sit { at: [4.3, 0.85], seat: 0.46, facing: [0.0, 1.0] },
                ],
            },
            Person {
                stature: 1.62,
                steps: &[Touch { target: [1.45, 4.1, 0.56], facing: [0.0, 1.0], side: Side::Left }],
            },
            Person {
                stature: 1.75,
                steps: &[Walk(&[[4.7, 2.2], [2.2, 1.5], [1.4, 1.2]]), Stand { facing: [-1.0, 0.0] }],
            },
            Person { stature: 1.83, steps: &[Walk(&[[2.5, 4.2], [2.3, 2.6], [3.6, 1.6]])] },
        ],
    },
    Room {
        name: "living_rect",
        room: RoomType::Living,
        polygon: &[[0.0, 0.0], [6.5, 0.0], [6.5, 5.0], [0.0, 5.0]],
        height: 2.8,
        people: &[
            Person { stature: 1.76, steps: &[Sit { at: [2.8, 0.55], seat: 0.42, facing: [0.0, 1.0] }] },
            Person { stature: 1.66, steps: &[Sit { at: [3.7, 0.55], seat: 0.42, facing: [0.0, 1.0] }] },
            Person { stature: 1.70, steps: &[Sit { at: [0.7, 2.5], seat: 0.42, facing: [1.0, 0.0] }] },
            Person {
                stature: 1.82,
                steps: &[
                    Walk(&[[6.2, 4.4], [4.4, 4.1], [3.5, 3.9]]),
                    Touch { target: [3.1, 4.55, 0.52], facing: [0.0, 1.0], side: Side::Right },
                ],
            },
            Person {
                stature: 1.72,
                steps: &[Walk(&[[6.3, 1.5], [5.1, 2.5], [5.1, 3.6]]), Stand { facing: [-1.0, 0.0] }],
            },
            Person {
                stature: 1.60,
                steps: &[Walk(&[[1.0, 4.6], [1.5, 3.6], [2.0, 3.3]]), Stand { facing: [0.0, 1.0] }],
            },
        ],
    },
    Room {
        name: "living_l",
        room: RoomType::Living,
        polygon: &[[0.0, 0.0], [8.0, 0.0], [8.0, 4.0], [4.5, 4.0], [4.5, 7.0], [0.0, 7.0]],
        height: 2.9,
        people: &[
            Person { stature: 1.74, steps: &[Sit { at: [0.6, 2.0], seat: 0.42, facing: [1.0, 0.0] }] },
            Person { stature: 1.69, steps: &[Sit { at: [0.6, 3.0], seat: 0.42, facing: [1.0, 0.0] }] },
            Person {
                stature: 1.80,
                steps: &[
                    Walk(&[[3.9, 4.5], [3.5, 5.5], [3.0, 6.0]]),
                    Stand { facing: [0.0, -1.0] },
                    Sit { at: [3.0, 6.4], seat: 0.40, facing: [0.0, -1.0] },
                ],
            },
            Person {
                stature: 1.65,
                steps: &[Touch { target: [1.5, 6.4, 1.3], facing: [0.0, 1.0], side: Side::Right }],
            },
            Person {
                stature: 1.77,
                steps: &[
                    Walk(&[[5.5, 0.6], [6.8, 1.5], [7.0, 2.0]]),
                    Touch { target: [7.45, 2.0, 0.78], facing: [1.0, 0.0], side: Side::Left },
                ],
            },
            Person { stature: 1.71, steps: &[Walk(&[[7.6, 3.6], [5.0, 2.2], [3.2, 4.5], [2.6, 5.2]])] },
        ],
    },
    Room {
        name: "dining_rect",
        room: RoomType::Dining,
        polygon: &[[0.0, 0.0], [5.0, 0.0], [5.0, 4.2], [0.0, 4.2]],
        height: 2.7,
        people: &[
            Person { stature: 1.73, steps: &[Sit { at: [2.1, 1.25], seat: 0.46, facing: [0.0, 1.0] }] },
            Person { stature: 1.61, steps: &[Sit { at: [2.9, 1.25], seat: 0.46, facing: [0.0, 1.0] }] },
            Person { stature: 1.79, steps: &[Sit { at: [2.5, 2.95], seat: 0.46, facing: [0.0, -1.0] }] },
            Person {
                stature: 1.68,
                steps: &[Touch { target: [3.2, 2.1, 0.76], facing: [-1.0, 0.0], side: Side::Right }],
            },
            Person {
                stature: 1.75,
                steps: &[Touch { target: [0.45, 3.2, 0.9], facing: [-1.0, 0.0], side: Side::Left }],
            },
            Person { stature: 1.84, steps: &[Walk(&[[4.55, 0.5], [4.5, 2.0], [4.4, 3.8], [3.0, 3.9]])] },
            Person { stature: 1.58, steps: &[Walk(&[[0.4, 0.4], [4.0, 0.4]]), Stand { facing: [0.0, 1.0] }] },
        ],
    },
    Room {
        name: "dining_l",
        room: RoomType::Dining,
        polygon: &[[0.0, 0.0], [6.0, 0.0], [6.0, 3.0], [3.5, 3.0], [3.5, 6.0], [0.0, 6.0]],
        height: 2.8,
        people: &[
            Person { stature: 1.70, steps: &[Sit { at: [1.75, 3.55], seat: 0.45, facing: [0.0, 1.0] }] },
            Person { stature: 1.77, steps: &[Sit { at: [1.75, 5.05], seat: 0.45, facing: [0.0, -1.0] }] },
            Person { stature: 1.66, steps: &[Sit { at: [0.95, 4.3], seat: 0.45, facing: [1.0, 0.0] }] },
            Person {
                stature: 1.81,
                steps: &[Touch { target: [5.45, 1.5, 1.1], facing: [1.0, 0.0], side: Side::Right }],
            },
            Person { stature: 1.72, steps: &[Walk(&[[5.6, 2.6], [2.6, 1.5], [2.8, 3.5], [2.9, 5.5]])] },
            Person {
                stature: 1.63,
                steps: &[Walk(&[[1.5, 0.4], [3.0, 0.6], [4.8, 0.6]]), Stand { facing: [1.0, 0.0] }],
            },
        ],
    },
];

fn v2(p: [f64; 2]) -> DVec2 {
    DVec2::from(p)
}

/// The pose a step ends in, given where the person stands.
fn pose_of(step: &Step, body: &Body, last: Option<&Pose>) -> Option<(Pose, Action)> {
    let here = last.map(|p| p.get(shade_sim::human::Joint::Pelvis).truncate());
    match step {
        Walk(_) => None,
        Stand { facing } => Some((stand(body, here.unwrap_or(DVec2::ZERO), yaw(*facing)), Action::Stand)),
        Sit { at, seat, facing } => Some((sit(body, v2(*at), *seat, yaw(*facing)), Action::Sit)),
        Lie { at, surface, facing } => Some((lie(body, v2(*at), *surface, yaw(*facing)), Action::Lie)),
        Touch { target, facing, side } => Some((touch(body, DVec3::from(*target), yaw(*facing), *side), Action::Touch)),
    }
}

fn build(room: &Room) -> Scene {
    let plan = FloorPlan { polygon: room.polygon.to_vec(), height: room.height };
    let mut scene = Scene::new(room.room, plan);
    for (i, person) in room.people.iter().enumerate() {
        let body = Body::new(person.stature);
        let mut motion = Motion::new(body, FPS);
        for step in person.steps {
            if let Walk(points) = step {
                let path = Polyline::new(points.iter().map(|&p| v2(p)).collect()).expect("paths have length");
                motion.walk(&path, SPEED);
                continue;
            }
            let (pose, action) = pose_of(step, &body, motion.last()).expect("non-walk steps have a pose");
            motion.blend_to(&pose, if matches!(step, Stand { .. }) { 8 } else { BLEND });
            motion.hold(pose, HOLD, action);
        }
        scene.humans.push(motion.into_human(format!("h{i}")));
    }
    scene
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = std::env::args().nth(1).unwrap_or_else(|| "scenes/examples".into());
    std::fs::create_dir_all(&dir)?;
    for room in ROOMS {
        let scene = build(room);
        let path = Path::new(&dir).join(format!("{}.json", room.name));
        scene.save(&path)?;
        println!("wrote {} ({} humans)", path.display(), scene.humans.len());
    }
    Ok(())
}
