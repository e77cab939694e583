//! A scene as a complete MuJoCo world (MJCF): floor, walls, furniture bodies made of their template
//! parts with per-category materials, and each human as mocap bodies (one per bone, a capsule each)
//! whose motion is a keyframe sequence (`<key mpos mquat>` per frame).
//!
//! Furniture is static by default; with `free_furniture` each piece gets a free joint and a mass
//! from its parts' volume at 300 kg/m³. MuJoCo reports no contacts between mocap bodies and bodies
//! without joints, so the world lists a `<contact><pair>` for every bone and static part or wall
//! that come within 5 cm of each other over the recorded motion (pairs that can never touch would
//! only cost narrow-phase tests each step). The floor gets no pairs. The text is deterministic: stable order, fixed precision, names from the scene's ids
//! (`o3`, `o3_seat`, `h1_left_knee-left_ankle`).

use super::palette::{MATERIALS, material};
use crate::furniture::{Part, PartRole, template, wall_boxes};
use crate::geom::OBox;
use crate::scene::{Object, Scene};
use glam::{DQuat, DVec3};
use std::fmt::Write;

/// Options of the export.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MjcfOptions {
    /// Give furniture free joints (dynamic) instead of fixing it to the world. Default false.
    pub free_furniture: bool,
    /// Write the humans' motion as `<keyframe>`s. Default true; robosuite arenas leave them out
    /// (a merged robot changes the model's sizes) and use the companion motion file instead.
    pub keyframes: bool,
    /// Write the `<contact><pair>`s between bones and static geoms. Default true; robosuite arenas
    /// leave them out: merged into a robosuite 1.5.2 environment, the world stops at the
    /// environment's first `mj_forward` ("treeIterInit: contact 0 is between two static bodies",
    /// MuJoCo 3.9), where the same world alone steps through every keyframe.
    pub contact_pairs: bool,
}

impl Default for MjcfOptions {
    fn default() -> MjcfOptions {
        MjcfOptions { free_furniture: false, keyframes: true, contact_pairs: true }
    }
}

impl MjcfOptions {
    /// A robosuite arena: static furniture, no keyframes, no contact pairs.
    pub fn robosuite() -> MjcfOptions {
        MjcfOptions { free_furniture: false, keyframes: false, contact_pairs: false }
    }
}

/// The humans' motion for a replay loop: mocap body names and, per frame, `[x, y, z, qw, qx, qy,
/// qz]` of each, in the order of `bodies`.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct MocapMotion {
    /// Frames per second.
    pub fps: f64,
    /// Mocap body names.
    pub bodies: Vec<String>,
    /// One row per frame, one pose per body.
    pub frames: Vec<Vec<[f64; 7]>>,
}

/// The companion motion of `scene_mjcf`'s mocap bodies.
pub fn mocap_motion(scene: &Scene) -> MocapMotion {
    let mut bodies = Vec::new();
    for (h, human) in scene.humans.iter().enumerate() {
        for b in 0..human.skeleton.bones.len() {
            bodies.push(bone_name(scene, h, b));
        }
    }
    let frames = scene.humans.iter().map(|h| h.frames.len()).max().unwrap_or(0);
    let round = |x: f64| (x * 1e5).round() / 1e5;
    let frames = (0..frames)
        .map(|f| {
            scene
                .humans
                .iter()
                .enumerate()
                .flat_map(|(h, human)| (0..human.skeleton.bones.len()).map(move |b| (h, b)))
                .map(|(h, b)| {
                    let (p, q) = bone_pose(scene, h, b, f);
                    [p.x, p.y, p.z, q.w, q.x, q.y, q.z].map(round)
                })
                .collect()
        })
        .collect();
    MocapMotion { fps: scene.humans.first().map_or(30.0, |h| h.fps), bodies, frames }
}

pub(crate) fn v3(v: DVec3) -> String {
    format!("{} {} {}", num(v.x), num(v.y), num(v.z))
}

/// Fixed precision, no negative zero.
fn num(x: f64) -> String {
    let s = format!("{x:.5}");
    let s = s.trim_end_matches('0').trim_end_matches('.').to_string();
    if s == "-0" || s.is_empty() { "0".into() } else { s }
}

fn quat(q: DQuat) -> String {
    format!("{} {} {} {}", num(q.w), num(q.x), num(q.y), num(q.z))
}

fn role_name(role: PartRole) -> &'static str {
    match role {
        PartRole::Seat => "seat",
        PartRole::Back => "back",
        PartRole::Arm => "arm",
        PartRole::Leg => "leg",
        PartRole::Top => "top",
        PartRole::Body => "body",
        PartRole::Panel => "panel",
        PartRole::Shade => "shade",
        PartRole::Cord => "cord",
    }
}

/// Bone name `pelvis-spine`.
pub(crate) fn bone_name(scene: &Scene, h: usize, b: usize) -> String {
    let human = &scene.humans[h];
    let bone = &human.skeleton.bones[b];
    format!("{}_{}-{}", human.id, human.skeleton.joints[bone.a], human.skeleton.joints[bone.b])
}

/// Pose of a bone's mocap body in frame `f`: its midpoint, its z axis along the bone.
pub(crate) fn bone_pose(scene: &Scene, h: usize, b: usize, f: usize) -> (DVec3, DQuat) {
    let human = &scene.humans[h];
    let f = f.min(human.frames.len() - 1);
    let bone = &human.skeleton.bones[b];
    let (p, q) = (human.joint_at(f, bone.a), human.joint_at(f, bone.b));
    ((p + q) * 0.5, DQuat::from_rotation_arc(DVec3::Z, (q - p).normalize_or(DVec3::Z)))
}

/// How far (m) a bone's swept box and a static part's box may be apart and still get a contact
/// pair: contacts need the boxes to overlap, the margin keeps pairs for near misses.
pub const PAIR_MARGIN: f64 = 0.05;

/// A static geom humans can touch: its name and its world AABB.
struct StaticGeom {
    name: String,
    aabb: (DVec3, DVec3),
}

impl StaticGeom {
    fn of(name: String, b: &OBox) -> StaticGeom {
        let (lo, hi) = b.footprint_aabb();
        let (z0, z1) = b.z_range();
        StaticGeom { name, aabb: (lo.extend(z0), hi.extend(z1)) }
    }
}

/// The box a bone's capsule sweeps over the whole motion.
fn swept_aabb(scene: &Scene, h: usize, b: usize) -> (DVec3, DVec3) {
    let human = &scene.humans[h];
    let bone = &human.skeleton.bones[b];
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for f in 0..human.frames.len() {
        for p in [human.joint_at(f, bone.a), human.joint_at(f, bone.b)] {
            lo = lo.min(p);
            hi = hi.max(p);
        }
    }
    (lo - DVec3::splat(bone.radius), hi + DVec3::splat(bone.radius))
}

fn overlaps(a: (DVec3, DVec3), b: (DVec3, DVec3), margin: f64) -> bool {
    a.0.cmple(b.1 + DVec3::splat(margin)).all() && b.0.cmple(a.1 + DVec3::splat(margin)).all()
}

/// The MJCF text of `scene`.
pub fn scene_mjcf(scene: &Scene, opts: MjcfOptions) -> String {
    let mut x = String::new();
    let _ = writeln!(x, "<mujoco model=\"shade-sim {} scene\">", scene.room_type);
    x.push_str("  <compiler angle=\"radian\" autolimits=\"true\"/>\n");
    x.push_str("  <option timestep=\"0.002\" gravity=\"0 0 -9.81\"/>\n");
    x.push_str("  <default>\n    <geom friction=\"0.7 0.005 0.0001\"/>\n  </default>\n");
    write_assets(&mut x);
    x.push_str("  <worldbody>\n");
    let mut statics = write_room(&mut x, scene);
    statics.extend(write_furniture(&mut x, scene, opts.free_furniture));
    let bones = write_humans(&mut x, scene);
    x.push_str("  </worldbody>\n");
    if opts.contact_pairs {
        write_pairs(&mut x, &bones, &statics);
    }
    if opts.keyframes {
        write_keyframes(&mut x, scene);
    }
    x.push_str("</mujoco>\n");
    x
}

fn write_assets(x: &mut String) {
    x.push_str("  <asset>\n");
    x.push_str("    <texture name=\"grid\" type=\"2d\" builtin=\"checker\" rgb1=\"0.82 0.78 0.72\" rgb2=\"0.76 0.72 0.66\" width=\"256\" height=\"256\"/>\n");
    x.push_str("    <material name=\"floor\" texture=\"grid\" texrepeat=\"8 8\"/>\n");
    for (name, rgba) in MATERIALS.iter().filter(|(n, _)| *n != "floor") {
        let _ = writeln!(x, "    <material name=\"{name}\" rgba=\"{}\"/>", rgba.map(num).join(" "));
    }
    x.push_str("  </asset>\n");
}

/// Light, floor and walls; returns the walls as static geoms.
fn write_room(x: &mut String, scene: &Scene) -> Vec<StaticGeom> {
    let (lo, hi) = scene.floor_plan.polygon().bounds();
    let mid = (lo + hi) * 0.5;
    let half = (hi - lo) * 0.5 + 1.0;
    let _ = writeln!(
        x,
        "    <light name=\"sun\" pos=\"{} {} {}\" dir=\"0 0 -1\" directional=\"true\"/>",
        num(mid.x),
        num(mid.y),
        num(scene.floor_plan.height + 2.0)
    );
    let _ = writeln!(
        x,
        "    <geom name=\"floor\" type=\"plane\" pos=\"{} {} 0\" size=\"{} {} 0.1\" material=\"floor\"/>",
        num(mid.x),
        num(mid.y),
        num(half.x),
        num(half.y)
    );
    let mut walls = Vec::new();
    for (i, w) in wall_boxes(scene) {
        let name = format!("wall{i}");
        let _ = writeln!(
            x,
            "    <geom name=\"{name}\" type=\"box\" pos=\"{}\" quat=\"{}\" size=\"{}\" material=\"wall\"/>",
            v3(w.center),
            quat(DQuat::from_rotation_z(w.yaw)),
            v3(w.half())
        );
        walls.push(StaticGeom::of(name, &w));
    }
    walls
}

/// One body per object, one box geom per template part; returns the parts of static pieces.
fn write_furniture(x: &mut String, scene: &Scene, free_furniture: bool) -> Vec<StaticGeom> {
    let mut statics = Vec::new();
    for o in &scene.objects {
        let b = o.obox();
        let free = free_furniture && !o.category.is_hanging();
        let _ = writeln!(
            x,
            "    <body name=\"{}\" pos=\"{}\" quat=\"{}\">",
            o.id,
            v3(b.center),
            quat(DQuat::from_rotation_z(b.yaw))
        );
        if free {
            let _ = writeln!(x, "      <freejoint name=\"{}_free\"/>", o.id);
        }
        for (name, p) in part_names(o) {
            let density = if free { " density=\"300\"" } else { "" };
            let _ = writeln!(
                x,
                "      <geom name=\"{name}\" type=\"box\" pos=\"{}\" size=\"{}\" material=\"{}\"{density}/>",
                v3(b.to_local(p.obox.center)),
                v3(p.obox.half()),
                material(o.category.group())
            );
            if !free {
                statics.push(StaticGeom::of(name, &p.obox));
            }
        }
        x.push_str("    </body>\n");
    }
    statics
}

/// An object's template parts with their geom names: `o3_seat`, `o3_leg`, `o3_leg1`, ….
pub fn part_names(o: &Object) -> Vec<(String, Part)> {
    let mut roles = std::collections::BTreeMap::new();
    template(o)
        .parts
        .into_iter()
        .map(|p| {
            let k = roles.entry(p.role).or_insert(0usize);
            let name = format!("{}_{}{}", o.id, role_name(p.role), if *k > 0 { k.to_string() } else { String::new() });
            *k += 1;
            (name, p)
        })
        .collect()
}

/// One mocap body with a capsule per bone, posed as in frame 0; returns the bones' names and
/// swept boxes.
fn write_humans(x: &mut String, scene: &Scene) -> Vec<StaticGeom> {
    let mut bones = Vec::new();
    for (h, human) in scene.humans.iter().enumerate() {
        for (b, bone) in human.skeleton.bones.iter().enumerate() {
            let name = bone_name(scene, h, b);
            let (pos, q) = bone_pose(scene, h, b, 0);
            let half = human.joint_at(0, bone.a).distance(human.joint_at(0, bone.b)) * 0.5;
            let _ = writeln!(
                x,
                "    <body name=\"{name}\" mocap=\"true\" pos=\"{}\" quat=\"{}\"><geom name=\"{name}\" type=\"capsule\" fromto=\"0 0 {} 0 0 {}\" size=\"{}\" material=\"human\"/></body>",
                v3(pos),
                quat(q),
                num(-half.max(1e-4)),
                num(half.max(1e-4)),
                num(bone.radius)
            );
            bones.push(StaticGeom { name, aabb: swept_aabb(scene, h, b) });
        }
    }
    bones
}

/// A `<pair>` for every bone and static geom that come within `PAIR_MARGIN` of each other over the
/// motion (MuJoCo reports no mocap-vs-static contacts otherwise).
fn write_pairs(x: &mut String, bones: &[StaticGeom], statics: &[StaticGeom]) {
    let pairs: Vec<(&str, &str)> = bones
        .iter()
        .flat_map(|b| {
            statics.iter().filter(|s| overlaps(b.aabb, s.aabb, PAIR_MARGIN)).map(|s| (b.name.as_str(), s.name.as_str()))
        })
        .collect();
    if pairs.is_empty() {
        return;
    }
    x.push_str("  <contact>\n");
    for (b, s) in pairs {
        let _ = writeln!(x, "    <pair geom1=\"{b}\" geom2=\"{s}\"/>");
    }
    x.push_str("  </contact>\n");
}

/// One `<key>` per frame with every mocap body's pose.
fn write_keyframes(x: &mut String, scene: &Scene) {
    let motion = mocap_motion(scene);
    if motion.bodies.is_empty() {
        return;
    }
    x.push_str("  <keyframe>\n");
    for (f, poses) in motion.frames.iter().enumerate() {
        let mpos: Vec<String> =
            poses.iter().map(|p| p[..3].iter().map(|v| num(*v)).collect::<Vec<_>>().join(" ")).collect();
        let mquat: Vec<String> =
            poses.iter().map(|p| p[3..].iter().map(|v| num(*v)).collect::<Vec<_>>().join(" ")).collect();
        let _ = writeln!(
            x,
            "    <key name=\"frame{f}\" time=\"{}\" mpos=\"{}\" mquat=\"{}\"/>",
            num(f as f64 / motion.fps),
            mpos.join(" "),
            mquat.join(" ")
        );
    }
    x.push_str("  </keyframe>\n");
}
