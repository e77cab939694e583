//! Scene JSON → validation → everything a command does with an accepted scene short of sampling a
//! model: the physical check (without its stability run), the MJCF and PNG exports, the
//! conditioning. Any panic is a finding.
#![no_main]

use libfuzzer_sys::fuzz_target;
use shade_sim::export::{MjcfOptions, render_plan, scene_mjcf};
use shade_sim::human::Conditions;
use shade_sim::scene::Scene;
use shade_sim::sim::{CheckConfig, check_scene};
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let Ok(scene) = Scene::from_json(text, Path::new("fuzz.json")) else { return };
    let _ = check_scene(&scene, &CheckConfig { stability: false, ..CheckConfig::default() });
    let _ = scene_mjcf(&scene, MjcfOptions::default());
    let _ = render_plan(&scene);
    let _ = Conditions::of(&scene);
});
