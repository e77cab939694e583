//! 256 × 256 rasterisation over a room window: floor plans, box footprints, capsule footprints.
//!
//! A pixel is set when its centre lies inside the shape. Row 0 is the window's top (largest y), so a
//! mask saved as an image shows the room with +y up. Only pixels inside a shape's bounding window are
//! visited, so a footprint costs its own area, not the whole grid.

use super::{OBox, Polygon, point_segment_distance};
use glam::DVec2;
use std::ops::Range;

/// Resolution of every mask (pixels per side).
pub const RES: usize = 256;

/// The square region of the floor that conditioning and metrics rasterise.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoomWindow {
    /// Centre of the window in world coordinates.
    pub center: DVec2,
    /// Side length in metres.
    pub side: f64,
}

impl RoomWindow {
    /// A window `side` metres wide centred on the floor plan's bounding-box centre (a scene's
    /// is `Scene::room_window`, its side the room type's).
    pub fn around(side: f64, floor: &Polygon) -> RoomWindow {
        let (min, max) = floor.bounds();
        RoomWindow { center: (min + max) * 0.5, side }
    }

    /// A window `side` metres wide over `floor` that keeps `focus` (the bounding box of what must
    /// be seen: a scene's people) in view. Along each axis on which the plan fits in the window it
    /// is [`RoomWindow::around`]'s; along an axis on which the plan is wider, it is centred on the
    /// focus as far as the plan's bounding box allows (never reaching past it).
    pub fn around_focus(side: f64, floor: &Polygon, focus: Option<(DVec2, DVec2)>) -> RoomWindow {
        let mut window = RoomWindow::around(side, floor);
        let Some((lo, hi)) = focus else { return window };
        let (min, max) = floor.bounds();
        let want = (lo + hi) * 0.5;
        for k in 0..2 {
            if max[k] - min[k] > side {
                window.center[k] = want[k].clamp(min[k] + side * 0.5, max[k] - side * 0.5);
            }
        }
        window
    }

    /// This window moved along each axis as little as keeps every point of `focus` (a bounding
    /// box) within `reach` of its centre; centred on `focus` along an axis on which it spans more
    /// than twice `reach`. Unmoved when `focus` is within reach already, or `None`.
    pub fn reaching(mut self, focus: Option<(DVec2, DVec2)>, reach: f64) -> RoomWindow {
        let Some((lo, hi)) = focus else { return self };
        for k in 0..2 {
            self.center[k] = if hi[k] - lo[k] > 2.0 * reach {
                (lo[k] + hi[k]) * 0.5
            } else {
                self.center[k].clamp(hi[k] - reach, lo[k] + reach)
            };
        }
        self
    }

    /// Side of one pixel in metres.
    pub fn pixel(&self) -> f64 {
        self.side / RES as f64
    }

    /// Area of one pixel in m².
    pub fn pixel_area(&self) -> f64 {
        self.pixel() * self.pixel()
    }

    /// World position of the centre of pixel (column `i`, row `j`).
    pub fn pixel_center(&self, i: usize, j: usize) -> DVec2 {
        let px = self.pixel();
        let half = self.side * 0.5;
        DVec2::new(self.center.x - half + (i as f64 + 0.5) * px, self.center.y + half - (j as f64 + 0.5) * px)
    }

    /// (column, row) ranges of the pixels whose centres may lie in the world box `min`..`max`.
    pub fn pixel_ranges(&self, min: DVec2, max: DVec2) -> (Range<usize>, Range<usize>) {
        let px = self.pixel();
        let half = self.side * 0.5;
        let col = |x: f64| ((x - (self.center.x - half)) / px - 0.5).clamp(-1.0, RES as f64);
        let row = |y: f64| (((self.center.y + half) - y) / px - 0.5).clamp(-1.0, RES as f64);
        let i0 = col(min.x).ceil().max(0.0) as usize;
        let i1 = (col(max.x).floor() + 1.0).clamp(0.0, RES as f64) as usize;
        let j0 = row(max.y).ceil().max(0.0) as usize;
        let j1 = (row(min.y).floor() + 1.0).clamp(0.0, RES as f64) as usize;
        (i0..i1.max(i0), j0..j1.max(j0))
    }
}

/// A 256 × 256 binary mask, row-major from the top row.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Mask {
    bits: Vec<bool>,
}

impl Default for Mask {
    fn default() -> Mask {
        Mask::new()
    }
}

impl Mask {
    /// An empty mask.
    pub fn new() -> Mask {
        Mask { bits: vec![false; RES * RES] }
    }

    /// Whether pixel (column `i`, row `j`) is set.
    pub fn get(&self, i: usize, j: usize) -> bool {
        self.bits[j * RES + i]
    }

    /// Sets pixel (column `i`, row `j`).
    pub fn set(&mut self, i: usize, j: usize) {
        self.bits[j * RES + i] = true;
    }

    /// Number of set pixels.
    pub fn count(&self) -> usize {
        self.bits.iter().filter(|&&b| b).count()
    }

    /// Number of pixels set in both masks.
    pub fn overlap(&self, other: &Mask) -> usize {
        self.bits.iter().zip(&other.bits).filter(|&(&a, &b)| a && b).count()
    }

    /// The complement.
    pub fn inverted(&self) -> Mask {
        Mask { bits: self.bits.iter().map(|b| !b).collect() }
    }

    /// Rows, top first, as slices of pixels.
    pub fn rows(&self) -> impl Iterator<Item = &[bool]> {
        self.bits.chunks(RES)
    }

    /// Sets every pixel whose centre is inside `polygon` (scanline, even–odd).
    pub fn fill_polygon(&mut self, window: &RoomWindow, polygon: &Polygon) {
        let mut xs = Vec::new();
        for j in 0..RES {
            let y = window.pixel_center(0, j).y;
            xs.clear();
            for (a, b) in polygon.edges() {
                if (a.y > y) != (b.y > y) {
                    xs.push(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x));
                }
            }
            xs.sort_by(f64::total_cmp);
            for pair in xs.chunks_exact(2) {
                let (cols, _) = window.pixel_ranges(DVec2::new(pair[0], y), DVec2::new(pair[1], y));
                for i in cols {
                    let x = window.pixel_center(i, j).x;
                    if x > pair[0] && x < pair[1] {
                        self.set(i, j);
                    }
                }
            }
        }
    }

    /// Sets every pixel whose centre is inside the footprint of `b`.
    pub fn fill_footprint(&mut self, window: &RoomWindow, b: &OBox) {
        let (min, max) = b.footprint_aabb();
        let (cols, rows) = window.pixel_ranges(min, max);
        let (ax, ay) = b.axes();
        let (hx, hy) = (b.size.x * 0.5, b.size.y * 0.5);
        let c = b.center.truncate();
        for j in rows {
            for i in cols.clone() {
                let d = window.pixel_center(i, j) - c;
                if d.dot(ax).abs() <= hx && d.dot(ay).abs() <= hy {
                    self.set(i, j);
                }
            }
        }
    }

    /// Sets every pixel whose centre is within `radius` of the segment `a`–`b` (a capsule's shadow).
    pub fn fill_capsule(&mut self, window: &RoomWindow, a: DVec2, b: DVec2, radius: f64) {
        let (cols, rows) = window.pixel_ranges(a.min(b) - radius, a.max(b) + radius);
        for j in rows {
            for i in cols.clone() {
                if point_segment_distance(window.pixel_center(i, j), a, b) <= radius {
                    self.set(i, j);
                }
            }
        }
    }

    /// A mask of `polygon`.
    pub fn of_polygon(window: &RoomWindow, polygon: &Polygon) -> Mask {
        let mut m = Mask::new();
        m.fill_polygon(window, polygon);
        m
    }

    /// A mask of one box footprint.
    pub fn of_footprint(window: &RoomWindow, b: &OBox) -> Mask {
        let mut m = Mask::new();
        m.fill_footprint(window, b);
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn window() -> RoomWindow {
        RoomWindow { center: DVec2::ZERO, side: 6.4 }
    }

    #[test]
    fn a_window_keeps_its_focus_in_view_only_where_the_plan_is_wider_than_it() {
        let rect =
            |w: f64, d: f64| Polygon::new(vec![DVec2::ZERO, DVec2::new(w, 0.0), DVec2::new(w, d), DVec2::new(0.0, d)]);
        let people = Some((DVec2::new(0.5, 0.5), DVec2::new(2.5, 1.5)));
        // A 5 × 4 m plan fits a 6.2 m window: centred on the plan, wherever the people are.
        let fits = RoomWindow::around_focus(6.2, &rect(5.0, 4.0), people);
        assert_eq!(fits, RoomWindow::around(6.2, &rect(5.0, 4.0)));
        // A 20 × 4 m hall: along x the window moves to the people (centre 1.5) as far as the plan
        // allows (3.1, its edge at the wall); along y, where the plan fits, it stays centred.
        let hall = RoomWindow::around_focus(6.2, &rect(20.0, 4.0), people);
        assert_eq!(hall.center, DVec2::new(3.1, 2.0));
        // People in the middle of the hall: the window is centred on them.
        let middle = Some((DVec2::new(9.0, 1.0), DVec2::new(12.0, 3.0)));
        assert_eq!(RoomWindow::around_focus(6.2, &rect(20.0, 4.0), middle).center, DVec2::new(10.5, 2.0));
        // Nobody to keep in view: the plan's centre.
        assert_eq!(RoomWindow::around_focus(6.2, &rect(20.0, 4.0), None).center, DVec2::new(10.0, 2.0));
    }

    #[test]
    fn a_window_moves_as_little_as_keeps_its_focus_within_reach() {
        let w = RoomWindow { center: DVec2::new(6.2, 2.0), side: 12.4 };
        // A seat 0.6 m from the west wall, 5.6 m from the centre: the window moves 0.36 m west
        // along x, not at all along y.
        let seat = Some((DVec2::new(0.6, 1.6), DVec2::new(0.6, 1.6)));
        let moved = w.reaching(seat, 5.24);
        assert!((moved.center - DVec2::new(5.84, 2.0)).abs().max_element() < 1e-12, "{}", moved.center);
        assert_eq!(moved.side, 12.4);
        // Within reach already, or nobody: unmoved.
        assert_eq!(w.reaching(Some((DVec2::new(1.0, 0.5), DVec2::new(11.0, 3.5))), 5.24), w);
        assert_eq!(w.reaching(None, 5.24), w);
        // People spanning more than twice the reach: centred on them.
        let wide = w.reaching(Some((DVec2::new(0.0, 1.0), DVec2::new(11.0, 3.0))), 5.24);
        assert_eq!(wide.center, DVec2::new(5.5, 2.0));
    }

    #[test]
    fn pixel_centres_and_ranges_agree() {
        let w = window();
        assert_eq!(w.pixel(), 0.025);
        assert_eq!(w.pixel_center(0, 0), DVec2::new(-3.1875, 3.1875));
        let (c, r) = w.pixel_ranges(DVec2::new(-3.2, -3.2), DVec2::new(3.2, 3.2));
        assert_eq!((c, r), (0..256, 0..256));
        let (c, r) = w.pixel_ranges(DVec2::new(0.0, 0.0), DVec2::new(0.05, 0.05));
        assert_eq!((c.len(), r.len()), (2, 2));
        let (c, _) = w.pixel_ranges(DVec2::new(10.0, 0.0), DVec2::new(11.0, 0.0));
        assert!(c.is_empty());
    }

    #[test]
    fn square_covers_its_pixels_exactly() {
        // A 1 m square aligned with the grid covers exactly 40 × 40 pixels.
        let w = window();
        let sq = Polygon::rectangle(DVec2::ZERO, DVec2::ONE);
        assert_eq!(Mask::of_polygon(&w, &sq).count(), 1600);
        let b = OBox::new(DVec3::new(0.5, 0.5, 0.0), DVec3::ONE, 0.0);
        assert_eq!(Mask::of_footprint(&w, &b), Mask::of_polygon(&w, &sq));
    }
}
