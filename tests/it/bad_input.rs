//! Every kind of bad input gets one line `error: <file>: <what>` and exit code 2.

use crate::{shade_sim, stderr, write_file};
use glam::DVec2;
use serde_json::{Value, json};
use shade_sim::human::{Body, Motion, stand};
use shade_sim::scene::{Action, FloorPlan, RoomType, Scene};

/// A small valid bedroom: one double bed, one standing human with three frames.
fn valid() -> Value {
    let body = Body::default();
    let mut m = Motion::new(body, 30.0);
    m.hold(stand(&body, DVec2::new(1.0, 1.0), 0.0), 3, Action::Stand);
    let mut scene = Scene::new(
        RoomType::Bedroom,
        FloorPlan { polygon: vec![[0.0, 0.0], [4.0, 0.0], [4.0, 3.5], [0.0, 3.5]], height: 2.8 },
    );
    scene.humans.push(m.into_human("h0"));
    let mut v = serde_json::to_value(&scene).unwrap();
    v["objects"] = json!([{ "id": "o0", "category": "double_bed", "center": [2.0, 2.4, 0.25],
                            "size": [1.6, 2.0, 0.5], "yaw": 3.25 }]);
    v
}

/// Runs `inspect` on the JSON text and checks exit 2 and a one-line message containing `expect`.
fn rejects_text(text: &str, expect: &str) {
    let dir = tempfile::tempdir().unwrap();
    let file = write_file(dir.path(), "scene.json", text);
    let out = shade_sim(&["inspect", file.to_str().unwrap()]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "stderr: {err}");
    assert!(out.stdout.is_empty(), "nothing on stdout");
    assert_eq!(err.lines().count(), 1, "one line: {err}");
    let prefix = format!("error: {}: ", file.display());
    assert!(err.starts_with(&prefix), "names the file: {err}");
    assert!(err.contains(expect), "expected {expect:?} in {err}");
}

fn rejects(edit: impl FnOnce(&mut Value), expect: &str) {
    let mut v = valid();
    edit(&mut v);
    rejects_text(&serde_json::to_string(&v).unwrap(), expect);
}

#[test]
fn the_valid_base_is_accepted() {
    let dir = tempfile::tempdir().unwrap();
    let file = write_file(dir.path(), "scene.json", &valid().to_string());
    let out = shade_sim(&["inspect", file.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
}

#[test]
fn malformed_json() {
    // A document cut short: said so, with no field path (serde's is `?` there).
    rejects_text("{ \"format\": \"shade-scene/1\", ", ".json: the file ends inside the document (EOF while parsing");
    rejects_text(
        "{ \"format\": \"shade-scene/1\"",
        ".json: the file ends inside the document (EOF while parsing an object)",
    );
    rejects_text("{\"format\": \"shade-scene/1\" \"room_type\": 1}", "line 1, column");
    rejects_text(" \n", ".json: the file is empty");
}

#[test]
fn nan_and_overflowing_numbers() {
    let text = valid().to_string().replace("3.25", "NaN");
    rejects_text(&text, "objects[0].yaw");
    let text = valid().to_string().replace("3.25", "1e999");
    rejects_text(&text, "objects[0].yaw: number out of range");
}

#[test]
fn unknown_fields_at_any_depth() {
    rejects(|v| v["colour"] = json!("red"), "unknown field `colour`");
    rejects(|v| v["objects"][0]["mass"] = json!(3), "objects[0].mass: unknown field `mass`");
    rejects(
        |v| v["humans"][0]["skeleton"]["bones"][1]["length"] = json!(3),
        "humans[0].skeleton.bones[1].length: unknown field `length`",
    );
}

#[test]
fn categories_unknown_or_from_another_room() {
    rejects(|v| v["objects"][0]["category"] = json!("spaceship"), "objects[0].category: unknown variant `spaceship`");
    rejects(
        |v| v["objects"][0]["category"] = json!("dining_chair"),
        "objects[0].category: category \"dining_chair\" is not a bedroom category",
    );
    rejects(|v| v["room_type"] = json!("kitchen"), "room_type: unknown variant `kitchen`");
}

#[test]
fn non_positive_sizes() {
    rejects(|v| v["objects"][0]["size"][1] = json!(0.0), "objects[0].size[1]: must be positive, found 0");
    rejects(|v| v["objects"][0]["size"][2] = json!(-0.5), "objects[0].size[2]: must be positive, found -0.5");
    rejects(|v| v["floor_plan"]["height"] = json!(0), "floor_plan.height: must be positive");
    rejects(|v| v["humans"][0]["fps"] = json!(0), "humans[0].fps: must be positive");
    rejects(|v| v["humans"][0]["skeleton"]["bones"][0]["radius"] = json!(-1), "bones[0].radius: must be positive");
}

#[test]
fn bad_floor_polygons() {
    rejects(|v| v["floor_plan"]["polygon"] = json!([[0, 0], [1, 0]]), "floor polygon has 2 vertices, needs at least 3");
    rejects(|v| v["floor_plan"]["polygon"] = json!([[0, 0], [1, 0], [2, 0]]), "floor polygon has zero area");
    rejects(|v| v["floor_plan"]["polygon"] = json!([[0, 0], [1e-4, 0], [0, 1e-4]]), "floor polygon has zero area");
    rejects(
        |v| v["floor_plan"]["polygon"] = json!([[0, 0], [4, 4], [4, 0], [0, 4]]),
        "floor polygon intersects itself (edges 0 and 2)",
    );
    rejects(
        |v| v["floor_plan"]["polygon"] = json!([[0, 0], [0, 3], [4, 3], [4, 0]]),
        "floor_plan.polygon: floor polygon is clockwise",
    );
}

#[test]
fn humans_that_disagree_with_their_skeleton() {
    rejects(
        |v| {
            v["humans"][0]["frames"][1].as_array_mut().unwrap().pop();
        },
        "humans[0].frames[1]: frame has 18 joint positions, skeleton has 19 joints",
    );
    rejects(
        |v| v["humans"][0]["skeleton"]["bones"][3]["b"] = json!(19),
        "humans[0].skeleton.bones[3]: bone joint index 19 out of range",
    );
    rejects(|v| v["humans"][0]["skeleton"]["joints"][4] = json!("skull"), "lacks the required joint \"head\"");
    rejects(
        |v| v["humans"][0]["actions"][0]["end"] = json!(4),
        "humans[0].actions[0]: action range [0, 4) is empty or outside the 3 frames",
    );
    rejects(|v| v["humans"][0]["actions"][0]["start"] = json!(3), "action range [3, 3)");
    rejects(|v| v["humans"][0]["frames"] = json!([]), "humans[0].frames: human has no frames");
    rejects(|v| v["humans"][0]["actions"][0]["action"] = json!("dance"), "unknown variant `dance`");
}

#[test]
fn wrong_format_and_duplicate_ids() {
    rejects(
        |v| v["format"] = json!("shade-scene/2"),
        "format: format is \"shade-scene/2\", expected \"shade-scene/1\"",
    );
    rejects(
        |v| {
            let o = v["objects"][0].clone();
            v["objects"].as_array_mut().unwrap().push(o);
        },
        "objects[1].id: id \"o0\" is used twice",
    );
}

#[test]
fn several_problems_are_counted_in_one_line() {
    rejects(
        |v| {
            v["objects"][0]["size"][0] = json!(0);
            v["floor_plan"]["height"] = json!(-1);
        },
        "(and 1 more problem)",
    );
}

#[test]
fn missing_file() {
    let out = shade_sim(&["inspect", "/nonexistent/scene.json"]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert_eq!(err.trim_end(), "error: /nonexistent/scene.json: No such file or directory (os error 2)");
}

#[test]
fn conditions_on_bad_input_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let mut v = valid();
    v["floor_plan"]["polygon"] = json!([[0, 0], [1, 0]]);
    let file = write_file(dir.path(), "scene.json", &v.to_string());
    let out_dir = dir.path().join("cond");
    let out = shade_sim(&["conditions", file.to_str().unwrap(), "--out", out_dir.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(!out_dir.exists(), "no output folder for a rejected scene");
}

#[test]
fn conditions_into_an_unwritable_place_fails_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let file = write_file(dir.path(), "scene.json", &valid().to_string());
    let blocker = write_file(dir.path(), "taken", "a file, not a folder");
    let target = blocker.join("cond");
    let out = shade_sim(&["conditions", file.to_str().unwrap(), "--out", target.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(err.starts_with(&format!("error: {}: cannot create folder", target.display())), "{err}");
    assert_eq!(std::fs::read_to_string(&blocker).unwrap(), "a file, not a folder");
}

/// `<dir>/in` holding the valid scene as `a.json` and, as `b.json`, one broken by `edit`; returns
/// the folder and the broken file.
fn good_and_bad_folder(
    dir: &std::path::Path,
    edit: impl FnOnce(&mut Value),
) -> (std::path::PathBuf, std::path::PathBuf) {
    let inputs = dir.join("in");
    std::fs::create_dir_all(&inputs).unwrap();
    write_file(&inputs, "a.json", &valid().to_string());
    let mut v = valid();
    edit(&mut v);
    let bad = write_file(&inputs, "b.json", &v.to_string());
    (inputs, bad)
}

#[test]
fn repair_reads_every_scene_before_writing_any() {
    let dir = tempfile::tempdir().unwrap();
    let (inputs, bad) = good_and_bad_folder(dir.path(), |v| v["objects"][0]["size"][0] = json!(f64::NAN.to_string()));
    let out_dir = dir.path().join("out");
    let out = shade_sim(&["repair", inputs.to_str().unwrap(), "--out", out_dir.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with(&format!("error: {}: ", bad.display())), "{err}");
    assert!(!out_dir.exists(), "nothing written for a rejected folder");
}

#[test]
fn a_bad_repair_config_names_its_file_and_field() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write_file(dir.path(), "a.json", &valid().to_string());
    let out_dir = dir.path().join("out");
    for (text, says) in [
        (r#"{"settle": {"rounds": 5000}}"#, "settle.rounds: 5000 rounds is more than 1000"),
        (r#"{"steps": ["settle", "polish"]}"#, "steps[1]: unknown variant `polish`"),
        (r#"{"settle": {"max_step": -1}}"#, "settle.max_step: -1 is not a length"),
        ("{", "."),
    ] {
        let config = write_file(dir.path(), "repair.json", text);
        let out = shade_sim(&[
            "repair",
            scene.to_str().unwrap(),
            "--out",
            out_dir.to_str().unwrap(),
            "--config",
            config.to_str().unwrap(),
        ]);
        assert_eq!(out.status.code(), Some(2), "{text}");
        let err = stderr(&out);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.starts_with(&format!("error: {}: {says}", config.display())), "{text}: {err}");
        assert!(!out_dir.exists(), "nothing written for a bad config");
    }
}

/// Runs `args` (with `{}` replaced by the scene's path and `{out}` by a fresh output path) and
/// returns the exit code and stderr.
fn run_on(file: &std::path::Path, out_dir: &std::path::Path, args: &[&str]) -> (Option<i32>, String) {
    let out_path = out_dir.join("out");
    let args: Vec<String> = args
        .iter()
        .map(|a| {
            a.replace("{}", file.to_str().unwrap())
                .replace("{dir}", file.parent().unwrap().to_str().unwrap())
                .replace("{out}", out_path.to_str().unwrap())
        })
        .collect();
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let out = shade_sim(&args);
    (out.status.code(), stderr(&out))
}

#[test]
fn huge_but_finite_numbers_are_rejected_by_every_command_with_the_same_line() {
    type Edit = fn(&mut Value);
    let cases: [(Edit, &str); 8] = [
        (|v| v["objects"][0]["size"][0] = json!(1e20), "objects[0].size[0]: 1e20 is outside the allowed range 0 to 10"),
        (|v| v["objects"][0]["center"][1] = json!(1e20), "objects[0].center[1]: "),
        (
            |v| v["humans"][0]["frames"][1][4][0] = json!(1e308),
            "humans[0].frames[1][4][0]: 1e308 is outside the allowed range -2 to 6",
        ),
        (|v| v["floor_plan"]["polygon"][2] = json!([4e6, 3.5]), "floor_plan.polygon[2][0]: "),
        (|v| v["floor_plan"]["height"] = json!(1e4), "floor_plan.height: 10000 is outside"),
        (|v| v["humans"][0]["fps"] = json!(1e9), "humans[0].fps: "),
        (|v| v["humans"][0]["skeleton"]["bones"][0]["radius"] = json!(5), "bones[0].radius: 5 is outside"),
        (|v| v["objects"][0]["yaw"] = json!(1e12), "objects[0].yaw: "),
    ];
    for (edit, expect) in cases {
        let mut v = valid();
        edit(&mut v);
        rejects(|w| *w = v.clone(), expect);
    }
    // Every command that reads the scene rejects it before any work, with the same line.
    let dir = tempfile::tempdir().unwrap();
    let mut v = valid();
    v["objects"][0]["size"][0] = json!(1e20);
    let scenes = dir.path().join("scenes");
    std::fs::create_dir(&scenes).unwrap();
    let file = write_file(&scenes, "scene.json", &v.to_string());
    let expected =
        format!("error: {}: objects[0].size[0]: 1e20 is outside the allowed range 0 to 10\n", file.display());
    for args in [
        &["inspect", "{}"][..],
        &["check", "{}"],
        &["repair", "{}", "--out", "{out}"],
        &["export", "{}", "--format", "mjcf", "--out", "{out}"],
        &["conditions", "{}", "--out", "{out}"],
        &["eval", "--pred", "{dir}", "--ref", "{dir}", "--no-physics"],
    ] {
        let (code, err) = run_on(&file, dir.path(), args);
        assert_eq!((code, err.as_str()), (Some(2), expected.as_str()), "{args:?}");
        assert!(!dir.path().join("out").exists(), "{args:?} wrote nothing");
    }
}

#[test]
fn object_counts_beyond_the_room_type_s_slots_are_rejected() {
    rejects(
        |v| {
            let o = v["objects"][0].clone();
            let objects: Vec<Value> = (0..13)
                .map(|i| {
                    let mut o = o.clone();
                    o["id"] = json!(format!("o{i}"));
                    o
                })
                .collect();
            v["objects"] = json!(objects);
        },
        "objects: 13 objects, at most 12 allowed",
    );
}

#[test]
fn floor_plans_beyond_the_vertex_limit_or_a_room_s_size_are_rejected() {
    // 300 vertices on a circle: a valid simple polygon, past the 256-vertex limit.
    let circle: Vec<Value> = (0..300)
        .map(|i| {
            let a = i as f64 / 300.0 * std::f64::consts::TAU;
            json!([2.0 + 2.0 * a.cos(), 2.0 + 2.0 * a.sin()])
        })
        .collect();
    rejects(
        |v| v["floor_plan"]["polygon"] = json!(circle),
        "floor_plan.polygon: 300 floor polygon vertices, at most 256 allowed",
    );
    rejects(
        |v| v["floor_plan"]["polygon"] = json!([[0, 0], [400, 0], [400, 3.5], [0, 3.5]]),
        "floor_plan.polygon: 400 is outside the allowed range 0 to 50",
    );
}

#[test]
fn trailing_bytes_after_the_scene_are_rejected() {
    rejects_text(&format!("{}\0xyz", valid()), ": trailing characters");
    rejects_text(&format!("{}{{}}", valid()), ": trailing characters");
    // Whitespace after the document is fine.
    let dir = tempfile::tempdir().unwrap();
    let file = write_file(dir.path(), "scene.json", &format!("{}\n\n  \n", valid()));
    assert_eq!(shade_sim(&["inspect", file.to_str().unwrap()]).status.code(), Some(0));
}

#[test]
fn export_onto_its_own_input_is_refused_and_the_scene_kept() {
    let dir = tempfile::tempdir().unwrap();
    let text = valid().to_string();
    let file = write_file(dir.path(), "scene.json", &text);
    let same = dir.path().join(".").join("scene.json");
    for format in ["mjcf", "png", "glb"] {
        let out = shade_sim(&["export", file.to_str().unwrap(), "--format", format, "--out", same.to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(2), "{format}");
        let err = stderr(&out);
        assert_eq!(err, format!("error: {}: is the scene being exported; choose another --out\n", same.display()));
        assert_eq!(std::fs::read_to_string(&file).unwrap(), text, "the scene is untouched");
    }
}

#[test]
fn an_error_names_the_input_not_the_output_and_batches_do_not_stop_half_way() {
    // A folder with a good scene and one whose size is 1e308 (it panicked inside parry half-way
    // through a batch, after the good one was written, and `polish` named its own output file).
    let dir = tempfile::tempdir().unwrap();
    let (inputs, bad) = good_and_bad_folder(dir.path(), |v| {
        v["humans"] = json!([]);
        v["objects"][0]["size"][1] = json!(1e308);
    });
    let out_dir = dir.path().join("out");
    for args in [
        vec!["repair", inputs.to_str().unwrap(), "--out", out_dir.to_str().unwrap()],
        vec!["check", inputs.to_str().unwrap()],
        vec!["generate", "--input", inputs.to_str().unwrap(), "--out", out_dir.to_str().unwrap()],
    ] {
        let out = shade_sim(&args);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(
            err,
            format!("error: {}: objects[0].size[1]: 1e308 is outside the allowed range 0 to 10\n", bad.display()),
            "{args:?}"
        );
        assert!(!out_dir.exists(), "{args:?}: nothing written");
    }
}
