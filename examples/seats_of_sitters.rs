//! What the seated people of generated scenes sit on: for each input (the scenes `generate` wrote
//! for it, `<input>_<k>.json`), one line per sample naming the piece under each sitter, and how
//! many of the samples' side-by-side pairs share one sofa — the data's piece for two people side
//! by side; two on one chair is a failure and does not count. Two sit boxes are a side-by-side
//! pair when they belong to different people, face the same way within 20°, and stand at most
//! 0.9 m apart, no more than 0.25 m of it along the way they face (two people on one sofa, or two
//! diners on one side of a table, who sit on two chairs: the input says which). The piece under a
//! sitter is the first piece, lamps aside, whose footprint holds the centre of their sit box and
//! whose bottom is below it. It measures; it judges nothing.
//!
//! Run: `cargo run --release --example seats_of_sitters -- FOLDER…` (folders of generated scenes).

use shade_sim::geom::{facing, wrap_angle};
use shade_sim::human::{Conditions, ContactBox};
use shade_sim::scene::{Action, Group, Scene};
use std::collections::BTreeMap;
use std::path::Path;

/// Most a pair's facings differ by (radians).
const SAME_FACING: f64 = 20.0 * std::f64::consts::PI / 180.0;
/// Most two sitters of a pair are apart (m), and most of it along the way they face.
const PAIR_DISTANCE: f64 = 0.9;
const PAIR_DEPTH: f64 = 0.25;

/// The index of the piece under a sit box, if any.
fn seat_of(scene: &Scene, b: &ContactBox) -> Option<usize> {
    let centre = b.obox.center;
    scene.objects.iter().position(|o| {
        let obox = o.obox();
        o.category.group() != Group::Lamp
            && obox.footprint_contains(centre.truncate())
            && obox.center.z - obox.size.z * 0.5 < centre.z
    })
}

/// The pairs (indices into `sits`) of sit boxes side by side.
fn side_by_side(sits: &[&ContactBox]) -> Vec<(usize, usize)> {
    let mut pairs = Vec::new();
    for i in 0..sits.len() {
        for j in i + 1..sits.len() {
            let (a, b) = (&sits[i].obox, &sits[j].obox);
            let apart = (b.center - a.center).truncate();
            let ahead = facing(a.yaw);
            let near = apart.length() <= PAIR_DISTANCE && apart.dot(ahead).abs() <= PAIR_DEPTH;
            if sits[i].human != sits[j].human && wrap_angle(a.yaw - b.yaw).abs() <= SAME_FACING && near {
                pairs.push((i, j));
            }
        }
    }
    pairs
}

fn main() -> anyhow::Result<()> {
    let folders: Vec<String> = std::env::args().skip(1).collect();
    anyhow::ensure!(!folders.is_empty(), "usage: seats_of_sitters FOLDER…");
    for folder in &folders {
        let mut by_input: BTreeMap<String, Vec<Scene>> = BTreeMap::new();
        for file in Scene::files_in(Path::new(folder))? {
            let stem = file.file_stem().unwrap_or_default().to_string_lossy().into_owned();
            let input = stem.rsplit_once('_').map_or(stem.clone(), |(name, _)| name.to_string());
            by_input.entry(input).or_default().push(Scene::load(&file)?);
        }
        println!("{folder}");
        let (mut shared_all, mut pairs_all) = (0, 0);
        for (input, scenes) in &by_input {
            let (mut shared, mut pairs) = (0, 0);
            let mut lines = Vec::new();
            for scene in scenes {
                let boxes = Conditions::contact_boxes_of(scene);
                let sits: Vec<&ContactBox> = boxes.iter().filter(|b| b.action == Action::Sit).collect();
                let seats: Vec<Option<usize>> = sits.iter().map(|b| seat_of(scene, b)).collect();
                let names: Vec<String> = seats
                    .iter()
                    .map(|s| {
                        s.map_or("-".to_string(), |i| format!("{}:{}", scene.objects[i].id, scene.objects[i].category))
                    })
                    .collect();
                lines.push(names.join(" "));
                for (i, j) in side_by_side(&sits) {
                    pairs += 1;
                    let sofa = seats[i].is_some_and(|k| scene.objects[k].category.group() == Group::Sofa);
                    shared += usize::from(sofa && seats[i] == seats[j]);
                }
            }
            println!("  {input}: side-by-side pairs on one sofa {shared} of {pairs}");
            for line in lines {
                println!("    {line}");
            }
            (shared_all, pairs_all) = (shared_all + shared, pairs_all + pairs);
        }
        println!("  all inputs: side-by-side pairs on one sofa {shared_all} of {pairs_all}");
    }
    Ok(())
}
