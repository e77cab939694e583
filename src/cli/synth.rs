//! `shade-sim synth --room R --scenes N --seed S --out DIR [--require-clean]`: the procedural dataset.

use super::output::{print_json, print_text};
use super::{ExitStatus, GlobalArgs, RoomArg};
use clap::Args;
use shade_sim::data::layout::Spacing;
use shade_sim::data::{DatasetStats, SynthConfig, TOUCH_CHANCE, synthesize};
use shade_sim::physics::Physics;
use shade_sim::sim::SimPhysics;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct SynthArgs {
    /// Room type.
    #[arg(long, value_enum)]
    pub room: RoomArg,
    /// Number of rooms (split 80/10/10 into train, val, test).
    #[arg(long)]
    pub scenes: usize,
    /// Seed: the same seed gives the same files.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Output folder.
    #[arg(long)]
    pub out: PathBuf,
    /// Draw a room again (up to 8 draws) while `check` fails it with everyone where they were
    /// placed; stats.json counts the rooms that pass and those drawn again.
    #[arg(long)]
    pub require_clean: bool,
    /// Draw each gap the layout rules leave (a piece's back from its wall, a nightstand from its
    /// bed, a chair from its table, …) afresh for every piece, up to this far (m) either side of
    /// the rule's own; 0 keeps them exactly.
    #[arg(long, default_value_t = 0.0)]
    pub gap_spread: f64,
    /// Stand this share (0 to 1) of the sofas out in the room, facing in from a wall with their
    /// backs 0.8–1.4 m off it and a walkway behind, as open-plan rooms have them; 0 stands every
    /// sofa at a wall.
    #[arg(long, default_value_t = 0.0)]
    pub free_sofas: f64,
    /// Let a person touching a table (any piece that stands free of the walls) stand at any of its
    /// four sides, not only at its front: a hand on a dining table's end as well as its long side.
    #[arg(long)]
    pub touch_any_side: bool,
    /// The chance (0 to 1) that a piece people touch rather than sit or lie on (a table, a
    /// cabinet, a wardrobe) gets a person with a hand on it; 0.06 by default, the minority
    /// touching humans are in 3D-FRONT HUMAN.
    #[arg(long, default_value_t = TOUCH_CHANCE)]
    pub touch_chance: f64,
}

pub fn run(args: &SynthArgs, global: &GlobalArgs) -> anyhow::Result<ExitStatus> {
    anyhow::ensure!(args.scenes > 0, "--scenes: must be at least 1");
    anyhow::ensure!(
        args.gap_spread.is_finite() && (0.0..=0.2).contains(&args.gap_spread),
        "--gap-spread: must be between 0 and 0.2 (m), not {}",
        args.gap_spread
    );
    anyhow::ensure!(
        args.free_sofas.is_finite() && (0.0..=1.0).contains(&args.free_sofas),
        "--free-sofas: must be a share between 0 and 1, not {}",
        args.free_sofas
    );
    anyhow::ensure!(
        args.touch_chance.is_finite() && (0.0..=1.0).contains(&args.touch_chance),
        "--touch-chance: must be a chance between 0 and 1, not {}",
        args.touch_chance
    );
    // The layout and people settings that differ from the defaults, as the command line gave them.
    let mut flags = if args.gap_spread > 0.0 { format!(" --gap-spread {}", args.gap_spread) } else { String::new() };
    if args.free_sofas > 0.0 {
        flags.push_str(&format!(" --free-sofas {}", args.free_sofas));
    }
    if args.touch_any_side {
        flags.push_str(" --touch-any-side");
    }
    if args.touch_chance != TOUCH_CHANCE {
        flags.push_str(&format!(" --touch-chance {}", args.touch_chance));
    }
    let cfg = SynthConfig {
        room: args.room.into(),
        scenes: args.scenes,
        seed: args.seed,
        spacing: Spacing {
            spread: args.gap_spread,
            free_sofas: args.free_sofas,
            touch_any_side: args.touch_any_side,
            touch_chance: args.touch_chance,
        },
        command: format!(
            "shade-sim synth --room {} --scenes {} --seed {} --out {}{}{flags}",
            args.room.name(),
            args.scenes,
            args.seed,
            args.out.display(),
            if args.require_clean { " --require-clean" } else { "" }
        ),
    };
    let bar = super::progress::bar(global, args.scenes as u64, "synth");
    let start = std::time::Instant::now();
    let judge = args.require_clean.then_some(&SimPhysics as &dyn Physics);
    let stats = synthesize(&cfg, &args.out, judge, &|_| bar.inc(1))?;
    bar.finish_and_clear();
    if global.json {
        print_json(&stats)?;
    } else if global.quiet == 0 {
        print_text(&summary(&stats, &args.out, start.elapsed().as_secs_f64()))?;
    }
    Ok(ExitStatus::Success)
}

fn summary(s: &DatasetStats, out: &std::path::Path, seconds: f64) -> String {
    let all = s.all();
    let objects: usize = all.category_counts.values().sum();
    let mut text = format!(
        "{}: {} {} rooms ({} train, {} val, {} test), {} objects, category KL to 3D-FRONT {:.4}, {:.1} s\n",
        out.display(),
        all.rooms,
        s.room_type,
        s.splits["train"].rooms,
        s.splits["val"].rooms,
        s.splits["test"].rooms,
        objects,
        s.category_kl,
        seconds
    );
    if let (Some(passing), Some(redrawn)) = (all.passing_check, all.redrawn) {
        text.push_str(&format!(
            "  check (everyone where placed): {passing} of {} rooms pass, {redrawn} drawn again\n",
            all.rooms
        ));
    }
    let freq = all.frequencies(s.room_type);
    let target = shade_sim::data::target_frequencies(s.room_type);
    text.push_str("  category              ours   3D-FRONT\n");
    for (k, c) in s.room_type.categories().iter().enumerate() {
        text.push_str(&format!("  {:<20} {:>6.3} {:>9.3}\n", c.name(), freq[k], target[k]));
    }
    text
}
