//! Real furniture dimensions, per category, from the Sweet Home 3D furniture catalogs.
//!
//! `catalog.csv` (next to this file) lists items of the catalogs that Debian ships as
//! `sweethome3d-furniture` (Scopia, BlendSwap-CC-0 / CC-BY, KatorLegaz, the default catalog), each
//! assigned to one of our categories, with the source row, catalog, licence and full dimensions in
//! centimetres. Where a category has no exact counterpart the nearest real pieces stand in (console
//! tables use dressers and a low table; end tables use small round and side tables). Only the numbers
//! are used; no meshes ship with shade-sim.

use crate::scene::Category;
use std::collections::HashMap;
use std::sync::OnceLock;

const CSV: &str = include_str!("catalog.csv");

/// One real piece of furniture.
#[derive(Debug, Clone, PartialEq)]
pub struct CatalogItem {
    /// Our category.
    pub category: Category,
    /// Row in the source catalog table.
    pub source_row: usize,
    /// Source catalog.
    pub catalog: String,
    /// Licence of the source model.
    pub license: String,
    /// The catalog's name for it.
    pub name: String,
    /// Full extents in metres: width, depth, height.
    pub size: [f64; 3],
    /// Height above the floor of its bottom, metres (hanging lamps).
    pub elevation: f64,
}

fn parse_line(line: &str) -> Vec<String> {
    let mut fields = Vec::new();
    let mut field = String::new();
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                field.push('"');
                chars.next();
            }
            ('"', _) => quoted = !quoted,
            (',', false) => fields.push(std::mem::take(&mut field)),
            (c, _) => field.push(c),
        }
    }
    fields.push(field);
    fields
}

fn load() -> HashMap<Category, Vec<CatalogItem>> {
    let mut map: HashMap<Category, Vec<CatalogItem>> = HashMap::new();
    for line in CSV.lines().skip(1).filter(|l| !l.trim().is_empty()) {
        let f = parse_line(line);
        let num = |i: usize| f[i].parse::<f64>().expect("catalog.csv numbers are valid (tested)");
        let item = CatalogItem {
            category: Category::from_name(&f[0]).expect("catalog.csv categories are valid (tested)"),
            source_row: f[1].parse().expect("catalog.csv rows are integers (tested)"),
            catalog: f[2].clone(),
            license: f[3].clone(),
            name: f[4].clone(),
            size: [num(5) / 100.0, num(6) / 100.0, num(7) / 100.0],
            elevation: num(8) / 100.0,
        };
        map.entry(item.category).or_default().push(item);
    }
    map
}

/// The real pieces of `category` (never empty for a category of any room type).
pub fn catalog_items(category: Category) -> &'static [CatalogItem] {
    static CATALOG: OnceLock<HashMap<Category, Vec<CatalogItem>>> = OnceLock::new();
    CATALOG.get_or_init(load).get(&category).map(Vec::as_slice).unwrap_or(&[])
}

/// The lowest and highest of `category`'s real pieces (m); (0, ∞) for a category without any.
pub fn height_range(category: Category) -> (f64, f64) {
    size_range(category, 2)
}

/// How far (m) a piece may lie outside its category's real range ([`size_range`]) and still count
/// as one of them: the guidance keeps pieces within it (`GuidanceConfig::real_sizes`) and `eval`
/// counts the rooms with a piece beyond it (repair's `settle.max_grow_height` is as much).
pub const REAL_SIZE_MARGIN: f64 = 0.15;

/// The smallest and largest width (`axis` 0), depth (1) or height (2) of `category`'s real pieces
/// (m); (0, ∞) for a category without any.
pub fn size_range(category: Category, axis: usize) -> (f64, f64) {
    let sizes = catalog_items(category).iter().map(|i| i.size[axis]);
    let (lo, hi) = sizes.fold((f64::INFINITY, 0.0_f64), |(lo, hi), h| (lo.min(h), hi.max(h)));
    if lo.is_finite() { (lo, hi) } else { (0.0, f64::INFINITY) }
}

/// The share by which the procedural dataset draws a piece's width, depth and height off its
/// catalog item's (`data::layout::real_size`: uniform within ±7 % and ±4 %, then to the centimetre).
pub const SIZE_JITTER: [f64; 3] = [0.07, 0.07, 0.04];

/// The sizes (m) the procedural dataset draws for `category` on `axis`: its real range
/// ([`size_range`]) widened by [`SIZE_JITTER`] and half a centimetre of rounding. Every piece of
/// the data lies within it; (0, ∞) for a category without real pieces.
pub fn drawn_range(category: Category, axis: usize) -> (f64, f64) {
    let (lo, hi) = size_range(category, axis);
    let j = SIZE_JITTER[axis];
    ((lo * (1.0 - j) - 0.005).max(0.0), hi * (1.0 + j) + 0.005)
}

/// How far (m) `size` lies outside `category`'s real range on `axis` (0 inside it).
pub fn beyond_real(category: Category, axis: usize, size: f64) -> f64 {
    let (lo, hi) = size_range(category, axis);
    (lo - size).max(size - hi).max(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn height_range_spans_the_real_pieces() {
        // catalog.csv's double beds: 52.8 cm (a low platform bed) to 116 cm (a headboard).
        let (lo, hi) = height_range(Category::DoubleBed);
        assert!((lo - 0.528).abs() < 1e-9 && (hi - 1.16).abs() < 1e-9, "{lo} {hi}");
        for &c in Category::ALL {
            let (lo, hi) = height_range(c);
            assert!(catalog_items(c).iter().all(|i| (lo..=hi).contains(&i.size[2])), "{c}");
        }
    }

    #[test]
    fn every_category_has_real_pieces_with_sane_sizes() {
        for &c in Category::ALL {
            let items = catalog_items(c);
            assert!(!items.is_empty(), "{c} has no catalog items");
            for it in items {
                assert!(it.size.iter().all(|&s| s > 0.05 && s < 4.0), "{c}: {} {:?}", it.name, it.size);
            }
        }
        let bed = &catalog_items(Category::DoubleBed)[0];
        assert_eq!(bed.name, "Bed");
        assert!((DVec3::from(bed.size) - DVec3::new(1.705, 2.165, 1.108)).length() < 1e-12);
        assert_eq!(parse_line(r#"a,"b, c",d"#), vec!["a", "b, c", "d"]);
    }
}
