//! SCA, the scene-classification two-sample test: a small classifier learns to tell generated
//! layouts from the reference's on one half of each set, and its accuracy on the other half is the
//! score — 0.5 when it cannot tell them apart, 1.0 when every generated layout gives itself away.
//!
//! A layout is seen as its set of pieces: per furniture group, how many and what they are like
//! (size; distance from the walls, of the footprint and of the back edge; how square to the walls;
//! the gap to the nearest other piece; the volume shared with others; distance from the room's
//! centre), pooled over the group's pieces, with the per-category counts. The classifier is a
//! one-hidden-layer perceptron trained with AdamW on standardized features, in plain Rust and
//! deterministic for a seed. The SCA of ATISS and DiffuScene renders top-down images for a
//! pretrained CNN; a small network trained from scratch on a few hundred renders of ours could
//! not even tell real rooms from the same rooms with their pieces' places shuffled (living rooms:
//! 0.55; object sets: 0.86), so ours reads the object set. This module judges realism only, not
//! physics or contacts.

use crate::data::Rng;
use crate::geom::{OBox, Polygon, intersection_volume};
use crate::scene::{Group, RoomType, Scene};
use serde::{Deserialize, Serialize};

/// SCA's settings; the defaults are what `shade-sim eval` uses.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ScaConfig {
    /// Hidden units (default 32).
    pub hidden: usize,
    /// Lengths are seen to this resolution (m, default 0.05): finer differences do not show in a
    /// render a user looks at, and a classifier must not win on them. A turn off square is seen
    /// as the length its corners move, so to the same resolution.
    pub resolution: f64,
    /// The share of a piece's volume that others share is seen to this resolution (default 0.05).
    pub share_resolution: f64,
    /// AdamW steps, each on one batch, in passes over the training half in a fresh order each
    /// (default 500).
    pub steps: usize,
    /// Layouts per step (default 32).
    pub batch: usize,
    /// AdamW's step size (default 0.001).
    pub learning_rate: f64,
    /// AdamW's weight decay (default 0.01).
    pub weight_decay: f64,
    /// Splits into halves, each with a fresh classifier; the score is their mean (default 5).
    pub repeats: usize,
    /// Seed of the splits and the classifiers' initial weights (default 0).
    pub seed: u64,
}

impl Default for ScaConfig {
    fn default() -> ScaConfig {
        ScaConfig {
            resolution: 0.05,
            share_resolution: 0.05,
            hidden: 32,
            steps: 500,
            batch: 32,
            learning_rate: 1e-3,
            weight_decay: 0.01,
            repeats: 5,
            seed: 0,
        }
    }
}

/// The result of the test.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Sca {
    /// Mean held-out accuracy over the repeats (0.5: indistinguishable; lower is better down to 0.5).
    pub accuracy: f64,
    /// Each repeat's held-out accuracy.
    pub repeats: Vec<f64>,
    /// Layouts taken from each set (the smaller set's size); half train, half test.
    pub layouts: usize,
}

/// Fewest layouts per set the test runs with.
pub const SCA_MIN_LAYOUTS: usize = 8;

/// The furniture groups, in the order their features come.
const GROUPS: [Group; 8] =
    [Group::Bed, Group::Chair, Group::Stool, Group::Sofa, Group::Table, Group::Cabinet, Group::Shelf, Group::Lamp];

/// What is measured of each piece ([`piece_descriptors`]).
const DESCRIPTORS: usize = 9;

/// Nearest-neighbour gaps are capped here (m): farther is as good as alone.
const FAR: f64 = 3.0;

/// A layout's features, in this order: per furniture group, how many pieces it has and the mean,
/// least and greatest of each [`piece_descriptors`] value over them (zeros for none; lengths to
/// `resolution`, shares to `share_resolution`); the count of each of the room type's categories;
/// the floor area and the number of pieces.
pub fn layout_features(scene: &Scene, resolution: f64, share_resolution: f64) -> Vec<f32> {
    let polygon = scene.floor_plan.polygon();
    let boxes: Vec<OBox> = scene.objects.iter().map(|o| o.obox()).collect();
    let wall = polygon.longest_edge_direction().unwrap_or(0.0);
    let pieces: Vec<(Group, [f64; DESCRIPTORS])> = scene
        .objects
        .iter()
        .enumerate()
        .map(|(i, o)| (o.category.group(), piece_descriptors(i, &boxes, &polygon, wall, resolution, share_resolution)))
        .collect();
    let mut out = Vec::new();
    for g in GROUPS {
        let of: Vec<&[f64; DESCRIPTORS]> = pieces.iter().filter(|(pg, _)| *pg == g).map(|(_, d)| d).collect();
        out.push(of.len() as f64);
        for k in 0..DESCRIPTORS {
            let values = of.iter().map(|d| d[k]);
            let n = of.len().max(1) as f64;
            out.push(values.clone().sum::<f64>() / n);
            out.push(values.clone().fold(f64::INFINITY, f64::min).min(1e3) * f64::from(u8::from(!of.is_empty())));
            out.push(values.fold(f64::NEG_INFINITY, f64::max).max(-1e3) * f64::from(u8::from(!of.is_empty())));
        }
    }
    for &c in scene.room_type.categories() {
        out.push(scene.objects.iter().filter(|o| o.category == c).count() as f64);
    }
    out.push(polygon.area());
    out.push(scene.objects.len() as f64);
    out.into_iter().map(|v| v as f32).collect()
}

/// The names of [`layout_features`]' values, in their order (`cabinet.back.min`,
/// `count.nightstand`, `area`, …), for diagnostics that say which feature tells two sets apart.
pub fn layout_feature_names(room_type: RoomType) -> Vec<String> {
    const NAMES: [&str; DESCRIPTORS] =
        ["width", "depth", "height", "wall_gap", "back", "turned", "nearest", "shared", "from_centre"];
    let mut out = Vec::new();
    for g in GROUPS {
        let group = format!("{g:?}").to_lowercase();
        out.push(format!("{group}.count"));
        for name in NAMES {
            out.extend(["mean", "min", "max"].map(|pool| format!("{group}.{name}.{pool}")));
        }
    }
    out.extend(room_type.categories().iter().map(|c| format!("count.{}", c.name())));
    out.extend(["area".to_string(), "pieces".to_string()]);
    out
}

/// What a layout shows of piece `i` (its box among `boxes`) in a floor plan whose longest wall
/// runs at `wall` (rad): width, depth, height; its footprint's distance from the walls and its
/// back edge's (m, negative when outside); how far it is turned off square to the walls, as the
/// distance its footprint's corners move from where they would stand square (2 sin(|Δ| / 2) ×
/// half its diagonal, Δ within ±45°: a turn is seen as far as it shows, not as an angle a render
/// cannot show: every real piece turned 0.5° scored 0.998 when the angle itself was a feature);
/// the gap to the nearest other piece's footprint (m, negative when they overlap, [`FAR`] at
/// most); the volume it shares with others over its own; its distance from the floor's centre
/// over the room's scale.
fn piece_descriptors(
    i: usize,
    boxes: &[OBox],
    polygon: &Polygon,
    wall: f64,
    resolution: f64,
    share_resolution: f64,
) -> [f64; DESCRIPTORS] {
    let b = &boxes[i];
    let corners = b.footprint();
    let wall_gap = corners.iter().map(|&p| -polygon.signed_distance(p)).fold(f64::INFINITY, f64::min);
    let (_, ay) = b.axes();
    let back = -polygon.signed_distance(b.center.truncate() - ay * b.size.y * 0.5);
    let gap = |a: &OBox, c: &OBox| {
        a.footprint().iter().map(|&p| c.footprint_signed_distance(p)).fold(f64::INFINITY, f64::min)
    };
    let mut nearest = FAR;
    let mut shared = 0.0;
    for (j, other) in boxes.iter().enumerate() {
        if j == i {
            continue;
        }
        nearest = nearest.min(gap(b, other).min(gap(other, b)));
        shared += intersection_volume(b, other);
    }
    let (min, max) = polygon.bounds();
    let centre = (min + max) * 0.5;
    let scale = polygon.area().max(1e-6).sqrt();
    let to = |v: f64, step: f64| if step > 0.0 { (v / step).round() * step } else { v };
    let seen = |v: f64| to(v, resolution);
    let quarter = std::f64::consts::FRAC_PI_2;
    let off_square = (b.yaw - wall).rem_euclid(quarter);
    let off_square = off_square.min(quarter - off_square);
    let turned = 2.0 * (off_square * 0.5).sin() * b.size.truncate().length() * 0.5;
    [
        seen(b.size.x),
        seen(b.size.y),
        seen(b.size.z),
        seen(wall_gap),
        seen(back),
        seen(turned),
        seen(nearest),
        to(shared / b.volume().max(1e-9), share_resolution),
        seen(b.center.truncate().distance(centre)) / scale,
    ]
}

/// SCA of `generated` against `reference` (same room type), or `None` when either set has fewer
/// than [`SCA_MIN_LAYOUTS`] layouts. The larger set is cut to the smaller's size.
pub fn sca(generated: &[Scene], reference: &[Scene], cfg: &ScaConfig) -> Option<Sca> {
    let n = generated.len().min(reference.len());
    if n < SCA_MIN_LAYOUTS || cfg.repeats == 0 {
        return None;
    }
    let features = |set: &[Scene]| -> Vec<Vec<f32>> {
        set.iter().map(|s| layout_features(s, cfg.resolution, cfg.share_resolution)).collect()
    };
    let (fake, real) = (features(generated), features(reference));
    let half = n / 2;
    let mut repeats = Vec::with_capacity(cfg.repeats);
    for r in 0..cfg.repeats {
        let mut rng = Rng::for_item(cfg.seed, r as u64);
        // n layouts of each set (all of a set that has only n), then one split for both: a layout
        // in both sets lands in the same half of each, so identical sets score exactly 0.5.
        let mut subset = |len: usize| {
            let mut order: Vec<usize> = (0..len).collect();
            if len > n {
                rng.shuffle(&mut order);
                order.truncate(n);
            }
            order
        };
        let (f, t) = (subset(fake.len()), subset(real.len()));
        let mut split: Vec<usize> = (0..n).collect();
        rng.shuffle(&mut split);
        let (f, t): (Vec<usize>, Vec<usize>) = split.iter().map(|&k| (f[k], t[k])).unzip();
        let labelled = |range: std::ops::Range<usize>| -> Vec<(&[f32], bool)> {
            range
                .clone()
                .map(|k| (fake[f[k]].as_slice(), true))
                .chain(range.map(|k| (real[t[k]].as_slice(), false)))
                .collect()
        };
        let (train, test) = (labelled(0..half), labelled(half..n));
        let scaler = Standardizer::fit(&train);
        let train: Vec<(Vec<f32>, bool)> = train.iter().map(|(x, y)| (scaler.apply(x), *y)).collect();
        let mut net = Perceptron::new(scaler.mean.len(), cfg.hidden, &mut rng);
        net.train(&train, cfg, &mut rng);
        let right = test.iter().filter(|(x, fake)| (net.logit(&scaler.apply(x)) > 0.0) == *fake).count();
        repeats.push(right as f64 / test.len() as f64);
    }
    let accuracy = repeats.iter().sum::<f64>() / repeats.len() as f64;
    Some(Sca { accuracy, repeats, layouts: n })
}

/// Each feature's mean and spread over the training half, to put every feature on one scale.
struct Standardizer {
    mean: Vec<f32>,
    inverse_std: Vec<f32>,
}

impl Standardizer {
    fn fit(data: &[(&[f32], bool)]) -> Standardizer {
        let dims = data.first().map_or(0, |(x, _)| x.len());
        let n = data.len().max(1) as f64;
        let mean: Vec<f64> = (0..dims).map(|k| data.iter().map(|(x, _)| f64::from(x[k])).sum::<f64>() / n).collect();
        let inverse_std = (0..dims)
            .map(|k| {
                let var = data.iter().map(|(x, _)| (f64::from(x[k]) - mean[k]).powi(2)).sum::<f64>() / n;
                // A feature that never varies here stays 0.
                if var > 1e-12 { (1.0 / var.sqrt()) as f32 } else { 0.0 }
            })
            .collect();
        Standardizer { mean: mean.into_iter().map(|m| m as f32).collect(), inverse_std }
    }

    fn apply(&self, x: &[f32]) -> Vec<f32> {
        x.iter().zip(&self.mean).zip(&self.inverse_std).map(|((v, m), s)| ((v - m) * s).clamp(-10.0, 10.0)).collect()
    }
}

/// A one-hidden-layer perceptron with a ReLU and a logistic output.
struct Perceptron {
    /// Input weights, `hidden` rows of `dims`.
    w1: Vec<f32>,
    b1: Vec<f32>,
    w2: Vec<f32>,
    b2: f32,
    dims: usize,
}

impl Perceptron {
    fn new(dims: usize, hidden: usize, rng: &mut Rng) -> Perceptron {
        let s1 = (2.0 / dims.max(1) as f64).sqrt();
        let s2 = (1.0 / hidden as f64).sqrt();
        Perceptron {
            w1: (0..hidden * dims).map(|_| (rng.normal() * s1) as f32).collect(),
            b1: vec![0.0; hidden],
            w2: (0..hidden).map(|_| (rng.normal() * s2) as f32).collect(),
            b2: 0.0,
            dims,
        }
    }

    fn hidden_of(&self, x: &[f32]) -> Vec<f32> {
        self.b1
            .iter()
            .zip(self.w1.chunks(self.dims))
            .map(|(b, row)| (b + row.iter().zip(x).map(|(w, v)| w * v).sum::<f32>()).max(0.0))
            .collect()
    }

    /// The logit of "generated" for `x`.
    fn logit(&self, x: &[f32]) -> f32 {
        self.hidden_of(x).iter().zip(&self.w2).map(|(h, w)| h * w).sum::<f32>() + self.b2
    }

    /// `cfg.steps` steps of AdamW on the logistic loss over `data` (input, is generated), in
    /// batches drawn in a fresh order each pass.
    fn train(&mut self, data: &[(Vec<f32>, bool)], cfg: &ScaConfig, rng: &mut Rng) {
        let hidden = self.b1.len();
        let mut params = Adam::new(self.w1.len() + hidden * 2 + 1);
        let mut order: Vec<usize> = (0..data.len()).collect();
        let mut steps = 0;
        while steps < cfg.steps {
            rng.shuffle(&mut order);
            for chunk in order.chunks(cfg.batch.max(1)).take(cfg.steps - steps) {
                steps += 1;
                // Gradients laid out as w1, b1, w2, b2.
                let mut grad = vec![0.0f32; params.len()];
                let (gw1, rest) = grad.split_at_mut(self.w1.len());
                let (gb1, rest) = rest.split_at_mut(hidden);
                let (gw2, gb2) = rest.split_at_mut(hidden);
                let scale = 1.0 / chunk.len() as f32;
                for &k in chunk {
                    let (x, fake) = (&data[k].0, data[k].1);
                    let h = self.hidden_of(x);
                    let z = h.iter().zip(&self.w2).map(|(h, w)| h * w).sum::<f32>() + self.b2;
                    let d = (1.0 / (1.0 + (-z).exp()) - f32::from(u8::from(fake))) * scale;
                    gb2[0] += d;
                    for j in 0..hidden {
                        gw2[j] += d * h[j];
                        if h[j] > 0.0 {
                            let dh = d * self.w2[j];
                            gb1[j] += dh;
                            for (g, v) in gw1[j * self.dims..(j + 1) * self.dims].iter_mut().zip(x) {
                                *g += dh * v;
                            }
                        }
                    }
                }
                let mut weights: Vec<&mut f32> = self
                    .w1
                    .iter_mut()
                    .chain(self.b1.iter_mut())
                    .chain(self.w2.iter_mut())
                    .chain(std::iter::once(&mut self.b2))
                    .collect();
                params.step(&mut weights, &grad, cfg);
            }
        }
    }
}

/// AdamW's running moments.
struct Adam {
    m: Vec<f32>,
    v: Vec<f32>,
    t: i32,
}

impl Adam {
    fn new(n: usize) -> Adam {
        Adam { m: vec![0.0; n], v: vec![0.0; n], t: 0 }
    }

    fn len(&self) -> usize {
        self.m.len()
    }

    fn step(&mut self, weights: &mut [&mut f32], grad: &[f32], cfg: &ScaConfig) {
        const B1: f32 = 0.9;
        const B2: f32 = 0.999;
        self.t += 1;
        let (c1, c2) = (1.0 - B1.powi(self.t), 1.0 - B2.powi(self.t));
        let (lr, decay) = (cfg.learning_rate as f32, cfg.weight_decay as f32);
        for (k, w) in weights.iter_mut().enumerate() {
            let g = grad[k];
            self.m[k] = B1 * self.m[k] + (1.0 - B1) * g;
            self.v[k] = B2 * self.v[k] + (1.0 - B2) * g * g;
            let update = (self.m[k] / c1) / ((self.v[k] / c2).sqrt() + 1e-8);
            **w -= lr * (update + decay * **w);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::generate_room;
    use crate::scene::{Category, Object, RoomType};

    fn living_rooms(seed: u64, n: u64) -> Vec<Scene> {
        (0..n).map(|k| generate_room(RoomType::Living, seed, k, false).scene).collect()
    }

    #[test]
    fn the_features_see_each_piece_in_its_group() {
        let mut scene = living_rooms(1, 1).remove(0);
        // A 1.2 × 0.8 m table alone, 1 m from the west wall of a 6 × 5 m room, turned 0.3 rad.
        scene.floor_plan.polygon = vec![[0.0, 0.0], [6.0, 0.0], [6.0, 5.0], [0.0, 5.0]];
        let mut table = Object::standing("o0", Category::DiningTable, [1.6, 2.5], [1.2, 0.8, 0.75]);
        table.yaw = 0.3;
        scene.objects = vec![table.clone()];
        let f = layout_features(&scene, 0.0, 0.0);
        let stride = 1 + 3 * DESCRIPTORS;
        assert_eq!(f.len(), GROUPS.len() * stride + RoomType::Living.categories().len() + 2);
        let g = GROUPS.iter().position(|g| *g == Group::Table).unwrap();
        let at = |k: usize, which: usize| f[g * stride + 1 + 3 * k + which];
        assert_eq!((f[g * stride], f[0]), (1.0, 0.0), "one table, no bed");
        // Mean, least and greatest of one piece are its own values.
        assert_eq!((at(0, 0), at(0, 1), at(0, 2)), (1.2, 1.2, 1.2));
        assert_eq!(at(2, 0), 0.75);
        // Its footprint's corner nearest the west wall: 1.6 − (0.6 cos 0.3 + 0.4 sin 0.3) by hand.
        let wall_gap = 1.6 - (0.6 * 0.3f64.cos() + 0.4 * 0.3f64.sin());
        assert!((f64::from(at(3, 0)) - wall_gap).abs() < 1e-5, "{}", at(3, 0));
        // Turned 0.3 rad: its corners, half of √(1.2² + 0.8²) out, move 2 sin(0.15) × 0.7211 m.
        let turned = 2.0 * 0.15f64.sin() * (0.36f64 + 0.16).sqrt();
        assert!((f64::from(at(5, 0)) - turned).abs() < 1e-6, "{} vs {turned}", at(5, 0));
        assert_eq!((at(6, 0), at(7, 0)), (FAR as f32, 0.0), "alone: no neighbour, nothing shared");
        // A second table overlapping it by 0.6 × 0.6 m: a corner of each 0.2 m deep in the other
        // (the gap is −0.2 m) and 0.36 of their 0.96 m² footprints shared.
        table.yaw = 0.0;
        let mut other = table.clone();
        other.center[0] += 0.6;
        other.center[1] += 0.2;
        scene.objects = vec![table, other];
        let f = layout_features(&scene, 0.0, 0.0);
        let at = |k: usize, which: usize| f[g * stride + 1 + 3 * k + which];
        assert!((at(6, 0) + 0.2).abs() < 1e-5 && (at(7, 0) - 0.375).abs() < 1e-5, "{} {}", at(6, 0), at(7, 0));
        // Lengths are seen to the resolution.
        let coarse = layout_features(&scene, 0.25, 0.1);
        assert_eq!(coarse[g * stride + 1], 1.25);
        assert!((coarse[g * stride + 1 + 3 * 7] - 0.4).abs() < 1e-6, "0.375 of its volume shared, seen to 0.1");
    }

    #[test]
    fn every_feature_has_its_name() {
        let scene = living_rooms(2, 1).remove(0);
        let names = layout_feature_names(RoomType::Living);
        assert_eq!(names.len(), layout_features(&scene, 0.05, 0.05).len());
        let stride = 1 + 3 * DESCRIPTORS;
        let table = GROUPS.iter().position(|g| *g == Group::Table).unwrap();
        assert_eq!(names[table * stride], "table.count");
        assert_eq!(names[table * stride + 1 + 3 * 4 + 1], "table.back.min");
        assert_eq!(names[GROUPS.len() * stride], format!("count.{}", RoomType::Living.categories()[0].name()));
        assert_eq!(names.last().map(String::as_str), Some("pieces"));
    }

    #[test]
    fn identical_sets_score_a_half_and_two_draws_of_one_generator_about_a_half() {
        let rooms = living_rooms(3, 60);
        let r = sca(&rooms, &rooms, &ScaConfig::default()).unwrap();
        assert_eq!(r.layouts, 60);
        assert_eq!(r.accuracy, 0.5, "{r:?}");
        // Two draws of the same generator are as hard to tell apart.
        let r = sca(&living_rooms(4, 60), &rooms, &ScaConfig::default()).unwrap();
        assert!((r.accuracy - 0.5).abs() <= 0.15, "{r:?}");
    }

    #[test]
    fn pieces_turned_further_than_a_render_shows_give_themselves_away_and_slighter_turns_do_not() {
        let rooms = living_rooms(3, 80);
        let turned = |degrees: f64| -> Vec<Scene> {
            let mut out = rooms.clone();
            for (k, o) in out.iter_mut().flat_map(|s| s.objects.iter_mut()).enumerate() {
                o.yaw += degrees.to_radians() * if k % 2 == 0 { 1.0 } else { -1.0 };
            }
            out
        };
        let slight = sca(&turned(0.5), &rooms, &ScaConfig::default()).unwrap();
        assert!((slight.accuracy - 0.5).abs() <= 0.15, "0.5°: {slight:?}");
        let visible = sca(&turned(12.0), &rooms, &ScaConfig::default()).unwrap();
        assert!(visible.accuracy >= 0.8, "12°: {visible:?}");
    }

    #[test]
    fn rooms_with_three_dining_tables_give_themselves_away() {
        let rooms = living_rooms(3, 60);
        let odd: Vec<Scene> = living_rooms(5, 60)
            .into_iter()
            .map(|mut s| {
                let window = s.room_window();
                s.objects.retain(|o| o.category.group() != Group::Sofa);
                for k in 0..3 {
                    let at = window.center + glam::DVec2::new(-1.5 + 1.5 * k as f64, 0.0);
                    s.objects.push(Object::standing(
                        format!("t{k}"),
                        Category::DiningTable,
                        at.into(),
                        [1.2, 0.8, 0.75],
                    ));
                }
                s
            })
            .collect();
        let r = sca(&odd, &rooms, &ScaConfig::default()).unwrap();
        assert!(r.accuracy >= 0.9, "{r:?}");
        assert_eq!(r, sca(&odd, &rooms, &ScaConfig::default()).unwrap(), "deterministic");
        assert!(sca(&odd[..7], &rooms, &ScaConfig::default()).is_none());
    }
}
