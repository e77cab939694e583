//! A smoke fuzz, seconds long: the reference scenes and hand-built inputs, mutated (numbers replaced
//! by huge, tiny, zero or negative ones, keys deleted, array elements repeated, the text cut short
//! or given a stray byte), are either rejected with a typed error or read, checked, exported and
//! conditioned without a panic.

use crate::{json_files, reference_scenes, shade_sim, stderr, write_file};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use serde_json::Value;
use shade_sim::export::{MjcfOptions, render_plan, scene_mjcf};
use shade_sim::human::Conditions;
use shade_sim::scene::Scene;
use shade_sim::sim::{CheckConfig, check_scene};
use std::path::Path;

/// The seed corpus: every reference scene and hand-built input, as JSON.
fn corpus() -> Vec<Value> {
    let mut files = reference_scenes();
    files.extend(json_files("tests/inputs"));
    files.iter().map(|f| serde_json::from_str(&std::fs::read_to_string(f).unwrap()).unwrap()).collect()
}

/// One edit of a scene's JSON.
#[derive(Debug, Clone)]
enum Mutation {
    /// The `pick`-th number (mod their count) becomes `value`.
    Number { pick: usize, value: f64 },
    /// The `pick`-th object key (mod their count) is removed.
    DeleteKey { pick: usize },
    /// The `pick`-th array's (mod their count) first element is repeated.
    Repeat { pick: usize },
}

const VALUES: [f64; 12] = [0.0, -1.0, 1e-300, 1e-9, 0.5, 7.0, 60.0, 1e6, -1e6, 1e20, 1e308, -1e308];

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        4 => (any::<usize>(), 0..VALUES.len()).prop_map(|(pick, k)| Mutation::Number { pick, value: VALUES[k] }),
        1 => any::<usize>().prop_map(|pick| Mutation::DeleteKey { pick }),
        1 => any::<usize>().prop_map(|pick| Mutation::Repeat { pick }),
    ]
}

/// Visits every value in document order.
fn visit(v: &mut Value, f: &mut dyn FnMut(&mut Value)) {
    f(v);
    match v {
        Value::Array(a) => a.iter_mut().for_each(|x| visit(x, f)),
        Value::Object(o) => o.values_mut().for_each(|x| visit(x, f)),
        _ => {}
    }
}

/// Applies `m` to the `pick`-th value of the kind it edits (nothing when there is none).
fn apply(doc: &mut Value, m: &Mutation) {
    let is_kind = |v: &Value| match m {
        Mutation::Number { .. } => v.is_number(),
        Mutation::DeleteKey { .. } => v.as_object().is_some_and(|o| !o.is_empty()),
        Mutation::Repeat { .. } => v.as_array().is_some_and(|a| !a.is_empty()),
    };
    let mut count = 0;
    visit(doc, &mut |v| count += is_kind(v) as usize);
    if count == 0 {
        return;
    }
    let target = match m {
        Mutation::Number { pick, .. } | Mutation::DeleteKey { pick } | Mutation::Repeat { pick } => pick % count,
    };
    let mut seen = 0;
    visit(doc, &mut |v| {
        if !is_kind(v) {
            return;
        }
        if seen == target {
            match (m, &mut *v) {
                (Mutation::Number { value, .. }, v) => *v = serde_json::json!(value),
                (Mutation::DeleteKey { pick }, Value::Object(o)) => {
                    let key = o.keys().nth(pick % o.len()).unwrap().clone();
                    o.remove(&key);
                }
                (Mutation::Repeat { .. }, Value::Array(a)) => {
                    let first = a[0].clone();
                    a.push(first);
                }
                _ => {}
            }
        }
        seen += 1;
    });
}

/// What every command does with a scene it accepts, short of sampling a model.
fn exercise(text: &str) {
    let Ok(scene) = Scene::from_json(text, Path::new("fuzz.json")) else { return };
    let cfg = CheckConfig { stability: false, ..CheckConfig::default() };
    let report = check_scene(&scene, &cfg);
    assert!(report.violations.iter().all(|v| v.depth.is_finite()));
    assert!(scene_mjcf(&scene, MjcfOptions::default()).starts_with("<mujoco"));
    let _ = render_plan(&scene);
    let _ = Conditions::of(&scene);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn mutated_scenes_are_rejected_or_handled_without_a_panic(
        seed in any::<usize>(),
        edits in proptest::collection::vec(mutation(), 1..4),
        cut in proptest::option::weighted(0.15, any::<usize>()),
        stray in proptest::option::weighted(0.15, (any::<usize>(), any::<u8>())),
    ) {
        let seeds = corpus();
        let mut doc = seeds[seed % seeds.len()].clone();
        for m in &edits {
            apply(&mut doc, m);
        }
        let mut bytes = doc.to_string().into_bytes();
        if let Some(cut) = cut {
            bytes.truncate(cut % (bytes.len() + 1));
        }
        if let Some((at, byte)) = stray {
            bytes.insert(at % (bytes.len() + 1), byte);
        }
        // Scenes are UTF-8: other bytes are the reader's `error:` line (tested below).
        if let Ok(text) = String::from_utf8(bytes) {
            exercise(&text);
        }
    }
}

/// The same through the command line: exit 0, 1 or 2 with one error line, never a panic's 101.
#[test]
fn mutated_scenes_through_check_exit_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let seeds = corpus();
    let mut runner = proptest::test_runner::TestRunner::deterministic();
    let edits = proptest::collection::vec(mutation(), 1..4);
    for k in 0..12 {
        let mut doc = seeds[k % seeds.len()].clone();
        for m in edits.new_tree(&mut runner).unwrap().current() {
            apply(&mut doc, &m);
        }
        let file = write_file(dir.path(), &format!("s{k}.json"), &doc.to_string());
        let out = shade_sim(&["check", "--no-stability", file.to_str().unwrap()]);
        let err = stderr(&out);
        match out.status.code() {
            Some(0 | 1) => {}
            Some(2) => assert!(err.lines().count() == 1 && err.starts_with("error: "), "{err}"),
            other => panic!("{other:?} on {}: {err}", file.display()),
        }
    }
    // Bytes that are not UTF-8.
    let bad = dir.path().join("latin1.json");
    std::fs::write(&bad, b"{\"format\": \"shade-scene/1\xe9\"}").unwrap();
    let out = shade_sim(&["check", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).starts_with(&format!("error: {}: ", bad.display())));
}
