//! Saving and loading scenes: round trips, atomic writes, validation before writing.

use glam::DVec2;
use shade_sim::human::{Body, Motion, sit};
use shade_sim::scene::{Action, Category, FloorPlan, Object, ProblemKind, RoomType, Scene, SceneError};

fn scene() -> Scene {
    let mut s = Scene::new(
        RoomType::Dining,
        FloorPlan {
            polygon: vec![[0.0, 0.0], [5.0, 0.0], [5.0, 2.0], [3.0, 2.0], [3.0, 4.0], [0.0, 4.0]],
            height: 2.7,
        },
    );
    s.objects.push(Object {
        id: "o0".into(),
        category: Category::DiningTable,
        center: [1.5, 2.0, 0.375],
        size: [1.6, 0.9, 0.75],
        yaw: 0.1,
    });
    let body = Body::new(1.66);
    let mut m = Motion::new(body, 30.0);
    m.hold(sit(&body, DVec2::new(1.5, 1.2), 0.46, 0.0), 4, Action::Sit);
    s.humans.push(m.into_human("h0"));
    s
}

#[test]
fn save_then_load_round_trips_exactly() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("s.json");
    let s = scene();
    s.save(&path).unwrap();
    let back = Scene::load(&path).unwrap();
    assert_eq!(back, s);
    assert_eq!(back.to_json(), std::fs::read_to_string(&path).unwrap());
    // One frame per line: 4 frames → 4 lines that start with "[[".
    let frame_lines = back.to_json().lines().filter(|l| l.trim_start().starts_with("[[")).count();
    assert_eq!(frame_lines, 4);
}

/// Generated scenes carry arbitrary f64s (17 significant digits): reading and writing them again
/// gives the same bytes (serde_json parses floats exactly with `float_roundtrip`).
#[test]
fn generated_scene_files_load_and_save_byte_for_byte() {
    for file in crate::reference_scenes() {
        let text = std::fs::read_to_string(&file).unwrap();
        assert_eq!(Scene::load(&file).unwrap().to_json(), text, "{}", file.display());
    }
}

#[test]
fn an_invalid_scene_is_not_written_and_the_old_file_survives() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("s.json");
    let good = scene();
    good.save(&path).unwrap();
    let mut bad = good.clone();
    bad.objects[0].center[2] = f64::NAN;
    match bad.save(&path) {
        Err(SceneError::Invalid { problems, .. }) => {
            assert_eq!(problems[0].path, "objects[0].center");
            assert_eq!(problems[0].kind, ProblemKind::NotFinite);
        }
        other => panic!("expected Invalid, got {other:?}"),
    }
    assert_eq!(Scene::load(&path).unwrap(), good);
    let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(names.len(), 1, "no temporary files left: {names:?}");
}

#[test]
fn writing_into_a_missing_folder_is_an_io_error_naming_the_file() {
    let err = scene().save("/nonexistent/dir/s.json").unwrap_err();
    assert!(matches!(err, SceneError::Io { .. }));
    assert!(err.to_string().starts_with("/nonexistent/dir/s.json: "), "{err}");
}

#[test]
fn inputs_without_objects_or_humans_fields_load() {
    let text = r#"{"format": "shade-scene/1", "room_type": "living",
                  "floor_plan": {"polygon": [[0,0],[3,0],[3,3]], "height": 2.5}}"#;
    let s = Scene::from_json(text, std::path::Path::new("inline.json")).unwrap();
    assert!(s.objects.is_empty() && s.humans.is_empty());
}
