//! The training curve as a PNG: training loss (blue) and EMA validation loss (orange) against the
//! step, on a log scale, with the range written on the axes.

use super::canvas::{Canvas, Color, View};
use super::font::draw_text;
use glam::DVec2;
use std::path::Path;

const WIDTH: u32 = 800;
const HEIGHT: u32 = 480;
const MARGIN: f64 = 60.0;
const TRAIN: Color = [40, 90, 200];
const VAL: Color = [230, 120, 20];
const INK: Color = [30, 30, 30];

/// One point of a training curve: the step, the training loss and, where measured, the
/// validation loss.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LossPoint {
    /// Optimiser step.
    pub step: u64,
    /// Training loss.
    pub loss: f64,
    /// Validation loss at this step, if measured.
    pub val_loss: Option<f64>,
}

/// Draws the curve `log` into a canvas.
pub fn loss_canvas(log: &[LossPoint]) -> Canvas {
    let mut canvas = Canvas::new(WIDTH, HEIGHT, [255, 255, 255]);
    // World coordinates are pixels with y up.
    let view = View { top_left: DVec2::new(0.0, HEIGHT as f64), scale: 1.0, offset: DVec2::ZERO };
    let (x0, x1, y0, y1) = (MARGIN, WIDTH as f64 - 20.0, MARGIN, HEIGHT as f64 - 30.0);
    canvas.line(&view, DVec2::new(x0, y0), DVec2::new(x1, y0), 1.0, INK);
    canvas.line(&view, DVec2::new(x0, y0), DVec2::new(x0, y1), 1.0, INK);
    let values = log.iter().flat_map(|l| std::iter::once(l.loss).chain(l.val_loss)).filter(|v| *v > 0.0);
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v.log10()), b.max(v.log10())));
    let last = log.last().map_or(1, |l| l.step.max(1));
    if lo.is_finite() {
        let hi = if hi - lo < 1e-6 { lo + 1.0 } else { hi };
        let at = |step: u64, v: f64| {
            DVec2::new(x0 + (x1 - x0) * step as f64 / last as f64, y0 + (y1 - y0) * (v.log10() - lo) / (hi - lo))
        };
        let train: Vec<DVec2> = log.iter().filter(|l| l.loss > 0.0).map(|l| at(l.step, l.loss)).collect();
        for w in train.windows(2) {
            canvas.line(&view, w[0], w[1], 1.5, TRAIN);
        }
        let val: Vec<DVec2> =
            log.iter().filter_map(|l| l.val_loss.filter(|v| *v > 0.0).map(|v| at(l.step, v))).collect();
        for w in val.windows(2) {
            canvas.line(&view, w[0], w[1], 2.0, VAL);
        }
        for p in &val {
            canvas.disc(&view, *p, 3.0, VAL);
        }
        draw_text(&mut canvas, 4, 26, &format!("{:.4}", 10f64.powf(hi)), 1, INK);
        draw_text(&mut canvas, 4, (HEIGHT as f64 - y0 - 4.0) as i64, &format!("{:.4}", 10f64.powf(lo)), 1, INK);
    }
    draw_text(&mut canvas, MARGIN as i64, 8, "LOSS - TRAIN", 2, TRAIN);
    draw_text(&mut canvas, MARGIN as i64 + 170, 8, "VAL EMA", 2, VAL);
    draw_text(&mut canvas, (WIDTH - 200) as i64, (HEIGHT as f64 - y0 + 10.0) as i64, &format!("STEP {last}"), 2, INK);
    canvas
}

/// Writes the training curve of `log` to `path`, atomically.
///
/// # Errors
/// Any I/O error of writing `path`.
pub fn render_loss_png(log: &[LossPoint], path: &Path) -> std::io::Result<()> {
    loss_canvas(log).save_png(path)
}
