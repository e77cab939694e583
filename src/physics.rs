//! The physics that guidance, repair and the dataset builders may ask about, as a trait (`sim`
//! implements it with exact geometry and a Rapier replay). Generation, repair and `data` depend on
//! this, never on `sim` itself.
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

/// The bodies-against-furniture questions generation, repair and the dataset builders ask.
pub trait Physics: Send + Sync {
    /// Whether `shade-sim check` with its default settings finds nothing wrong with `scene` (no
    /// penetration, missing support, overlap, piece through a wall or unstable piece).
    fn passes_check(&self, scene: &Scene) -> bool;

    /// Every bone in a piece or a wall deeper than `tolerance` (m), with the check's own exact
    /// depths: the deepest solid per owner, per bone and frame.
    fn exact_contacts(&self, scene: &Scene, tolerance: f64) -> Vec<EngineContact>;

    /// For every object the replayed bodies push on deeper than `tolerance` (m): the direction
    /// away from them scaled by the deepest contact, in object order.
    fn pushes(&self, scene: &Scene, tolerance: f64) -> Vec<(usize, DVec2)>;

    /// How object `object` of `scene` meets the people ([`PieceFit`]): how far their bones enter
    /// its parts beyond `tolerance` (m), and who lacks support in the whole scene.
    fn piece_fit(&self, scene: &Scene, object: usize, tolerance: f64) -> PieceFit;
}

/// How one piece meets the people of its scene.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PieceFit {
    /// The sum over every human, frame and bone of how far the bone enters the piece's parts
    /// beyond the tolerance asked for (m; the deepest part per bone and frame, the check's exact
    /// capsule depths).
    pub depth: f64,
    /// The people (indices) the check finds without support in the scene: a sitter, sleeper or
    /// toucher further than 5 cm from any piece, or inside the one under them.
    pub unsupported: Vec<usize>,
}

/// Penetrations shallower than this are not pushed or repaired (m), as in the check.
pub const PHYS_TOLERANCE: f64 = 0.02;

/// Judges for tests.
#[cfg(test)]
pub(crate) mod testing {
    use super::{EngineContact, Physics, PieceFit};
    use crate::scene::Scene;
    use glam::DVec2;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// Fails the first `fail` scenes with at least `min_humans` people it is asked to check and
    /// passes the rest (scenes with fewer people always); sees no contacts.
    #[derive(Debug, Default)]
    pub struct FailFirst {
        /// Scenes to fail.
        pub fail: usize,
        /// Fewest people a scene it counts has.
        pub min_humans: usize,
        /// Scenes counted so far.
        pub asked: AtomicUsize,
    }

    impl FailFirst {
        pub fn new(fail: usize) -> FailFirst {
            FailFirst { fail, min_humans: 0, asked: AtomicUsize::new(0) }
        }

        /// Counting only scenes with at least two people (not one person checked alone).
        pub fn rooms(fail: usize) -> FailFirst {
            FailFirst { min_humans: 2, ..FailFirst::new(fail) }
        }
    }

    /// Passes the first `pass` scenes it is asked to check and fails the rest; sees no contacts.
    #[derive(Debug, Default)]
    pub struct PassFirst {
        /// Scenes to pass.
        pub pass: usize,
        /// Scenes asked about so far.
        pub asked: AtomicUsize,
    }

    impl Physics for PassFirst {
        fn passes_check(&self, _: &Scene) -> bool {
            self.asked.fetch_add(1, Ordering::SeqCst) < self.pass
        }

        fn exact_contacts(&self, _: &Scene, _: f64) -> Vec<EngineContact> {
            Vec::new()
        }

        fn pushes(&self, _: &Scene, _: f64) -> Vec<(usize, DVec2)> {
            Vec::new()
        }

        fn piece_fit(&self, _: &Scene, _: usize, _: f64) -> PieceFit {
            PieceFit::default()
        }
    }

    impl Physics for FailFirst {
        fn passes_check(&self, scene: &Scene) -> bool {
            scene.humans.len() < self.min_humans || self.asked.fetch_add(1, Ordering::SeqCst) >= self.fail
        }

        fn exact_contacts(&self, _: &Scene, _: f64) -> Vec<EngineContact> {
            Vec::new()
        }

        fn pushes(&self, _: &Scene, _: f64) -> Vec<(usize, DVec2)> {
            Vec::new()
        }

        fn piece_fit(&self, _: &Scene, _: usize, _: f64) -> PieceFit {
            PieceFit::default()
        }
    }
}
