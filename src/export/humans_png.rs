//! A picture of a scene's humans: a top view and a side view (looking along +y) side by side.
//!
//! Each human is drawn as its capsules: a faint pose every half second of walking or standing, and
//! the middle frame of every action span in full colour; contact boxes are outlined in the top view
//! and objects, if any, are grey footprints. This is for people checking poses and conditioning;
//! the full plan render with labels belongs to `export --format png`.

use super::canvas::{Canvas, Color, View};
use crate::human::contact_boxes;
use crate::scene::{Action, Human, Scene};
use glam::{DVec2, DVec3};

const PANEL: f64 = 560.0;
const MARGIN: f64 = 20.0;
const BACKGROUND: Color = [255, 255, 255];
const FLOOR: Color = [236, 232, 222];
const WALL: Color = [60, 60, 60];
const GRID: Color = [215, 215, 215];
const OBJECT: Color = [190, 190, 190];

/// Colour of an action (unlabelled frames are grey).
pub fn action_color(action: Option<Action>) -> Color {
    match action {
        Some(Action::Walk) => [40, 110, 220],
        Some(Action::Stand) => [20, 170, 190],
        Some(Action::Sit) => [235, 130, 20],
        Some(Action::Lie) => [150, 60, 200],
        Some(Action::Touch) => [30, 160, 70],
        None => [150, 150, 150],
    }
}

fn faint(c: Color) -> Color {
    c.map(|v| (v as u16 + 2 * 255).div_euclid(3) as u8)
}

/// Renders the top and side views of `scene`'s humans, each view 560 pixels square.
pub fn render_humans(scene: &Scene) -> Canvas {
    render_humans_sized(scene, PANEL)
}

/// As [`render_humans`], with views of `panel` pixels.
pub fn render_humans_sized(scene: &Scene, panel: f64) -> Canvas {
    let polygon = scene.floor_plan.polygon();
    let (min, max) = polygon.bounds();
    let height = scene.floor_plan.height;
    let span = (max - min).max_element().max(height).max(1.0);
    let scale = (panel - 2.0 * MARGIN) / span;
    let top = View { top_left: DVec2::new(min.x, max.y), scale, offset: DVec2::splat(MARGIN) };
    let side = View {
        top_left: DVec2::new(min.x, height),
        scale,
        offset: DVec2::new(panel + MARGIN, MARGIN + (max.y - min.y - height).max(0.0) * scale * 0.5),
    };
    let mut canvas = Canvas::new((2.0 * panel) as u32, panel as u32, BACKGROUND);

    // Top view: floor, 1 m grid, objects, walls.
    canvas.fill_polygon(&top, &polygon.points, FLOOR);
    grid(&mut canvas, &top, min, max);
    for o in &scene.objects {
        canvas.fill_polygon(&top, &o.obox().footprint(), OBJECT);
    }
    canvas.outline(&top, &polygon.points, 2.0, WALL);
    // Side view: floor and ceiling lines, objects as their x–z extents.
    grid(&mut canvas, &side, DVec2::new(min.x, 0.0), DVec2::new(max.x, height));
    for o in &scene.objects {
        let (lo, hi) = o.obox().footprint_aabb();
        let (z0, z1) = o.obox().z_range();
        let rect = [DVec2::new(lo.x, z0), DVec2::new(hi.x, z0), DVec2::new(hi.x, z1), DVec2::new(lo.x, z1)];
        canvas.fill_polygon(&side, &rect, OBJECT);
    }
    canvas.line(&side, DVec2::new(min.x, 0.0), DVec2::new(max.x, 0.0), 2.0, WALL);
    canvas.line(&side, DVec2::new(min.x, height), DVec2::new(max.x, height), 1.0, GRID);

    for human in &scene.humans {
        for (frame, color) in frames_to_draw(human) {
            draw_pose(&mut canvas, &top, human, frame, color, |p| (p.truncate(), p.z));
            draw_pose(&mut canvas, &side, human, frame, color, |p| (DVec2::new(p.x, p.z), -p.y));
        }
        for b in contact_boxes(human) {
            canvas.outline(&top, &b.obox.footprint(), 2.0, [200, 30, 30]);
        }
    }
    canvas
}

fn grid(canvas: &mut Canvas, view: &View, min: DVec2, max: DVec2) {
    let mut x = min.x.floor();
    while x <= max.x {
        canvas.line(view, DVec2::new(x, min.y), DVec2::new(x, max.y), 1.0, GRID);
        x += 1.0;
    }
    let mut y = min.y.floor();
    while y <= max.y {
        canvas.line(view, DVec2::new(min.x, y), DVec2::new(max.x, y), 1.0, GRID);
        y += 1.0;
    }
}

/// Faint frames every half second of free-space motion, then the middle frame of every span.
fn frames_to_draw(human: &Human) -> Vec<(usize, Color)> {
    let step = ((human.fps * 0.5).round() as usize).max(1);
    let mut out: Vec<(usize, Color)> = human
        .actions
        .iter()
        .filter(|s| s.action.is_free_space())
        .flat_map(|s| (s.start..s.end).step_by(step).map(|f| (f, faint(action_color(Some(s.action))))))
        .collect();
    out.extend(human.actions.iter().map(|s| ((s.start + s.end) / 2, action_color(Some(s.action)))));
    if human.actions.is_empty() && !human.frames.is_empty() {
        out.push((human.frames.len() / 2, action_color(None)));
    }
    out
}

/// Draws one frame's capsules, far ones first; `project` gives (2D position, depth).
fn draw_pose(
    canvas: &mut Canvas,
    view: &View,
    human: &Human,
    frame: usize,
    color: Color,
    project: impl Fn(DVec3) -> (DVec2, f64),
) {
    let mut bones: Vec<(f64, DVec2, DVec2, f64)> = human
        .skeleton
        .bones
        .iter()
        .map(|b| {
            let (pa, da) = project(human.joint_at(frame, b.a));
            let (pb, db) = project(human.joint_at(frame, b.b));
            ((da + db) * 0.5, pa, pb, b.radius)
        })
        .collect();
    bones.sort_by(|x, y| x.0.total_cmp(&y.0));
    let edge = color.map(|v| (v as f64 * 0.6) as u8);
    for &(_, a, b, r) in &bones {
        canvas.capsule(view, a, b, r, edge);
        canvas.capsule(view, a, b, (r - 1.2 / view.scale).max(0.0), color);
    }
}
