//! Points on the body surface (the union of the bone capsules), for interpenetration (E_pen).
//!
//! Points are laid out once per skeleton (evenly by area: rings on each capsule's cylinder,
//! Fibonacci spirals on its end caps), points buried inside another capsule of the same body in the
//! reference frame are dropped, and each remaining point is stored relative to its bone, so it
//! follows the bone in every frame.

use crate::scene::Skeleton;
use glam::DVec3;
use std::f64::consts::{PI, TAU};

/// A point attached to a bone: along the axis at `t` ∈ [0, 1], then `radius` out along `dir`
/// (x, y in the plane normal to the bone, z along the bone).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Attached {
    bone: usize,
    t: f64,
    dir: DVec3,
}

/// Evenly spread surface points of a skeleton's capsules.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceSampler {
    points: Vec<Attached>,
}

impl SurfaceSampler {
    /// About `target` points for `skeleton`, laid out on the pose `reference` (one position per
    /// joint; a neutral pose such as the first frame).
    pub fn new(skeleton: &Skeleton, reference: &[DVec3], target: usize) -> SurfaceSampler {
        let first = Self::layout(skeleton, reference, target);
        let kept = first.points.len().max(1);
        // Re-lay with more points so that about `target` survive the burial filter.
        let scaled = (target as f64 * target as f64 / kept as f64).round() as usize;
        Self::layout(skeleton, reference, scaled)
    }

    fn layout(skeleton: &Skeleton, reference: &[DVec3], target: usize) -> SurfaceSampler {
        let bones = &skeleton.bones;
        let length = |b: usize| reference[bones[b].a].distance(reference[bones[b].b]);
        let area = |b: usize| {
            let r = bones[b].radius;
            TAU * r * length(b) + 4.0 * PI * r * r
        };
        let total: f64 = (0..bones.len()).map(area).sum();
        let mut points = Vec::new();
        for (b, bone) in bones.iter().enumerate() {
            let r = bone.radius;
            let l = length(b);
            let n = target as f64 * area(b) / total;
            let n_cyl = n * (TAU * r * l) / area(b);
            let n_cap = ((n - n_cyl) * 0.5).round().max(1.0) as usize;
            let rings = (n_cyl * l / (TAU * r)).sqrt().round().max(1.0) as usize;
            let per_ring = (n_cyl / rings as f64).round().max(3.0) as usize;
            for i in 0..rings {
                let t = (i as f64 + 0.5) / rings as f64;
                for k in 0..per_ring {
                    let angle = TAU * (k as f64 + 0.5 * (i % 2) as f64) / per_ring as f64;
                    points.push(Attached { bone: b, t, dir: DVec3::new(angle.cos(), angle.sin(), 0.0) });
                }
            }
            for (t, sign) in [(0.0, -1.0), (1.0, 1.0)] {
                for dir in fibonacci_hemisphere(n_cap) {
                    points.push(Attached { bone: b, t, dir: DVec3::new(dir.x, dir.y, sign * dir.z) });
                }
            }
        }
        let sampler = SurfaceSampler { points };
        let world = sampler.points(skeleton, reference);
        let points = sampler
            .points
            .iter()
            .zip(&world)
            .filter(|(p, q)| !buried(skeleton, reference, p.bone, **q))
            .map(|(p, _)| *p)
            .collect();
        SurfaceSampler { points }
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether there are no points.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// World positions of the points for one frame of joint positions.
    pub fn points(&self, skeleton: &Skeleton, joints: &[DVec3]) -> Vec<DVec3> {
        let frames: Vec<(DVec3, DVec3, DVec3, DVec3)> = skeleton
            .bones
            .iter()
            .map(|bone| {
                let (a, b) = (joints[bone.a], joints[bone.b]);
                let axis = (b - a).normalize_or(DVec3::Z);
                let (e1, e2) = axis.any_orthonormal_pair();
                (a, b - a, e1, e2)
            })
            .collect();
        self.points
            .iter()
            .map(|p| {
                let (a, ab, e1, e2) = frames[p.bone];
                let axis = ab.normalize_or(DVec3::Z);
                let r = skeleton.bones[p.bone].radius;
                a + ab * p.t + (e1 * p.dir.x + e2 * p.dir.y + axis * p.dir.z) * r
            })
            .collect()
    }
}

/// Whether `p` lies strictly inside a capsule other than `own`.
fn buried(skeleton: &Skeleton, joints: &[DVec3], own: usize, p: DVec3) -> bool {
    skeleton
        .bones
        .iter()
        .enumerate()
        .any(|(i, bone)| i != own && segment_distance_3d(p, joints[bone.a], joints[bone.b]) < bone.radius - 1e-9)
}

/// Distance from `p` to the 3D segment `a`–`b`.
pub fn segment_distance_3d(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 == 0.0 { 0.0 } else { ((p - a).dot(ab) / len2).clamp(0.0, 1.0) };
    p.distance(a + ab * t)
}

/// `n` unit directions spread over the upper hemisphere (z ≥ 0).
fn fibonacci_hemisphere(n: usize) -> impl Iterator<Item = DVec3> {
    let golden = PI * (3.0 - 5f64.sqrt());
    (0..n).map(move |i| {
        let z = 1.0 - (i as f64 + 0.5) / n as f64;
        let r = (1.0 - z * z).sqrt();
        let a = golden * i as f64;
        DVec3::new(r * a.cos(), r * a.sin(), z)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::human::{Body, stand};
    use glam::DVec2;

    #[test]
    fn about_a_thousand_points_on_the_surface() {
        let body = Body::default();
        let skeleton = body.skeleton();
        let pose = stand(&body, DVec2::new(1.0, 1.0), 0.4);
        let sampler = SurfaceSampler::new(&skeleton, &pose.0, 1000);
        assert!((900..1100).contains(&sampler.len()), "{}", sampler.len());
        let pts = sampler.points(&skeleton, &pose.0);
        // Every point is on the surface of the union: on some capsule, inside none.
        for p in &pts {
            let d = skeleton
                .bones
                .iter()
                .map(|b| segment_distance_3d(*p, pose.0[b.a], pose.0[b.b]) - b.radius)
                .fold(f64::INFINITY, f64::min);
            assert!(d.abs() < 1e-6, "point off the surface by {d}");
        }
        // The points span the body: feet near the floor, head near the stature.
        let zmin = pts.iter().map(|p| p.z).fold(f64::INFINITY, f64::min);
        let zmax = pts.iter().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max);
        assert!(zmin < 0.03 && (zmax - 1.75).abs() < 0.03, "{zmin} {zmax}");
    }
}
