//! Retargeting a clip onto our 19-joint body: which of the file's joints is our pelvis, knee,
//! wrist…, by the joint names of the common rigs, or by the shape of the hierarchy when the names
//! are unknown. Positions stay in the file's units and axes.
//!
//! Named rigs (names compared in lower case, without a `prefix:` and without `_`, `-`, `.` or
//! spaces, so `mixamorig:LeftUpLeg`, `LeftUpLeg` and `left_up_leg` are one name):
//! - **MotionBuilder-style** — CMU's BVH conversion, Mixamo, Axis Neuron, Rokoko: `Hips`,
//!   `LeftUpLeg` / `LeftLeg` / `LeftFoot` / `LeftToeBase` (or `LeftToe`), `LeftArm` /
//!   `LeftForeArm` / `LeftHand`, `Neck`, `Head`;
//! - **BioVision-style** — mocapbank, the BVH samples of many tools: `Hips`, `LeftHip` /
//!   `LeftKnee` / `LeftAnkle` / `LeftToe(s)`, `LeftShoulder` / `LeftElbow` / `LeftWrist`, `Neck`,
//!   `Head`;
//! - **SMPL / SMPL-H / SMPL-X** joint names (`pelvis`, `left_hip`, …, `left_foot` for the toe);
//! - **ours** — the 19 names of `JOINT_NAMES` (a shade-scene human's joints saved as an array):
//!   taken one for one, nothing derived.
//!
//! Spine and chest are points on the trunk (the chain of joints from the pelvis to the neck) at
//! our body's proportions of its length, so rigs with one to four spine joints retarget alike. The
//! head is halfway between the file's head joint and the top of the head (its end site) where
//! there is one, else half a head-to-neck length above the head joint.
//!
//! Topology fallback, for a hierarchy with other names: the root is the pelvis; the lowest leaf
//! and the lowest one that branches off above its hip are the toes (then ankle, knee and hip up
//! the chain); the highest leaf is the head; the two leaves farthest from the neck on separate
//! branches of the trunk are the hands (shoulder, elbow and wrist down the branch, after a short
//! clavicle). Left is the side the feet point left of.

use super::clip::Clip;
use crate::human::{JOINT_NAMES, Joint};
use glam::DVec3;

/// Our joints' positions at every frame, in the file's units and axes, and how they were found.
#[derive(Debug, Clone, PartialEq)]
pub struct Retargeted {
    /// The rig recognised: `"shade-sim"` (ours), `"MotionBuilder-style"`, `"BioVision-style"`,
    /// `"SMPL"` or `"topology"`.
    pub rig: &'static str,
    /// One entry per frame, in `JOINT_NAMES` order.
    pub frames: Vec<[DVec3; 19]>,
}

/// Where each of our joints comes from: indices into the clip's joints.
#[derive(Debug, Clone)]
struct Mapping {
    pelvis: usize,
    neck: usize,
    head: usize,
    head_end: Option<usize>,
    /// Pelvis to neck, both included.
    trunk: Vec<usize>,
    /// Left then right: hip, knee, ankle, toe.
    legs: [[usize; 4]; 2],
    /// Left then right: shoulder, elbow, wrist.
    arms: [[usize; 3]; 2],
}

/// A named rig: each slot's accepted names (normalised).
struct NamedRig {
    name: &'static str,
    pelvis: &'static [&'static str],
    neck: &'static [&'static str],
    head: &'static [&'static str],
    head_end: &'static [&'static str],
    /// Left leg (hip, knee, ankle, toe); the right's names swap "left" for "right".
    leg: [&'static [&'static str]; 4],
    /// Left arm (shoulder, elbow, wrist).
    arm: [&'static [&'static str]; 3],
    /// The trunk where the file has no hierarchy (pelvis … neck).
    trunk: &'static [&'static str],
}

const RIGS: [NamedRig; 3] = [
    NamedRig {
        name: "MotionBuilder-style",
        pelvis: &["hips"],
        // CMU's conversion has two neck joints; the upper one is at the shoulders, as our neck.
        neck: &["neck1", "neck"],
        head: &["head"],
        head_end: &["headtopend", "headend", "head/end"],
        leg: [&["leftupleg"], &["leftleg"], &["leftfoot"], &["lefttoebase", "lefttoe"]],
        arm: [&["leftarm"], &["leftforearm"], &["lefthand"]],
        trunk: &["hips", "spine", "spine1", "spine2", "neck"],
    },
    NamedRig {
        name: "BioVision-style",
        pelvis: &["hips"],
        neck: &["neck"],
        head: &["head"],
        head_end: &["head/end", "headend"],
        leg: [&["lefthip"], &["leftknee"], &["leftankle"], &["lefttoe", "lefttoes", "leftankle/end"]],
        arm: [&["leftshoulder"], &["leftelbow"], &["leftwrist"]],
        trunk: &["hips", "chest", "neck"],
    },
    NamedRig {
        name: "SMPL",
        pelvis: &["pelvis"],
        neck: &["neck"],
        head: &["head"],
        head_end: &[],
        leg: [&["lefthip"], &["leftknee"], &["leftankle"], &["leftfoot"]],
        arm: [&["leftshoulder"], &["leftelbow"], &["leftwrist"]],
        trunk: &["pelvis", "spine1", "spine2", "spine3", "neck"],
    },
];

/// Our proportions along the trunk: spine and chest as fractions of the pelvis–neck length
/// (`stand_local`: pelvis 0.55, spine 0.64, chest 0.73, neck 0.83 of the stature).
const SPINE_ALONG_TRUNK: f64 = (0.64 - 0.55) / (0.83 - 0.55);
const CHEST_ALONG_TRUNK: f64 = (0.73 - 0.55) / (0.83 - 0.55);

/// A joint name compared across rigs: lower case, no `prefix:`, no `_ - .` or spaces.
fn normalise(name: &str) -> String {
    let base = name.rsplit(':').next().unwrap_or(name);
    base.chars().filter(|c| c.is_alphanumeric() || *c == '/').flat_map(char::to_lowercase).collect()
}

/// Our 19 joints from `clip`, whose up axis is `up` (for the topology fallback).
pub fn retarget(clip: &Clip, up: DVec3) -> Result<Retargeted, String> {
    let names: Vec<String> = clip.names.iter().map(|n| normalise(n)).collect();
    if let Some(ours) = our_joints(&names) {
        let frames = clip.frames.iter().map(|f| ours.map(|j| f[j])).collect();
        return Ok(Retargeted { rig: "shade-sim", frames });
    }
    let hierarchy = clip.parents.iter().any(Option::is_some);
    let named = RIGS.iter().find_map(|rig| by_names(rig, &names, clip, hierarchy).map(|m| (rig.name, m)));
    let (rig, mapping) = match named {
        Some(found) => found,
        None if hierarchy => ("topology", by_topology(clip, up)?),
        None => {
            let known: Vec<&str> = std::iter::once("ours").chain(RIGS.iter().map(|r| r.name)).collect();
            return Err(format!(
                "unknown rig: the joint names match none of {} and the file has no hierarchy to go by",
                known.join(", ")
            ));
        }
    };
    Ok(Retargeted { rig, frames: clip.frames.iter().map(|f| pose(&mapping, f)).collect() })
}

/// Where each of our 19 joints is among `names` (normalised), if all of them are there.
fn our_joints(names: &[String]) -> Option<[usize; 19]> {
    let mut at = [0; 19];
    for (slot, ours) in at.iter_mut().zip(JOINT_NAMES) {
        *slot = names.iter().position(|n| *n == normalise(ours))?;
    }
    Some(at)
}

fn by_names(rig: &NamedRig, names: &[String], clip: &Clip, hierarchy: bool) -> Option<Mapping> {
    let find = |accepted: &[&str]| accepted.iter().find_map(|a| names.iter().position(|n| n == a));
    let side = |accepted: &[&str], right: bool| -> Option<usize> {
        let swapped: Vec<String> =
            accepted.iter().map(|a| if right { a.replacen("left", "right", 1) } else { a.to_string() }).collect();
        swapped.iter().find_map(|a| names.iter().position(|n| n == a))
    };
    let leg = |right| -> Option<[usize; 4]> {
        Some([side(rig.leg[0], right)?, side(rig.leg[1], right)?, side(rig.leg[2], right)?, side(rig.leg[3], right)?])
    };
    let arm = |right| -> Option<[usize; 3]> {
        Some([side(rig.arm[0], right)?, side(rig.arm[1], right)?, side(rig.arm[2], right)?])
    };
    let (pelvis, neck) = (find(rig.pelvis)?, find(rig.neck)?);
    let trunk = if hierarchy {
        path(clip, pelvis, neck)?
    } else {
        rig.trunk.iter().map(|t| names.iter().position(|n| n == t)).collect::<Option<Vec<_>>>()?
    };
    Some(Mapping {
        pelvis,
        neck,
        head: find(rig.head)?,
        head_end: find(rig.head_end),
        trunk,
        legs: [leg(false)?, leg(true)?],
        arms: [arm(false)?, arm(true)?],
    })
}

/// The joints from `from` down to `to` (both included), if `to` descends from `from`.
fn path(clip: &Clip, from: usize, to: usize) -> Option<Vec<usize>> {
    let up = ancestors(clip, to);
    let k = up.iter().position(|&j| j == from)?;
    Some(up[..=k].iter().rev().copied().collect())
}

/// `j` and its parents up to the root (cut short where a file's parents loop).
fn ancestors(clip: &Clip, j: usize) -> Vec<usize> {
    let mut out = vec![j];
    while let Some(p) = clip.parents[*out.last().expect("non-empty")] {
        out.push(p);
        if out.len() > clip.names.len() {
            break;
        }
    }
    out
}

fn by_topology(clip: &Clip, up: DVec3) -> Result<Mapping, String> {
    let unknown = |what: &str| format!("unknown rig: the joint names are not a known rig's, and {what}");
    let first = &clip.frames[0];
    let height = |j: usize| first[j].dot(up);
    let pelvis = clip.parents.iter().position(Option::is_none).ok_or_else(|| unknown("it has no root"))?;
    let leaves: Vec<usize> = (0..clip.names.len()).filter(|&j| clip.children(j).next().is_none()).collect();
    let lowest = |among: &mut dyn Iterator<Item = usize>| among.min_by(|a, b| height(*a).total_cmp(&height(*b)));
    // Toe: the leaf itself, or its joint where the leaf is an end site.
    let toe_of =
        |leaf: usize| if clip.names[leaf].ends_with("/end") { clip.parents[leaf].unwrap_or(leaf) } else { leaf };
    let chain_up = |from: usize, n: usize| -> Option<Vec<usize>> {
        let up: Vec<usize> = ancestors(clip, from).into_iter().take(n).collect();
        (up.len() == n && !up.contains(&pelvis)).then_some(up)
    };
    // A leg up from a foot's leaf: from its toe joint, or from the end site itself where the
    // chain has no toe joint.
    let leg_from = |leaf: usize| chain_up(toe_of(leaf), 4).or_else(|| chain_up(leaf, 4));
    let foot_a = lowest(&mut leaves.iter().copied()).ok_or_else(|| unknown("it has no leaves"))?;
    let leg_a = leg_from(foot_a).ok_or_else(|| unknown("its lowest chain is too short for a leg"))?;
    let foot_b = lowest(&mut leaves.iter().copied().filter(|&l| !ancestors(clip, l).contains(&leg_a[3])))
        .ok_or_else(|| unknown("it has one leg"))?;
    let leg_b = leg_from(foot_b).ok_or_else(|| unknown("its second leg is too short"))?;
    let top = leaves.iter().copied().max_by(|a, b| height(*a).total_cmp(&height(*b))).expect("leaves");
    let (head, head_end) = match clip.names[top].ends_with("/end") {
        true => (clip.parents[top].unwrap_or(top), Some(top)),
        false => (top, None),
    };
    let neck = clip.parents[head].ok_or_else(|| unknown("its head is its root"))?;
    let trunk = path(clip, pelvis, neck).ok_or_else(|| unknown("its neck is not above its root"))?;
    // Hands: the leaves farthest from the neck off the trunk, on separate branches of it.
    let branch = |leaf: usize| -> Option<Vec<usize>> {
        let up = ancestors(clip, leaf);
        let k = up.iter().position(|j| trunk.contains(j))?;
        let mut chain: Vec<usize> = up[..k].to_vec();
        chain.reverse();
        Some(chain)
    };
    let legs = [&leg_a, &leg_b];
    let candidates: Vec<(usize, Vec<usize>)> = leaves
        .iter()
        .filter(|&&l| l != top && !legs.iter().any(|leg| ancestors(clip, l).contains(&leg[3])))
        .filter_map(|&l| branch(l).map(|b| (l, b)))
        .filter(|(_, b)| b.len() >= 3)
        .collect();
    let far = |c: &&(usize, Vec<usize>)| first[c.0].distance(first[neck]);
    let hand_a = candidates.iter().max_by(|a, b| far(a).total_cmp(&far(b))).ok_or_else(|| unknown("it has no arms"))?;
    let hand_b = candidates
        .iter()
        .filter(|c| c.1[0] != hand_a.1[0])
        .max_by(|a, b| far(a).total_cmp(&far(b)))
        .ok_or_else(|| unknown("it has one arm"))?;
    let arm = |chain: &[usize]| -> [usize; 3] {
        // Skip a clavicle: a first segment much shorter than the next.
        let seg = |i: usize| first[chain[i]].distance(first[chain[i + 1]]);
        let start = usize::from(chain.len() >= 4 && seg(0) < 0.75 * seg(1));
        [chain[start], chain[start + 1], chain[start + 2]]
    };
    let (arm_a, arm_b) = (arm(&hand_a.1), arm(&hand_b.1));
    let [leg_a, leg_b] = [leg_a, leg_b].map(|l| [l[3], l[2], l[1], l[0]]);
    // Left: where the feet point left of (up × forward).
    let forward = (first[leg_a[3]] - first[leg_a[2]]) + (first[leg_b[3]] - first[leg_b[2]]);
    let left = up.cross(forward - up * forward.dot(up));
    // Each pair with the one whose first joint lies further left first.
    let side = |j: usize| first[j].dot(left);
    let legs = if side(leg_a[0]) >= side(leg_b[0]) { [leg_a, leg_b] } else { [leg_b, leg_a] };
    let arms = if side(arm_a[0]) >= side(arm_b[0]) { [arm_a, arm_b] } else { [arm_b, arm_a] };
    Ok(Mapping { pelvis, neck, head, head_end, trunk, legs, arms })
}

/// The point at `fraction` of the polyline through `points`' length.
fn along(points: &[DVec3], fraction: f64) -> DVec3 {
    let total: f64 = points.windows(2).map(|w| w[0].distance(w[1])).sum();
    let mut left = fraction * total;
    for w in points.windows(2) {
        let d = w[0].distance(w[1]);
        if left <= d && d > 0.0 {
            return w[0].lerp(w[1], left / d);
        }
        left -= d;
    }
    *points.last().expect("a trunk")
}

fn pose(m: &Mapping, frame: &[DVec3]) -> [DVec3; 19] {
    let mut out = [DVec3::ZERO; 19];
    let trunk: Vec<DVec3> = m.trunk.iter().map(|&j| frame[j]).collect();
    out[Joint::Pelvis.index()] = frame[m.pelvis];
    out[Joint::Spine.index()] = along(&trunk, SPINE_ALONG_TRUNK);
    out[Joint::Chest.index()] = along(&trunk, CHEST_ALONG_TRUNK);
    out[Joint::Neck.index()] = frame[m.neck];
    out[Joint::Head.index()] = match m.head_end {
        Some(end) => frame[m.head].lerp(frame[end], 0.5),
        None => frame[m.head] + (frame[m.head] - frame[m.neck]) * 0.5,
    };
    let sides = [crate::human::Side::Left, crate::human::Side::Right];
    for (k, side) in sides.into_iter().enumerate() {
        for (ours, theirs) in side.leg().into_iter().zip(m.legs[k]) {
            out[ours.index()] = frame[theirs];
        }
        for (ours, theirs) in side.arm().into_iter().zip(m.arms[k]) {
            out[ours.index()] = frame[theirs];
        }
    }
    out
}
