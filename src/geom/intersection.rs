//! Exact intersection volume and IoU of two oriented boxes.
//!
//! Boxes rotate only about z, so the intersection is a vertical prism: (exact footprint overlap
//! area) × (overlap of the z ranges). No sampling, no approximation.

use super::{OBox, footprint_intersection_area};

/// Volume of the intersection of two boxes, m³.
pub fn intersection_volume(a: &OBox, b: &OBox) -> f64 {
    let (a0, a1) = a.z_range();
    let (b0, b1) = b.z_range();
    let dz = a1.min(b1) - a0.max(b0);
    if dz <= 0.0 {
        return 0.0;
    }
    footprint_intersection_area(a, b) * dz
}

/// Intersection over union of two boxes, in [0, 1]; 0 when both are empty.
pub fn iou_3d(a: &OBox, b: &OBox) -> f64 {
    let inter = intersection_volume(a, b);
    let union = a.volume() + b.volume() - inter;
    if union <= 0.0 { 0.0 } else { (inter / union).clamp(0.0, 1.0) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn unit_cubes_offset_by_half_have_iou_one_third() {
        let a = OBox::new(DVec3::ZERO, DVec3::ONE, 0.0);
        let b = OBox::new(DVec3::new(0.5, 0.0, 0.0), DVec3::ONE, 0.0);
        assert!((intersection_volume(&a, &b) - 0.5).abs() < 1e-12);
        assert!((iou_3d(&a, &b) - 1.0 / 3.0).abs() < 1e-12);
    }

    #[test]
    fn rotated_box_inside_bigger_box() {
        // A 1×1×1 cube turned 45° inside a 2×2×2 box: fully contained, IoU = 1/8.
        let big = OBox::new(DVec3::ZERO, DVec3::splat(2.0), 0.0);
        let small = OBox::new(DVec3::ZERO, DVec3::ONE, std::f64::consts::FRAC_PI_4);
        assert!((intersection_volume(&big, &small) - 1.0).abs() < 1e-12);
        assert!((iou_3d(&big, &small) - 0.125).abs() < 1e-12);
    }

    #[test]
    fn vertical_offset_scales_the_volume() {
        let a = OBox::new(DVec3::ZERO, DVec3::ONE, 0.3);
        let b = OBox::new(DVec3::new(0.0, 0.0, 0.75), DVec3::ONE, 0.3);
        assert!((intersection_volume(&a, &b) - 0.25).abs() < 1e-12);
        let c = OBox::new(DVec3::new(0.0, 0.0, 1.0), DVec3::ONE, 0.3);
        assert_eq!(intersection_volume(&a, &c), 0.0);
    }
}
