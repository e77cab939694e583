//! A motion as read from a file, before retargeting: named joints (with their parents, where the
//! file has a hierarchy), their positions at every frame in the file's own units and axes, and
//! the frame rate. The readers (`bvh`, `npy`) make one; `rig` maps it onto our 19-joint body.

use glam::DVec3;

/// Joint positions over time, as the file has them.
#[derive(Debug, Clone, PartialEq)]
pub struct Clip {
    /// Joint names (a BVH's end sites are named `<parent>/end`).
    pub names: Vec<String>,
    /// Each joint's parent (none for the root, and for every joint of a joint array).
    pub parents: Vec<Option<usize>>,
    /// Frames per second.
    pub fps: f64,
    /// One entry per frame, one position per joint, in the file's units and axes.
    pub frames: Vec<Vec<DVec3>>,
}

impl Clip {
    /// The index of the joint called `name`.
    pub fn joint(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| n == name)
    }

    /// The joints whose parent is `j`.
    pub fn children(&self, j: usize) -> impl Iterator<Item = usize> + '_ {
        self.parents.iter().enumerate().filter(move |(_, p)| **p == Some(j)).map(|(i, _)| i)
    }
}

/// Most frames a motion file may hold.
pub const MAX_FRAMES: usize = 1_000_000;
/// Most joint positions (frames × joints) a motion file may hold: 240 MB of positions.
pub const MAX_POSITIONS: usize = 10_000_000;
/// Most joints a motion file may name.
pub const MAX_JOINTS: usize = 1024;
