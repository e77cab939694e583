//! Simple polygons: area, orientation, containment, self-intersection and point sampling.

use super::clip::signed_area;
use glam::DVec2;

/// A polygon given by its vertices in order (the last connects back to the first).
#[derive(Debug, Clone, PartialEq)]
pub struct Polygon {
    /// Vertices, without repeating the first.
    pub points: Vec<DVec2>,
}

/// A point on a polygon's boundary with the outward unit normal there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoundarySample {
    /// The point.
    pub point: DVec2,
    /// Outward unit normal of the edge it lies on (for a counter-clockwise polygon).
    pub normal: DVec2,
}

/// One edge of a polygon seen from inside: where it starts, its unit direction, its length and the
/// unit normal pointing into the polygon (whichever way the vertices wind).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wall {
    /// The edge's first vertex.
    pub start: DVec2,
    /// Unit direction from the first vertex to the second (zero for a zero-length edge).
    pub along: DVec2,
    /// Length of the edge.
    pub length: f64,
    /// Unit normal into the polygon.
    pub inward: DVec2,
}

impl Wall {
    /// The point `t` along the wall from its start and `offset` into the room.
    pub fn point(&self, t: f64, offset: f64) -> DVec2 {
        self.start + self.along * t + self.inward * offset
    }
}

impl Polygon {
    /// A polygon from its vertices.
    pub fn new(points: Vec<DVec2>) -> Polygon {
        Polygon { points }
    }

    /// An axis-aligned rectangle, counter-clockwise.
    pub fn rectangle(min: DVec2, max: DVec2) -> Polygon {
        Polygon::new(vec![min, DVec2::new(max.x, min.y), max, DVec2::new(min.x, max.y)])
    }

    /// Edges as (start, end) pairs.
    pub fn edges(&self) -> impl Iterator<Item = (DVec2, DVec2)> + '_ {
        let n = self.points.len();
        (0..n).map(move |i| (self.points[i], self.points[(i + 1) % n]))
    }

    /// Every edge as a wall seen from inside, in edge order.
    pub fn walls(&self) -> impl Iterator<Item = Wall> + '_ {
        // Counter-clockwise polygons have the inside on the left of each edge.
        let left = self.signed_area() > 0.0;
        self.edges().map(move |(a, b)| {
            let length = a.distance(b);
            let along = if length > 0.0 { (b - a) / length } else { DVec2::ZERO };
            Wall { start: a, along, length, inward: if left { along.perp() } else { -along.perp() } }
        })
    }

    /// Shoelace area: positive for counter-clockwise vertices.
    pub fn signed_area(&self) -> f64 {
        signed_area(&self.points)
    }

    /// Enclosed area (absolute).
    pub fn area(&self) -> f64 {
        self.signed_area().abs()
    }

    /// Length of the boundary.
    pub fn perimeter(&self) -> f64 {
        self.edges().map(|(a, b)| a.distance(b)).sum()
    }

    /// Axis-aligned bounds: (min, max).
    pub fn bounds(&self) -> (DVec2, DVec2) {
        let min = self.points.iter().fold(DVec2::splat(f64::INFINITY), |m, &p| m.min(p));
        let max = self.points.iter().fold(DVec2::splat(f64::NEG_INFINITY), |m, &p| m.max(p));
        (min, max)
    }

    /// Whether all vertices lie on one line (or one point): the polygon encloses nothing.
    pub fn is_degenerate(&self) -> bool {
        let Some(&p0) = self.points.first() else { return true };
        let far = self.points.iter().copied().max_by(|a, b| a.distance_squared(p0).total_cmp(&b.distance_squared(p0)));
        let Some(far) = far.filter(|f| *f != p0) else { return true };
        let d = far - p0;
        self.points.iter().all(|&p| d.perp_dot(p - p0).abs() <= 1e-12 * d.length_squared())
    }

    /// The direction (rad) of the longest edge (the room's longest wall); `None` without edges.
    pub fn longest_edge_direction(&self) -> Option<f64> {
        let (a, b) = self.edges().max_by(|x, y| (x.1 - x.0).length().total_cmp(&(y.1 - y.0).length()))?;
        Some((b - a).to_angle())
    }

    /// Whether `p` is inside (even–odd rule; points exactly on an edge may go either way).
    pub fn contains(&self, p: DVec2) -> bool {
        let mut inside = false;
        for (a, b) in self.edges() {
            if (a.y > p.y) != (b.y > p.y) {
                let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
                if p.x < x {
                    inside = !inside;
                }
            }
        }
        inside
    }

    /// Distance from `p` to the nearest boundary point.
    pub fn distance_to_boundary(&self, p: DVec2) -> f64 {
        self.edges().map(|(a, b)| point_segment_distance(p, a, b)).fold(f64::INFINITY, f64::min)
    }

    /// The boundary point nearest to `p` (`p` itself for a polygon without edges).
    pub fn nearest_boundary_point(&self, p: DVec2) -> DVec2 {
        self.edges()
            .map(|(a, b)| closest_point_on_segment(p, a, b))
            .min_by(|x, y| x.distance_squared(p).total_cmp(&y.distance_squared(p)))
            .unwrap_or(p)
    }

    /// Signed distance to the boundary: negative inside, positive outside.
    pub fn signed_distance(&self, p: DVec2) -> f64 {
        let d = self.distance_to_boundary(p);
        if self.contains(p) { -d } else { d }
    }

    /// The first pair of edges (i < j) that cross or touch where they should not, including
    /// zero-length edges and an edge folding back on its neighbour; `None` for a simple polygon.
    pub fn first_self_intersection(&self) -> Option<(usize, usize)> {
        let n = self.points.len();
        let edge = |i: usize| (self.points[i], self.points[(i + 1) % n]);
        if let Some(i) = (0..n).find(|&i| edge(i).0 == edge(i).1) {
            return Some((i, (i + 1) % n));
        }
        for i in 0..n {
            let (a, b) = edge(i);
            for j in i + 1..n {
                let (c, d) = edge(j);
                let adjacent = j == i + 1 || (i == 0 && j == n - 1);
                if adjacent {
                    // Neighbours share one vertex; they only overlap when folding back.
                    let (u, v) = if j == i + 1 { (b - a, d - c) } else { (a - b, c - d) };
                    if u.perp_dot(v) == 0.0 && u.dot(v) < 0.0 {
                        return Some((i, j));
                    }
                } else if segments_intersect(a, b, c, d) {
                    return Some((i, j));
                }
            }
        }
        None
    }

    /// `n` points spread evenly by arc length along the boundary, starting at vertex 0, with
    /// outward normals (assuming counter-clockwise order).
    pub fn sample_boundary(&self, n: usize) -> Vec<BoundarySample> {
        let perimeter = self.perimeter();
        if n == 0 || perimeter <= 0.0 {
            return Vec::new();
        }
        let step = perimeter / n as f64;
        let mut out = Vec::with_capacity(n);
        let mut walked = 0.0;
        for (a, b) in self.edges() {
            let len = a.distance(b);
            if len == 0.0 {
                continue;
            }
            let dir = (b - a) / len;
            let normal = DVec2::new(dir.y, -dir.x);
            while out.len() < n {
                let t = out.len() as f64 * step - walked;
                if t >= len {
                    break;
                }
                out.push(BoundarySample { point: a + dir * t, normal });
            }
            walked += len;
        }
        out
    }

    /// Interior points on a regular grid of the given spacing (cell centres inside the polygon),
    /// row by row from the bottom.
    pub fn sample_interior(&self, spacing: f64) -> Vec<DVec2> {
        let (min, max) = self.bounds();
        let mut out = Vec::new();
        let mut y = min.y + spacing * 0.5;
        while y < max.y {
            let mut x = min.x + spacing * 0.5;
            while x < max.x {
                let p = DVec2::new(x, y);
                if self.contains(p) {
                    out.push(p);
                }
                x += spacing;
            }
            y += spacing;
        }
        out
    }
}

/// Distance from `p` to the segment `a`–`b`.
pub fn point_segment_distance(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    p.distance(closest_point_on_segment(p, a, b))
}

/// The point of the segment `a`–`b` nearest to `p`.
pub fn closest_point_on_segment(p: DVec2, a: DVec2, b: DVec2) -> DVec2 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 == 0.0 { 0.0 } else { ((p - a).dot(ab) / len2).clamp(0.0, 1.0) };
    a + ab * t
}

fn orient(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    (b - a).perp_dot(c - a)
}

fn on_segment(a: DVec2, b: DVec2, p: DVec2) -> bool {
    p.x >= a.x.min(b.x) && p.x <= a.x.max(b.x) && p.y >= a.y.min(b.y) && p.y <= a.y.max(b.y)
}

/// Whether the closed segments `a`–`b` and `c`–`d` share a point.
pub fn segments_intersect(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> bool {
    let (o1, o2, o3, o4) = (orient(a, b, c), orient(a, b, d), orient(c, d, a), orient(c, d, b));
    if ((o1 > 0.0 && o2 < 0.0) || (o1 < 0.0 && o2 > 0.0)) && ((o3 > 0.0 && o4 < 0.0) || (o3 < 0.0 && o4 > 0.0)) {
        return true;
    }
    (o1 == 0.0 && on_segment(a, b, c))
        || (o2 == 0.0 && on_segment(a, b, d))
        || (o3 == 0.0 && on_segment(c, d, a))
        || (o4 == 0.0 && on_segment(c, d, b))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn poly(p: &[[f64; 2]]) -> Polygon {
        Polygon::new(p.iter().map(|&q| DVec2::from(q)).collect())
    }

    #[test]
    fn longest_edge_direction_of_a_rectangle_and_an_empty_polygon() {
        // A wall's direction, walked either way: along x for a wide room, along y for a deep one.
        let wide = poly(&[[0.0, 0.0], [4.0, 0.0], [4.0, 3.0], [0.0, 3.0]]).longest_edge_direction().unwrap();
        let deep = poly(&[[0.0, 0.0], [2.0, 0.0], [2.0, 5.0], [0.0, 5.0]]).longest_edge_direction().unwrap();
        assert!(wide.sin().abs() < 1e-12 && deep.cos().abs() < 1e-12, "{wide} {deep}");
        assert_eq!(Polygon::new(Vec::new()).longest_edge_direction(), None);
    }

    #[test]
    fn l_shape_area_and_containment() {
        let l = poly(&[[0.0, 0.0], [4.0, 0.0], [4.0, 2.0], [2.0, 2.0], [2.0, 4.0], [0.0, 4.0]]);
        assert_eq!(l.signed_area(), 12.0);
        assert_eq!(l.perimeter(), 16.0);
        assert!(l.contains(DVec2::new(1.0, 3.0)));
        assert!(!l.contains(DVec2::new(3.0, 3.0)));
        assert_eq!(l.first_self_intersection(), None);
        assert!((l.signed_distance(DVec2::new(3.0, 3.0)) - 1.0).abs() < 1e-12);
        assert!((l.signed_distance(DVec2::new(1.0, 1.0)) + 1.0).abs() < 1e-12);
    }

    #[test]
    fn bow_tie_and_fold_back_are_self_intersecting() {
        let bow = poly(&[[0.0, 0.0], [2.0, 2.0], [2.0, 0.0], [0.0, 2.0]]);
        assert_eq!(bow.first_self_intersection(), Some((0, 2)));
        let fold = poly(&[[0.0, 0.0], [2.0, 0.0], [1.0, 0.0], [1.0, 1.0]]);
        assert!(fold.first_self_intersection().is_some());
        let repeated = poly(&[[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
        assert_eq!(repeated.first_self_intersection(), Some((1, 2)));
        // A vertex touching a non-adjacent edge.
        let touch = poly(&[[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [2.0, 0.0], [0.0, 4.0]]);
        assert!(touch.first_self_intersection().is_some());
    }

    #[test]
    fn walls_face_into_the_room_whichever_way_it_winds() {
        let ccw = Polygon::rectangle(DVec2::ZERO, DVec2::new(2.0, 1.0));
        let mut cw = ccw.clone();
        cw.points.reverse();
        for room in [ccw, cw] {
            let walls: Vec<Wall> = room.walls().collect();
            assert_eq!(walls.len(), 4);
            for w in &walls {
                // A metre along (or half way) and 10 cm in lies inside, 10 cm out lies outside.
                let t = w.length.min(1.0) * 0.5;
                assert!(room.contains(w.point(t, 0.1)), "{w:?}");
                assert!(!room.contains(w.point(t, -0.1)), "{w:?}");
                assert!((w.along.length() - 1.0).abs() < 1e-12 && w.along.dot(w.inward).abs() < 1e-12);
            }
            assert_eq!(walls.iter().map(|w| w.length).sum::<f64>(), 6.0);
        }
        let first = Polygon::rectangle(DVec2::ZERO, DVec2::new(2.0, 1.0)).walls().next().unwrap();
        assert_eq!(first.point(1.5, 0.25), DVec2::new(1.5, 0.25));
    }

    #[test]
    fn boundary_samples_are_even_and_on_edges() {
        let sq = Polygon::rectangle(DVec2::ZERO, DVec2::new(2.0, 1.0));
        let s = sq.sample_boundary(12);
        assert_eq!(s.len(), 12);
        assert_eq!(s[0].point, DVec2::ZERO);
        assert_eq!(s[0].normal, DVec2::new(0.0, -1.0));
        for w in s.windows(2) {
            assert!(sq.distance_to_boundary(w[1].point) < 1e-12);
        }
        assert!((s[3].point - DVec2::new(1.5, 0.0)).length() < 1e-12);
        assert_eq!(sq.sample_interior(0.5).len(), 8);
    }
}
