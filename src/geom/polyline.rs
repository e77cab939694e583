//! Open 2D polylines parameterised by arc length (walking paths).

use glam::DVec2;

/// An open polyline with at least two distinct points.
#[derive(Debug, Clone, PartialEq)]
pub struct Polyline {
    points: Vec<DVec2>,
    /// Arc length at each point.
    cumulative: Vec<f64>,
}

impl Polyline {
    /// A polyline through `points`; `None` with fewer than two points or zero length.
    pub fn new(points: Vec<DVec2>) -> Option<Polyline> {
        let mut cumulative = vec![0.0];
        for w in points.windows(2) {
            cumulative.push(cumulative.last().copied().unwrap_or(0.0) + w[0].distance(w[1]));
        }
        let ok = points.len() >= 2 && cumulative.last().is_some_and(|&l| l > 0.0);
        ok.then_some(Polyline { points, cumulative })
    }

    /// Total length.
    pub fn length(&self) -> f64 {
        *self.cumulative.last().expect("at least two points")
    }

    /// The vertices.
    pub fn points(&self) -> &[DVec2] {
        &self.points
    }

    fn segment(&self, s: f64) -> usize {
        let last = self.points.len() - 2;
        self.cumulative[1..].iter().position(|&c| s <= c).unwrap_or(last).min(last)
    }

    /// Point at arc length `s`; beyond the ends the first or last segment is extended.
    pub fn point_at(&self, s: f64) -> DVec2 {
        let mut i = self.segment(s);
        while i + 1 < self.points.len() - 1 && self.points[i] == self.points[i + 1] {
            i += 1;
        }
        let (a, b) = (self.points[i], self.points[i + 1]);
        let len = a.distance(b);
        if len == 0.0 {
            return a;
        }
        a + (b - a) * ((s - self.cumulative[i]) / len)
    }

    /// Unit direction of travel at arc length `s`, averaged over a window of ±`smooth` metres so
    /// corners turn gradually.
    pub fn direction_at(&self, s: f64, smooth: f64) -> DVec2 {
        let d = self.point_at(s + smooth) - self.point_at(s - smooth);
        d.try_normalize().unwrap_or_else(|| {
            let i = self.segment(s);
            (self.points[i + 1] - self.points[i]).normalize_or(DVec2::Y)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arc_length_parameterisation() {
        let p = Polyline::new(vec![DVec2::ZERO, DVec2::new(3.0, 0.0), DVec2::new(3.0, 4.0)]).unwrap();
        assert_eq!(p.length(), 7.0);
        assert_eq!(p.point_at(1.5), DVec2::new(1.5, 0.0));
        assert_eq!(p.point_at(5.0), DVec2::new(3.0, 2.0));
        assert_eq!(p.point_at(-1.0), DVec2::new(-1.0, 0.0));
        assert_eq!(p.point_at(8.0), DVec2::new(3.0, 5.0));
        assert_eq!(p.direction_at(1.0, 0.1), DVec2::X);
        let corner = p.direction_at(3.0, 0.5);
        assert!((corner - DVec2::new(1.0, 1.0).normalize()).length() < 1e-12);
        assert!(Polyline::new(vec![DVec2::ONE, DVec2::ONE]).is_none());
    }
}
