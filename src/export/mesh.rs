//! Triangle meshes for pictures and glTF: a unit box, a capsule along z, a flat floor polygon.
//! Positions and normals in f32, counter-clockwise triangles seen from outside.

use crate::geom::Polygon;
use std::f64::consts::{FRAC_PI_2, TAU};

/// An indexed triangle mesh.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TriMesh {
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Unit vertex normals.
    pub normals: Vec<[f32; 3]>,
    /// Three vertex indices per triangle.
    pub indices: Vec<u32>,
}

impl TriMesh {
    fn vertex(&mut self, p: [f64; 3], n: [f64; 3]) -> u32 {
        self.positions.push(p.map(|v| v as f32));
        self.normals.push(n.map(|v| v as f32));
        (self.positions.len() - 1) as u32
    }

    /// The box from −0.5 to 0.5 on every axis, four vertices per face (flat normals).
    pub fn unit_box() -> TriMesh {
        let mut m = TriMesh::default();
        for axis in 0..3 {
            for sign in [-1.0, 1.0] {
                let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
                let mut n = [0.0; 3];
                n[axis] = sign;
                let corner = |a: f64, b: f64| {
                    let mut p = [0.0; 3];
                    p[axis] = 0.5 * sign;
                    p[u] = a * 0.5;
                    p[v] = b * 0.5;
                    p
                };
                let base = m.positions.len() as u32;
                for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                    m.vertex(corner(a, b), n);
                }
                // (u, v, axis) is right-handed, so u→v winds counter-clockwise seen from +axis.
                let quad = if sign > 0.0 { [0, 1, 2, 0, 2, 3] } else { [0, 2, 1, 0, 3, 2] };
                m.indices.extend(quad.map(|i| base + i));
            }
        }
        m
    }

    /// A capsule along z: a cylinder from −`half` to `half` of radius `radius` with hemispherical
    /// caps; `segments` around, `rings` per cap.
    pub fn capsule(radius: f64, half: f64, segments: usize, rings: usize) -> TriMesh {
        let mut m = TriMesh::default();
        // Latitude rows from the bottom pole to the top pole; the two equator rows of each cap
        // are joined by the cylinder's band.
        let mut rows = Vec::new();
        for r in 0..=rings {
            rows.push((-FRAC_PI_2 + FRAC_PI_2 * r as f64 / rings as f64, -half));
        }
        for r in 0..=rings {
            rows.push((FRAC_PI_2 * r as f64 / rings as f64, half));
        }
        for &(lat, z0) in &rows {
            for s in 0..=segments {
                let lon = TAU * s as f64 / segments as f64;
                let n = [lat.cos() * lon.cos(), lat.cos() * lon.sin(), lat.sin()];
                m.vertex([n[0] * radius, n[1] * radius, z0 + n[2] * radius], n);
            }
        }
        let width = segments as u32 + 1;
        for r in 0..rows.len() as u32 - 1 {
            for s in 0..segments as u32 {
                let (a, b) = (r * width + s, (r + 1) * width + s);
                m.indices.extend([a, a + 1, b + 1, a, b + 1, b]);
            }
        }
        m
    }

    /// The floor polygon at z = 0, facing up.
    pub fn floor(polygon: &Polygon) -> TriMesh {
        let mut m = TriMesh::default();
        for p in &polygon.points {
            m.vertex([p.x, p.y, 0.0], [0.0, 0.0, 1.0]);
        }
        m.indices = polygon.triangulate().into_iter().flatten().map(|i| i as u32).collect();
        m
    }

    /// Smallest and largest position on each axis.
    pub fn bounds(&self) -> ([f32; 3], [f32; 3]) {
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        for p in &self.positions {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        (lo, hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// Signed volume by the divergence theorem: positive iff triangles wind outwards.
    fn volume(m: &TriMesh) -> f32 {
        m.indices
            .chunks(3)
            .map(|t| {
                let [a, b, c] = [0, 1, 2].map(|k| Vec3::from(m.positions[t[k] as usize]));
                a.dot(b.cross(c)) / 6.0
            })
            .sum()
    }

    #[test]
    fn the_unit_box_is_closed_outward_and_of_volume_one() {
        let m = TriMesh::unit_box();
        assert_eq!((m.positions.len(), m.indices.len()), (24, 36));
        assert!((volume(&m) - 1.0).abs() < 1e-6);
        // Each triangle's geometric normal agrees with its vertices' normals.
        for t in m.indices.chunks(3) {
            let [a, b, c] = [0, 1, 2].map(|k| Vec3::from(m.positions[t[k] as usize]));
            assert!((b - a).cross(c - a).normalize().dot(Vec3::from(m.normals[t[0] as usize])) > 0.99);
        }
    }

    #[test]
    fn a_capsule_has_the_volume_of_a_cylinder_and_a_ball() {
        let (r, h) = (0.1, 0.3);
        let m = TriMesh::capsule(r, h, 48, 24);
        let exact = std::f64::consts::PI * r * r * (2.0 * h) + 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
        let v = f64::from(volume(&m));
        assert!((v - exact).abs() / exact < 0.01, "{v} vs {exact}");
        let (lo, hi) = m.bounds();
        assert!((hi[2] - 0.4).abs() < 1e-6 && (lo[2] + 0.4).abs() < 1e-6);
        assert!(m.normals.iter().all(|n| (Vec3::from(*n).length() - 1.0).abs() < 1e-5));
    }
}
