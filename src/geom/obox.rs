//! Oriented boxes: a centre, full extents and a rotation about +z.

use glam::{DVec2, DVec3};

/// A box rotated about the vertical axis (the only rotation furniture has in `shade-scene/1`).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct OBox {
    /// Centre in world coordinates.
    pub center: DVec3,
    /// Full extents along the local axes (x = width, y = depth, z = height).
    pub size: DVec3,
    /// Rotation about +z from local to world, counter-clockwise, radians.
    pub yaw: f64,
}

impl OBox {
    /// A box from centre, full extents and yaw.
    pub fn new(center: DVec3, size: DVec3, yaw: f64) -> OBox {
        OBox { center, size, yaw }
    }

    /// Half extents.
    pub fn half(&self) -> DVec3 {
        self.size * 0.5
    }

    /// Volume in m³.
    pub fn volume(&self) -> f64 {
        self.size.x * self.size.y * self.size.z
    }

    /// Footprint area in m².
    pub fn footprint_area(&self) -> f64 {
        self.size.x * self.size.y
    }

    /// World directions of the local x (width) and y (depth, the front) axes.
    pub fn axes(&self) -> (DVec2, DVec2) {
        let (s, c) = self.yaw.sin_cos();
        (DVec2::new(c, s), DVec2::new(-s, c))
    }

    /// Bottom and top z.
    pub fn z_range(&self) -> (f64, f64) {
        (self.center.z - self.size.z * 0.5, self.center.z + self.size.z * 0.5)
    }

    /// The four footprint corners, counter-clockwise.
    pub fn footprint(&self) -> [DVec2; 4] {
        let (ax, ay) = self.axes();
        let c = self.center.truncate();
        let hx = ax * (self.size.x * 0.5);
        let hy = ay * (self.size.y * 0.5);
        [c - hx - hy, c + hx - hy, c + hx + hy, c - hx + hy]
    }

    /// Axis-aligned bounds of the footprint: (min, max).
    pub fn footprint_aabb(&self) -> (DVec2, DVec2) {
        let (ax, ay) = self.axes();
        let e = ax.abs() * (self.size.x * 0.5) + ay.abs() * (self.size.y * 0.5);
        let c = self.center.truncate();
        (c - e, c + e)
    }

    /// `p` in the box's local frame (origin at the centre).
    pub fn to_local(&self, p: DVec3) -> DVec3 {
        let d = p - self.center;
        let (s, c) = self.yaw.sin_cos();
        DVec3::new(c * d.x + s * d.y, -s * d.x + c * d.y, d.z)
    }

    /// A local point in world coordinates.
    pub fn to_world(&self, local: DVec3) -> DVec3 {
        let (s, c) = self.yaw.sin_cos();
        self.center + DVec3::new(c * local.x - s * local.y, s * local.x + c * local.y, local.z)
    }

    /// Whether `p` lies inside or on the box.
    pub fn contains(&self, p: DVec3) -> bool {
        let q = self.to_local(p).abs();
        let h = self.half();
        q.x <= h.x && q.y <= h.y && q.z <= h.z
    }

    /// Whether the 2D point `p` lies inside or on the footprint.
    pub fn footprint_contains(&self, p: DVec2) -> bool {
        let q = self.to_local(p.extend(self.center.z)).abs();
        q.x <= self.size.x * 0.5 && q.y <= self.size.y * 0.5
    }

    /// Signed distance from `p` to the box surface: negative inside, positive outside, exact.
    pub fn signed_distance(&self, p: DVec3) -> f64 {
        let q = self.to_local(p).abs() - self.half();
        let outside = q.max(DVec3::ZERO).length();
        let inside = q.max_element().min(0.0);
        outside + inside
    }

    /// Signed distance from a 2D point to the footprint rectangle (the 2D analogue of
    /// [`OBox::signed_distance`]).
    pub fn footprint_signed_distance(&self, p: DVec2) -> f64 {
        let l = self.to_local(p.extend(self.center.z));
        let q = DVec2::new(l.x.abs() - self.size.x * 0.5, l.y.abs() - self.size.y * 0.5);
        q.max(DVec2::ZERO).length() + q.max_element().min(0.0)
    }

    /// The same box moved by `offset` and turned by `dyaw` about the vertical axis through `pivot`.
    pub fn transformed(&self, pivot: DVec2, dyaw: f64, offset: DVec3) -> OBox {
        let (s, c) = dyaw.sin_cos();
        let d = self.center.truncate() - pivot;
        let rotated = pivot + DVec2::new(c * d.x - s * d.y, s * d.x + c * d.y);
        OBox::new(rotated.extend(self.center.z) + offset, self.size, self.yaw + dyaw)
    }
}

/// The yaw whose front (local +y) faces the horizontal direction `dir`.
pub fn yaw_facing(dir: DVec2) -> f64 {
    (-dir.x).atan2(dir.y)
}

/// `a` as an angle in (−π, π].
pub fn wrap_angle(a: f64) -> f64 {
    let w = a.rem_euclid(std::f64::consts::TAU);
    if w > std::f64::consts::PI { w - std::f64::consts::TAU } else { w }
}

/// The horizontal unit direction the front (local +y) of something with `yaw` faces.
pub fn facing(yaw: f64) -> DVec2 {
    DVec2::new(-yaw.sin(), yaw.cos())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn signed_distance_by_hand() {
        let b = OBox::new(DVec3::new(1.0, 2.0, 0.5), DVec3::new(2.0, 1.0, 1.0), FRAC_PI_2);
        // Rotated 90°: world x-extent is 1 (depth), world y-extent is 2 (width).
        assert!((b.signed_distance(DVec3::new(1.0, 2.0, 0.5)) + 0.5).abs() < 1e-12);
        assert!((b.signed_distance(DVec3::new(2.0, 2.0, 0.5)) - 0.5).abs() < 1e-12);
        assert!((b.signed_distance(DVec3::new(1.0, 3.5, 0.5)) - 0.5).abs() < 1e-12);
        // Corner region: distance to the edge at (1.5, 3, z=1) from (2.5, 4, 1): sqrt(2).
        assert!((b.signed_distance(DVec3::new(2.5, 4.0, 1.0)) - 2f64.sqrt()).abs() < 1e-12);
        assert!(b.contains(DVec3::new(1.4, 2.9, 0.1)));
        assert!(!b.contains(DVec3::new(1.6, 2.0, 0.5)));
    }

    #[test]
    fn footprint_is_counter_clockwise_and_matches_aabb() {
        let b = OBox::new(DVec3::new(0.0, 0.0, 0.0), DVec3::new(2.0, 1.0, 1.0), 0.3);
        let fp = b.footprint();
        let area: f64 = (0..4).map(|i| fp[i].perp_dot(fp[(i + 1) % 4])).sum::<f64>() * 0.5;
        assert!((area - 2.0).abs() < 1e-12);
        let (lo, hi) = b.footprint_aabb();
        for p in fp {
            assert!(p.x >= lo.x - 1e-12 && p.x <= hi.x + 1e-12 && p.y >= lo.y - 1e-12 && p.y <= hi.y + 1e-12);
        }
    }
}
