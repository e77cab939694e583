//! Masks as greyscale PNGs (set pixels white), row 0 at the top like the mask.

use super::canvas::png_bytes;
use crate::geom::{Mask, RES};
use crate::scene::write_atomic;
use std::path::Path;

/// PNG bytes of a mask.
pub fn mask_png(mask: &Mask) -> Vec<u8> {
    let raw: Vec<u8> = mask.rows().flat_map(|row| row.iter().map(|&b| if b { 255 } else { 0 })).collect();
    png_bytes(&raw, RES as u32, RES as u32, image::ExtendedColorType::L8)
}

/// Writes a mask as PNG, atomically.
///
/// # Errors
/// Any I/O error of writing `path`.
pub fn save_mask_png(mask: &Mask, path: &Path) -> std::io::Result<()> {
    write_atomic(path, &mask_png(mask))
}
