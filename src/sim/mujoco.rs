//! The humans replayed in MuJoCo (feature `mujoco`): furniture parts and walls as static box
//! geoms, each bone a mocap body with a capsule, and an explicit `<contact><pair>` for every
//! bone–solid pair, because MuJoCo never reports contacts between a mocap body and a body
//! without joints. Per frame the mocap poses are set, `mj_forward` runs, and the contacts deeper
//! than the tolerance are read.

use super::EngineContact;
use super::solids::{Owner, Solid, furniture_solids, wall_solids};
use crate::scene::Scene;
use glam::{DQuat, DVec3};
use mujoco_rs::prelude::*;
use std::collections::HashMap;
use std::fmt::Write;

/// The MJCF of the replay world (deterministic text).
pub fn replay_mjcf(scene: &Scene, solids: &[Solid]) -> String {
    let mut x = String::from("<mujoco model=\"shade-sim-replay\">\n  <worldbody>\n");
    for (k, s) in solids.iter().enumerate() {
        let h = s.obox.half();
        let q = DQuat::from_rotation_z(s.obox.yaw);
        let c = s.obox.center;
        let _ = writeln!(
            x,
            "    <geom name=\"s{k}\" type=\"box\" pos=\"{:.6} {:.6} {:.6}\" quat=\"{:.8} 0 0 {:.8}\" size=\"{:.6} {:.6} {:.6}\"/>",
            c.x, c.y, c.z, q.w, q.z, h.x, h.y, h.z
        );
    }
    for (i, human) in scene.humans.iter().enumerate() {
        for (j, bone) in human.skeleton.bones.iter().enumerate() {
            let half = human.joint_at(0, bone.a).distance(human.joint_at(0, bone.b)) * 0.5;
            let _ = writeln!(
                x,
                "    <body name=\"h{i}b{j}\" mocap=\"true\"><geom name=\"h{i}b{j}\" type=\"capsule\" fromto=\"0 0 {:.6} 0 0 {:.6}\" size=\"{:.6}\"/></body>",
                -half.max(1e-4),
                half.max(1e-4),
                bone.radius
            );
        }
    }
    x.push_str("  </worldbody>\n  <contact>\n");
    for (i, human) in scene.humans.iter().enumerate() {
        for j in 0..human.skeleton.bones.len() {
            for k in 0..solids.len() {
                let _ = writeln!(x, "    <pair geom1=\"h{i}b{j}\" geom2=\"s{k}\"/>");
            }
        }
    }
    x.push_str("  </contact>\n</mujoco>\n");
    x
}

/// Replays every human of `scene` in MuJoCo and returns the contacts deeper than `tolerance`.
///
/// # Errors
/// MuJoCo's message when the generated model does not load.
pub fn mujoco_replay(scene: &Scene, tolerance: f64) -> Result<Vec<EngineContact>, String> {
    let solids: Vec<Solid> = furniture_solids(scene).into_iter().chain(wall_solids(scene)).collect();
    let model = MjModel::from_xml_string(&replay_mjcf(scene, &solids)).map_err(|e| e.to_string())?;
    let mut data = MjData::new(&model);
    let mut geom_owner: HashMap<usize, Owner> = HashMap::new();
    for (k, s) in solids.iter().enumerate() {
        if let Some(id) = model.name_to_id(MjtObjBase::mjOBJ_GEOM, &format!("s{k}")) {
            geom_owner.insert(id, s.owner);
        }
    }
    let mut geom_bone: HashMap<usize, (usize, usize)> = HashMap::new();
    let mut mocap = Vec::new();
    for (i, human) in scene.humans.iter().enumerate() {
        for j in 0..human.skeleton.bones.len() {
            if let Some(id) = model.name_to_id(MjtObjBase::mjOBJ_GEOM, &format!("h{i}b{j}")) {
                geom_bone.insert(id, (i, j));
            }
            mocap.push((i, j));
        }
    }
    let frames = scene.humans.iter().map(|h| h.frames.len()).max().unwrap_or(0);
    let mut out = Vec::new();
    for f in 0..frames {
        for (m, &(i, j)) in mocap.iter().enumerate() {
            let human = &scene.humans[i];
            let frame = f.min(human.frames.len() - 1);
            let bone = &human.skeleton.bones[j];
            let (a, b) = (human.joint_at(frame, bone.a), human.joint_at(frame, bone.b));
            let q = DQuat::from_rotation_arc(DVec3::Z, (b - a).normalize_or(DVec3::Z));
            let c = (a + b) * 0.5;
            data.mocap_pos_mut()[m] = [c.x, c.y, c.z];
            data.mocap_quat_mut()[m] = [q.w, q.x, q.y, q.z];
        }
        data.forward();
        let mut deepest: HashMap<(usize, usize, Owner), f64> = HashMap::new();
        for c in data.contact() {
            let (g1, g2) = (c.geom[0] as usize, c.geom[1] as usize);
            let pair = match (geom_bone.get(&g1), geom_owner.get(&g2), geom_bone.get(&g2), geom_owner.get(&g1)) {
                (Some(b), Some(o), _, _) | (_, _, Some(b), Some(o)) => (b.0, b.1, *o),
                _ => continue,
            };
            let depth = -c.dist;
            if depth > tolerance && f < scene.humans[pair.0].frames.len() {
                let e = deepest.entry(pair).or_insert(0.0);
                *e = e.max(depth);
            }
        }
        out.extend(deepest.into_iter().map(|((human, bone, owner), depth)| EngineContact {
            human,
            bone,
            owner,
            frame: f,
            depth,
        }));
    }
    super::replay::sort_contacts(&mut out);
    Ok(out)
}
