//! The physics that guidance and repair may ask about, as a trait (`sim` implements it with exact
//! geometry and a Rapier replay). Generation and repair depend on this, never on `sim` itself.
//!
//! It defines the questions and the answers' types; it computes nothing.

use crate::scene::Scene;
use glam::DVec2;

/// What a solid belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Owner {
    /// Object `i` of the scene.
    Object(usize),
    /// The wall on floor-plan edge `i`.
    Wall(usize),
}

/// A bone in contact with furniture or a wall in one frame.
#[derive(Debug, Clone, PartialEq)]
pub struct EngineContact {
    /// Index of the human in the scene.
    pub human: usize,
    /// Index of the bone in its skeleton.
    pub bone: usize,
    /// What it touches.
    pub owner: Owner,
    /// The frame.
    pub frame: usize,
    /// Penetration depth (m, positive).
    pub depth: f64,
}

/// The bodies-against-furniture questions generation and repair ask.
pub trait Physics: Send + Sync {
    /// Every bone in a piece or a wall deeper than `tolerance` (m), with the check's own exact
    /// depths: the deepest solid per owner, per bone and frame.
    fn exact_contacts(&self, scene: &Scene, tolerance: f64) -> Vec<EngineContact>;

    /// For every object the replayed bodies push on deeper than `tolerance` (m): the direction
    /// away from them scaled by the deepest contact, in object order.
    fn pushes(&self, scene: &Scene, tolerance: f64) -> Vec<(usize, DVec2)>;
}

/// Penetrations shallower than this are not pushed or repaired (m), as in the check.
pub const PHYS_TOLERANCE: f64 = 0.02;
