//! The colours of exported worlds (MJCF and glTF share them): one material per furniture group,
//! plus floor, walls and humans. The plan PNG has its own, print-friendlier palette.

use crate::scene::Group;

/// Material names and linear RGBA colours, in a fixed order.
pub const MATERIALS: [(&str, [f64; 4]); 9] = [
    ("floor", [0.79, 0.75, 0.69, 1.0]),
    ("wall", [0.9, 0.9, 0.87, 0.35]),
    ("bed", [0.55, 0.45, 0.75, 1.0]),
    ("seat", [0.85, 0.55, 0.25, 1.0]),
    ("sofa", [0.45, 0.6, 0.8, 1.0]),
    ("wood", [0.6, 0.42, 0.26, 1.0]),
    ("storage", [0.7, 0.7, 0.66, 1.0]),
    ("lamp", [0.95, 0.92, 0.6, 1.0]),
    ("human", [0.9, 0.7, 0.55, 1.0]),
];

/// Material name of a category group.
pub fn material(group: Group) -> &'static str {
    match group {
        Group::Bed => "bed",
        Group::Chair | Group::Stool => "seat",
        Group::Sofa => "sofa",
        Group::Table => "wood",
        Group::Cabinet | Group::Shelf => "storage",
        Group::Lamp => "lamp",
    }
}

/// Index of a material in [`MATERIALS`].
pub fn material_index(name: &str) -> usize {
    MATERIALS.iter().position(|(n, _)| *n == name).expect("a material of the palette")
}
