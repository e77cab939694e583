//! Property tests of the geometry core.

use glam::{DVec2, DVec3};
use proptest::prelude::*;
use shade_sim::geom::{Mask, OBox, Polygon, RoomWindow, footprint_intersection_area, intersection_volume, iou_3d};

fn obox() -> impl Strategy<Value = OBox> {
    ((-2.0..2.0f64, -2.0..2.0f64, 0.0..1.5f64), (0.05..2.0f64, 0.05..2.0f64, 0.05..2.0f64), -4.0..4.0f64)
        .prop_map(|((x, y, z), (w, d, h), yaw)| OBox::new(DVec3::new(x, y, z), DVec3::new(w, d, h), yaw))
}

fn moved(b: &OBox, pivot: DVec2, angle: f64, shift: DVec3) -> OBox {
    b.transformed(pivot, angle, shift)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn iou_is_symmetric_bounded_and_one_on_itself(a in obox(), b in obox()) {
        let ab = iou_3d(&a, &b);
        let ba = iou_3d(&b, &a);
        prop_assert!((ab - ba).abs() < 1e-9);
        prop_assert!((0.0..=1.0).contains(&ab));
        prop_assert!((iou_3d(&a, &a) - 1.0).abs() < 1e-9);
        let v = intersection_volume(&a, &b);
        prop_assert!(v <= a.volume().min(b.volume()) + 1e-9);
    }

    #[test]
    fn iou_is_invariant_under_a_common_rigid_motion(
        a in obox(), b in obox(), px in -3.0..3.0f64, py in -3.0..3.0f64, angle in -4.0..4.0f64,
        sx in -5.0..5.0f64, sy in -5.0..5.0f64, sz in -1.0..1.0f64,
    ) {
        let (pivot, shift) = (DVec2::new(px, py), DVec3::new(sx, sy, sz));
        let before = iou_3d(&a, &b);
        let after = iou_3d(&moved(&a, pivot, angle, shift), &moved(&b, pivot, angle, shift));
        prop_assert!((before - after).abs() < 1e-9, "{before} vs {after}");
    }

    #[test]
    fn clipped_area_matches_sampling(a in obox(), b in obox()) {
        // Count a fine grid inside both footprints: agrees with the exact area within the grid error.
        let exact = footprint_intersection_area(&a, &b);
        let (lo, hi) = a.footprint_aabb();
        let step = 0.01;
        let mut n = 0usize;
        let mut y = lo.y + step * 0.5;
        while y < hi.y {
            let mut x = lo.x + step * 0.5;
            while x < hi.x {
                let p = DVec2::new(x, y);
                if a.footprint_contains(p) && b.footprint_contains(p) { n += 1; }
                x += step;
            }
            y += step;
        }
        let sampled = n as f64 * step * step;
        let tolerance = 2.0 * step * (a.size.x + a.size.y + b.size.x + b.size.y) + 1e-9;
        prop_assert!((exact - sampled).abs() <= tolerance, "exact {exact} sampled {sampled}");
    }

    #[test]
    fn sdf_sign_agrees_with_containment(b in obox(), x in -4.0..4.0f64, y in -4.0..4.0f64, z in -1.0..3.0f64) {
        let p = DVec3::new(x, y, z);
        let d = b.signed_distance(p);
        prop_assume!(d.abs() > 1e-9);
        prop_assert_eq!(d < 0.0, b.contains(p));
        // The distance is exact: moving by |d| towards the centre never crosses more than the surface.
        prop_assert!(d >= -b.half().min_element() - 1e-9);
    }

    #[test]
    fn rasterised_footprints_match_their_area(b in obox()) {
        let w = RoomWindow { center: DVec2::ZERO, side: 6.2 };
        let px = w.pixel();
        let m = Mask::of_footprint(&w, &b);
        let area = m.count() as f64 * w.pixel_area();
        // Pixels whose centres are inside differ from the exact area by at most a border of one
        // pixel along the perimeter.
        let tolerance = 2.0 * (b.size.x + b.size.y) * px + 4.0 * px * px;
        prop_assert!((area - b.footprint_area()).abs() <= tolerance, "{area} vs {}", b.footprint_area());
    }

    #[test]
    fn rasterised_polygons_match_their_area(
        x0 in -3.0..-0.5f64, y0 in -3.0..-0.5f64, x1 in 0.5..3.0f64, y1 in 0.5..3.0f64,
        fx in 0.2..0.8f64, fy in 0.2..0.8f64,
    ) {
        // An L-shape: the box with its top-right corner cut out.
        let cx = x0 + (x1 - x0) * fx;
        let cy = y0 + (y1 - y0) * fy;
        let l = Polygon::new(vec![
            DVec2::new(x0, y0), DVec2::new(x1, y0), DVec2::new(x1, cy),
            DVec2::new(cx, cy), DVec2::new(cx, y1), DVec2::new(x0, y1),
        ]);
        prop_assert!(l.first_self_intersection().is_none());
        let w = RoomWindow::around(shade_sim::scene::RoomType::Bedroom.window_side(), &l);
        let m = Mask::of_polygon(&w, &l);
        let area = m.count() as f64 * w.pixel_area();
        let tolerance = l.perimeter() * w.pixel() + 4.0 * w.pixel_area();
        prop_assert!((area - l.area()).abs() <= tolerance, "{area} vs {}", l.area());
        // Every set pixel's centre is inside the polygon.
        for (j, row) in m.rows().enumerate() {
            for (i, &set) in row.iter().enumerate() {
                if set { prop_assert!(l.contains(w.pixel_center(i, j))); }
            }
        }
    }
}
