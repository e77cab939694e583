//! Hand-built inputs outside the synthetic distribution (`tests/inputs/`, made by
//! `examples/hand_built_inputs.rs`): the default pipeline with `--require-clean` on each, against
//! the outcome recorded for the shipped models.

use crate::{shade_sim, stderr};

/// Each input and whether `generate --require-clean --seed 0` finds a layout `check` passes.
const EXPECTED: [(&str, bool); 5] = [
    ("dinner_for_three", true),
    ("three_on_a_sofa", true),
    ("tight_bedroom", true),
    ("walker_behind_sitter", true),
    ("walker_through_middle", true),
];

#[test]
fn require_clean_on_hand_built_inputs_gives_the_recorded_outcome() {
    let files = crate::json_files("tests/inputs");
    let names: Vec<String> = files.iter().map(|f| f.file_stem().unwrap().to_string_lossy().into_owned()).collect();
    assert_eq!(names, EXPECTED.map(|(n, _)| n.to_string()), "one expectation per input");
    let dir = tempfile::tempdir().unwrap();
    for (file, (name, clean)) in files.iter().zip(EXPECTED) {
        let out = dir.path().join(name);
        let run = shade_sim(&[
            "--no-progress",
            "-q",
            "generate",
            "--input",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--require-clean",
            "--seed",
            "0",
        ]);
        assert_eq!(run.status.code(), Some(if clean { 0 } else { 1 }), "{name}: {}", stderr(&run));
        if clean {
            // What it wrote passes the check on its own.
            let scene = out.join(format!("{name}_0.json"));
            let check = shade_sim(&["check", scene.to_str().unwrap()]);
            assert_eq!(check.status.code(), Some(0), "{name}: {}", String::from_utf8_lossy(&check.stdout));
        }
    }
}
