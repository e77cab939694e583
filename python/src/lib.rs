//! `shade_sim._native`: the Python face of the shade-sim library, a thin layer over it.
//!
//! Scenes cross as [`PyScene`] (the library's `Scene` behind an `Arc`, immutable from Python);
//! violations and whole scenes as plain dicts (through their JSON form, so Python sees exactly
//! the file format); frames and boxes as numpy arrays. Every call that does real work releases
//! the GIL (and turns a panic, a bug, into a `RuntimeError`). Errors keep the command line's one-line text (without its `error: ` prefix):
//! `SceneError` for a scene that cannot be read or breaks the format, `ModelError` for a model
//! folder that cannot be loaded, `MotionError` for a motion that cannot be imported, `ValueError`
//! for a bad argument. The pure-Python parts
//! (`robosuite_arena`, the type stubs) live in `python/shade_sim/`.
//!
//! It adds no behaviour of its own: generation is `pipeline::make_layouts`, the check is
//! `sim::check_scene`, the exports are `export::scene_mjcf` and `export::mocap_motion`, the import
//! of motion is `pipeline::import_placed`.

use glam::DVec2;
use numpy::{PyArray2, PyArray3};
use pyo3::exceptions::{PyIndexError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList, PyString, PyTuple};
use shade_sim::export::{MjcfOptions, mocap_motion, robot_spot, scene_mjcf};
use shade_sim::generator::{Checkpoint, Generator, GuidanceConfig};
use shade_sim::human::{people_meeting, seats_in_the_way};
use shade_sim::motion::{ImportOptions, Placement, Trim, Units, UpAxis, npy::read_npz, read_motion};
use shade_sim::pipeline::{
    LayoutOptions, import_placed, input_notes, make_grouped_layouts, off_the_floor_warnings, people_in_walls_message,
    rejections_message, room_groups,
};
use shade_sim::repair::RepairConfig;
use shade_sim::scene::{ActionSpan, FloorPlan, RoomType, Scene, validate_floor_plan};
use shade_sim::sim::{CheckConfig, check_scene};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};

pyo3::create_exception!(
    shade_sim,
    SceneError,
    PyValueError,
    "A scene that cannot be read or breaks the shade-scene/1 format (the CLI's `error:` line)."
);
pyo3::create_exception!(
    shade_sim,
    MotionError,
    PyValueError,
    "A motion file or array that cannot be imported (the CLI's `error:` line)."
);
pyo3::create_exception!(
    shade_sim,
    ModelError,
    PyValueError,
    "A model folder (config.json + model.safetensors) that cannot be loaded."
);

/// A shade-scene/1 scene: a room type, a floor plan, objects and humans. Immutable; `generate`
/// returns new ones.
#[pyclass(frozen, name = "Scene", module = "shade_sim")]
struct PyScene {
    scene: Arc<Scene>,
}

impl PyScene {
    fn new(scene: Scene) -> PyScene {
        PyScene { scene: Arc::new(scene) }
    }
}

#[pymethods]
impl PyScene {
    /// The room type: "bedroom", "living" or "dining".
    #[getter]
    fn room_type(&self) -> String {
        self.scene.room_type.to_string()
    }

    /// The objects' ids, in file order.
    #[getter]
    fn object_ids(&self) -> Vec<String> {
        self.scene.objects.iter().map(|o| o.id.clone()).collect()
    }

    /// The objects' categories, in file order.
    #[getter]
    fn categories(&self) -> Vec<String> {
        self.scene.objects.iter().map(|o| o.category.name().to_string()).collect()
    }

    /// The humans' ids, in file order.
    #[getter]
    fn human_ids(&self) -> Vec<String> {
        self.scene.humans.iter().map(|h| h.id.clone()).collect()
    }

    /// The floor plan's polygon as an (N, 2) array (m, counter-clockwise).
    fn floor<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let rows: Vec<Vec<f64>> = self.scene.floor_plan.polygon.iter().map(|p| p.to_vec()).collect();
        Ok(PyArray2::from_vec2(py, &rows)?)
    }

    /// The objects' boxes as an (N, 7) array: centre x, y, z, size x, y, z (m), yaw (rad).
    fn boxes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let rows: Vec<Vec<f64>> = self
            .scene
            .objects
            .iter()
            .map(|o| vec![o.center[0], o.center[1], o.center[2], o.size[0], o.size[1], o.size[2], o.yaw])
            .collect();
        if rows.is_empty() {
            return Ok(PyArray2::zeros(py, [0, 7], false));
        }
        Ok(PyArray2::from_vec2(py, &rows)?)
    }

    /// The joint positions of a human (its index or id) as a (T, J, 3) array (m, z up).
    fn frames<'py>(&self, py: Python<'py>, human: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let index = match human.extract::<usize>() {
            Ok(i) => i,
            Err(_) => {
                let id: String = human.extract()?;
                self.scene
                    .humans
                    .iter()
                    .position(|h| h.id == id)
                    .ok_or_else(|| PyIndexError::new_err(format!("no human with id {id:?}")))?
            }
        };
        let h = self.scene.humans.get(index).ok_or_else(|| {
            PyIndexError::new_err(format!("human {index}: the scene has {}", self.scene.humans.len()))
        })?;
        let frames: Vec<Vec<Vec<f64>>> = h.frames.iter().map(|f| f.iter().map(|p| p.to_vec()).collect()).collect();
        Ok(PyArray3::from_vec3(py, &frames)?)
    }

    /// The scene as a dict of the file format (what `json.load` gives for its file).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let text = detached(py, || self.scene.to_json())?;
        py.import("json")?.call_method1("loads", (text,))
    }

    /// The scene as its file's text (pretty JSON, byte-identical for equal scenes).
    fn to_json(&self, py: Python<'_>) -> PyResult<String> {
        detached(py, || self.scene.to_json())
    }

    /// Writes the scene to `path` atomically (validated first).
    fn save(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        detached(py, || self.scene.save(&path))?.map_err(scene_error)
    }

    fn __repr__(&self) -> String {
        format!(
            "Scene({}, {} objects, {} humans)",
            self.scene.room_type,
            self.scene.objects.len(),
            self.scene.humans.len()
        )
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other.cast::<PyScene>().is_ok_and(|o| o.get().scene == self.scene)
    }
}

/// Runs `f` without the GIL. A panic inside the library (a bug: validated input never panics)
/// becomes a `RuntimeError` with the CLI's "internal error" text instead of pyo3's
/// `PanicException`, which `except Exception` does not catch.
fn detached<T: Send>(py: Python<'_>, f: impl FnOnce() -> T + Send) -> PyResult<T> {
    py.detach(|| std::panic::catch_unwind(std::panic::AssertUnwindSafe(f))).map_err(|payload| {
        let message = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "a panic".into());
        PyRuntimeError::new_err(format!("internal error: {message} (a bug: please report it with the input)"))
    })
}

fn scene_error(e: impl std::fmt::Display) -> PyErr {
    SceneError::new_err(e.to_string())
}

fn model_error(e: impl std::fmt::Display) -> PyErr {
    ModelError::new_err(e.to_string())
}

/// A scene from a `Scene`, a path (str or os.PathLike) or a dict of the file format (numpy arrays
/// allowed where the format has number arrays).
fn scene_of(py: Python<'_>, source: &Bound<'_, PyAny>) -> PyResult<Arc<Scene>> {
    if let Ok(scene) = source.cast::<PyScene>() {
        return Ok(scene.get().scene.clone());
    }
    if source.is_instance_of::<PyDict>() {
        let text = json_of(py, source).map_err(|e| SceneError::new_err(format!("<dict>: not JSON data: {e}")))?;
        return Scene::from_json(&text, Path::new("<dict>")).map(Arc::new).map_err(scene_error);
    }
    if source.is_instance_of::<PyString>() || source.hasattr("__fspath__")? {
        let path: PathBuf = source.extract()?;
        return detached(py, || Scene::load(&path))?.map(Arc::new).map_err(scene_error);
    }
    let kind = source.get_type().name()?;
    Err(PyValueError::new_err(format!("expected a Scene, a path or a dict, not {kind}")))
}

/// `value` as JSON text, numpy arrays and scalars (frames from a body model, say) written as
/// their lists.
fn json_of(py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<String> {
    let kwargs = PyDict::new(py);
    kwargs.set_item("default", py.import("operator")?.getattr("methodcaller")?.call1(("tolist",))?)?;
    py.import("json")?.call_method("dumps", (value,), Some(&kwargs))?.extract()
}

/// Reads and validates a scene from a path (str or os.PathLike) or a dict of the file format.
#[pyfunction]
fn load_scene(py: Python<'_>, source: &Bound<'_, PyAny>) -> PyResult<PyScene> {
    Ok(PyScene { scene: scene_of(py, source)? })
}

/// The generators of the shipped models, loaded once per process and room type.
fn shipped_generator(room: RoomType) -> PyResult<Arc<Generator>> {
    static LOADED: OnceLock<Mutex<HashMap<RoomType, Arc<Generator>>>> = OnceLock::new();
    let mut loaded = LOADED.get_or_init(Default::default).lock().unwrap_or_else(|e| e.into_inner());
    if let Some(g) = loaded.get(&room) {
        return Ok(g.clone());
    }
    let generator = Arc::new(shade_sim::generator::shipped_generator(room).map_err(model_error)?);
    loaded.insert(room, generator.clone());
    Ok(generator)
}

/// Furnished layouts for `input` (a Scene, path or dict; or a list of them): sampled with each
/// room type's shipped model (or the model folder `model`), guided by `guidance` ("all", "none"
/// or a list of mot, bound, obj, phys, exact), repaired unless `repair` is False (a path: a
/// repair config file), and with `require_clean` resampled with new seeds (up to `attempts` rounds) until
/// `samples` layouts pass `check`. Returns the layouts kept (a list per input for a list), fewer
/// than `samples` (maybe none) where `require_clean` found no more. The same arguments give the
/// same scenes, byte for byte; a list gives what `shade-sim generate` gives for a folder of the
/// same inputs in the same order (and samples them in batches: faster than one at a time).
#[pyfunction]
#[pyo3(signature = (input, samples=1, seed=0, guidance="all", repair=None, require_clean=false, attempts=8, model=None))]
#[allow(clippy::too_many_arguments)]
fn generate<'py>(
    py: Python<'py>,
    input: &Bound<'py, PyAny>,
    samples: usize,
    seed: u64,
    guidance: &str,
    repair: Option<&Bound<'py, PyAny>>,
    require_clean: bool,
    attempts: usize,
    model: Option<PathBuf>,
) -> PyResult<Bound<'py, PyAny>> {
    if samples == 0 {
        return Err(PyValueError::new_err("samples: must be at least 1"));
    }
    if attempts == 0 {
        return Err(PyValueError::new_err("attempts: must be at least 1"));
    }
    let many = input.is_instance_of::<PyList>() || input.is_instance_of::<PyTuple>();
    let inputs: Vec<Scene> = if many {
        input.try_iter()?.map(|item| Ok((*scene_of(py, &item?)?).clone())).collect::<PyResult<_>>()?
    } else {
        vec![(*scene_of(py, input)?).clone()]
    };
    let guidance = GuidanceConfig::parse(guidance).map_err(|e| PyValueError::new_err(format!("guidance: {e}")))?;
    let repair = repair_of(repair)?;
    let groups = room_groups(&inputs);
    let custom = match &model {
        Some(dir) => Some(Arc::new(Generator::new(detached(py, || Checkpoint::load(dir))?.map_err(model_error)?))),
        None => None,
    };
    let mut generators = Vec::with_capacity(groups.len());
    for (room, _) in &groups {
        let generator = match &custom {
            Some(g) => g.clone(),
            None => shipped_generator(*room)?,
        };
        let model = &generator.checkpoint.meta.model;
        if !model.serves(*room) {
            let message = format!("input is a {room} but the model generates {}", model.room_names());
            return Err(PyValueError::new_err(message));
        }
        generators.push(generator);
    }
    // As the command line: more people in contact than the model conditions on, a floor unlike
    // its training rooms', said before sampling.
    for ((_, members), generator) in groups.iter().zip(&generators) {
        for &i in members {
            for note in input_notes(generator, &inputs[i]) {
                user_warning(py, &format!("input {i}: {note}"))?;
            }
        }
    }
    let opts = LayoutOptions { samples, seed, guidance, repair, require_clean, attempts, ..LayoutOptions::default() };
    let layouts = detached(py, || make_grouped_layouts(&inputs, &groups, &generators, &opts, &mut |_| {}))?
        .map_err(model_error)?;
    // As the command line's warnings: an input whose people are in a wall has no clean layout, and
    // people inside each other are the input's doing.
    for (i, (walls, input)) in layouts.people_in_walls.iter().zip(&inputs).enumerate() {
        let rejected = (require_clean && layouts.kept[i].is_empty()).then(|| rejections_message(&layouts.rejected[i]));
        if let Some(why) = people_in_walls_message(walls).or(rejected.flatten()) {
            user_warning(py, &format!("input {i}: {why}"))?;
        }
        for m in people_meeting(input, opts.check.tolerance) {
            user_warning(py, &format!("input {i}: {m}"))?;
        }
        for s in seats_in_the_way(input, opts.check.tolerance) {
            user_warning(py, &format!("input {i}: {s}"))?;
        }
        for w in off_the_floor_warnings(input, &opts.check) {
            user_warning(py, &format!("input {i}: {w}"))?;
        }
    }
    let mut per_input = layouts.kept.into_iter().map(|kept| kept.into_iter().map(|l| PyScene::new(l.scene)).collect());
    if many {
        let lists: Vec<Vec<PyScene>> = per_input.collect();
        Ok(lists.into_pyobject(py)?.into_any())
    } else {
        let only: Vec<PyScene> = per_input.next().unwrap_or_default();
        Ok(only.into_pyobject(py)?.into_any())
    }
}

/// A Python `UserWarning` with `message`.
fn user_warning(py: Python<'_>, message: &str) -> PyResult<()> {
    let message = std::ffi::CString::new(message).expect("no NUL in the message");
    PyErr::warn(py, &py.get_type::<pyo3::exceptions::PyUserWarning>(), &message, 1)
}

/// `repair=`: None or True (the default repair), False (none), or a repair config file's path.
fn repair_of(repair: Option<&Bound<'_, PyAny>>) -> PyResult<Option<RepairConfig>> {
    let Some(value) = repair else { return Ok(Some(RepairConfig::default())) };
    if let Ok(on) = value.extract::<bool>() {
        return Ok(on.then(RepairConfig::default));
    }
    let path: PathBuf = value
        .extract()
        .map_err(|_| PyValueError::new_err("repair: expected True, False or a repair config file's path"))?;
    RepairConfig::load(&path).map(Some).map_err(|e| PyValueError::new_err(e.to_string()))
}

/// The physics check of a scene: every violation as a dict (kind, human, bone, object, other,
/// frame, frames, depth; the keys `shade-sim check --json` writes). Empty: the scene passes.
/// `stability=False` skips the furniture stability run (the slow part). People inside each other
/// (no layout causes or mends that) are a `UserWarning`.
#[pyfunction]
#[pyo3(signature = (scene, stability=true))]
fn check<'py>(py: Python<'py>, scene: &Bound<'py, PyAny>, stability: bool) -> PyResult<Bound<'py, PyAny>> {
    let scene = scene_of(py, scene)?;
    let cfg = CheckConfig { stability, ..CheckConfig::default() };
    let report = detached(py, || check_scene(&scene, &cfg))?;
    for m in people_meeting(&scene, cfg.tolerance) {
        user_warning(py, &m.to_string())?;
    }
    let text = serde_json::to_string(&report.violations).expect("violations serialise");
    py.import("json")?.call_method1("loads", (text,))
}

/// The scene as a MuJoCo world (MJCF text): static furniture (or free bodies with
/// `free_furniture`), the humans as mocap capsules, their motion as keyframes (unless `keyframes`
/// is False), contact pairs between bones and static geoms (unless `contact_pairs` is False, as
/// robosuite environments need).
#[pyfunction]
#[pyo3(signature = (scene, free_furniture=false, keyframes=true, contact_pairs=true))]
fn to_mjcf(
    py: Python<'_>,
    scene: &Bound<'_, PyAny>,
    free_furniture: bool,
    keyframes: bool,
    contact_pairs: bool,
) -> PyResult<String> {
    let scene = scene_of(py, scene)?;
    detached(py, || scene_mjcf(&scene, MjcfOptions { free_furniture, keyframes, contact_pairs }))
}

/// The humans' motion for the mocap bodies of `to_mjcf`: a dict with `fps`, `bodies` (names) and
/// `frames`, a (T, B, 7) array of position and quaternion (w, x, y, z) per body.
#[pyfunction]
fn mocap_motion_of<'py>(py: Python<'py>, scene: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyDict>> {
    let scene = scene_of(py, scene)?;
    let motion = detached(py, || mocap_motion(&scene))?;
    let out = PyDict::new(py);
    out.set_item("fps", motion.fps)?;
    out.set_item("bodies", PyList::new(py, &motion.bodies)?)?;
    let frames: Vec<Vec<Vec<f64>>> = motion.frames.iter().map(|f| f.iter().map(|p| p.to_vec()).collect()).collect();
    let array = if frames.is_empty() || motion.bodies.is_empty() {
        PyArray3::zeros(py, [frames.len(), motion.bodies.len(), 7], false)
    } else {
        PyArray3::from_vec3(py, &frames)?
    };
    out.set_item("frames", array)?;
    Ok(out)
}

/// Where a robot's base can stand: the floor point (x, y) furthest from the walls, the
/// furniture's footprints and every place a person's joints pass over, or None when no point is
/// `clearance` metres clear.
#[pyfunction]
#[pyo3(signature = (scene, clearance=0.35))]
fn free_spot(py: Python<'_>, scene: &Bound<'_, PyAny>, clearance: f64) -> PyResult<Option<(f64, f64)>> {
    if !clearance.is_finite() || clearance < 0.0 {
        return Err(PyValueError::new_err("clearance: must be a non-negative number"));
    }
    let scene = scene_of(py, scene)?;
    Ok(detached(py, || robot_spot(&scene, clearance))?.map(|[x, y]| (x, y)))
}

/// `trim=`'s entry for one motion: (from, to) seconds, to None for the clip's end.
type TrimArg = (f64, Option<f64>);

/// A generation input from motion: `room`'s floor `floor` with one human per motion, in order
/// (ids h0, h1…), as `shade-sim import-motion` writes it. A motion is a file's path (BVH, .npy,
/// .npz) or the bytes of a .npz archive (`<motion k>` in errors; the Python wrapper makes them from
/// arrays). `floor`: (W, D) m from the origin, a list of (x, y) corners, or a scene (Scene, path,
/// dict) whose floor plan is taken; `height` is the ceiling of the first two. `place`, `trim` and
/// `actions` give one entry (or None) per motion, in order: (x, y, yaw_deg), (from, to) seconds
/// with to None for the end, and spans whose action is given rather than labelled; a place of
/// "auto" is the first of the plan's centre and a 5 × 5 grid, each facing four ways, that keeps the
/// clip inside the plan and out of its walls (`pipeline::import_placed`).
#[pyfunction]
#[pyo3(signature = (motions, room, floor, place=None, trim=None, fps=30.0, stature=None, units="auto", up="auto", source_fps=30.0, height=2.8, actions=None))]
#[allow(clippy::too_many_arguments)]
fn import_motion<'py>(
    py: Python<'py>,
    motions: Vec<Bound<'py, PyAny>>,
    room: &str,
    floor: &Bound<'py, PyAny>,
    place: Option<Vec<Option<Bound<'py, PyAny>>>>,
    trim: Option<Vec<Option<TrimArg>>>,
    fps: f64,
    stature: Option<f64>,
    units: &str,
    up: &str,
    source_fps: f64,
    height: f64,
    actions: Option<Vec<Option<Bound<'py, PyAny>>>>,
) -> PyResult<PyScene> {
    let room = RoomType::ALL
        .into_iter()
        .find(|r| r.to_string() == room)
        .ok_or_else(|| PyValueError::new_err(format!("room: {room:?} is not bedroom, living or dining")))?;
    let (place, trim, actions) = (place.unwrap_or_default(), trim.unwrap_or_default(), actions.unwrap_or_default());
    if place.len() > motions.len() || trim.len() > motions.len() || actions.len() > motions.len() {
        let most = motions.len();
        return Err(PyValueError::new_err(format!("place, trim and actions: one entry per motion, at most {most}")));
    }
    for (name, v) in [("fps", fps), ("source_fps", source_fps)] {
        if !(v.is_finite() && (1.0..=1000.0).contains(&v)) {
            return Err(PyValueError::new_err(format!("{name}: must be 1 to 1000 frames per second, not {v}")));
        }
    }
    if let Some(s) = stature.filter(|s| !(s.is_finite() && (0.5..=2.5).contains(s))) {
        return Err(PyValueError::new_err(format!("stature: must be 0.5 to 2.5 m, not {s}")));
    }
    let mut opts = ImportOptions::new(room, floor_plan_of(py, floor, height)?);
    // Each entry: None (kept where captured), "auto" (found by `place_to_fit`) or (x, y, yaw_deg).
    let mut auto = vec![false; place.len()];
    opts.places = Vec::with_capacity(place.len());
    for (k, p) in place.iter().enumerate() {
        let Some(p) = p else {
            opts.places.push(None);
            continue;
        };
        if p.extract::<String>().is_ok_and(|s| s == "auto") {
            auto[k] = true;
            opts.places.push(None);
            continue;
        }
        let (x, y, yaw) = p
            .extract::<(f64, f64, f64)>()
            .ok()
            .filter(|v| [v.0, v.1, v.2].iter().all(|x| x.is_finite()))
            .ok_or_else(|| PyValueError::new_err("place: each entry is None, \"auto\" or (x, y, yaw_deg)"))?;
        opts.places.push(Some(Placement { at: DVec2::new(x, y), yaw_degrees: yaw }));
    }
    opts.trims = trim.into_iter().map(|t| t.map(|(from, to)| Trim { from, to })).collect();
    opts.actions = actions
        .iter()
        .map(|spans| spans.as_ref().map_or(Ok(Vec::new()), |s| spans_of(py, s)))
        .collect::<PyResult<_>>()?;
    opts.fps = fps;
    opts.source_fps = source_fps;
    opts.stature = stature;
    opts.units = match units {
        "auto" => Units::Auto,
        "m" => Units::Metres,
        "cm" => Units::Centimetres,
        "in" => Units::Inches,
        "cmu" => Units::Cmu,
        _ => return Err(PyValueError::new_err(format!("units: {units:?} is not auto, m, cm, in or cmu"))),
    };
    opts.up = match up {
        "auto" => UpAxis::Auto,
        "y" => UpAxis::Y,
        "z" => UpAxis::Z,
        _ => return Err(PyValueError::new_err(format!("up: {up:?} is not auto, y or z"))),
    };
    enum Source {
        File(PathBuf),
        Npz(Vec<u8>),
    }
    let sources: Vec<Source> = motions
        .iter()
        .map(|m| match m.cast::<PyBytes>() {
            Ok(bytes) => Ok(Source::Npz(bytes.as_bytes().to_vec())),
            Err(_) => m.extract::<PathBuf>().map(Source::File).map_err(|_| {
                PyValueError::new_err(
                    "motions: each is a path, an array or a dict of arrays (or a .npz archive's bytes)",
                )
            }),
        })
        .collect::<PyResult<_>>()?;
    let (scene, reports) = detached(py, || {
        let clips = sources
            .iter()
            .enumerate()
            .map(|(k, source)| match source {
                Source::File(path) => Ok((path.clone(), read_motion(path, opts.source_fps)?)),
                Source::Npz(bytes) => {
                    let name = PathBuf::from(format!("<motion {k}>"));
                    read_npz(bytes, opts.source_fps)
                        .map(|clip| (name.clone(), clip))
                        .map_err(|m| shade_sim::motion::MotionError::invalid(name, m))
                }
            })
            .collect::<Result<Vec<_>, _>>()?;
        import_placed(&clips, &opts, &auto).map(|imported| (imported.scene, imported.reports))
    })?
    .map_err(|e| MotionError::new_err(e.to_string()))?;
    // As the command line's warnings.
    for r in reports.iter().filter(|r| !r.ever_upright) {
        let file = r.file.display();
        user_warning(
            py,
            &format!(
                "{file}: the trunk is never upright (within 45° of the up axis); if the person stands or sits at all, the up axis is wrong (up=)"
            ),
        )?;
    }
    for m in people_meeting(&scene, CheckConfig::default().tolerance) {
        user_warning(py, &format!("{m}; put their clips apart (place=)"))?;
    }
    for s in seats_in_the_way(&scene, CheckConfig::default().tolerance) {
        user_warning(py, &s.to_string())?;
    }
    Ok(PyScene::new(scene))
}

/// One motion's `actions=` entry: a list of `{"action": "sit", "start": 30, "end": 90}` (frames as
/// written), read as `--actions` reads its file.
fn spans_of(py: Python<'_>, spans: &Bound<'_, PyAny>) -> PyResult<Vec<ActionSpan>> {
    let not_spans =
        |e: &dyn std::fmt::Display| PyValueError::new_err(format!("actions: not a list of action spans: {e}"));
    let text: String = json_of(py, spans).map_err(|e| not_spans(&e))?;
    serde_json::from_str(&text).map_err(|e| not_spans(&e))
}

/// `floor=`: (W, D), a list of (x, y) corners, or a scene whose floor plan is taken.
fn floor_plan_of(py: Python<'_>, floor: &Bound<'_, PyAny>, height: f64) -> PyResult<FloorPlan> {
    if !(height.is_finite() && height > 0.0) {
        return Err(PyValueError::new_err(format!("height: must be a positive number of metres, not {height}")));
    }
    let plan = if let Ok((w, d)) = floor.extract::<(f64, f64)>() {
        if !(w.is_finite() && d.is_finite() && w > 0.0 && d > 0.0) {
            return Err(PyValueError::new_err(format!(
                "floor: ({w}, {d}): the sides must be positive numbers of metres"
            )));
        }
        FloorPlan::rectangle(w, d, height)
    } else if let Ok(polygon) = floor.extract::<Vec<[f64; 2]>>() {
        FloorPlan { polygon, height }
    } else {
        return scene_of(py, floor).map(|scene| scene.floor_plan.clone()).map_err(|e| {
            PyValueError::new_err(format!(
                "floor: expected (W, D) in metres, a list of (x, y) corners, or a scene (Scene, path or dict): {e}"
            ))
        });
    };
    // A plan the scene format refuses is named as the floor, not later as the first motion's input.
    match validate_floor_plan(&plan).first() {
        Some(problem) => Err(PyValueError::new_err(format!("floor: {problem}"))),
        None => Ok(plan),
    }
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyScene>()?;
    m.add("SceneError", m.py().get_type::<SceneError>())?;
    m.add("ModelError", m.py().get_type::<ModelError>())?;
    m.add("MotionError", m.py().get_type::<MotionError>())?;
    m.add_function(wrap_pyfunction!(load_scene, m)?)?;
    m.add_function(wrap_pyfunction!(generate, m)?)?;
    m.add_function(wrap_pyfunction!(check, m)?)?;
    m.add_function(wrap_pyfunction!(to_mjcf, m)?)?;
    m.add_function(wrap_pyfunction!(mocap_motion_of, m)?)?;
    m.add_function(wrap_pyfunction!(free_spot, m)?)?;
    m.add_function(wrap_pyfunction!(import_motion, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
