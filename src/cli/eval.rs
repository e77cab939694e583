//! `shade-sim eval --pred DIR… --ref DIR [--json] [--no-physics] [--out FILE]`: SHADE's Table 1 for sets of
//! generated scenes.
//!
//! The reference gives the category frequencies for CKL: its `test` split when it is a dataset,
//! else all its scenes. Each `--pred` folder is one row. When the reference is a dataset with a
//! `train` split, the text table ends with the CKL that real training layouts score at the rows'
//! size (the floor a perfect generator would reach; `eval::ckl_floor`), and each row carries it as
//! `ckl_floor` in `--json` and `--out`; for rows as large as the test split, also the CKL of real
//! layouts that keep each test scene's own contact pieces (`eval::contact_floor`, `ckl_contact_floor`).
//! `--baseline NAME` adds each row's layout metrics relative to the row NAME (`layout_ratio`).
//! CKL by category (`categories` in JSON: both shares and each term) names, under the table, the
//! categories each row draws least often against the reference.
//!
//! Realism beyond SHADE's table, against the same reference scenes: each category's per-room count
//! distribution (`count KL`, the mean over categories of KL(reference ‖ row), and `unseen`, the
//! share of the row's rooms with a count no room of the training data has — the dataset's `train`
//! split, else the reference itself, and every split of each `--extra-data` dataset (a model's
//! second draw of training rooms); `counts` in JSON, with the offending category counts), `unreal`, the share of rooms with a piece further than 15 cm outside
//! its category's real sizes (`sizes` in JSON, by category and axis), `odd size`, the share of
//! pieces with a size the procedural data never draws for their category (`odd_pieces` in JSON;
//! 0 for the data), and SCA (`eval::sca`: the held-out accuracy of a small classifier
//! trained to tell the row's layouts from the reference's; 0.5 is indistinguishable). `--no-sca`
//! skips SCA.

use super::output::{print_json, print_text};
use super::{ExitStatus, GlobalArgs};
use anyhow::Context;
use clap::Args;
use rayon::prelude::*;
use shade_sim::eval::{
    CklFloor, CountDistribution, EvalRow, PhysicsRates, ScaConfig, category_frequencies, ckl_floor, contact_floor,
    count_report, evaluate, sca, size_report,
};
use shade_sim::scene::{Action, RoomType, Scene, SceneError};
use shade_sim::sim::{CheckConfig, ViolationKind, check_scene};
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
pub struct EvalArgs {
    /// Folders of generated scenes, one table row each.
    #[arg(long, required = true, num_args = 1..)]
    pub pred: Vec<PathBuf>,
    /// Reference dataset (its test split) or folder of scenes.
    #[arg(long = "ref")]
    pub reference: PathBuf,
    /// Skip the physics checks (faster).
    #[arg(long)]
    pub no_physics: bool,
    /// Also write the rows as JSON to this file (atomically).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// The row (a --pred folder's name) the others' layout metrics are compared with: adds the
    /// mean of Col_mot, R_out and Col_obj each over the baseline's (`layout_ratio`).
    #[arg(long)]
    pub baseline: Option<String>,
    /// Skip SCA, the classifier two-sample test (a few seconds a row).
    #[arg(long)]
    pub no_sca: bool,
    /// Another dataset of the reference's room type whose every split joins the rooms `unseen`
    /// counts against (the counts a real room has), as `train --extra-data` joins it to a model's
    /// training rooms; repeatable.
    #[arg(long)]
    pub extra_data: Vec<PathBuf>,
}

/// The scene files under `dir` (recursively, not stats.json / calibration.json), sorted; an error
/// when there are none. Shared by `eval`, `generate` and `demo`.
pub fn scene_files(dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let out = Scene::files_in(dir).map_err(|e| match e {
        SceneError::Io { file, error } => anyhow::anyhow!("{}: cannot read folder: {error}", file.display()),
        other => other.into(),
    })?;
    anyhow::ensure!(!out.is_empty(), "{}: no scene files", dir.display());
    Ok(out)
}

fn load_all(dir: &Path) -> anyhow::Result<Vec<Scene>> {
    Ok(load_named(dir)?.1)
}

/// The scene files under `dir` and their scenes, in the same order.
fn load_named(dir: &Path) -> anyhow::Result<(Vec<PathBuf>, Vec<Scene>)> {
    let files = scene_files(dir)?;
    let scenes = files.iter().map(Scene::load).collect::<Result<_, _>>()?;
    Ok((files, scenes))
}

/// The physics rates of `scenes`; a failure in one names its file (`files[i]` for `scenes[i]`).
fn physics(files: &[PathBuf], scenes: &[Scene]) -> anyhow::Result<PhysicsRates> {
    let reports: Vec<_> = scenes
        .par_iter()
        .zip(files)
        .map(|(s, f)| super::guarded(f, || Ok(check_scene(s, &CheckConfig::default()))))
        .collect();
    let reports = super::all_or_first_error(reports)?;
    let contact: usize = scenes
        .iter()
        .map(|s| {
            s.humans
                .iter()
                .filter(|h| h.actions.iter().any(|a| a.action != Action::Walk && a.action != Action::Stand))
                .count()
        })
        .sum();
    let objects: usize = scenes.iter().map(|s| s.objects.len()).sum();
    let rate = |a: usize, b: usize| if b == 0 { 0.0 } else { a as f64 / b as f64 };
    Ok(PhysicsRates {
        penetrating_scenes: rate(
            reports.iter().filter(|r| r.count(ViolationKind::Penetration) > 0).count(),
            scenes.len(),
        ),
        unsupported_humans: rate(reports.iter().map(|r| r.count(ViolationKind::Unsupported)).sum(), contact),
        unstable_objects: rate(reports.iter().map(|r| r.count(ViolationKind::Unstable)).sum(), objects),
        violating_scenes: rate(reports.iter().filter(|r| !r.is_clean()).count(), scenes.len()),
    })
}

pub fn run(args: &EvalArgs, global: &GlobalArgs) -> anyhow::Result<ExitStatus> {
    let test = args.reference.join("test");
    let reference = load_all(if test.is_dir() { &test } else { &args.reference })?;
    let room = reference[0].room_type;
    let freq = category_frequencies(reference.iter(), room);
    let counts = CountDistribution::of(&reference, room);
    // The training rooms, when the reference is a dataset with them: the pool of the CKL floors and
    // the counts a real room has.
    let train = args.reference.join("train");
    let pool = if test.is_dir() && train.is_dir() { Some(load_all(&train)?) } else { None };
    let mut extra = Vec::new();
    for dir in &args.extra_data {
        let scenes = load_all(dir)?;
        if let Some(s) = scenes.iter().find(|s| s.room_type != room) {
            anyhow::bail!("{}: holds {} scenes, the reference is {room}", dir.display(), s.room_type);
        }
        extra.extend(scenes);
    }
    let seen = CountDistribution::of(pool.as_deref().unwrap_or(&reference).iter().chain(&extra), room);
    let mut rows = Vec::new();
    for dir in &args.pred {
        let (files, scenes) = load_named(dir)?;
        if let Some(s) = scenes.iter().find(|s| s.room_type != room) {
            anyhow::bail!("{}: holds {} scenes, the reference is {room}", dir.display(), s.room_type);
        }
        // A split folder is named with its dataset: `bedroom-cal/test`.
        let last = |p: &Path| p.file_name().map(|n| n.to_string_lossy().into_owned());
        let name = match (last(dir), dir.parent().and_then(last)) {
            (Some(n), Some(parent)) if ["train", "val", "test"].contains(&n.as_str()) => format!("{parent}/{n}"),
            (Some(n), _) => n,
            _ => dir.display().to_string(),
        };
        let mut row = evaluate(&name, &scenes, room, &freq);
        if !args.no_physics {
            row.physics = Some(physics(&files, &scenes)?);
        }
        row.counts = Some(count_report(&scenes, &counts, &seen));
        row.sizes = Some(size_report(&scenes));
        if !args.no_sca {
            row.sca = sca(&scenes, &reference, &ScaConfig::default());
        }
        rows.push(row);
    }
    if let Some(name) = &args.baseline {
        let Some(base) = rows.iter().find(|r| &r.name == name).cloned() else {
            let names: Vec<&str> = rows.iter().map(|r| r.name.as_str()).collect();
            anyhow::bail!("--baseline {name}: no such row (rows: {})", names.join(", "));
        };
        for r in &mut rows {
            r.layout_ratio = Some(r.layout_ratio_to(&base));
        }
    }
    let (floors, contact) = match &pool {
        Some(pool) => ckl_floors(pool, &reference, &rows, room, &freq),
        None => (Vec::new(), None),
    };
    for r in &mut rows {
        r.ckl_floor = floors.iter().find(|f| f.layouts == r.scenes).copied();
        r.ckl_contact_floor = contact.filter(|f| f.layouts == r.scenes);
    }
    if let Some(out) = &args.out {
        let mut text = serde_json::to_string_pretty(&rows)?;
        text.push('\n');
        shade_sim::scene::write_atomic(out, text.as_bytes())
            .with_context(|| format!("{}: cannot write", out.display()))?;
    }
    if global.json {
        print_json(&rows)?;
    } else if global.quiet == 0 {
        print_text(&table(&rows))?;
        for f in &floors {
            print_text(&format!(
                "CKL of {} real layouts drawn from the train split ({} draws): mean {:.4}, p10 {:.4}, p90 {:.4}\n",
                f.layouts, f.draws, f.mean, f.p10, f.p90
            ))?;
        }
        if let Some(f) = contact {
            print_text(&format!(
                "CKL of the test scenes' own contact pieces, the rest drawn from the train split ({} draws): mean {:.4}, p10 {:.4}, p90 {:.4}\n",
                f.draws, f.mean, f.p10, f.p90
            ))?;
        }
        for r in &rows {
            print_text(&largest_ckl_terms(r))?;
        }
    }
    Ok(ExitStatus::Success)
}

/// Categories named per row under the table.
const CKL_TERMS_SHOWN: usize = 3;

/// The row's largest CKL terms, one line: the categories it draws least often against the
/// reference, with both shares.
fn largest_ckl_terms(row: &EvalRow) -> String {
    let terms: Vec<String> = row
        .categories
        .iter()
        .filter(|c| c.ckl_term > 0.0)
        .take(CKL_TERMS_SHOWN)
        .map(|c| {
            format!("{} {:.4} ({:.2} % → {:.2} %)", c.category, c.ckl_term, 100.0 * c.reference, 100.0 * c.generated)
        })
        .collect();
    match terms.is_empty() {
        true => format!("CKL's largest terms, {}: none\n", row.name),
        false => format!(
            "CKL's largest terms, {} (share of the reference's pieces → the row's): {}\n",
            row.name,
            terms.join(", ")
        ),
    }
}

/// Draws of real layouts per floor.
const FLOOR_DRAWS: usize = 200;

/// The CKL floor for each distinct row size, drawn from the dataset's train split `pool`, and the
/// contact floor of its `test` scenes when a row is as large as they are.
fn ckl_floors(
    pool: &[Scene],
    test: &[Scene],
    rows: &[EvalRow],
    room: RoomType,
    freq: &[f64],
) -> (Vec<CklFloor>, Option<CklFloor>) {
    let mut sizes: Vec<usize> = rows.iter().map(|r| r.scenes).collect();
    sizes.sort_unstable();
    sizes.dedup();
    let contact = sizes.contains(&test.len()).then(|| contact_floor(test, pool, room, freq, FLOOR_DRAWS, 0)).flatten();
    (sizes.into_iter().filter_map(|n| ckl_floor(pool, room, freq, n, FLOOR_DRAWS, 0)).collect(), contact)
}

fn table(rows: &[EvalRow]) -> String {
    let ratio = rows.iter().any(|r| r.layout_ratio.is_some());
    let mut t = String::from(
        "method               scenes  contact IoU↑  Col_mot↓  R_out↓  Col_obj↓  CKL↓    count KL↓  unseen↓  unreal↓  odd size↓  SCA→0.5  E_pen↓  pen. scenes↓  unsupported↓  unstable↓  violating↓",
    );
    t.push_str(if ratio { "  layout÷base↓\n" } else { "\n" });
    for r in rows {
        let p = r.physics.map_or_else(
            || "             -             -          -           -".to_string(),
            |p| {
                format!(
                    "  {:>12.3}  {:>12.3}  {:>9.3}  {:>10.3}",
                    p.penetrating_scenes, p.unsupported_humans, p.unstable_objects, p.violating_scenes
                )
            },
        );
        let q = r.layout_ratio.map_or_else(String::new, |q| format!("  {q:>12.3}"));
        let (count_kl, unseen) = r
            .counts
            .as_ref()
            .map_or(("-".into(), "-".into()), |c| (format!("{:.3}", c.count_kl), format!("{:.3}", c.unseen_rooms)));
        let sca = r.sca.as_ref().map_or("-".into(), |s| format!("{:.3}", s.accuracy));
        let (unreal, odd) = r
            .sizes
            .as_ref()
            .map_or(("-".into(), "-".into()), |s| (format!("{:.3}", s.unreal_rooms), format!("{:.3}", s.odd_pieces)));
        t.push_str(&format!(
            "{:<20} {:>6}  {:>12.3}  {:>8.3}  {:>6.3}  {:>8.3}  {:>6.3}  {count_kl:>9}  {unseen:>7}  {unreal:>7}  {odd:>10}  {sca:>7}  {:>6.2}{p}{q}\n",
            r.name, r.scenes, r.contact_iou, r.col_mot, r.r_out, r.col_obj, r.ckl, r.e_pen
        ));
    }
    t
}
