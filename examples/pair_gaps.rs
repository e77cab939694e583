//! How well the pieces of a folder of scenes keep to the two relations every real room of the
//! data keeps exactly: a nightstand 4 cm beside its bed, its back level with the bed's head
//! (the nearest bed), and a dining chair 4 cm from its table (the nearest dining table). Prints the
//! 10th / 25th / 50th / 75th / 90th percentile of each gap (m; negative: inside the other piece)
//! and, for the nightstands, how closely their distance from the bed's centre line follows the
//! bed's width (Pearson's r: 0.99 in the data, which keeps it exactly). Then the diners: each
//! person seated on a dining chair, and how far their knees are from the nearest dining table's
//! footprint (0 when its top reaches over them, as it does for every diner of the data), with the
//! share within 10 cm, and the signed distance (negative: over the table's top) the "within" is
//! measured from. The chairs are counted twice more: those seating someone (a sit box's centre on
//! their footprint) and the spare ones.
//!
//! Run: `cargo run --release --example pair_gaps -- DIR…` (a dataset's split, or `generate`'s
//! output for it).

use shade_sim::eval::pearson;
use shade_sim::generator::at_table::knees_of;
use shade_sim::human::Conditions;
use shade_sim::scene::{Action, Category, Object, Scene};

/// `o`'s centre in the frame of `of` (x along its width, y along its depth).
fn in_frame(o: &Object, of: &Object) -> (f64, f64) {
    let local = of.obox().to_local(o.obox().center);
    (local.x, local.y)
}

fn nearest<'a>(o: &Object, among: &[&'a Object]) -> Option<&'a Object> {
    let d = |b: &&Object| (o.center[0] - b.center[0]).hypot(o.center[1] - b.center[1]);
    among.iter().min_by(|a, b| d(a).total_cmp(&d(b))).copied()
}

fn percentiles(mut v: Vec<f64>) -> String {
    if v.is_empty() {
        return "-".into();
    }
    v.sort_by(f64::total_cmp);
    let at = |q: f64| v[((v.len() - 1) as f64 * q).round() as usize];
    format!("{:+.3} / {:+.3} / {:+.3} / {:+.3} / {:+.3}", at(0.1), at(0.25), at(0.5), at(0.75), at(0.9))
}

fn main() -> anyhow::Result<()> {
    let (mut side, mut back, mut from_centre, mut half_width, mut chairs) = (vec![], vec![], vec![], vec![], vec![]);
    let (mut seated_chairs, mut spare_chairs, mut knees_to_table) = (vec![], vec![], vec![]);
    for dir in std::env::args().skip(1) {
        for file in Scene::files_in(std::path::Path::new(&dir))? {
            let scene = Scene::load(&file)?;
            let of = |pick: fn(Category) -> bool| -> Vec<&Object> {
                scene.objects.iter().filter(|o| pick(o.category)).collect()
            };
            let beds = of(|c| matches!(c, Category::DoubleBed | Category::SingleBed | Category::KidsBed));
            let tables = of(|c| c == Category::DiningTable);
            let sit_boxes: Vec<_> =
                Conditions::contact_boxes_of(&scene).into_iter().filter(|b| b.action == Action::Sit).collect();
            for o in &scene.objects {
                if o.category == Category::Nightstand
                    && let Some(bed) = nearest(o, &beds)
                {
                    let (u, v) = in_frame(o, bed);
                    side.push(u.abs() - bed.size[0] / 2.0 - o.size[0] / 2.0);
                    back.push(v + bed.size[1] / 2.0 - o.size[1] / 2.0);
                    from_centre.push(u.abs());
                    half_width.push(bed.size[0] / 2.0);
                }
                if o.category == Category::DiningChair
                    && let Some(table) = nearest(o, &tables)
                {
                    let (u, v) = in_frame(o, table);
                    let edge = (u.abs() - table.size[0] / 2.0).max(v.abs() - table.size[1] / 2.0);
                    let gap = edge - o.size[1] / 2.0;
                    chairs.push(gap);
                    let seated = sit_boxes.iter().any(|b| o.obox().footprint_contains(b.obox.center.truncate()));
                    if seated { &mut seated_chairs } else { &mut spare_chairs }.push(gap);
                }
            }
            for b in &sit_boxes {
                let seat = scene.objects.iter().find(|o| o.obox().footprint_contains(b.obox.center.truncate()));
                if let (Some(seat), Some(knees)) = (seat, knees_of(&scene, b))
                    && seat.category == Category::DiningChair
                {
                    let gap = tables.iter().map(|t| t.obox().footprint_signed_distance(knees)).reduce(f64::min);
                    knees_to_table.push(gap.unwrap_or(f64::INFINITY));
                }
            }
        }
    }
    println!("percentiles 10 / 25 / 50 / 75 / 90 (m)");
    if !side.is_empty() {
        println!("nightstands ({}): beside the bed {}", side.len(), percentiles(side));
        println!("  back behind the bed's head {}", percentiles(back));
        println!("  r(distance from the bed's centre line, bed half width) {:.3}", pearson(&from_centre, &half_width));
    }
    if !chairs.is_empty() {
        println!("dining chairs ({}): from the table {}", chairs.len(), percentiles(chairs));
        println!("  seating someone ({}) {}", seated_chairs.len(), percentiles(seated_chairs));
        println!("  spare ({}) {}", spare_chairs.len(), percentiles(spare_chairs));
    }
    if !knees_to_table.is_empty() {
        let near = knees_to_table.iter().filter(|&&d| d <= 0.1).count();
        let share = 100.0 * near as f64 / knees_to_table.len() as f64;
        println!("diners ({}): knees within 10 cm of a table's top {near} ({share:.1} %)", knees_to_table.len());
        println!("  knees from the nearest table, negative over its top {}", percentiles(knees_to_table));
    }
    Ok(())
}
