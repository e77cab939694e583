//! A small RGB canvas with a world-to-pixel view: filled polygons, capsules (thick lines with round
//! ends) and discs, antialiasing-free and deterministic. PNG encoding writes atomically.

use crate::scene::write_atomic;
use glam::DVec2;
use image::{ImageEncoder, Rgb, RgbImage};
use std::path::Path;

/// An RGB colour.
pub type Color = [u8; 3];

/// Maps world coordinates (metres, y up) to pixels (y down).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    /// World point shown at the top-left pixel corner.
    pub top_left: DVec2,
    /// Pixels per metre.
    pub scale: f64,
    /// Pixel offset of the view's top-left corner in the canvas (for side-by-side panels).
    pub offset: DVec2,
}

impl View {
    /// World point → pixel coordinates (continuous).
    pub fn to_pixel(&self, p: DVec2) -> DVec2 {
        DVec2::new((p.x - self.top_left.x) * self.scale, (self.top_left.y - p.y) * self.scale) + self.offset
    }
}

/// An image being drawn.
#[derive(Debug, Clone)]
pub struct Canvas {
    image: RgbImage,
}

impl Canvas {
    /// A canvas of `width` × `height` pixels filled with `background`.
    pub fn new(width: u32, height: u32, background: Color) -> Canvas {
        Canvas { image: RgbImage::from_pixel(width, height, Rgb(background)) }
    }

    /// Width and height in pixels.
    pub fn dimensions(&self) -> (u32, u32) {
        self.image.dimensions()
    }

    /// Colour of a pixel.
    pub fn pixel(&self, x: u32, y: u32) -> Color {
        self.image.get_pixel(x, y).0
    }

    /// Sets one pixel (ignored outside the canvas).
    pub fn put(&mut self, x: i64, y: i64, color: Color) {
        let (w, h) = self.image.dimensions();
        if x >= 0 && y >= 0 && (x as u32) < w && (y as u32) < h {
            self.image.put_pixel(x as u32, y as u32, Rgb(color));
        }
    }

    /// Visits pixels whose centres lie in the pixel-space box `lo`..`hi`, clipped to the canvas.
    fn for_pixels(&mut self, lo: DVec2, hi: DVec2, mut inside: impl FnMut(DVec2) -> bool, color: Color) {
        let (w, h) = self.image.dimensions();
        let x0 = (lo.x - 0.5).ceil().max(0.0) as u32;
        let y0 = (lo.y - 0.5).ceil().max(0.0) as u32;
        let x1 = ((hi.x - 0.5).floor() + 1.0).clamp(0.0, w as f64) as u32;
        let y1 = ((hi.y - 0.5).floor() + 1.0).clamp(0.0, h as f64) as u32;
        for y in y0..y1 {
            for x in x0..x1 {
                if inside(DVec2::new(x as f64 + 0.5, y as f64 + 0.5)) {
                    self.image.put_pixel(x, y, Rgb(color));
                }
            }
        }
    }

    /// Fills a polygon given in world coordinates (even–odd rule).
    pub fn fill_polygon(&mut self, view: &View, points: &[DVec2], color: Color) {
        if points.len() < 3 {
            return;
        }
        let px: Vec<DVec2> = points.iter().map(|&p| view.to_pixel(p)).collect();
        let lo = px.iter().fold(DVec2::splat(f64::INFINITY), |m, &p| m.min(p));
        let hi = px.iter().fold(DVec2::splat(f64::NEG_INFINITY), |m, &p| m.max(p));
        let polygon = crate::geom::Polygon::new(px);
        self.for_pixels(lo, hi, |p| polygon.contains(p), color);
    }

    /// A capsule from `a` to `b` (world) of world radius `radius`, at least half a pixel wide.
    pub fn capsule(&mut self, view: &View, a: DVec2, b: DVec2, radius: f64, color: Color) {
        let (pa, pb) = (view.to_pixel(a), view.to_pixel(b));
        let r = (radius * view.scale).max(0.5);
        let lo = pa.min(pb) - r;
        let hi = pa.max(pb) + r;
        self.for_pixels(lo, hi, |p| crate::geom::point_segment_distance(p, pa, pb) <= r, color);
    }

    /// A line of `width` pixels between world points.
    pub fn line(&mut self, view: &View, a: DVec2, b: DVec2, width: f64, color: Color) {
        self.capsule(view, a, b, width * 0.5 / view.scale, color);
    }

    /// A filled disc.
    pub fn disc(&mut self, view: &View, center: DVec2, radius: f64, color: Color) {
        self.capsule(view, center, center, radius, color);
    }

    /// The outline of a closed polygon, `width` pixels wide.
    pub fn outline(&mut self, view: &View, points: &[DVec2], width: f64, color: Color) {
        for i in 0..points.len() {
            self.line(view, points[i], points[(i + 1) % points.len()], width, color);
        }
    }

    /// The image.
    pub fn into_image(self) -> RgbImage {
        self.image
    }

    /// PNG bytes of the canvas.
    pub fn png_bytes(&self) -> Vec<u8> {
        png_bytes(self.image.as_raw(), self.image.width(), self.image.height(), image::ExtendedColorType::Rgb8)
    }

    /// Writes the canvas as PNG, atomically.
    ///
    /// # Errors
    /// Any I/O error of writing `path`.
    pub fn save_png(&self, path: &Path) -> std::io::Result<()> {
        write_atomic(path, &self.png_bytes())
    }
}

/// PNG-encodes raw pixels.
pub fn png_bytes(raw: &[u8], width: u32, height: u32, color: image::ExtendedColorType) -> Vec<u8> {
    let mut out = Vec::new();
    image::codecs::png::PngEncoder::new(&mut out)
        .write_image(raw, width, height, color)
        .expect("encoding to memory with matching dimensions cannot fail");
    out
}
