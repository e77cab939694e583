//! `sim`'s answer to [`crate::physics::Physics`]: the check's verdict, exact capsule–box depths and
//! the Rapier replay's pushes, for guidance, repair and the dataset builders, which see physics
//! only through the trait.

use super::{exact_contacts, rapier_pushes};
use crate::physics::{EngineContact, Physics, PieceFit};
use crate::scene::Scene;
use glam::DVec2;

/// The physics `check` itself uses: exact depths (parry) and a Rapier replay.
#[derive(Debug, Clone, Copy, Default)]
pub struct SimPhysics;

impl Physics for SimPhysics {
    fn passes_check(&self, scene: &Scene) -> bool {
        super::check_scene(scene, &super::CheckConfig::default()).is_clean()
    }

    fn exact_contacts(&self, scene: &Scene, tolerance: f64) -> Vec<EngineContact> {
        exact_contacts(scene, tolerance)
    }

    fn pushes(&self, scene: &Scene, tolerance: f64) -> Vec<(usize, DVec2)> {
        rapier_pushes(scene, tolerance)
    }

    fn piece_fit(&self, scene: &Scene, object: usize, tolerance: f64) -> PieceFit {
        super::piece_fit(scene, object, tolerance)
    }
}
