//! Draws every pose generator side by side (top and side views) to check that poses look like a
//! person: stand, six frames of one gait cycle, sit on a 45 cm seat, lie on a 55 cm mattress,
//! touch a 75 cm table top and a 1.4 m shelf.
//!
//! Run: `cargo run --example pose_gallery -- out/pose_gallery.png`

use glam::{DVec2, DVec3};
use shade_sim::export::render_humans_sized;
use shade_sim::geom::Polyline;
use shade_sim::human::{Body, Gait, Motion, Pose, Side, lie, sit, stand, touch};
use shade_sim::scene::{Action, FloorPlan, RoomType, Scene};

fn main() -> std::io::Result<()> {
    let out = std::env::args().nth(1).unwrap_or_else(|| "out/pose_gallery.png".into());
    let body = Body::default();
    let east = -std::f64::consts::FRAC_PI_2; // facing +x: profiles in the side view
    let mut poses: Vec<(Pose, Action)> = vec![(stand(&body, DVec2::new(0.5, 0.0), east), Action::Stand)];
    let gait = Gait::default();
    let path = Polyline::new(vec![DVec2::new(0.0, 0.0), DVec2::new(10.0, 0.0)]).expect("a straight path");
    let stride = 2.0 * gait.step_length(&body);
    for k in 0..6 {
        let s = 3.0 + stride * k as f64 / 6.0;
        let p = gait.pose_at(&body, &path, s);
        let shift = DVec3::new(1.6 + 0.9 * k as f64 - s, 0.0, 0.0);
        poses.push((p.translated(shift), Action::Walk));
    }
    poses.push((sit(&body, DVec2::new(7.3, 0.0), 0.45, east), Action::Sit));
    poses.push((lie(&body, DVec2::new(9.5, 0.0), 0.55, east), Action::Lie));
    poses.push((touch(&body, DVec3::new(11.6, 0.0, 0.75), east, Side::Right), Action::Touch));
    poses.push((touch(&body, DVec3::new(12.9, 0.0, 1.4), east, Side::Right), Action::Touch));

    let plan = FloorPlan { polygon: vec![[0.0, -1.0], [13.5, -1.0], [13.5, 1.0], [0.0, 1.0]], height: 2.2 };
    let mut scene = Scene::new(RoomType::Living, plan);
    for (i, (pose, action)) in poses.into_iter().enumerate() {
        let mut m = Motion::new(body, 30.0);
        m.hold(pose, 1, action);
        scene.humans.push(m.into_human(format!("h{i}")));
    }
    if let Some(dir) = std::path::Path::new(&out).parent() {
        std::fs::create_dir_all(dir)?;
    }
    render_humans_sized(&scene, 1000.0).save_png(std::path::Path::new(&out))?;
    println!("wrote {out}");
    Ok(())
}
