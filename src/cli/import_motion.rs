//! `shade-sim import-motion MOTION… --room R --floor WxD|PLAN.json --out SCENE.json`: motion
//! capture (BVH) and joint arrays (`.npy`/`.npz`) as a generation input, one human per file.

use super::output::{print_json, print_text, same_file};
use super::{ExitStatus, GlobalArgs, RoomArg};
use anyhow::{Context, bail};
use clap::{Args, ValueEnum};
use glam::DVec2;
use shade_sim::human::{people_meeting, seats_in_the_way};
use shade_sim::motion::{ImportOptions, MotionError, Placement, Trim, Units, UpAxis, read_motion};
use shade_sim::pipeline::{Imported, import_placed, off_the_floor_message};
use shade_sim::scene::{ActionSpan, FloorPlan, validate_floor_plan};
use shade_sim::sim::{CheckConfig, people_off_the_floor};
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
pub struct ImportMotionArgs {
    /// Motion files: BVH (.bvh) or joint positions (.npy, .npz); one human each, in order.
    #[arg(required = true)]
    pub motions: Vec<PathBuf>,
    /// Room type of the input.
    #[arg(long, value_enum)]
    pub room: RoomArg,
    /// The floor: `WxD` (a W × D m rectangle from the origin) or a JSON file holding a floor plan
    /// (a scene, or its `floor_plan` object).
    #[arg(long)]
    pub floor: String,
    /// The input to write (shade-scene/1, no objects).
    #[arg(long)]
    pub out: PathBuf,
    /// Put a clip's start at X,Y (m) facing YAW_DEG (0 faces +y), or `auto`: the first of the
    /// plan's centre and a 5 × 5 grid, each facing four ways, that keeps the clip inside the floor
    /// plan, out of its walls and apart from the clips placed before it; once per motion, in
    /// order. Without it, a clip keeps its own coordinates. X may be negative (`-1,2,90`).
    #[arg(long, value_name = "X,Y,YAW_DEG|auto", allow_hyphen_values = true)]
    pub place: Vec<String>,
    /// Frames per second of the humans written.
    #[arg(long, default_value_t = 30.0)]
    pub fps: f64,
    /// The person's stature (m): the clip is scaled to it. Default: measured from the clip, units
    /// detected.
    #[arg(long)]
    pub stature: Option<f64>,
    /// Units of the files' positions.
    #[arg(long, value_enum, default_value_t = UnitsArg::Auto)]
    pub units: UnitsArg,
    /// Up axis of the files.
    #[arg(long, value_enum, default_value_t = UpArg::Auto)]
    pub up: UpArg,
    /// Frame rate of .npy arrays (which carry none).
    #[arg(long, default_value_t = 30.0)]
    pub source_fps: f64,
    /// Ceiling height of a `WxD` floor (m).
    #[arg(long, default_value_t = 2.8)]
    pub height: f64,
    /// A JSON list of spans `{"action": "sit", "start": 30, "end": 90}` (frames as written) that
    /// override the automatic labels; once per motion, in order.
    #[arg(long)]
    pub actions: Vec<PathBuf>,
    /// Keep only the file's seconds FROM to TO (`FROM:` to its end); once per motion, in order.
    /// The written clip starts at FROM: its frames and times, in messages and --actions, count
    /// from there.
    #[arg(long, value_name = "FROM:TO", allow_hyphen_values = true)]
    pub trim: Vec<String>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum UnitsArg {
    Auto,
    M,
    Cm,
    In,
    /// The CMU database's unit (1/0.45 inch).
    Cmu,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum UpArg {
    Auto,
    Y,
    Z,
}

fn floor_of(arg: &str, height: f64) -> anyhow::Result<FloorPlan> {
    let rect = arg.split_once(['x', 'X']).and_then(|(w, d)| Some((w.parse::<f64>().ok()?, d.parse::<f64>().ok()?)));
    let (plan, name) = match rect {
        Some((w, d)) => {
            if !(w.is_finite() && d.is_finite() && w > 0.0 && d > 0.0 && height.is_finite() && height > 0.0) {
                bail!("--floor {arg}: the sides and --height must be positive numbers of metres");
            }
            (FloorPlan::rectangle(w, d, height), format!("--floor {arg}"))
        }
        None => {
            let text = std::fs::read_to_string(Path::new(arg))
                .with_context(|| format!("{arg}: not WxD, and not a readable file"))?;
            let value: serde_json::Value = serde_json::from_str(&text).with_context(|| format!("{arg}: not JSON"))?;
            let plan = value.get("floor_plan").cloned().unwrap_or(value);
            let plan = serde_json::from_value(plan)
                .with_context(|| format!("{arg}: not a floor plan (`polygon` and `height`)"))?;
            (plan, arg.to_string())
        }
    };
    // A plan the scene format refuses (a polygon crossing itself, a room over its size limits) is
    // named here, not later as the first motion's input.
    if let Some(problem) = validate_floor_plan(&plan).first() {
        bail!("{name}: {problem}");
    }
    Ok(plan)
}

/// `--place X,Y,YAW_DEG` (`Some`), or `--place auto` (`None`: found by `place_to_fit`).
fn placement(arg: &str) -> anyhow::Result<Option<Placement>> {
    if arg.trim() == "auto" {
        return Ok(None);
    }
    let v: Vec<f64> = arg.split(',').map(|s| s.trim().parse::<f64>()).collect::<Result<_, _>>().unwrap_or_default();
    match v[..] {
        [x, y, yaw] if v.iter().all(|x| x.is_finite()) => {
            Ok(Some(Placement { at: DVec2::new(x, y), yaw_degrees: yaw }))
        }
        _ => bail!("--place {arg}: expected X,Y,YAW_DEG (three numbers) or auto"),
    }
}

fn trim(arg: &str) -> anyhow::Result<Trim> {
    let number = |s: &str| s.trim().parse::<f64>().ok().filter(|v| v.is_finite());
    match arg.split_once(':') {
        Some((from, to)) if number(from).is_some() && (to.trim().is_empty() || number(to).is_some()) => {
            Ok(Trim { from: number(from).unwrap_or_default(), to: number(to) })
        }
        _ => bail!("--trim {arg}: expected FROM:TO or FROM: (seconds)"),
    }
}

fn spans(file: &Path) -> anyhow::Result<Vec<ActionSpan>> {
    let text = std::fs::read_to_string(file).with_context(|| file.display().to_string())?;
    serde_json::from_str(&text).with_context(|| format!("{}: not a list of action spans", file.display()))
}

pub fn run(args: &ImportMotionArgs, global: &GlobalArgs) -> anyhow::Result<ExitStatus> {
    if [&args.place, &args.trim].iter().any(|v| v.len() > args.motions.len()) || args.actions.len() > args.motions.len()
    {
        bail!("--place, --trim and --actions are given once per motion file, at most {}", args.motions.len());
    }
    for (name, v) in [("--fps", args.fps), ("--source-fps", args.source_fps)] {
        if !(v.is_finite() && (1.0..=1000.0).contains(&v)) {
            bail!("{name}: must be 1 to 1000 frames per second, not {v}");
        }
    }
    if let Some(s) = args.stature.filter(|s| !(s.is_finite() && (0.5..=2.5).contains(s))) {
        bail!("--stature: must be 0.5 to 2.5 m, not {s}");
    }
    let mut opts = ImportOptions::new(args.room.into(), floor_of(&args.floor, args.height)?);
    opts.places = args.place.iter().map(|p| placement(p)).collect::<anyhow::Result<_>>()?;
    let auto: Vec<bool> = args.place.iter().map(|p| p.trim() == "auto").collect();
    opts.actions = args.actions.iter().map(|f| spans(f)).collect::<anyhow::Result<_>>()?;
    opts.trims = args.trim.iter().map(|t| trim(t).map(Some)).collect::<anyhow::Result<_>>()?;
    opts.fps = args.fps;
    opts.source_fps = args.source_fps;
    opts.stature = args.stature;
    opts.units = match args.units {
        UnitsArg::Auto => Units::Auto,
        UnitsArg::M => Units::Metres,
        UnitsArg::Cm => Units::Centimetres,
        UnitsArg::In => Units::Inches,
        UnitsArg::Cmu => Units::Cmu,
    };
    opts.up = match args.up {
        UpArg::Auto => UpAxis::Auto,
        UpArg::Y => UpAxis::Y,
        UpArg::Z => UpAxis::Z,
    };
    if args.motions.iter().any(|m| same_file(m, &args.out)) {
        bail!("{}: --out is one of the motion files; it would be overwritten", args.out.display());
    }
    let clips = args
        .motions
        .iter()
        .map(|file| Ok((file.clone(), read_motion(file, opts.source_fps)?)))
        .collect::<Result<Vec<_>, MotionError>>()?;
    let Imported { scene, reports, places } = import_placed(&clips, &opts, &auto)?;
    scene.save(&args.out)?;
    for r in reports.iter().filter(|r| !r.ever_upright) {
        tracing::warn!(
            "{}: the trunk is never upright (within 45° of the up axis); if the person stands or sits at all, \
             the up axis is wrong (--up)",
            r.file.display()
        );
    }
    let meetings = people_meeting(&scene, CheckConfig::default().tolerance);
    for m in &meetings {
        tracing::warn!("{}: {m}; put their clips apart (--place)", args.out.display());
    }
    for s in seats_in_the_way(&scene, CheckConfig::default().tolerance) {
        tracing::warn!("{}: {s}", args.out.display());
    }
    let off_the_floor = people_off_the_floor(&scene, &CheckConfig::default());
    for v in &off_the_floor {
        tracing::warn!("{}: {}", args.out.display(), off_the_floor_message(&scene, v));
    }
    let place_of = |i: usize| places[i].map(|p| [p.at.x, p.at.y, p.yaw_degrees]);
    if global.json {
        let rows: Vec<serde_json::Value> = reports
            .iter()
            .zip(&scene.humans)
            .enumerate()
            .map(|(i, (r, h))| {
                serde_json::json!({
                    "file": r.file, "human": h.id, "place": place_of(i), "rig": r.rig, "metres_per_unit": r.scale, "y_up": r.y_up,
                    "stature": r.stature, "frames_read": r.frames.0, "frames_written": r.frames.1, "actions": r.actions,
                    "ever_upright": r.ever_upright,
                })
            })
            .collect();
        print_json(
            &serde_json::json!({ "out": args.out, "humans": rows, "people_meeting": meetings, "off_the_floor": off_the_floor }),
        )?;
    } else if global.quiet == 0 {
        let mut text = String::new();
        for (i, (r, h)) in reports.iter().zip(&scene.humans).enumerate() {
            let spans: Vec<String> =
                r.actions.iter().map(|s| format!("{} {}–{}", s.action.name(), s.start, s.end)).collect();
            let placed = match (auto.get(i), places[i]) {
                (Some(true), Some(p)) => {
                    format!(", placed at ({:.2}, {:.2}) facing {}°", p.at.x, p.at.y, p.yaw_degrees)
                }
                _ => String::new(),
            };
            text += &format!(
                "{} → {}{placed}: {} rig, {} m per unit, {}-up, {:.2} m tall, {} → {} frames at {} fps; {}\n",
                r.file.display(),
                h.id,
                r.rig,
                r.scale,
                if r.y_up { "y" } else { "z" },
                r.stature,
                r.frames.0,
                r.frames.1,
                args.fps,
                spans.join(", ")
            );
        }
        text += &format!("{}: {} humans, no objects\n", args.out.display(), scene.humans.len());
        print_text(&text)?;
    }
    Ok(ExitStatus::Success)
}
