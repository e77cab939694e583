//! The humans replayed in MuJoCo (feature `mujoco`), in the very world `export` writes for users:
//! furniture parts and walls as static box geoms, each bone a mocap body with a capsule, and the
//! explicit `<contact><pair>`s that make MuJoCo report mocap-vs-static contacts. Per frame the
//! mocap poses are set, `mj_forward` runs, and the contacts deeper than the tolerance are read.
//!
//! This is the one place `sim` uses `export`: checking the exported world is the point.

use super::EngineContact;
use super::solids::Owner;
use crate::export::{MjcfOptions, mocap_motion, scene_mjcf};
use crate::scene::Scene;
use mujoco_rs::prelude::*;
use std::collections::HashMap;

/// Replays every human of `scene` in its exported MuJoCo world and returns the contacts deeper
/// than `tolerance`.
///
/// # Errors
/// MuJoCo's message when the exported model does not load.
pub fn mujoco_replay(scene: &Scene, tolerance: f64) -> Result<Vec<EngineContact>, String> {
    let xml = scene_mjcf(scene, MjcfOptions { keyframes: false, ..MjcfOptions::default() });
    let model = MjModel::from_xml_string(&xml).map_err(|e| e.to_string())?;
    let mut data = MjData::new(&model);
    let motion = mocap_motion(scene);
    // Geom → what it belongs to, through its body (objects) or its name (walls).
    let objects: HashMap<&str, usize> = scene.objects.iter().enumerate().map(|(i, o)| (o.id.as_str(), i)).collect();
    let mut owner_of: HashMap<usize, Owner> = HashMap::new();
    let mut bone_of: HashMap<usize, (usize, usize)> = HashMap::new();
    let bones: Vec<(usize, usize)> = scene
        .humans
        .iter()
        .enumerate()
        .flat_map(|(h, human)| (0..human.skeleton.bones.len()).map(move |b| (h, b)))
        .collect();
    for g in 0..model.ngeom() as usize {
        let body = model.geom_bodyid()[g] as usize;
        let body_name = model.id_to_name(MjtObjBase::mjOBJ_BODY, body).unwrap_or_default();
        let geom_name = model.id_to_name(MjtObjBase::mjOBJ_GEOM, g).unwrap_or_default();
        if let Some(&i) = objects.get(body_name) {
            owner_of.insert(g, Owner::Object(i));
        } else if let Some(i) = geom_name.strip_prefix("wall").and_then(|i| i.parse().ok()) {
            owner_of.insert(g, Owner::Wall(i));
        } else if let Some(m) = motion.bodies.iter().position(|n| *n == body_name) {
            bone_of.insert(g, bones[m]);
        }
    }
    let mut out = Vec::new();
    for (f, poses) in motion.frames.iter().enumerate() {
        for (m, p) in poses.iter().enumerate() {
            data.mocap_pos_mut()[m] = [p[0], p[1], p[2]];
            data.mocap_quat_mut()[m] = [p[3], p[4], p[5], p[6]];
        }
        data.forward();
        let mut deepest: HashMap<(usize, usize, Owner), f64> = HashMap::new();
        for c in data.contact() {
            let (g1, g2) = (c.geom[0] as usize, c.geom[1] as usize);
            let pair = match (bone_of.get(&g1), owner_of.get(&g2), bone_of.get(&g2), owner_of.get(&g1)) {
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
