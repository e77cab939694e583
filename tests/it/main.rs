//! Integration tests: one binary (ripgrep's layout), one module per area.

mod bad_input;
mod cli;
mod conditions;
mod data;
mod examples;
mod export;
mod geom_props;
mod hand_built;
mod import;
mod layers;
mod model;
mod motion;
mod scene_io;
mod sim;
mod smoke_fuzz;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs the `shade-sim` binary with `args`.
pub fn shade_sim(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_shade-sim")).args(args).output().expect("the binary runs")
}

/// The repository root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The `.json` files of a folder of the repository, sorted.
pub fn json_files(folder: &str) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(root().join(folder))
        .unwrap_or_else(|e| panic!("{folder}: {e}"))
        .map(|e| e.expect("readable entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    files.sort();
    files
}

/// The example scene files (inputs: people and floor plans), sorted.
pub fn example_scenes() -> Vec<PathBuf> {
    json_files("scenes/examples")
}

/// The reference scenes (the examples furnished by the shipped models), sorted.
pub fn reference_scenes() -> Vec<PathBuf> {
    json_files("scenes/reference")
}

/// stderr as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// stdout as text.
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Writes `text` to `dir/name` and returns the path.
pub fn write_file(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).expect("temp dir is writable");
    p
}
