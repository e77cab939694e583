//! Room types, furniture categories, actions and the affordance table.
//!
//! The one-hot order of each room type's categories is fixed by the format (DESIGN.md) and must not
//! change: trained checkpoints and other tools depend on it. This module does not know about sizes or
//! placement (that is `data`), only names, orders and which actions a category supports.

use serde::{Deserialize, Serialize};
use std::fmt;

/// The kind of room a scene describes; it selects the category vocabulary and the room window.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RoomType {
    /// Bedrooms: 21 categories, at most 12 objects, a 6.2 m room window.
    Bedroom,
    /// Living rooms: 24 categories, at most 21 objects, a 12.4 m room window.
    Living,
    /// Dining rooms: the living-room vocabulary, at most 21 objects, a 12.4 m room window.
    Dining,
}

/// What a human does during a range of frames.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Action {
    /// Walking: the feet mark floor that must stay free.
    Walk,
    /// Standing: the feet mark floor that must stay free.
    Stand,
    /// Sitting: needs a seat under the pelvis and thighs.
    Sit,
    /// Lying: needs a surface under the torso.
    Lie,
    /// Touching: a hand reaches a piece of furniture.
    Touch,
}

impl Action {
    /// All actions, in declaration order.
    pub const ALL: [Action; 5] = [Action::Walk, Action::Stand, Action::Sit, Action::Lie, Action::Touch];

    /// Walking and standing humans mark free space; the others need furniture.
    pub fn is_free_space(self) -> bool {
        matches!(self, Action::Walk | Action::Stand)
    }

    /// Sitting, lying and touching humans are in contact with furniture.
    pub fn is_contact(self) -> bool {
        !self.is_free_space()
    }

    /// The name used in files (`"walk"`, `"sit"`, ...).
    pub fn name(self) -> &'static str {
        match self {
            Action::Walk => "walk",
            Action::Stand => "stand",
            Action::Sit => "sit",
            Action::Lie => "lie",
            Action::Touch => "touch",
        }
    }
}

impl fmt::Display for Action {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

macro_rules! categories {
    ($($variant:ident => $name:literal, $group:ident;)*) => {
        /// A furniture category: the union of the bedroom and living/dining vocabularies.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
        #[serde(rename_all = "snake_case")]
        pub enum Category {
            $(#[doc = $name] $variant,)*
        }

        impl Category {
            /// Every category, alphabetically.
            pub const ALL: &'static [Category] = &[$(Category::$variant,)*];

            /// The name used in files (`"double_bed"`, ...).
            pub fn name(self) -> &'static str {
                match self { $(Category::$variant => $name,)* }
            }

            /// The functional group the category belongs to (drives affordances and templates).
            pub fn group(self) -> Group {
                match self { $(Category::$variant => Group::$group,)* }
            }

            /// Parses a file name of a category.
            pub fn from_name(name: &str) -> Option<Category> {
                match name { $($name => Some(Category::$variant),)* _ => None }
            }
        }
    };
}

categories! {
    Armchair => "armchair", Chair;
    Bookshelf => "bookshelf", Shelf;
    Cabinet => "cabinet", Cabinet;
    CeilingLamp => "ceiling_lamp", Lamp;
    ChaiseLongueSofa => "chaise_longue_sofa", Sofa;
    Chair => "chair", Chair;
    ChildrenCabinet => "children_cabinet", Cabinet;
    ChineseChair => "chinese_chair", Chair;
    CoffeeTable => "coffee_table", Table;
    ConsoleTable => "console_table", Table;
    CornerSideTable => "corner_side_table", Table;
    Desk => "desk", Table;
    DiningChair => "dining_chair", Chair;
    DiningTable => "dining_table", Table;
    DoubleBed => "double_bed", Bed;
    DressingChair => "dressing_chair", Chair;
    DressingTable => "dressing_table", Table;
    KidsBed => "kids_bed", Bed;
    LShapedSofa => "l_shaped_sofa", Sofa;
    LazySofa => "lazy_sofa", Sofa;
    LoungeChair => "lounge_chair", Chair;
    LoveseatSofa => "loveseat_sofa", Sofa;
    MultiSeatSofa => "multi_seat_sofa", Sofa;
    Nightstand => "nightstand", Cabinet;
    PendantLamp => "pendant_lamp", Lamp;
    RoundEndTable => "round_end_table", Table;
    Shelf => "shelf", Shelf;
    SingleBed => "single_bed", Bed;
    Sofa => "sofa", Sofa;
    Stool => "stool", Stool;
    Table => "table", Table;
    TvStand => "tv_stand", Cabinet;
    Wardrobe => "wardrobe", Cabinet;
    WineCabinet => "wine_cabinet", Cabinet;
}

/// Functional groups of categories (MIME's affordance classes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Group {
    /// Beds: lie (60 %) or sit (40 %).
    Bed,
    /// Chairs and armchairs: sit.
    Chair,
    /// Stools: sit.
    Stool,
    /// Sofas of every shape: sit (and lie, after calibration's category augmentation).
    Sofa,
    /// Tables and desks: touch.
    Table,
    /// Cabinets, nightstands, tv stands, wardrobes: touch.
    Cabinet,
    /// Shelves and bookshelves: touch.
    Shelf,
    /// Lamps hanging from the ceiling: no human contact.
    Lamp,
}

impl Category {
    /// The contact actions this category supports, most likely first (MIME's mapping).
    pub fn affordances(self) -> &'static [Action] {
        match self.group() {
            Group::Bed => &[Action::Lie, Action::Sit],
            Group::Sofa => &[Action::Sit, Action::Lie],
            Group::Chair | Group::Stool => &[Action::Sit],
            Group::Table | Group::Cabinet | Group::Shelf => &[Action::Touch],
            Group::Lamp => &[],
        }
    }

    /// Whether a human doing `action` can use this category.
    pub fn affords(self, action: Action) -> bool {
        self.affordances().contains(&action)
    }

    /// Probability that a contact human on this category does `action` in the MIME mapping
    /// (beds: lie 0.6, sit 0.4; sofas: sit — people lie on sofas only after calibration's category
    /// augmentation; everything else: its single action).
    pub fn affordance_probability(self, action: Action) -> f64 {
        match (self.group(), action) {
            (Group::Bed, Action::Lie) => 0.6,
            (Group::Bed, Action::Sit) => 0.4,
            (Group::Sofa, Action::Lie) => 0.0,
            _ if self.affords(action) => 1.0,
            _ => 0.0,
        }
    }

    /// Lamps hang from the ceiling: they are left out of floor-occupancy metrics (Col_mot).
    pub fn is_hanging(self) -> bool {
        self.group() == Group::Lamp
    }
}

impl fmt::Display for Category {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

use Category as C;

const BEDROOM: [Category; 21] = [
    C::Armchair,
    C::Bookshelf,
    C::Cabinet,
    C::CeilingLamp,
    C::Chair,
    C::ChildrenCabinet,
    C::CoffeeTable,
    C::Desk,
    C::DoubleBed,
    C::DressingChair,
    C::DressingTable,
    C::KidsBed,
    C::Nightstand,
    C::PendantLamp,
    C::Shelf,
    C::SingleBed,
    C::Sofa,
    C::Stool,
    C::Table,
    C::TvStand,
    C::Wardrobe,
];

const LIVING_DINING: [Category; 24] = [
    C::Armchair,
    C::Bookshelf,
    C::Cabinet,
    C::CeilingLamp,
    C::ChaiseLongueSofa,
    C::ChineseChair,
    C::CoffeeTable,
    C::ConsoleTable,
    C::CornerSideTable,
    C::Desk,
    C::DiningChair,
    C::DiningTable,
    C::LShapedSofa,
    C::LazySofa,
    C::LoungeChair,
    C::LoveseatSofa,
    C::MultiSeatSofa,
    C::PendantLamp,
    C::RoundEndTable,
    C::Shelf,
    C::Stool,
    C::TvStand,
    C::Wardrobe,
    C::WineCabinet,
];

impl RoomType {
    /// All room types.
    pub const ALL: [RoomType; 3] = [RoomType::Bedroom, RoomType::Living, RoomType::Dining];

    /// The room type's categories in one-hot order.
    pub fn categories(self) -> &'static [Category] {
        match self {
            RoomType::Bedroom => &BEDROOM,
            RoomType::Living | RoomType::Dining => &LIVING_DINING,
        }
    }

    /// The one-hot index of `category`, or `None` when the room type does not have it.
    pub fn category_index(self, category: Category) -> Option<usize> {
        self.categories().iter().position(|&c| c == category)
    }

    /// How many of `objects` are of each of the room type's categories, in one-hot order (pieces
    /// of other categories are not counted).
    pub fn category_counts(self, objects: &[super::Object]) -> Vec<usize> {
        let mut counts = vec![0usize; self.categories().len()];
        for i in objects.iter().filter_map(|o| self.category_index(o.category)) {
            counts[i] += 1;
        }
        counts
    }

    /// Maximum number of objects (token slots) a scene of this type holds.
    pub fn max_objects(self) -> usize {
        match self {
            RoomType::Bedroom => 12,
            RoomType::Living | RoomType::Dining => 21,
        }
    }

    /// Side of the square room window rasterised at 256 × 256, in metres.
    pub fn window_side(self) -> f64 {
        match self {
            RoomType::Bedroom => 6.2,
            RoomType::Living | RoomType::Dining => 12.4,
        }
    }

    /// How far from the room window's centre the generator places a piece's centre, in metres
    /// along each axis: the procedural training rooms' extreme (their datasets' centre bounds,
    /// 2.77 / 5.245 / 4.255 m) rounded down to the centimetre; a test holds every shipped model's
    /// bounds to it. The window keeps the people in contact within it
    /// ([`super::Scene::room_window`]), or no piece could reach under them.
    pub fn reach(self) -> f64 {
        match self {
            RoomType::Bedroom => 2.77,
            RoomType::Living => 5.24,
            RoomType::Dining => 4.25,
        }
    }

    /// The name used in files.
    pub fn name(self) -> &'static str {
        match self {
            RoomType::Bedroom => "bedroom",
            RoomType::Living => "living",
            RoomType::Dining => "dining",
        }
    }
}

impl fmt::Display for RoomType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vocabularies_have_the_documented_sizes_and_order() {
        assert_eq!(RoomType::Bedroom.categories().len(), 21);
        assert_eq!(RoomType::Living.categories().len(), 24);
        assert_eq!(RoomType::Dining.categories(), RoomType::Living.categories());
        assert_eq!(RoomType::Bedroom.category_index(Category::DoubleBed), Some(8));
        assert_eq!(RoomType::Bedroom.category_index(Category::Wardrobe), Some(20));
        assert_eq!(RoomType::Living.category_index(Category::DiningChair), Some(10));
        assert_eq!(RoomType::Living.category_index(Category::WineCabinet), Some(23));
        assert_eq!(RoomType::Living.category_index(Category::DoubleBed), None);
        assert_eq!(RoomType::Bedroom.max_objects(), 12);
        assert_eq!(RoomType::Dining.max_objects(), 21);
    }

    #[test]
    fn names_round_trip_through_serde() {
        for &c in Category::ALL {
            let json = serde_json::to_string(&c).unwrap();
            assert_eq!(json, format!("\"{}\"", c.name()));
            assert_eq!(Category::from_name(c.name()), Some(c));
        }
        assert_eq!(Category::ALL.len(), 34);
    }

    #[test]
    fn affordances_follow_mime() {
        assert_eq!(Category::DoubleBed.affordances(), &[Action::Lie, Action::Sit]);
        assert!(Category::DiningChair.affords(Action::Sit));
        assert!(Category::LShapedSofa.affords(Action::Sit));
        assert!(Category::Stool.affords(Action::Sit));
        assert!(Category::Wardrobe.affords(Action::Touch));
        assert!(Category::Desk.affords(Action::Touch));
        assert!(!Category::Desk.affords(Action::Sit));
        assert!(Category::PendantLamp.affordances().is_empty());
        assert_eq!(Category::KidsBed.affordance_probability(Action::Lie), 0.6);
        assert_eq!(Category::Chair.affordance_probability(Action::Sit), 1.0);
        assert_eq!(Category::Chair.affordance_probability(Action::Lie), 0.0);
    }
}
