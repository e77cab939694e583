//! Loads an exported world in MuJoCo (feature `mujoco`), steps it and checks that it is sane:
//! every position finite and no piece of furniture moving more than 5 cm.

use crate::scene::Scene;
use mujoco_rs::prelude::*;
use serde::{Deserialize, Serialize};

/// What validation found.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MujocoValidation {
    /// Steps run.
    pub steps: usize,
    /// Simulated seconds.
    pub seconds: f64,
    /// Furniture that moved more than the limit: (object id, displacement in m).
    pub moved: Vec<(String, f64)>,
    /// Whether any position became NaN or infinite.
    pub non_finite: bool,
}

impl MujocoValidation {
    /// Whether the world passed.
    pub fn ok(&self) -> bool {
        self.moved.is_empty() && !self.non_finite
    }
}

/// Largest displacement of a piece of furniture that still passes (m).
pub const MAX_MOVE: f64 = 0.05;

/// Loads `mjcf`, steps it `steps` times and reports furniture of `scene` that moved or anything
/// non-finite.
///
/// # Errors
/// MuJoCo's message when the model does not load.
pub fn validate_in_mujoco(scene: &Scene, mjcf: &str, steps: usize) -> Result<MujocoValidation, String> {
    let model = MjModel::from_xml_string(mjcf).map_err(|e| e.to_string())?;
    let mut data = MjData::new(&model);
    data.forward();
    let ids: Vec<(String, usize)> = scene
        .objects
        .iter()
        .filter_map(|o| model.name_to_id(MjtObjBase::mjOBJ_BODY, &o.id).map(|i| (o.id.clone(), i)))
        .collect();
    let start: Vec<[f64; 3]> = ids.iter().map(|(_, i)| data.xpos()[*i]).collect();
    for _ in 0..steps {
        data.step();
    }
    let non_finite = data.qpos().iter().any(|x| !x.is_finite()) || data.xpos().iter().flatten().any(|x| !x.is_finite());
    let moved = ids
        .iter()
        .zip(&start)
        .filter_map(|((name, i), s)| {
            let p = data.xpos()[*i];
            let d = ((p[0] - s[0]).powi(2) + (p[1] - s[1]).powi(2) + (p[2] - s[2]).powi(2)).sqrt();
            (!d.is_finite() || d > MAX_MOVE).then(|| (name.clone(), d))
        })
        .collect();
    Ok(MujocoValidation { steps, seconds: steps as f64 * model.opt().timestep, moved, non_finite })
}
