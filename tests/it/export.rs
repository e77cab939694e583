//! MJCF export: deterministic text, names from ids, and the real MuJoCo (Rust and Python) loading
//! and stepping the worlds.

use crate::{reference_scenes, shade_sim};
use shade_sim::data::generate_room;
use shade_sim::export::{MjcfOptions, scene_mjcf};
use shade_sim::scene::RoomType;

/// A generated room saved and exported with `format` into a temporary folder: (folder, output).
#[cfg(feature = "mujoco")]
fn exported(room: RoomType, index: u64, format: &str, extra: &[&str]) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("room.json");
    generate_room(room, 4, index, false).scene.save(&scene).unwrap();
    let out = dir.path().join("room.xml");
    let mut args = vec!["-q", "export", scene.to_str().unwrap(), "--format", format, "--out", out.to_str().unwrap()];
    args.extend_from_slice(extra);
    let o = shade_sim(&args);
    assert_eq!(o.status.code(), Some(0), "{}", crate::stderr(&o));
    (dir, out)
}

/// Runs `script` with the python of the venv `venv` (made by the setup scripts) and `args`;
/// fails the test with Python's stderr when it fails.
#[cfg(feature = "mujoco")]
pub fn python(venv: &str, script: &str, args: &[&std::path::Path]) -> String {
    let out = std::process::Command::new(crate::root().join(venv).join("bin/python"))
        .env("PYTHONWARNINGS", "ignore")
        .arg("-c")
        .arg(script)
        .args(args)
        .output()
        .expect("the venv's python runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stdout).into_owned()
}

#[test]
fn mjcf_is_deterministic_and_named_after_the_scene() {
    let s = generate_room(RoomType::Living, 3, 7, false).scene;
    let a = scene_mjcf(&s, MjcfOptions::default());
    assert_eq!(a, scene_mjcf(&s.clone(), MjcfOptions::default()));
    for o in &s.objects {
        assert!(a.contains(&format!("<body name=\"{}\" ", o.id)), "{}", o.id);
    }
    let bones: usize = s.humans.iter().map(|h| h.skeleton.bones.len()).sum();
    assert_eq!(a.matches("mocap=\"true\"").count(), bones);
    let frames = s.humans.iter().map(|h| h.frames.len()).max().unwrap();
    assert_eq!(a.matches("<key name=").count(), frames);
    // Static furniture needs explicit pairs, but only where a bone comes near a part.
    let parts: usize = s.objects.iter().map(|o| shade_sim::export::part_names(o).len()).sum();
    let pairs = a.matches("<pair ").count();
    assert!(pairs > 0 && pairs < bones * parts / 4, "{pairs} pairs of {} possible", bones * parts);
    let free = scene_mjcf(&s, MjcfOptions { free_furniture: true, ..MjcfOptions::default() });
    // Free pieces get joints and need no pairs; lamps stay fixed to the ceiling.
    for o in &s.objects {
        let joint = format!("<freejoint name=\"{}_free\"/>", o.id);
        let paired = free.contains(&format!("geom2=\"{}_", o.id));
        assert_eq!(free.contains(&joint), !o.category.is_hanging(), "{}", o.id);
        assert!(!paired || o.category.is_hanging(), "{}", o.id);
    }
}

#[cfg(feature = "mujoco")]
#[test]
fn exported_worlds_load_step_and_stay_put_in_mujoco() {
    use shade_sim::export::validate_in_mujoco;
    for room in RoomType::ALL {
        let s = generate_room(room, 3, 1, false).scene;
        for free in [false, true] {
            let v = validate_in_mujoco(
                &s,
                &scene_mjcf(&s, MjcfOptions { free_furniture: free, ..MjcfOptions::default() }),
                1000,
            )
            .unwrap();
            assert!(v.ok(), "{room} free={free}: {v:?}");
            assert!((v.seconds - 2.0).abs() < 1e-9);
        }
    }
    // A cabinet floating at 1 m falls when free: validation says so, naming it.
    let mut s = generate_room(RoomType::Bedroom, 3, 2, false).scene;
    let mut floating = s.objects[0].clone();
    floating.id = "floating".into();
    floating.category = shade_sim::scene::Category::Cabinet;
    floating.center = [s.objects[0].center[0], s.objects[0].center[1], 2.0];
    floating.size = [0.3, 0.3, 0.3];
    s.objects.push(floating);
    let v =
        validate_in_mujoco(&s, &scene_mjcf(&s, MjcfOptions { free_furniture: true, ..MjcfOptions::default() }), 1000)
            .unwrap();
    assert!(v.moved.iter().any(|(id, d)| id == "floating" && *d > 0.5), "{v:?}");
}

#[cfg(feature = "mujoco")]
#[test]
fn export_command_validates_and_python_mujoco_loads_the_file() {
    let (_dir, xml) = exported(RoomType::Dining, 0, "mjcf", &["--validate"]);
    // The Python package installed by scripts/setup_mujoco.sh: load, replay the keyframes, step.
    let script = r#"
import sys, mujoco, numpy as np
m = mujoco.MjModel.from_xml_path(sys.argv[1])
d = mujoco.MjData(m)
assert m.nkey > 0 and m.nmocap > 0
for k in range(m.nkey):
    mujoco.mj_resetDataKeyframe(m, d, k)
    mujoco.mj_forward(m, d)
for _ in range(500):
    mujoco.mj_step(m, d)
assert np.isfinite(d.qpos).all() and np.isfinite(d.xpos).all()
print(m.nbody, m.ngeom, m.nkey)
"#;
    python(".venv-mujoco", script, &[&xml]);
}

#[test]
fn export_without_the_feature_or_with_bad_input_exits_2() {
    let dir = tempfile::tempdir().unwrap();
    let o = shade_sim(&["export", "/nonexistent.json", "--out", dir.path().join("x.xml").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!dir.path().join("x.xml").exists());
}

#[test]
fn plan_png_shows_furniture_in_its_colour() {
    use shade_sim::export::{group_color, render_plan};
    let s = generate_room(RoomType::Bedroom, 3, 5, false).scene;
    let bed =
        s.objects.iter().find(|o| o.category.group() == shade_sim::scene::Group::Bed).expect("bedrooms have a bed");
    let image = render_plan(&s).into_image();
    // Sample the bed a quarter of the way along its depth from the centre, away from its label and
    // from people lying on it: at least some of those pixels carry the bed's colour.
    let polygon = s.floor_plan.polygon();
    let (min, max) = polygon.bounds();
    let scale = (900.0 - 80.0) / (max - min).max_element();
    let b = bed.obox();
    let hits = (0..40)
        .filter(|k| {
            let local = glam::DVec3::new((*k as f64 / 40.0 - 0.5) * b.size.x * 0.8, -b.size.y * 0.35, 0.0);
            let p = b.to_world(local);
            let (x, y) = (40.0 + (p.x - min.x) * scale, 60.0 + (max.y - p.y) * scale);
            image.get_pixel(x as u32, y as u32).0 == group_color(bed.category.group())
        })
        .count();
    assert!(hits >= 10, "{hits} of 40 samples in the bed's colour");
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("room.json");
    s.save(&scene).unwrap();
    let png = dir.path().join("plan.png");
    let o = shade_sim(&["-q", "export", scene.to_str().unwrap(), "--format", "png", "--out", png.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0));
    assert_eq!(image::open(&png).unwrap().to_rgb8(), image);
}

/// The robosuite arena loads with `robosuite.models.arenas.Arena`, merges into a
/// `MujocoWorldBase` with a Panda robot, steps, and the companion motion replays on the mocap
/// bodies (robosuite from scripts/setup_robosuite.sh).
#[cfg(feature = "mujoco")]
#[test]
fn robosuite_loads_the_arena_with_a_robot_and_replays_the_motion() {
    let (dir, xml) = exported(RoomType::Living, 2, "robosuite", &[]);
    let motion: shade_sim::export::MocapMotion =
        serde_json::from_slice(&std::fs::read(dir.path().join("room.motion.json")).unwrap()).unwrap();
    assert!(!motion.frames.is_empty() && motion.frames[0].len() == motion.bodies.len());
    assert!(!std::fs::read_to_string(&xml).unwrap().contains("<keyframe>"));
    let script = r#"
import json, sys, numpy as np, mujoco
from robosuite.models.arenas import Arena
from robosuite.models.world import MujocoWorldBase
from robosuite.models.robots import Panda
world = MujocoWorldBase()
world.merge(Arena(sys.argv[1]))
robot = Panda()
robot.set_base_xpos([0.5, 0.5, 0.0])
world.merge(robot)
model = world.get_model(mode="mujoco")
d = mujoco.MjData(model)
motion = json.load(open(sys.argv[2]))
ids = [model.body(name).mocapid[0] for name in motion["bodies"]]
for frame in motion["frames"]:
    for i, p in zip(ids, frame):
        d.mocap_pos[i] = p[:3]
        d.mocap_quat[i] = p[3:]
    mujoco.mj_step(model, d)
assert np.isfinite(d.qpos).all() and np.isfinite(d.xpos).all()
assert np.allclose(d.mocap_pos[ids[0]], motion["frames"][-1][0][:3])
print("ok", model.nbody, model.nmocap)
"#;
    let motion_file = dir.path().join("room.motion.json");
    assert!(python(".venv", script, &[&xml, &motion_file]).starts_with("ok"));
}

/// The file name without its extension.
fn stem(p: &std::path::Path) -> String {
    p.file_stem().unwrap().to_string_lossy().into_owned()
}

/// The MJCF of every reference scene is the file in `mjcf/` (insta binary snapshots, so the
/// reference exports are plain XML files MuJoCo loads). `bash scripts/build_reference_scenes.sh`
/// rewrites them.
#[test]
fn reference_exports_match_the_snapshots() {
    let references = reference_scenes();
    assert_eq!(references.len(), crate::example_scenes().len(), "one reference scene per example");
    for file in references {
        let scene = shade_sim::scene::Scene::load(&file).unwrap();
        // A reference scene is its example furnished: same floor plan and people.
        let example =
            shade_sim::scene::Scene::load(crate::root().join("scenes/examples").join(file.file_name().unwrap()))
                .unwrap();
        assert!(example.objects.is_empty() && !scene.objects.is_empty());
        assert_eq!((&scene.floor_plan, &scene.humans), (&example.floor_plan, &example.humans));
        insta::with_settings!({
            snapshot_path => crate::root().join("mjcf"),
            prepend_module_to_snapshot => false,
            omit_expression => true,
        }, {
            insta::assert_binary_snapshot!(&format!("{}.xml", stem(&file)), scene_mjcf(&scene, MjcfOptions::default()).into_bytes());
        });
    }
}

/// Every example and reference scene exports to every format through the command line; the
/// Python `mujoco` package loads every MJCF world (static and free furniture), replays its
/// keyframes and steps it, robosuite loads every arena with a robot and replays the motion, and
/// the Khronos glTF validator passes every glb.
#[cfg(feature = "mujoco")]
#[test]
fn every_scene_exports_to_every_format_and_the_python_consumers_load_them() {
    let dir = tempfile::tempdir().unwrap();
    let (mut worlds, mut free_worlds, mut arenas) = (Vec::new(), Vec::new(), Vec::new());
    for file in crate::example_scenes().into_iter().chain(reference_scenes()) {
        let kind = if file.starts_with(crate::root().join("scenes/reference")) { "reference" } else { "example" };
        let name = format!("{kind}_{}", stem(&file));
        for (format, ext, extra) in [
            ("mjcf", "xml", None),
            ("mjcf", "free.xml", Some("--free-furniture")),
            ("robosuite", "arena.xml", None),
            ("png", "png", None),
            ("glb", "glb", None),
        ] {
            let out = dir.path().join(format!("{name}.{ext}"));
            let mut args =
                vec!["-q", "export", file.to_str().unwrap(), "--format", format, "--out", out.to_str().unwrap()];
            args.extend(extra);
            let o = shade_sim(&args);
            assert_eq!(o.status.code(), Some(0), "{name} {format}: {}", crate::stderr(&o));
            assert!(std::fs::metadata(&out).unwrap().len() > 1000, "{}", out.display());
        }
        worlds.push(dir.path().join(format!("{name}.xml")));
        free_worlds.push(dir.path().join(format!("{name}.free.xml")));
        arenas.push(dir.path().join(format!("{name}.arena.xml")));
    }
    // Static worlds: no furniture body moves. Free worlds (generated layouts may overlap, and
    // people push furniture): nothing explodes — finite, inside the room's box, and slower than 5 m/s
    // unless two pieces start more than 5 cm into each other (scenes/reference/bedroom_l: a
    // nightstand 25 cm into the bed, both holding people, which repair does not undo).
    // Reference scenes (with contact humans) report bone–furniture contacts through the pairs.
    let script = r#"
import sys, mujoco, numpy as np
for path in sys.argv[1:]:
    free = path.endswith(".free.xml")
    m = mujoco.MjModel.from_xml_path(path)
    d = mujoco.MjData(m)
    furniture = [b for b in range(1, m.nbody) if m.body_mocapid[b] < 0]
    touching = 0
    wedged = False
    for k in range(m.nkey):
        mujoco.mj_resetDataKeyframe(m, d, k)
        mujoco.mj_forward(m, d)
        touching += sum(1 for c in d.contact[:d.ncon] if m.geom_bodyid[c.geom1] in furniture or m.geom_bodyid[c.geom2] in furniture)
        # Two pieces starting more than 5 cm into each other are pushed apart hard: no speed bound.
        wedged |= any(c.dist < -0.05 and m.geom_bodyid[c.geom1] in furniture and m.geom_bodyid[c.geom2] in furniture for c in d.contact[:d.ncon])
    start = d.xpos[furniture].copy()
    lo, hi = d.xpos.min(axis=0) - 1.0, d.xpos.max(axis=0) + 1.0
    for _ in range(500):
        mujoco.mj_step(m, d)
    assert np.isfinite(d.qpos).all() and np.isfinite(d.qvel).all() and np.isfinite(d.xpos).all(), path
    moved = np.linalg.norm(d.xpos[furniture] - start, axis=1).max(initial=0.0)
    if free:
        assert (d.xpos >= lo).all() and (d.xpos <= hi).all(), path
        assert wedged or np.abs(d.qvel).max(initial=0.0) < 5.0, path
    else:
        assert moved < 1e-9, (path, moved)
    print(path.rsplit("/", 1)[-1], m.nbody, m.nkey, touching, round(float(moved), 3))
"#;
    let mut args: Vec<&std::path::Path> = worlds.iter().map(|p| p.as_path()).collect();
    args.extend(free_worlds.iter().map(|p| p.as_path()));
    let report = python(".venv-mujoco", script, &args);
    assert_eq!(report.lines().count(), worlds.len() * 2);
    // Wherever the exact check finds a bone in furniture, MuJoCo must see a contact too (a scene
    // whose people only rest on surfaces may have none), and some reference scene has one.
    let mut total = 0;
    for file in reference_scenes() {
        let line = report.lines().find(|l| l.starts_with(&format!("reference_{}.xml ", stem(&file)))).unwrap();
        let touching: usize = line.split(' ').nth(3).unwrap().parse().unwrap();
        let o = shade_sim(&["--json", "check", "--tolerance", "0", "--no-stability", file.to_str().unwrap()]);
        let checked: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        let penetrations = checked[0]["violations"].as_array().unwrap().iter().filter(|v| v["kind"] == "penetration");
        if penetrations.count() > 0 {
            assert!(touching > 0, "no bone–furniture contact reported in {line}");
        }
        total += touching;
    }
    assert!(total > 0, "{report}");
    let script = r#"
import json, sys, numpy as np, mujoco
from robosuite.models.arenas import Arena
from robosuite.models.world import MujocoWorldBase
from robosuite.models.robots import Panda
for arena in sys.argv[1:]:
    world = MujocoWorldBase()
    world.merge(Arena(arena))
    robot = Panda()
    robot.set_base_xpos([0.5, 0.5, 0.0])
    world.merge(robot)
    model = world.get_model(mode="mujoco")
    d = mujoco.MjData(model)
    motion = json.load(open(arena.replace(".arena.xml", ".arena.motion.json")))
    ids = [model.body(name).mocapid[0] for name in motion["bodies"]]
    for frame in motion["frames"][::3]:
        for i, p in zip(ids, frame):
            d.mocap_pos[i] = p[:3]
            d.mocap_quat[i] = p[3:]
        mujoco.mj_step(model, d)
    assert np.isfinite(d.qpos).all() and np.isfinite(d.xpos).all(), arena
    print("ok", arena.rsplit("/", 1)[-1], model.nbody)
"#;
    let args: Vec<&std::path::Path> = arenas.iter().map(|p| p.as_path()).collect();
    assert_eq!(python(".venv", script, &args).matches("ok ").count(), arenas.len());
    // The Khronos glTF validator (npm, installed by scripts/test.sh): no errors, no warnings.
    for glb in worlds.iter().map(|w| w.with_extension("glb")) {
        let o = std::process::Command::new("node")
            .arg(crate::root().join("scripts/glb_viewer/validate.mjs"))
            .arg(&glb)
            .output()
            .expect("node runs");
        let report = crate::stdout(&o);
        assert!(o.status.success() && report.contains(": 0 errors, 0 warnings"), "{report}{}", crate::stderr(&o));
    }
}

/// The glb parses back with the `gltf` crate: every object, part and bone is a named node, the
/// animation moves each bone through its midpoints, the root turns z-up into glTF's y-up, and
/// the floor's triangles cover the floor plan.
#[test]
fn glb_parses_back_with_the_scenes_nodes_and_motion() {
    let file = reference_scenes().into_iter().find(|f| stem(f) == "bedroom_l").unwrap();
    let scene = shade_sim::scene::Scene::load(&file).unwrap();
    let bytes = shade_sim::export::scene_glb(&scene);
    assert_eq!(bytes, shade_sim::export::scene_glb(&scene.clone()), "deterministic");
    let glb = gltf::Gltf::from_slice(&bytes).expect("a valid glb");
    let blob = glb.blob.clone().expect("a BIN chunk");
    let buffers = |_: gltf::Buffer| Some(blob.as_slice());
    let node = |name: &str| glb.nodes().find(|n| n.name() == Some(name)).unwrap_or_else(|| panic!("no node {name}"));
    for o in &scene.objects {
        let parts: Vec<String> = node(&o.id).children().map(|c| c.name().unwrap().to_string()).collect();
        let expected: Vec<String> = shade_sim::export::part_names(o).into_iter().map(|(n, _)| n).collect();
        assert_eq!(parts, expected);
    }
    // Root: scene +z is glTF +y.
    let root = glb.scenes().next().unwrap().nodes().next().unwrap();
    let (_, r, _) = root.transform().decomposed();
    let up = glam::Quat::from_array(r) * glam::Vec3::Z;
    assert!((up - glam::Vec3::Y).length() < 1e-6, "{up}");
    // Floor area.
    let floor = node("floor").mesh().unwrap().primitives().next().unwrap();
    let reader = floor.reader(buffers);
    let p: Vec<glam::Vec3> = reader.read_positions().unwrap().map(glam::Vec3::from).collect();
    let area: f32 = reader
        .read_indices()
        .unwrap()
        .into_u32()
        .collect::<Vec<_>>()
        .chunks(3)
        .map(|t| (p[t[1] as usize] - p[t[0] as usize]).cross(p[t[2] as usize] - p[t[0] as usize]).z * 0.5)
        .sum();
    assert!((f64::from(area) - scene.floor_plan.polygon().area()).abs() < 1e-3, "{area}");
    // The animation: two channels per bone; a bone's translation at frame f is its midpoint.
    let animation = glb.animations().next().expect("the motion");
    let bones: usize = scene.humans.iter().map(|h| h.skeleton.bones.len()).sum();
    assert_eq!(animation.channels().count(), 2 * bones);
    let (h, human) = scene.humans.iter().enumerate().max_by_key(|(_, h)| h.frames.len()).unwrap();
    let bone = &human.skeleton.bones[3];
    let name = format!("{}_{}-{}", human.id, human.skeleton.joints[bone.a], human.skeleton.joints[bone.b]);
    let channel = animation
        .channels()
        .find(|c| {
            c.target().node().name() == Some(name.as_str())
                && c.target().property() == gltf::animation::Property::Translation
        })
        .unwrap();
    let reader = channel.reader(buffers);
    let times: Vec<f32> = reader.read_inputs().unwrap().collect();
    assert_eq!(times.len(), human.frames.len());
    assert!((f64::from(*times.last().unwrap()) - (human.frames.len() - 1) as f64 / human.fps).abs() < 1e-5);
    let gltf::animation::util::ReadOutputs::Translations(t) = reader.read_outputs().unwrap() else { panic!() };
    for (f, got) in t.enumerate() {
        let mid = (human.joint_at(f, bone.a) + human.joint_at(f, bone.b)) * 0.5;
        assert!((glam::DVec3::from(got.map(f64::from)) - mid).length() < 1e-5, "human {h} frame {f}");
    }
}
