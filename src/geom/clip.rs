//! Convex polygon clipping (Sutherland–Hodgman) and the exact intersection area of two
//! oriented rectangles.

use super::OBox;
use glam::DVec2;

/// The intersection of two convex counter-clockwise polygons, counter-clockwise (possibly empty).
pub fn clip_convex(subject: &[DVec2], clip: &[DVec2]) -> Vec<DVec2> {
    let mut out: Vec<DVec2> = subject.to_vec();
    for i in 0..clip.len() {
        if out.is_empty() {
            break;
        }
        let a = clip[i];
        let b = clip[(i + 1) % clip.len()];
        let edge = b - a;
        let side = |p: DVec2| edge.perp_dot(p - a);
        let input = std::mem::take(&mut out);
        for j in 0..input.len() {
            let p = input[j];
            let q = input[(j + 1) % input.len()];
            let (sp, sq) = (side(p), side(q));
            if sp >= 0.0 {
                out.push(p);
            }
            if (sp >= 0.0) != (sq >= 0.0) {
                let t = sp / (sp - sq);
                out.push(p + (q - p) * t);
            }
        }
    }
    out
}

/// Area of a polygon by the shoelace formula (positive when counter-clockwise).
pub fn signed_area(points: &[DVec2]) -> f64 {
    let n = points.len();
    (0..n).map(|i| points[i].perp_dot(points[(i + 1) % n])).sum::<f64>() * 0.5
}

/// Exact area of the intersection of the footprints of two oriented boxes.
pub fn footprint_intersection_area(a: &OBox, b: &OBox) -> f64 {
    let (alo, ahi) = a.footprint_aabb();
    let (blo, bhi) = b.footprint_aabb();
    if alo.x >= bhi.x || blo.x >= ahi.x || alo.y >= bhi.y || blo.y >= ahi.y {
        return 0.0;
    }
    signed_area(&clip_convex(&a.footprint(), &b.footprint())).max(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn rotated_square_in_square() {
        // A unit square rotated 45° about the same centre: the overlap is a regular octagon,
        // area 2(√2 − 1) for side 1.
        let a = OBox::new(DVec3::ZERO, DVec3::ONE, 0.0);
        let b = OBox::new(DVec3::ZERO, DVec3::ONE, std::f64::consts::FRAC_PI_4);
        let expected = 2.0 * (2f64.sqrt() - 1.0);
        assert!((footprint_intersection_area(&a, &b) - expected).abs() < 1e-12);
    }

    #[test]
    fn disjoint_and_touching_are_zero() {
        let a = OBox::new(DVec3::ZERO, DVec3::ONE, 0.0);
        let b = OBox::new(DVec3::new(1.0, 0.0, 0.0), DVec3::ONE, 0.0);
        assert_eq!(footprint_intersection_area(&a, &b), 0.0);
        let c = OBox::new(DVec3::new(5.0, 0.0, 0.0), DVec3::ONE, 0.7);
        assert_eq!(footprint_intersection_area(&a, &c), 0.0);
    }
}
