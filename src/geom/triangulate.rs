//! Triangles of a simple polygon by ear clipping (O(n²), for floor plans of a few dozen corners).
//! Used to draw floors; it does not handle holes or self-intersecting outlines.

use super::polygon::Polygon;
use glam::DVec2;

fn cross(o: DVec2, a: DVec2, b: DVec2) -> f64 {
    (a - o).perp_dot(b - o)
}

/// Whether `p` lies inside or on the counter-clockwise triangle `a b c`.
fn in_triangle(p: DVec2, a: DVec2, b: DVec2, c: DVec2) -> bool {
    cross(a, b, p) >= 0.0 && cross(b, c, p) >= 0.0 && cross(c, a, p) >= 0.0
}

impl Polygon {
    /// Counter-clockwise triangles (vertex indices) covering the polygon, `n − 2` of them for `n`
    /// corners; clockwise input is handled. Collinear corners give zero-area triangles.
    pub fn triangulate(&self) -> Vec<[usize; 3]> {
        let p = &self.points;
        let mut left: Vec<usize> = (0..p.len()).collect();
        if self.signed_area() < 0.0 {
            left.reverse();
        }
        let mut out = Vec::with_capacity(p.len().saturating_sub(2));
        while left.len() > 3 {
            let n = left.len();
            let ear = (0..n).find(|&i| {
                let (a, b, c) = (left[(i + n - 1) % n], left[i], left[(i + 1) % n]);
                cross(p[a], p[b], p[c]) > 0.0
                    && left.iter().all(|&k| k == a || k == b || k == c || !in_triangle(p[k], p[a], p[b], p[c]))
            });
            // A polygon with only collinear corners left has no ear: clip any corner.
            let i = ear.unwrap_or(0);
            out.push([left[(i + n - 1) % n], left[i], left[(i + 1) % n]]);
            left.remove(i);
        }
        if left.len() == 3 {
            out.push([left[0], left[1], left[2]]);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(p: &Polygon, t: &[[usize; 3]]) -> f64 {
        t.iter().map(|&[a, b, c]| cross(p.points[a], p.points[b], p.points[c]) * 0.5).sum()
    }

    #[test]
    fn an_l_shaped_room_is_covered_exactly_once() {
        let l = Polygon::new(
            [[0.0, 0.0], [5.0, 0.0], [5.0, 2.0], [2.0, 2.0], [2.0, 4.0], [0.0, 4.0]]
                .map(|[x, y]| DVec2::new(x, y))
                .to_vec(),
        );
        let t = l.triangulate();
        assert_eq!(t.len(), 4);
        // Every triangle counter-clockwise, areas summing to the polygon's (14 m²), and the
        // reflex corner's notch (3.5, 3) in none of them.
        for &[a, b, c] in &t {
            assert!(cross(l.points[a], l.points[b], l.points[c]) > 0.0);
            assert!(!in_triangle(DVec2::new(3.5, 3.0), l.points[a], l.points[b], l.points[c]));
        }
        assert!((area(&l, &t) - 14.0).abs() < 1e-12);
    }

    #[test]
    fn clockwise_input_gives_counter_clockwise_triangles() {
        let mut r = Polygon::rectangle(DVec2::ZERO, DVec2::new(4.0, 3.0));
        r.points.reverse();
        let t = r.triangulate();
        assert_eq!(t.len(), 2);
        assert!((area(&r, &t) - 12.0).abs() < 1e-12);
    }
}
