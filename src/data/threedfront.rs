//! Category figures of 3D-FRONT, the targets the procedural dataset follows.
//!
//! Object counts are from the ATISS-format `dataset_stats` files as collected in
//! `threedfront_stats.json` (bedrooms: 4,004 rooms; living rooms: the published living-room
//! statistics). 3D-FRONT's dining-room counts are not among those figures; dining rooms use the
//! living-room vocabulary and, as their target, the living-room frequencies (which are themselves led
//! by dining chairs and tables).

use crate::scene::{Category, RoomType};

/// Objects per category over all bedrooms.
pub const BEDROOM_COUNTS: [(Category, f64); 21] = {
    use Category::*;
    [
        (Nightstand, 5278.0),
        (DoubleBed, 3320.0),
        (Wardrobe, 3115.0),
        (PendantLamp, 2459.0),
        (CeilingLamp, 1222.0),
        (TvStand, 579.0),
        (Chair, 442.0),
        (SingleBed, 411.0),
        (DressingTable, 404.0),
        (Cabinet, 391.0),
        (Table, 381.0),
        (Desk, 315.0),
        (Stool, 222.0),
        (Shelf, 158.0),
        (KidsBed, 158.0),
        (Bookshelf, 139.0),
        (ChildrenCabinet, 139.0),
        (DressingChair, 119.0),
        (Armchair, 72.0),
        (Sofa, 29.0),
        (CoffeeTable, 19.0),
    ]
};

/// Bedrooms behind [`BEDROOM_COUNTS`].
pub const BEDROOM_ROOMS: f64 = 4004.0;

/// Objects per category over all living rooms.
pub const LIVING_COUNTS: [(Category, f64); 24] = {
    use Category::*;
    [
        (DiningChair, 1852.0),
        (PendantLamp, 965.0),
        (CoffeeTable, 626.0),
        (CornerSideTable, 526.0),
        (DiningTable, 505.0),
        (TvStand, 452.0),
        (MultiSeatSofa, 385.0),
        (Armchair, 351.0),
        (ConsoleTable, 269.0),
        (LoungeChair, 235.0),
        (Stool, 192.0),
        (Cabinet, 168.0),
        (Bookshelf, 160.0),
        (LoveseatSofa, 152.0),
        (CeilingLamp, 132.0),
        (WineCabinet, 88.0),
        (LShapedSofa, 75.0),
        (RoundEndTable, 42.0),
        (Shelf, 26.0),
        (ChineseChair, 23.0),
        (Wardrobe, 20.0),
        (ChaiseLongueSofa, 8.0),
        (Desk, 7.0),
        (LazySofa, 6.0),
    ]
};

/// The target frequency of each category of `room`, in the room type's one-hot order (sums to 1).
pub fn target_frequencies(room: RoomType) -> Vec<f64> {
    let counts: &[(Category, f64)] = match room {
        RoomType::Bedroom => &BEDROOM_COUNTS,
        RoomType::Living | RoomType::Dining => &LIVING_COUNTS,
    };
    let total: f64 = counts.iter().map(|c| c.1).sum();
    room.categories().iter().map(|c| counts.iter().find(|(k, _)| k == c).map_or(0.0, |(_, n)| n / total)).collect()
}

/// KL divergence Σ p (log(p + ε) − log(q + ε)) with ε = 1e-6 (the CKL metric's form).
pub fn kl_divergence(p: &[f64], q: &[f64]) -> f64 {
    p.iter().zip(q).map(|(&a, &b)| a * ((a + 1e-6).ln() - (b + 1e-6).ln())).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frequencies_cover_the_vocabularies() {
        for room in RoomType::ALL {
            let f = target_frequencies(room);
            assert_eq!(f.len(), room.categories().len());
            assert!((f.iter().sum::<f64>() - 1.0).abs() < 1e-12);
            assert!(f.iter().all(|&x| x > 0.0), "{room}: every category occurs");
            assert!(kl_divergence(&f, &f).abs() < 1e-12);
        }
    }
}
