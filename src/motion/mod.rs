//! Real human motion in: motion-capture files (BVH) and joint-position arrays (`.npy`/`.npz`)
//! turned into the humans of a `shade-scene/1` generation input.
//!
//! Reading ([`bvh`], [`npy`]) gives joint positions in the file's units and axes; [`rig`] finds
//! our 19 joints among them; [`import_motion`] then makes the up axis z, the units metres (from the
//! body's measured height), keeps the stretch of time asked for ([`Trim`]), puts the lowest toe
//! on the floor, places the clip where asked, resamples it and labels every frame's action
//! ([`labels`]); a pelvis or ankle that leaves the floor plan is an error naming the frame.
//! [`import_clips`] does the same for clips already read (arrays handed over in memory). A body
//! reaching into a wall is refused by the callers with the check's own test
//! (`pipeline::import_placed`). It does not generate furniture, and it does not smooth or fix
//! the motion beyond that.

pub mod bvh;
mod clip;
mod error;
pub mod labels;
pub mod npy;
pub mod rig;

pub use clip::{Clip, MAX_FRAMES, MAX_JOINTS, MAX_POSITIONS};
pub use error::MotionError;
pub use labels::{LabelConfig, label_frames};
pub use rig::{Retargeted, retarget};

use crate::human::{Body, Joint, Pose, round_mm, stand_local};
use crate::scene::{ActionSpan, FloorPlan, Human, RoomType, Scene, validate};
use glam::{DVec2, DVec3};
use std::path::{Path, PathBuf};

/// The units of a file's positions.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Units {
    /// Told by the body's height: 1–2.5 units tall is metres, 100–250 centimetres, 39–99 inches,
    /// 25–38 CMU's units.
    #[default]
    Auto,
    /// Metres.
    Metres,
    /// Centimetres.
    Centimetres,
    /// Inches.
    Inches,
    /// The CMU motion-capture database's length unit (its ASF files' 0.45 scale: 1/0.45 inch), kept
    /// by its BVH conversion.
    Cmu,
}

impl Units {
    /// Metres per unit (`None` for `Auto`).
    pub fn metres(self) -> Option<f64> {
        match self {
            Units::Auto => None,
            Units::Metres => Some(1.0),
            Units::Centimetres => Some(0.01),
            Units::Inches => Some(0.0254),
            Units::Cmu => Some(0.0254 / 0.45),
        }
    }

    /// The units in which a body `height` units tall is 1–2.5 m tall, if one is.
    fn detect(height: f64) -> Option<Units> {
        let ranges = [
            (Units::Metres, 1.0, 2.5),
            (Units::Centimetres, 100.0, 250.0),
            (Units::Inches, 39.0, 99.0),
            (Units::Cmu, 25.0, 38.9),
        ];
        ranges.into_iter().find(|(_, lo, hi)| (*lo..=*hi).contains(&height)).map(|(u, _, _)| u)
    }
}

/// The up axis of a file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum UpAxis {
    /// Whichever of y and z the body spans further along in the first frame.
    #[default]
    Auto,
    /// y up (BVH's usual convention): x stays, y becomes z, z becomes −y.
    Y,
    /// z up, as our scenes.
    Z,
}

/// Where a clip's start goes: its pelvis over `at`, facing `yaw_degrees` (0 faces +y, 90 faces −x:
/// the scenes' yaw convention).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    /// The floor position of the pelvis at the first frame (m).
    pub at: DVec2,
    /// The facing at the first frame (degrees).
    pub yaw_degrees: f64,
}

/// The stretch of a clip kept: from `from` seconds of the file to `to` (or its end). A capture's
/// calibration pose at the start, or a walk out of the room at the end, is left out this way.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Trim {
    /// Seconds of the file where the written clip starts (its frame 0).
    pub from: f64,
    /// Seconds of the file where it ends; `None`: the file's end.
    pub to: Option<f64>,
}

impl Trim {
    /// The frames of a clip at `fps` with `frames` frames that lie in `[from, to]` seconds, or why
    /// there are none.
    pub fn frames(&self, frames: usize, fps: f64) -> Result<std::ops::Range<usize>, String> {
        if frames == 0 {
            return Err("the clip has no frames to trim".into());
        }
        let end = (frames - 1) as f64 / fps;
        let shown = || match self.to {
            Some(to) => format!("--trim {}:{}", self.from, to),
            None => format!("--trim {}:", self.from),
        };
        let ordered = self.to.is_none_or(|to| to.is_finite() && self.from < to);
        if !(self.from.is_finite() && self.from >= 0.0 && ordered) {
            return Err(format!("{}: expected FROM:TO seconds with 0 ≤ FROM < TO", shown()));
        }
        let to = self.to.unwrap_or(end);
        if self.from > end {
            return Err(format!("{}: starts after the clip's end ({end:.2} s)", shown()));
        }
        // A hundredth of a frame of slack, as in resampling: frame times written to 6 digits.
        let first = (self.from * fps - 0.01).ceil().max(0.0) as usize;
        let last = ((to * fps + 0.01).floor() as usize).min(frames - 1);
        Ok(first..last + 1)
    }
}

/// How to import.
#[derive(Debug, Clone)]
pub struct ImportOptions {
    /// The room type of the input written.
    pub room_type: RoomType,
    /// Its floor plan.
    pub floor: FloorPlan,
    /// Placement of each clip, in file order (`None`, or a list shorter than the files: the clip
    /// keeps its own coordinates).
    pub places: Vec<Option<Placement>>,
    /// Frames per second of the humans written (default 30).
    pub fps: f64,
    /// The person's stature (m): the clip is scaled to it. `None`: measured, units detected.
    pub stature: Option<f64>,
    /// The files' units (where no stature is given).
    pub units: Units,
    /// The files' up axis.
    pub up: UpAxis,
    /// Frame rate of `.npy` arrays, which carry none (default 30).
    pub source_fps: f64,
    /// The action labeller's thresholds.
    pub labels: LabelConfig,
    /// Per clip, spans (in the written frames) whose action is given rather than labelled.
    pub actions: Vec<Vec<ActionSpan>>,
    /// Per clip, in file order, the stretch kept (`None`, or a list shorter than the files: all of
    /// it). Frames and times of the written clip count from its start.
    pub trims: Vec<Option<Trim>>,
}

impl ImportOptions {
    /// Defaults for a room: 30 fps, measured stature, detected units and up axis.
    pub fn new(room_type: RoomType, floor: FloorPlan) -> ImportOptions {
        ImportOptions {
            room_type,
            floor,
            places: Vec::new(),
            fps: 30.0,
            stature: None,
            units: Units::Auto,
            up: UpAxis::Auto,
            source_fps: 30.0,
            labels: LabelConfig::default(),
            actions: Vec::new(),
            trims: Vec::new(),
        }
    }
}

/// What the import found in one file.
#[derive(Debug, Clone, PartialEq)]
pub struct ImportReport {
    /// The file.
    pub file: PathBuf,
    /// The rig recognised (`rig::Retargeted::rig`).
    pub rig: &'static str,
    /// Metres per file unit.
    pub scale: f64,
    /// Whether the file was y-up.
    pub y_up: bool,
    /// The person's stature (m).
    pub stature: f64,
    /// Frames in the file, and written (after `--trim` and resampling).
    pub frames: (usize, usize),
    /// The spans written.
    pub actions: Vec<ActionSpan>,
    /// Whether the trunk is within 45° of upright in some frame. A clip that never is either lies
    /// throughout or was read with the wrong up axis (`--up`); the command warns.
    pub ever_upright: bool,
}

/// The stature of the person in `frames` (z-up, any unit), the larger of two estimates as
/// fractions of our standing body: the most the head joint rises above the lower toe (right where
/// the clip stands up at least once; rigs differ in where they put the pelvis and neck), and the
/// median over frames of the legs' and trunk's length — thigh, shank, pelvis to neck, neck to head
/// (right for a clip that never stands up).
pub fn measured_stature(frames: &[[DVec3; 19]]) -> f64 {
    let standing = stand_local(&Body::new(1.0)).0;
    let height =
        |p: &[DVec3; 19]| p[Joint::Head.index()].z - p[Joint::LeftToe.index()].z.min(p[Joint::RightToe.index()].z);
    let length = |p: &[DVec3; 19]| {
        let d = |a: Joint, b: Joint| p[a.index()].distance(p[b.index()]);
        let thigh = 0.5 * (d(Joint::LeftHip, Joint::LeftKnee) + d(Joint::RightHip, Joint::RightKnee));
        let shank = 0.5 * (d(Joint::LeftKnee, Joint::LeftAnkle) + d(Joint::RightKnee, Joint::RightAnkle));
        thigh + shank + d(Joint::Pelvis, Joint::Neck) + d(Joint::Neck, Joint::Head)
    };
    let tallest = frames.iter().map(height).fold(0.0, f64::max) / height(&standing);
    let mut lengths: Vec<f64> = frames.iter().map(length).collect();
    lengths.sort_by(f64::total_cmp);
    let median = lengths.get(lengths.len() / 2).map_or(0.0, |l| l / length(&standing));
    tallest.max(median)
}

/// A scene human's frames in our joint order (`None` if its skeleton lacks one of our joints).
pub fn body_frames(human: &Human) -> Option<Vec<[DVec3; 19]>> {
    let index: Vec<usize> = crate::scene::JOINT_NAMES.iter().map(|n| human.skeleton.joint(n)).collect::<Option<_>>()?;
    Some((0..human.frames.len()).map(|f| std::array::from_fn(|j| human.joint_at(f, index[j]))).collect())
}

/// Reads one motion file (`.bvh`, `.npy`, `.npz`) into a clip.
pub fn read_motion(file: &Path, source_fps: f64) -> Result<Clip, MotionError> {
    let bytes = std::fs::read(file).map_err(|error| MotionError::Io { file: file.to_path_buf(), error })?;
    let ext = file.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    let clip = match ext.as_str() {
        "bvh" => match std::str::from_utf8(&bytes) {
            Ok(text) => bvh::read_bvh(text),
            Err(e) => Err(format!("not a text file (byte {} is not UTF-8)", e.valid_up_to())),
        },
        "npy" => npy::read_npy(&bytes, source_fps),
        "npz" => npy::read_npz(&bytes, source_fps),
        _ => Err(format!("unknown motion format `.{ext}`: BVH (.bvh) or joint arrays (.npy, .npz)")),
    };
    clip.map_err(|message| MotionError::invalid(file, message))
}

/// A generation input: `opts.floor` with one human per file, in file order, ids `h0`, `h1`…
pub fn import_motion(files: &[PathBuf], opts: &ImportOptions) -> Result<(Scene, Vec<ImportReport>), MotionError> {
    let clips = files
        .iter()
        .map(|file| Ok((file.clone(), read_motion(file, opts.source_fps)?)))
        .collect::<Result<Vec<_>, MotionError>>()?;
    import_clips(&clips, opts)
}

/// [`import_motion`] of clips already read, each with the name its errors give (its file, or
/// `<motion 0>` for an array handed over in memory).
pub fn import_clips(
    clips: &[(PathBuf, Clip)],
    opts: &ImportOptions,
) -> Result<(Scene, Vec<ImportReport>), MotionError> {
    let mut scene = Scene {
        format: crate::scene::FORMAT.to_string(),
        room_type: opts.room_type,
        floor_plan: opts.floor.clone(),
        objects: Vec::new(),
        humans: Vec::new(),
    };
    let mut reports = Vec::new();
    for (i, (file, clip)) in clips.iter().enumerate() {
        let (human, report) = import_clip(clip, i, opts).map_err(|m| MotionError::invalid(file, m))?;
        scene.humans.push(human);
        reports.push(ImportReport { file: file.clone(), ..report });
    }
    if let Some(problem) = validate(&scene).into_iter().next() {
        // The file of the human at fault (`humans[k]…`), else the first (a floor plan's problem,
        // or the frames of all humans together).
        let human = problem.path.strip_prefix("humans[").and_then(|r| r.split(']').next()?.parse::<usize>().ok());
        let file = clips.get(human.unwrap_or(0)).map(|(file, _)| file.clone()).unwrap_or_default();
        return Err(MotionError::invalid(file, format!("the input it makes is not valid: {problem}")));
    }
    Ok((scene, reports))
}

/// One clip as the human `h{i}` of an input (`opts.places[i]` and `opts.actions[i]` apply to
/// it); the error is the message without the file.
pub fn import_clip(clip: &Clip, i: usize, opts: &ImportOptions) -> Result<(Human, ImportReport), String> {
    let place = opts.places.get(i).copied().flatten();
    let given = opts.actions.get(i).map_or(&[][..], Vec::as_slice);
    let read = clip.frames.len();
    let trimmed;
    let clip = match opts.trims.get(i).copied().flatten() {
        Some(trim) => {
            let kept = trim.frames(clip.frames.len(), clip.fps)?;
            let frames = clip.frames[kept].to_vec();
            trimmed = Clip { names: clip.names.clone(), parents: clip.parents.clone(), fps: clip.fps, frames };
            &trimmed
        }
        None => clip,
    };
    let y_up = match opts.up {
        UpAxis::Y => true,
        UpAxis::Z => false,
        UpAxis::Auto => {
            let extent = |axis: usize| {
                let v = clip.frames[0].iter().map(|p| p[axis]);
                v.clone().fold(f64::MIN, f64::max) - v.fold(f64::MAX, f64::min)
            };
            extent(1) > extent(2)
        }
    };
    let to_z_up = |p: DVec3| if y_up { DVec3::new(p.x, -p.z, p.y) } else { p };
    let upright =
        Clip { frames: clip.frames.iter().map(|f| f.iter().map(|&p| to_z_up(p)).collect()).collect(), ..clip.clone() };
    let Retargeted { rig, frames } = retarget(&upright, DVec3::Z)?;
    // Height and units.
    let toe = |f: &[DVec3; 19]| f[Joint::LeftToe.index()].z.min(f[Joint::RightToe.index()].z);
    let measured = measured_stature(&frames);
    let scale = match (opts.stature, opts.units.metres()) {
        (Some(stature), _) => stature / measured,
        (None, Some(metres)) => metres,
        (None, None) => Units::detect(measured).and_then(Units::metres).ok_or_else(|| {
            format!("cannot tell the units: the body is {measured:.3} units tall (is the up axis right?); pass --units or --stature")
        })?,
    };
    let stature = opts.stature.unwrap_or(measured * scale);
    if !(scale.is_finite() && scale > 0.0 && (0.5..=2.5).contains(&stature)) {
        return Err(format!("the body is {stature:.2} m tall once scaled; pass --units, --up or --stature"));
    }
    let body = Body::new(stature);
    let mut frames: Vec<[DVec3; 19]> = frames.iter().map(|f| f.map(|p| p * scale)).collect();
    if let Some(place) = place {
        placed(&mut frames, place);
    }
    let mut frames = resample(&frames, clip.fps, opts.fps);
    let lift = body.foot_radius() - frames.iter().map(toe).fold(f64::MAX, f64::min);
    frames.iter_mut().flatten().for_each(|p| p.z += lift);
    let polygon = opts.floor.polygon();
    for (f, pose) in frames.iter().enumerate() {
        for joint in [Joint::Pelvis, Joint::LeftAnkle, Joint::RightAnkle] {
            let p = pose[joint.index()];
            if !polygon.contains(p.truncate()) {
                return Err(format!(
                    "frame {f} ({:.2} s): the {} is outside the floor plan, at ({:.2}, {:.2}); place the clip with --place, or leave the frame out with --trim",
                    f as f64 / opts.fps,
                    crate::scene::JOINT_NAMES[joint.index()].replace('_', " "),
                    p.x,
                    p.y
                ));
            }
        }
    }
    let mut labels = label_frames(&frames, opts.fps, stature, &opts.labels);
    for span in given {
        if span.start >= span.end || span.end > frames.len() {
            return Err(format!(
                "--actions: span {}..{} is not within the {} frames written",
                span.start,
                span.end,
                frames.len()
            ));
        }
        labels[span.start..span.end].fill(span.action);
    }
    let actions = labels::runs(&labels);
    let ever_upright = frames.iter().any(|p| {
        let trunk = p[Joint::Neck.index()] - p[Joint::Pelvis.index()];
        trunk.angle_between(DVec3::Z) < std::f64::consts::FRAC_PI_4
    });
    let human = Human {
        id: format!("h{i}"),
        skeleton: body.skeleton(),
        fps: opts.fps,
        frames: frames
            .iter()
            .map(|f| f.iter().map(|p| [round_mm(p.x), round_mm(p.y), round_mm(p.z)]).collect())
            .collect(),
        actions: actions.clone(),
    };
    let report = ImportReport {
        file: PathBuf::new(),
        rig,
        scale,
        y_up,
        stature,
        frames: (read, frames.len()),
        actions,
        ever_upright,
    };
    Ok((human, report))
}

/// Moves and turns `frames` so that the first frame's pelvis is over `place.at`, facing its yaw.
fn placed(frames: &mut [[DVec3; 19]], place: Placement) {
    let first = Pose(frames[0]);
    let start = first.get(Joint::Pelvis).truncate().extend(0.0);
    let turn = place.yaw_degrees.to_radians() - first.yaw();
    for pose in frames.iter_mut() {
        *pose = Pose(*pose).translated(-start).placed(place.at.extend(0.0), turn).0;
    }
}

/// `frames` recorded at `from` fps, at `to` fps (linear between neighbours; the last frame kept
/// where the duration is not a whole number of new frames).
fn resample(frames: &[[DVec3; 19]], from: f64, to: f64) -> Vec<[DVec3; 19]> {
    let duration = (frames.len() - 1) as f64 / from;
    // (A frame time written to 6 digits, 0.033333, is not quite 30 fps: a hundredth of a frame
    // of slack keeps the last frame.)
    let n = (duration * to + 0.01).floor() as usize + 1;
    (0..n)
        .map(|k| {
            let t = k as f64 / to * from;
            let (a, w) = ((t.floor() as usize).min(frames.len() - 1), t.fract());
            let b = (a + 1).min(frames.len() - 1);
            Pose(frames[a]).lerp(&Pose(frames[b]), w).0
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::Trim;

    #[test]
    fn a_trim_keeps_the_frames_between_its_seconds_both_included() {
        let trim = |from, to| Trim { from, to };
        // 91 frames at 30 fps: 0 to 3 s.
        assert_eq!(trim(1.0, Some(2.0)).frames(91, 30.0), Ok(30..61));
        assert_eq!(trim(2.5, None).frames(91, 30.0), Ok(75..91));
        assert_eq!(trim(0.0, Some(10.0)).frames(91, 30.0), Ok(0..91));
        // A frame time written to 6 digits (0.033333 s) still lands on its frame.
        assert_eq!(trim(1.0, Some(2.0)).frames(91, 1.0 / 0.033333), Ok(30..61));
        assert!(trim(3.5, None).frames(91, 30.0).unwrap_err().contains("starts after the clip's end (3.00 s)"));
        assert!(trim(2.0, Some(1.0)).frames(91, 30.0).unwrap_err().contains("0 ≤ FROM < TO"));
        assert!(trim(f64::NAN, None).frames(91, 30.0).is_err());
        assert!(trim(0.0, Some(1.0)).frames(0, 30.0).unwrap_err().contains("no frames"));
    }
}
