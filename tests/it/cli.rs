//! The commands on the example scenes: typed JSON output, text output, files written.

use crate::{example_scenes, shade_sim, stderr, stdout};
use serde::Deserialize;
use shade_sim::geom::RES;
use shade_sim::human::ContactBox;
use shade_sim::scene::{Action, RoomType, SceneSummary};

#[derive(Deserialize)]
struct InspectJson {
    file: String,
    #[serde(flatten)]
    summary: SceneSummary,
}

#[test]
fn inspect_json_is_typed_and_matches_the_scene() {
    let file = crate::root().join("scenes/examples/bedroom_rect.json");
    let out = shade_sim(&["inspect", "--json", file.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let r: InspectJson = serde_json::from_slice(&out.stdout).expect("inspect --json deserialises");
    assert_eq!(r.file, file.display().to_string());
    let s = r.summary;
    assert_eq!(s.room_type, RoomType::Bedroom);
    assert_eq!(s.floor.vertices, 4);
    assert!((s.floor.area - 4.2 * 3.8).abs() < 1e-9);
    assert_eq!(s.objects, 0);
    assert_eq!(s.humans.len(), 5);
    let total: usize = s.humans.iter().map(|h| h.frames).sum();
    let labelled: usize = s.action_frames.values().sum();
    assert!(labelled <= total && labelled > 0);
    for a in [Action::Walk, Action::Sit, Action::Lie, Action::Touch] {
        assert!(s.action_frames.contains_key(&a), "{a} frames present");
    }
    // Everything stays inside the room.
    assert_eq!(s.extents[0], [0.0, 0.0, 0.0]);
    assert!(s.extents[1][0] <= 4.2 && s.extents[1][1] <= 3.8 && s.extents[1][2] == 2.7);
}

#[test]
fn inspect_text_names_room_humans_and_actions() {
    let file = crate::root().join("scenes/examples/dining_l.json");
    let out = shade_sim(&["inspect", file.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0));
    let text = stdout(&out);
    assert!(text.contains("dining room, floor 6.00 × 6.00 m (28.50 m², 6 vertices), ceiling 2.80 m"), "{text}");
    assert!(text.contains("humans: 6"));
    assert!(text.contains("sit 0–45"));
    assert!(text.lines().last().unwrap().starts_with("extents: x [0.00, 6.00]"));
}

#[derive(Deserialize)]
struct ConditionsJson {
    free_space_pixels: usize,
    floor_pixels: usize,
    contact_boxes: Vec<ContactBox>,
    files: Vec<String>,
}

fn count_white(png: &std::path::Path) -> usize {
    let img = image::open(png).expect("a PNG").to_luma8();
    assert_eq!(img.dimensions(), (RES as u32, RES as u32));
    img.pixels().filter(|p| p.0[0] == 255).count()
}

#[test]
fn conditions_writes_masks_boxes_and_pictures_for_every_example() {
    let dir = tempfile::tempdir().unwrap();
    for scene in example_scenes() {
        let out_dir = dir.path().join(scene.file_stem().unwrap());
        let out = shade_sim(&["conditions", "--json", scene.to_str().unwrap(), "--out", out_dir.to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
        let r: ConditionsJson = serde_json::from_slice(&out.stdout).expect("typed JSON");
        assert_eq!(r.files.len(), 6);
        assert_eq!(count_white(&out_dir.join("free_space.png")), r.free_space_pixels);
        assert_eq!(count_white(&out_dir.join("floor.png")), r.floor_pixels);
        assert!(r.free_space_pixels > 0 && r.floor_pixels > r.free_space_pixels);
        assert!(r.contact_boxes.len() >= 2);
        let written: Vec<ContactBox> =
            serde_json::from_slice(&std::fs::read(out_dir.join("contact_boxes.json")).unwrap()).unwrap();
        assert_eq!(written, r.contact_boxes);
        let humans = image::open(out_dir.join("humans.png")).unwrap();
        assert_eq!((humans.width(), humans.height()), (1120, 560));
        // Nothing half-written is left behind.
        let leftovers = std::fs::read_dir(&out_dir)
            .unwrap()
            .filter(|e| e.as_ref().unwrap().file_name().to_string_lossy().ends_with(".tmp"));
        assert_eq!(leftovers.count(), 0);
    }
}

#[test]
fn quiet_conditions_prints_nothing_and_version_works() {
    let dir = tempfile::tempdir().unwrap();
    let scene = crate::root().join("scenes/examples/living_rect.json");
    let out = shade_sim(&["-q", "conditions", scene.to_str().unwrap(), "--out", dir.path().to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0));
    assert!(out.stdout.is_empty() && out.stderr.is_empty());
    let v = shade_sim(&["--version"]);
    assert_eq!(stdout(&v).trim(), format!("shade-sim {}", env!("CARGO_PKG_VERSION")));
    let bad = shade_sim(&["inspect"]);
    assert_eq!(bad.status.code(), Some(2), "usage errors exit 2 too");
}

#[test]
fn negative_and_invalid_numbers_are_one_line_errors_in_every_command() {
    // A number starting with `-` is the option's value, checked by the command: before, clap took
    // it for a flag ("unexpected argument '-1' found" and its usage, several lines).
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let input = example_scenes()[0].clone();
    let (input, out) = (input.to_str().unwrap(), out.to_str().unwrap());
    for (args, want) in [
        (
            vec!["generate", "--input", input, "--out", out, "--eta", "-1"],
            "error: --eta: must be between 0 and 2, not -1",
        ),
        (
            vec!["generate", "--input", input, "--out", out, "--guidance-scale", "-0.5"],
            "error: --guidance-scale: must be",
        ),
        (
            vec!["generate", "--input", input, "--out", out, "--samples", "-1"],
            "error: invalid value '-1' for '--samples <SAMPLES>'",
        ),
        (vec!["check", input, "--tolerance", "-0.01"], "error: --tolerance: must be a non-negative number"),
        (
            vec!["synth", "--room", "dining", "--scenes", "1", "--out", out, "--gap-spread", "-0.05"],
            "error: --gap-spread: must be between 0 and 0.2 (m), not -0.05",
        ),
        (
            vec!["synth", "--room", "living", "--scenes", "1", "--out", out, "--free-sofas", "1.5"],
            "error: --free-sofas: must be a share between 0 and 1, not 1.5",
        ),
        (
            vec!["import-motion", input, "--room", "kitchen", "--floor", "5x4", "--out", out],
            "error: invalid value 'kitchen' for '--room <ROOM>' [possible values: bedroom, living, dining]",
        ),
    ] {
        let o = shade_sim(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        let err = stderr(&o);
        assert!(err.starts_with(want), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
    }
    assert!(!std::path::Path::new(out).exists());
    // A missing argument still gets clap's usage.
    let o = shade_sim(&["generate", "--input", input]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("Usage: shade-sim generate"), "{}", stderr(&o));
}
