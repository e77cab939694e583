//! Building a human's motion frame by frame: walks, held poses, blends, and action labels.

use super::{Body, Gait, Pose, round_mm};
use crate::geom::Polyline;
use crate::scene::{Action, ActionSpan, Human};

/// A motion under construction for one body.
#[derive(Debug, Clone)]
pub struct Motion {
    body: Body,
    fps: f64,
    frames: Vec<Pose>,
    actions: Vec<ActionSpan>,
}

impl Motion {
    /// An empty motion of `body` at `fps` frames per second.
    pub fn new(body: Body, fps: f64) -> Motion {
        Motion { body, fps, frames: Vec::new(), actions: Vec::new() }
    }

    /// The body.
    pub fn body(&self) -> &Body {
        &self.body
    }

    /// Frames so far.
    pub fn len(&self) -> usize {
        self.frames.len()
    }

    /// Whether no frame was added yet.
    pub fn is_empty(&self) -> bool {
        self.frames.is_empty()
    }

    /// The last frame, if any.
    pub fn last(&self) -> Option<&Pose> {
        self.frames.last()
    }

    /// Appends poses labelled with `action` (unlabelled when `None`: conditioning ignores them).
    pub fn push(&mut self, poses: impl IntoIterator<Item = Pose>, action: Option<Action>) -> &mut Motion {
        let start = self.frames.len();
        self.frames.extend(poses);
        let end = self.frames.len();
        if let Some(action) = action.filter(|_| end > start) {
            match self.actions.last_mut() {
                Some(last) if last.action == action && last.end == start => last.end = end,
                _ => self.actions.push(ActionSpan { start, end, action }),
            }
        }
        self
    }

    /// Walks `path` at `speed` m/s (labelled `walk`).
    pub fn walk(&mut self, path: &Polyline, speed: f64) -> &mut Motion {
        let poses = Gait { speed, fps: self.fps }.walk(&self.body, path);
        self.push(poses, Some(Action::Walk))
    }

    /// Holds `pose` for `frames` frames.
    pub fn hold(&mut self, pose: Pose, frames: usize, action: Action) -> &mut Motion {
        self.push(std::iter::repeat_n(pose, frames), Some(action))
    }

    /// Blends from the last frame to `pose` over `frames` unlabelled frames (the transition
    /// between a walk and sitting down, say). Does nothing on an empty motion.
    pub fn blend_to(&mut self, pose: &Pose, frames: usize) -> &mut Motion {
        if let Some(&from) = self.frames.last() {
            let blend = (1..=frames).map(|i| {
                let t = i as f64 / (frames + 1) as f64;
                from.lerp(pose, t * t * (3.0 - 2.0 * t))
            });
            self.push(blend.collect::<Vec<_>>(), None);
        }
        self
    }

    /// The finished motion as a scene human (positions rounded to 0.1 mm).
    pub fn into_human(self, id: impl Into<String>) -> Human {
        Human {
            id: id.into(),
            skeleton: self.body.skeleton(),
            fps: self.fps,
            frames: self.frames.iter().map(|p| p.0.iter().map(|q| q.to_array().map(round_mm)).collect()).collect(),
            actions: self.actions,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::human::{sit, stand};
    use glam::DVec2;

    #[test]
    fn spans_merge_and_blends_stay_unlabelled() {
        let body = Body::default();
        let path = Polyline::new(vec![DVec2::ZERO, DVec2::new(1.2, 0.0)]).unwrap();
        let mut m = Motion::new(body, 30.0);
        m.walk(&path, 1.2).hold(stand(&body, DVec2::new(1.2, 0.0), 0.0), 10, Action::Stand);
        m.hold(stand(&body, DVec2::new(1.2, 0.0), 0.0), 5, Action::Stand);
        m.blend_to(&sit(&body, DVec2::new(1.2, 0.3), 0.45, 0.0), 20);
        m.hold(sit(&body, DVec2::new(1.2, 0.3), 0.45, 0.0), 30, Action::Sit);
        let h = m.into_human("h0");
        assert_eq!(h.frames.len(), 31 + 15 + 20 + 30);
        let spans: Vec<_> = h.actions.iter().map(|s| (s.start, s.end, s.action)).collect();
        assert_eq!(spans, vec![(0, 31, Action::Walk), (31, 46, Action::Stand), (66, 96, Action::Sit)]);
        assert_eq!(h.action_at(50), None);
        assert!(
            crate::scene::validate(&crate::scene::Scene {
                humans: vec![h],
                ..crate::scene::Scene::new(
                    crate::scene::RoomType::Bedroom,
                    crate::scene::FloorPlan { polygon: vec![[0.0, 0.0], [3.0, 0.0], [3.0, 3.0]], height: 2.7 }
                )
            })
            .is_empty()
        );
    }
}
