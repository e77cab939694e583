//! `stats.json` of a dataset: per split, how many rooms, category counts, object-count histogram
//! and attribute bounds; and how the dataset was made.
//!
//! The bounds are what the model scales tokens by: object centres relative to the room window's
//! centre, full sizes, over the split's objects.

use crate::scene::{Category, RoomType, Scene};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Figures of one split.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SplitStats {
    /// Rooms.
    pub rooms: usize,
    /// Objects per category.
    pub category_counts: BTreeMap<Category, usize>,
    /// `object_count_histogram[n]` = rooms with n objects.
    pub object_count_histogram: Vec<usize>,
    /// Smallest object centre relative to the room window's centre (x, y, z).
    pub center_min: [f64; 3],
    /// Largest object centre relative to the room window's centre.
    pub center_max: [f64; 3],
    /// Smallest full size (w, d, h).
    pub size_min: [f64; 3],
    /// Largest full size.
    pub size_max: [f64; 3],
    /// Humans by action label of their first contact span (`walk` for walkers).
    pub humans: BTreeMap<String, usize>,
    /// Rooms that pass `shade-sim check`, for a dataset made with `--require-clean`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub passing_check: Option<usize>,
    /// Rooms the check sent back: drawn again (`synth`) or calibrated again (`calibrate`), for a
    /// dataset made with `--require-clean`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub redrawn: Option<usize>,
}

impl SplitStats {
    /// Adds one room.
    pub fn add(&mut self, scene: &Scene) {
        if self.rooms == 0 {
            self.center_min = [f64::INFINITY; 3];
            self.center_max = [f64::NEG_INFINITY; 3];
            self.size_min = [f64::INFINITY; 3];
            self.size_max = [f64::NEG_INFINITY; 3];
        }
        self.rooms += 1;
        let n = scene.objects.len();
        if self.object_count_histogram.len() <= n {
            self.object_count_histogram.resize(n + 1, 0);
        }
        self.object_count_histogram[n] += 1;
        let window = scene.room_window();
        for o in &scene.objects {
            *self.category_counts.entry(o.category).or_insert(0) += 1;
            let rel = [o.center[0] - window.center.x, o.center[1] - window.center.y, o.center[2]];
            for (k, (&r, &s)) in rel.iter().zip(&o.size).enumerate() {
                self.center_min[k] = self.center_min[k].min(r);
                self.center_max[k] = self.center_max[k].max(r);
                self.size_min[k] = self.size_min[k].min(s);
                self.size_max[k] = self.size_max[k].max(s);
            }
        }
        for h in &scene.humans {
            let label = h.contact_spans().next().map_or("walk", |s| s.action.name());
            *self.humans.entry(label.to_string()).or_insert(0) += 1;
        }
    }

    /// Counts one checked room: whether it passes the check, and whether it was drawn again.
    pub fn add_check(&mut self, passes: bool, redrawn: bool) {
        *self.passing_check.get_or_insert(0) += usize::from(passes);
        *self.redrawn.get_or_insert(0) += usize::from(redrawn);
    }

    /// Category frequencies in the room type's one-hot order.
    pub fn frequencies(&self, room: RoomType) -> Vec<f64> {
        let total: usize = self.category_counts.values().sum();
        room.categories()
            .iter()
            .map(|c| self.category_counts.get(c).copied().unwrap_or(0) as f64 / total.max(1) as f64)
            .collect()
    }
}

/// The whole `stats.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DatasetStats {
    /// Always `"shade-dataset/1"`.
    pub format: String,
    /// Room type of every scene.
    pub room_type: RoomType,
    /// The seed the rooms were drawn with.
    pub seed: u64,
    /// The command that made the dataset.
    pub command: String,
    /// Whether contact humans are misplaced as in the raw 3D-FRONT HUMAN (false once calibrated).
    pub raw: bool,
    /// Figures per split (`train`, `val`, `test`).
    pub splits: BTreeMap<String, SplitStats>,
    /// KL divergence of all rooms' category frequencies from the 3D-FRONT target.
    pub category_kl: f64,
}

/// Dataset format tag.
pub const DATASET_FORMAT: &str = "shade-dataset/1";

impl DatasetStats {
    /// The three split names, in order.
    pub const SPLITS: [&'static str; 3] = ["train", "val", "test"];

    /// Figures of all splits together.
    pub fn all(&self) -> SplitStats {
        let mut all = SplitStats::default();
        for s in self.splits.values() {
            all.rooms += s.rooms;
            for (c, n) in &s.category_counts {
                *all.category_counts.entry(*c).or_insert(0) += n;
            }
            if let (Some(p), Some(r)) = (s.passing_check, s.redrawn) {
                *all.passing_check.get_or_insert(0) += p;
                *all.redrawn.get_or_insert(0) += r;
            }
        }
        all
    }
}
