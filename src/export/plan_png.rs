//! A top-down plan of a scene as a picture: the floor, furniture footprints coloured by kind with
//! their category names, lamps as outlines, walking paths, contact humans in their contact pose,
//! a 1 m scale bar and a title line.

use super::canvas::{Canvas, Color, View};
use super::font::{draw_text, text_width};
use super::humans_png::action_color;
use crate::scene::{Group, Scene};
use glam::DVec2;

const SIZE: f64 = 900.0;
const MARGIN: f64 = 40.0;

/// Fill colour of a category group.
pub fn group_color(group: Group) -> Color {
    match group {
        Group::Bed => [186, 168, 222],
        Group::Chair | Group::Stool => [240, 190, 130],
        Group::Sofa => [150, 186, 226],
        Group::Table => [196, 160, 120],
        Group::Cabinet => [200, 200, 190],
        Group::Shelf => [170, 200, 170],
        Group::Lamp => [250, 230, 120],
    }
}

fn darker(c: Color) -> Color {
    c.map(|v| (v as f64 * 0.55) as u8)
}

/// Renders the plan.
pub fn render_plan(scene: &Scene) -> Canvas {
    let polygon = scene.floor_plan.polygon();
    let (min, max) = polygon.bounds();
    let span = (max - min).max_element().max(1.0);
    let scale = (SIZE - 2.0 * MARGIN) / span;
    let view = View { top_left: DVec2::new(min.x, max.y), scale, offset: DVec2::new(MARGIN, MARGIN + 20.0) };
    let width = ((max.x - min.x) * scale + 2.0 * MARGIN) as u32;
    let height = ((max.y - min.y) * scale + 2.0 * MARGIN + 40.0) as u32;
    let mut c = Canvas::new(width.max(320), height, [255, 255, 255]);
    c.fill_polygon(&view, &polygon.points, [240, 236, 226]);
    // Furniture, lamps last (outlines over everything).
    let mut order: Vec<usize> = (0..scene.objects.len()).collect();
    order.sort_by_key(|&i| scene.objects[i].category.is_hanging());
    for &i in &order {
        let o = &scene.objects[i];
        let fp = o.obox().footprint();
        let color = group_color(o.category.group());
        if o.category.is_hanging() {
            c.outline(&view, &fp, 2.0, darker(color));
        } else {
            c.fill_polygon(&view, &fp, color);
            c.outline(&view, &fp, 1.5, darker(color));
            // The front edge, thicker: where a person sits or reaches.
            c.line(&view, fp[2], fp[3], 3.0, darker(color));
        }
    }
    c.outline(&view, &polygon.points, 3.0, [50, 50, 50]);
    // People: walking paths as pelvis traces, contact humans in their contact pose.
    for h in &scene.humans {
        let Some(pelvis) = h.skeleton.joint("pelvis") else { continue };
        for span in h.actions.iter().filter(|s| s.action.is_free_space()) {
            let color = action_color(Some(span.action));
            for f in span.start + 1..span.end {
                c.line(&view, h.joint_at(f - 1, pelvis).truncate(), h.joint_at(f, pelvis).truncate(), 2.0, color);
            }
            c.disc(&view, h.joint_at(span.start, pelvis).truncate(), 0.06, color);
        }
        for span in h.contact_spans() {
            let f = (span.start + span.end) / 2;
            let color = action_color(Some(span.action));
            for b in &h.skeleton.bones {
                c.capsule(&view, h.joint_at(f, b.a).truncate(), h.joint_at(f, b.b).truncate(), b.radius, color);
            }
        }
    }
    // Labels after people, so they stay readable.
    for o in scene.objects.iter().filter(|o| !o.category.is_hanging()) {
        let p = view.to_pixel(o.center().truncate());
        let text = o.category.name();
        let w = text_width(text, 1) as i64;
        draw_text(&mut c, p.x as i64 - w / 2, p.y as i64 - 3, text, 1, [40, 40, 40]);
    }
    // Scale bar and title.
    let y = height as f64 - 22.0;
    let start = DVec2::new(MARGIN, y);
    let bar = DVec2::new(MARGIN + scale, y);
    for (a, b) in
        [(start, bar), (start - DVec2::Y * 5.0, start + DVec2::Y * 5.0), (bar - DVec2::Y * 5.0, bar + DVec2::Y * 5.0)]
    {
        let px = View { top_left: DVec2::ZERO, scale: 1.0, offset: DVec2::ZERO };
        c.line(&px, DVec2::new(a.x, -a.y), DVec2::new(b.x, -b.y), 2.0, [30, 30, 30]);
    }
    draw_text(&mut c, (MARGIN + scale + 8.0) as i64, (y - 7.0) as i64, "1 m", 2, [30, 30, 30]);
    let title = format!("{} - {} objects - {} humans", scene.room_type, scene.objects.len(), scene.humans.len());
    draw_text(&mut c, MARGIN as i64, 12, &title, 2, [30, 30, 30]);
    c
}
