//! The command line: clap definitions, global flags, exit statuses and the dispatch to commands.
//!
//! Commands print human text by default and JSON with `--json` on stdout; logs go to stderr.
//! Only this module (and `main.rs`) uses anyhow; the library returns typed errors.

mod calibrate;
mod check;
mod conditions;
mod demo;
mod eval;
mod export;
mod generate;
mod guard;
mod import;
mod import_motion;
mod inspect;
mod output;
mod progress;
mod repair;
mod scene_rows;
mod synth;
mod train;

use clap::{Args, Parser, Subcommand};
use std::process::ExitCode;

/// Human-aware furniture layouts, proven physically.
#[derive(Debug, Parser)]
#[command(name = "shade-sim", version, about, propagate_version = true)]
pub struct Cli {
    #[command(flatten)]
    pub global: GlobalArgs,
    #[command(subcommand)]
    pub command: Command,
}

/// Flags every command takes.
#[derive(Debug, Args)]
pub struct GlobalArgs {
    /// More log output on stderr (-v info, -vv debug).
    #[arg(short, long, action = clap::ArgAction::Count, global = true)]
    pub verbose: u8,
    /// Less output: errors only.
    #[arg(short, long, action = clap::ArgAction::Count, global = true, conflicts_with = "verbose")]
    pub quiet: u8,
    /// Machine-readable JSON on stdout instead of text.
    #[arg(long, global = true)]
    pub json: bool,
    /// No progress bars.
    #[arg(long, global = true)]
    pub no_progress: bool,
}

/// A room type on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum RoomArg {
    Bedroom,
    Living,
    Dining,
}

impl RoomArg {
    pub fn name(self) -> &'static str {
        shade_sim::scene::RoomType::from(self).name()
    }
}

impl From<RoomArg> for shade_sim::scene::RoomType {
    fn from(r: RoomArg) -> Self {
        match r {
            RoomArg::Bedroom => shade_sim::scene::RoomType::Bedroom,
            RoomArg::Living => shade_sim::scene::RoomType::Living,
            RoomArg::Dining => shade_sim::scene::RoomType::Dining,
        }
    }
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Summarise a scene: room, objects by category, humans, actions, frames, extents.
    Inspect(inspect::InspectArgs),
    /// Write a scene's conditioning: free-space and floor masks (PNG), contact boxes and floor
    /// points (JSON), and a top/side view of the humans (PNG).
    Conditions(conditions::ConditionsArgs),
    /// Procedural human-populated rooms (a 3D-FRONT HUMAN stand-in): DIR/{train,val,test}/*.json
    /// and DIR/stats.json.
    Synth(synth::SynthArgs),
    /// SHADE's calibration: fix misplaced contact humans, augment actions and orientations;
    /// writes the calibrated dataset and a before/after report.
    Calibrate(calibrate::CalibrateArgs),
    /// Physical validation: penetrations, support, overlaps, walls, floor plan, stability.
    /// Exit 0 clean, 1 violations, 2 bad input.
    Check(check::CheckArgs),
    /// Metrics of generated scene sets against a reference: contact IoU, Col_mot, R_out, Col_obj,
    /// CKL, E_pen and physics rates (SHADE's Table 1).
    Eval(eval::EvalArgs),
    /// Export a scene: a MuJoCo world (MJCF) or robosuite arena with the humans as mocap bodies,
    /// a glb with their motion as an animation, or a top-down plan (PNG).
    Export(export::ExportArgs),
    /// The main job on the shipped models: generate layouts for every example input, check them
    /// physically, export MJCF, PNG plans and glb into out/demo, print a table.
    Demo(demo::DemoArgs),
    /// Generate furniture layouts for an input's floor plan and humans with a SHADE model.
    Generate(generate::GenerateArgs),
    /// Train the SHADE denoiser on a calibrated dataset (resumable; checkpoints on Ctrl-C).
    Train(train::TrainArgs),
    /// Repair layouts: small exact corrections (furniture under its contact humans, inside the
    /// walls, apart, off walking paths), step by step as a repair config says.
    Repair(repair::RepairArgs),
    /// Convert the licensed MIME release of 3D-FRONT HUMAN (folders of boxes.npz) to shade-scene/1.
    #[command(name = "import-3dfront-human")]
    Import3dfrontHuman(import::ImportArgs),
    /// Motion capture (BVH) or joint arrays (.npy/.npz) as a generation input: one human per file,
    /// retargeted to our body, on the floor, placed, resampled, its actions labelled.
    ImportMotion(import_motion::ImportMotionArgs),
}

/// How the process ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ExitStatus {
    /// Done, nothing found.
    Success,
    /// Done, and something was found (violations, failed checks).
    Found,
    /// Bad input or a failure.
    Error,
}

impl From<ExitStatus> for ExitCode {
    fn from(s: ExitStatus) -> ExitCode {
        match s {
            ExitStatus::Success => ExitCode::from(0),
            ExitStatus::Found => ExitCode::from(1),
            ExitStatus::Error => ExitCode::from(2),
        }
    }
}

/// Parses the process's arguments. Every command reads a number that starts with `-` as a value,
/// not a flag (`generate --eta -1`, `import-motion --place -1,2,90`), so that a negative number
/// reaches the option's own check and its one-line error instead of clap's "unexpected argument".
/// A value an option cannot take (`--samples -1`, `--room kitchen`) is one line, `error: invalid
/// value 'kitchen' for '--room <ROOM>' [possible values: bedroom, living, dining]`, and exit 2;
/// help, version and usage errors (a missing or unknown argument) exit as clap gives them, with
/// the usage.
pub fn parse_args() -> Cli {
    use clap::error::ErrorKind;
    use clap::{CommandFactory, FromArgMatches};
    let command = negative_numbers_are_values(Cli::command());
    let parsed = command.try_get_matches().and_then(|m| Cli::from_arg_matches(&m));
    parsed.unwrap_or_else(|e| match e.kind() {
        ErrorKind::InvalidValue | ErrorKind::ValueValidation => {
            // clap's first paragraph (the value, the option, the possible values), as one line.
            let text = e.to_string();
            let first: Vec<&str> = text.lines().take_while(|l| !l.trim().is_empty()).map(str::trim).collect();
            eprintln!("{}", first.join(" "));
            std::process::exit(2) // ExitStatus::Error: bad input
        }
        _ => e.exit(),
    })
}

fn negative_numbers_are_values(command: clap::Command) -> clap::Command {
    let names: Vec<String> = command.get_subcommands().map(|s| s.get_name().to_string()).collect();
    names
        .iter()
        .fold(command.allow_negative_numbers(true), |c, name| c.mut_subcommand(name, negative_numbers_are_values))
}

/// Runs the parsed command.
pub fn run(cli: Cli) -> anyhow::Result<ExitStatus> {
    let result = match &cli.command {
        Command::Inspect(args) => inspect::run(args, &cli.global),
        Command::Conditions(args) => conditions::run(args, &cli.global),
        Command::Synth(args) => synth::run(args, &cli.global),
        Command::Calibrate(args) => calibrate::run(args, &cli.global),
        Command::Check(args) => check::run(args, &cli.global),
        Command::Eval(args) => eval::run(args, &cli.global),
        Command::Export(args) => export::run(args, &cli.global),
        Command::Demo(args) => demo::run(args, &cli.global),
        Command::Generate(args) => generate::run(args, &cli.global),
        Command::Train(args) => train::run(args, &cli.global),
        Command::Repair(args) => repair::run(args, &cli.global),
        Command::Import3dfrontHuman(args) => import::run(args, &cli.global),
        Command::ImportMotion(args) => import_motion::run(args, &cli.global),
    };
    match result {
        Err(e) if output::is_broken_pipe(&e) => Ok(ExitStatus::Success),
        other => other,
    }
}

pub use guard::{all_or_first_error, guarded, panic_message, quiet_panics};

/// An error chain on one line: `outer: inner: innermost`, newlines folded.
pub fn one_line(e: &anyhow::Error) -> String {
    format!("{e:#}").replace('\n', " ")
}

/// Logs to stderr at a level set by -v / -q (warnings by default).
pub fn init_logging(global: &GlobalArgs) {
    use tracing::Level;
    let level = match (global.quiet, global.verbose) {
        (q, _) if q > 0 => Level::ERROR,
        (_, 0) => Level::WARN,
        (_, 1) => Level::INFO,
        _ => Level::DEBUG,
    };
    let _ = tracing_subscriber::fmt()
        .with_max_level(level)
        .with_writer(std::io::stderr)
        .with_target(false)
        .without_time()
        .try_init();
}
