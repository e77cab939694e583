//! `shade-sim conditions SCENE --out DIR`: the conditioning a generator reads, as files.
//!
//! Writes `free_space.png` and `floor.png` (256² masks over the room window), `contact_boxes.json`,
//! `floor_points.json`, `window.json` and `humans.png` (top and side views). Each file is written
//! atomically.

use super::output::{print_json, print_text};
use super::{ExitStatus, GlobalArgs};
use anyhow::Context;
use clap::Args;
use serde::Serialize;
use shade_sim::export::{mask_png, render_humans};
use shade_sim::human::{Conditions, ContactBox, FloorPoint};
use shade_sim::scene::{Scene, write_atomic};
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
pub struct ConditionsArgs {
    /// The scene file (shade-scene/1 JSON).
    pub scene: PathBuf,
    /// Output folder (created if missing).
    #[arg(long)]
    pub out: PathBuf,
}

#[derive(Serialize)]
struct Window {
    center: [f64; 2],
    side: f64,
    resolution: usize,
}

#[derive(Serialize)]
struct Report {
    scene: String,
    out: String,
    free_space_pixels: usize,
    floor_pixels: usize,
    contact_boxes: Vec<ContactBox>,
    files: Vec<String>,
}

pub fn run(args: &ConditionsArgs, global: &GlobalArgs) -> anyhow::Result<ExitStatus> {
    let scene = Scene::load(&args.scene)?;
    let c = Conditions::of(&scene);
    let out = &args.out;
    std::fs::create_dir_all(out).with_context(|| format!("{}: cannot create folder", out.display()))?;
    let window = Window { center: c.window.center.to_array(), side: c.window.side, resolution: shade_sim::geom::RES };
    let points: &Vec<FloorPoint> = &c.floor_points;
    let files: Vec<(&str, Vec<u8>)> = vec![
        ("free_space.png", mask_png(&c.free_space)),
        ("floor.png", mask_png(&c.floor)),
        ("contact_boxes.json", json_bytes(&c.contact_boxes)?),
        ("floor_points.json", json_bytes(points)?),
        ("window.json", json_bytes(&window)?),
        ("humans.png", render_humans(&scene).png_bytes()),
    ];
    for (name, bytes) in &files {
        write(out, name, bytes)?;
    }
    let report = Report {
        scene: args.scene.display().to_string(),
        out: out.display().to_string(),
        free_space_pixels: c.free_space.count(),
        floor_pixels: c.floor.count(),
        contact_boxes: c.contact_boxes,
        files: files.iter().map(|(n, _)| out.join(n).display().to_string()).collect(),
    };
    if global.json {
        print_json(&report)?;
    } else if global.quiet == 0 {
        let mut text = format!(
            "{}: free space {} px, floor {} px, {} contact boxes\n",
            report.scene,
            report.free_space_pixels,
            report.floor_pixels,
            report.contact_boxes.len()
        );
        for b in &report.contact_boxes {
            let o = &b.obox;
            text.push_str(&format!(
                "  {:<6} {:<5} frames {}–{}  centre ({:.2}, {:.2}, {:.2})  size {:.2} × {:.2} × {:.2}  yaw {:.2}\n",
                b.human,
                b.action,
                b.frames[0],
                b.frames[1],
                o.center.x,
                o.center.y,
                o.center.z,
                o.size.x,
                o.size.y,
                o.size.z,
                o.yaw
            ));
        }
        text.push_str(&format!("wrote {} files to {}\n", report.files.len(), report.out));
        print_text(&text)?;
    }
    Ok(ExitStatus::Success)
}

fn json_bytes<T: Serialize + ?Sized>(value: &T) -> anyhow::Result<Vec<u8>> {
    let mut bytes = serde_json::to_vec_pretty(value)?;
    bytes.push(b'\n');
    Ok(bytes)
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> anyhow::Result<()> {
    let path = dir.join(name);
    write_atomic(&path, bytes).with_context(|| format!("{}: cannot write", path.display()))
}
