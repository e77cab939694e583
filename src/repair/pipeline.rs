//! The repair pipeline: the [`RepairStep`] trait every step implements, the [`Workspace`] the steps
//! share while they run (the people, who holds whom, the bones left in pieces, the physics), the
//! ordered [`Pipeline`] and the typed reports.
//!
//! It runs steps; what each step does is in its own file.

use super::config::{RepairConfig, StepName};
use super::occupancy::Occupancy;
use crate::physics::{EngineContact, Physics};
use crate::scene::Scene;
use serde::Serialize;

/// One repair step: reads and changes the scene's objects, never its people or floor plan.
pub trait RepairStep: Send + Sync {
    /// The step's name (its file, its config section).
    fn name(&self) -> StepName;
    /// Runs the step on `scene` with what earlier steps left in `work`.
    fn run(&self, scene: &mut Scene, work: &mut Workspace<'_>, config: &RepairConfig) -> StepReport;
}

/// What the steps share while repairing one scene.
pub struct Workspace<'a> {
    /// The scene's people, and which object holds which contact box.
    pub people: Occupancy,
    /// Whether each object holds anybody, fixed when a step after `settle` first asks
    /// ([`Workspace::holds`]); `left_out` updates it for the steps after it.
    holds: Option<Vec<bool>>,
    /// Bones still inside pieces after `fit_to_bodies` (exact depths), for `left_out`.
    pub bones: Option<Vec<EngineContact>>,
    /// Physics, for the steps that ask where bodies enter pieces.
    pub physics: &'a dyn Physics,
}

impl<'a> Workspace<'a> {
    /// The people of `scene`, each contact box given to an object that can hold it.
    pub fn new(scene: &Scene, config: &RepairConfig, physics: &'a dyn Physics) -> Workspace<'a> {
        let mut people = Occupancy::of(scene, &config.holding);
        people.assign(scene, &config.settle);
        Workspace { people, holds: None, bones: None, physics }
    }

    /// The people and whether each of the scene's `n` objects holds anybody (fixed on first ask).
    pub fn holds(&mut self, n: usize) -> (&Occupancy, &mut Vec<bool>) {
        let people = &self.people;
        let holds = self.holds.get_or_insert_with(|| people.holding(n));
        (people, holds)
    }

    /// Forgets who held whom as of the last ask (a step that reassigns the holders calls this).
    pub fn reassigned(&mut self) {
        self.holds = None;
    }
}

/// What one step changed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "step", rename_all = "snake_case")]
pub enum StepReport {
    /// `settle`.
    Settle(SettleReport),
    /// `relocate`: pieces moved to a free spot.
    Relocate {
        /// Pieces moved.
        relocated: usize,
    },
    /// `fit_into_room`: pieces narrowed to fit the floor plan.
    FitIntoRoom {
        /// Pieces narrowed.
        narrowed: usize,
    },
    /// `fit_to_bodies`: pieces reshaped out of bones.
    FitToBodies {
        /// Pieces reshaped.
        fitted: usize,
    },
    /// `left_out`: pieces left out.
    LeftOut {
        /// Pieces left out.
        left_out: usize,
    },
    /// `overlaps`: overlaps narrowed away or resolved by a removal.
    Overlaps {
        /// Pieces narrowed.
        narrowed: usize,
        /// Pieces removed.
        removed: usize,
    },
}

impl StepReport {
    /// Pieces the step changed (for `settle`, the changes of every kind it counts).
    pub fn changed(&self) -> usize {
        match *self {
            StepReport::Settle(s) => s.resized + s.turned + s.added + s.squared + s.walled,
            StepReport::Relocate { relocated: n }
            | StepReport::FitIntoRoom { narrowed: n }
            | StepReport::FitToBodies { fitted: n }
            | StepReport::LeftOut { left_out: n } => n,
            StepReport::Overlaps { narrowed, removed } => narrowed + removed,
        }
    }
}

/// What `settle` changed.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct SettleReport {
    /// Rounds run.
    pub rounds: usize,
    /// Objects resized to cover a contact box.
    pub resized: usize,
    /// Pieces turned to face like the person on them.
    pub turned: usize,
    /// Objects added for people nothing held.
    pub added: usize,
    /// Pieces turned square to the walls.
    pub squared: usize,
    /// Pieces put back against a wall.
    pub walled: usize,
    /// Largest total move of one object (m).
    pub max_move: f64,
}

impl SettleReport {
    /// Both reports' counts added; the larger of their largest moves.
    pub fn plus(&self, o: &SettleReport) -> SettleReport {
        SettleReport {
            rounds: self.rounds + o.rounds,
            resized: self.resized + o.resized,
            turned: self.turned + o.turned,
            added: self.added + o.added,
            squared: self.squared + o.squared,
            walled: self.walled + o.walled,
            max_move: self.max_move.max(o.max_move),
        }
    }
}

/// What repairing one scene changed, step by step in the order they ran.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct RepairReport {
    /// One report per step run.
    pub steps: Vec<StepReport>,
    /// Whether the steps' result failed `check` where the layout as given passed it, and the
    /// layout was given back unchanged ([`RepairConfig::keep_passing`]).
    pub kept_as_given: bool,
}

impl RepairReport {
    /// Pieces changed by all steps (none when the layout was kept as given).
    pub fn changed(&self) -> usize {
        if self.kept_as_given { 0 } else { self.steps.iter().map(StepReport::changed).sum() }
    }

    /// Every step's counts summed by kind.
    pub fn totals(&self) -> RepairTotals {
        let mut t = RepairTotals { kept_as_given: usize::from(self.kept_as_given), ..RepairTotals::default() };
        for s in &self.steps {
            match *s {
                StepReport::Settle(r) => t.settle = t.settle.plus(&r),
                StepReport::Relocate { relocated } => t.relocated += relocated,
                StepReport::FitIntoRoom { narrowed } => t.narrowed += narrowed,
                StepReport::FitToBodies { fitted } => t.fitted += fitted,
                StepReport::LeftOut { left_out } => t.left_out += left_out,
                StepReport::Overlaps { narrowed, removed } => {
                    t.narrowed += narrowed;
                    t.removed += removed;
                }
            }
        }
        t
    }
}

/// A [`RepairReport`]'s counts summed over its steps, by kind of change (JSON: one flat object).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct RepairTotals {
    /// What `settle` changed (rounds, resized, turned, added, squared, walled, max_move).
    #[serde(flatten)]
    pub settle: SettleReport,
    /// Pieces moved to a free spot.
    pub relocated: usize,
    /// Pieces narrowed (into the room, off paths, out of overlaps).
    pub narrowed: usize,
    /// Pieces reshaped out of bones.
    pub fitted: usize,
    /// Pieces left out.
    pub left_out: usize,
    /// Pieces removed from overlaps.
    pub removed: usize,
    /// Layouts given back as they were, which passed `check` before the steps and failed after.
    pub kept_as_given: usize,
}

impl std::iter::Sum for RepairTotals {
    /// Counts summed over scenes; the largest move is the largest of any.
    fn sum<I: Iterator<Item = RepairTotals>>(iter: I) -> RepairTotals {
        iter.fold(RepairTotals::default(), |a, t| RepairTotals {
            settle: a.settle.plus(&t.settle),
            relocated: a.relocated + t.relocated,
            narrowed: a.narrowed + t.narrowed,
            fitted: a.fitted + t.fitted,
            left_out: a.left_out + t.left_out,
            removed: a.removed + t.removed,
            kept_as_given: a.kept_as_given + t.kept_as_given,
        })
    }
}

/// An ordered list of repair steps.
pub struct Pipeline {
    steps: Vec<Box<dyn RepairStep>>,
}

impl Pipeline {
    /// The steps `config.steps` names, in its order.
    pub fn of(config: &RepairConfig) -> Pipeline {
        Pipeline { steps: config.steps.iter().map(|&s| super::step(s)).collect() }
    }

    /// The names of the steps, in order.
    pub fn names(&self) -> Vec<StepName> {
        self.steps.iter().map(|s| s.name()).collect()
    }

    /// Runs every step on `scene` in order; with `config.keep_passing`, a scene that passed the
    /// check before and fails it after gets its objects back as they were.
    pub fn run(&self, scene: &mut Scene, config: &RepairConfig, physics: &dyn Physics) -> RepairReport {
        let given = (config.keep_passing && physics.passes_check(scene)).then(|| scene.objects.clone());
        let mut work = Workspace::new(scene, config, physics);
        let steps = self.steps.iter().map(|s| s.run(scene, &mut work, config)).collect();
        let kept_as_given = match given {
            Some(objects) if !physics.passes_check(scene) => {
                scene.objects = objects;
                true
            }
            _ => false,
        };
        RepairReport { steps, kept_as_given }
    }
}
