//! Errors of loading, validating and saving scenes.
//!
//! Every error names the file; problems found by validation name the JSON path (`humans[0].frames[3]`)
//! and carry typed data, so callers can act on them without parsing strings.

use super::{Category, RoomType};
use std::fmt;
use std::path::PathBuf;

/// Why a scene could not be read or written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SceneError {
    /// The file could not be read or written.
    #[error("{}: {error}", file.display())]
    Io {
        /// The file.
        file: PathBuf,
        /// The operating-system error (part of the message, so not repeated as a source).
        error: std::io::Error,
    },
    /// The text is not JSON of the expected shape (syntax, unknown field, wrong type, unknown name).
    #[error("{}: {}{message} (line {line}, column {column})", file.display(), path_prefix(path))]
    Parse {
        /// The file.
        file: PathBuf,
        /// JSON path of the value that failed (empty for the document itself).
        path: String,
        /// serde's description.
        message: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
    },
    /// The JSON is well-formed but the scene breaks a rule of the format.
    #[error("{}: {}{}", file.display(), problems[0], more(problems.len()))]
    Invalid {
        /// The file.
        file: PathBuf,
        /// Every problem found, in document order (never empty).
        problems: Vec<Problem>,
    },
}

fn path_prefix(path: &str) -> String {
    if path.is_empty() || path == "." { String::new() } else { format!("{path}: ") }
}

fn more(n: usize) -> String {
    match n {
        0 | 1 => String::new(),
        2 => " (and 1 more problem)".to_string(),
        n => format!(" (and {} more problems)", n - 1),
    }
}

/// One rule a scene breaks, at a JSON path.
#[derive(Debug, Clone, PartialEq)]
pub struct Problem {
    /// JSON path, e.g. `floor_plan.polygon` or `humans[1].actions[0]`.
    pub path: String,
    /// What is wrong.
    pub kind: ProblemKind,
}

/// The rules of `shade-scene/1`.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum ProblemKind {
    /// `format` is not `shade-scene/1`.
    WrongFormat {
        /// What the file says.
        found: String,
    },
    /// The category is not in the room type's vocabulary.
    CategoryNotInRoom {
        /// The category.
        category: Category,
        /// The room type.
        room: RoomType,
    },
    /// NaN or infinite.
    NotFinite,
    /// A size, height, radius or rate that must be positive.
    NotPositive {
        /// The value found.
        value: f64,
    },
    /// The floor polygon has fewer than three vertices.
    TooFewVertices {
        /// Vertices found.
        count: usize,
    },
    /// The floor polygon encloses no area.
    ZeroArea,
    /// Two edges of the floor polygon cross or touch (or a vertex repeats).
    SelfIntersecting {
        /// Index of the first edge (from vertex i to i + 1).
        edge_a: usize,
        /// Index of the second edge.
        edge_b: usize,
    },
    /// The floor polygon runs clockwise.
    Clockwise,
    /// Two objects or two humans share an id.
    DuplicateId {
        /// The repeated id.
        id: String,
    },
    /// A human without frames.
    EmptyMotion,
    /// A frame's joint count differs from the skeleton's.
    FrameJointCount {
        /// Joints in the skeleton.
        expected: usize,
        /// Positions in the frame.
        got: usize,
    },
    /// A required joint name is missing from the skeleton.
    MissingJoint {
        /// The name.
        name: &'static str,
    },
    /// A joint name appears twice.
    DuplicateJoint {
        /// The name.
        name: String,
    },
    /// A bone refers to a joint that does not exist.
    BoneOutOfRange {
        /// The index used.
        index: usize,
        /// Joints in the skeleton.
        joints: usize,
    },
    /// A bone joins a joint to itself.
    DegenerateBone,
    /// An action range is empty or reaches past the last frame.
    ActionOutOfRange {
        /// Start frame.
        start: usize,
        /// End frame (exclusive).
        end: usize,
        /// Frames in the motion.
        frames: usize,
    },
    /// Two action ranges of one human overlap.
    OverlappingActions {
        /// Index of the earlier span.
        other: usize,
    },
    /// A finite number outside the physical bounds of the format ([`super::SceneLimits`]).
    OutOfRange {
        /// The value found.
        value: f64,
        /// Smallest allowed.
        min: f64,
        /// Largest allowed.
        max: f64,
    },
    /// More of something than the format allows ([`super::SceneLimits`], the room type's slots).
    TooMany {
        /// What is counted ("vertices", "objects", …).
        what: &'static str,
        /// How many there are.
        count: usize,
        /// The most allowed.
        max: usize,
    },
}

/// A number as `Display` writes it, but in exponent form beyond a million (1e308 is one short word,
/// not 309 digits).
struct Short(f64);

impl fmt::Display for Short {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.abs() >= 1e6 { write!(f, "{:e}", self.0) } else { write!(f, "{}", self.0) }
    }
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.path, self.kind)
    }
}

impl fmt::Display for ProblemKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use ProblemKind::*;
        match self {
            WrongFormat { found } => write!(f, "format is {found:?}, expected \"{}\"", super::FORMAT),
            CategoryNotInRoom { category, room } => {
                write!(f, "category \"{category}\" is not a {room} category")
            }
            NotFinite => write!(f, "number is not finite"),
            NotPositive { value } => write!(f, "must be positive, found {value}"),
            TooFewVertices { count } => write!(f, "floor polygon has {count} vertices, needs at least 3"),
            ZeroArea => write!(f, "floor polygon has zero area"),
            SelfIntersecting { edge_a, edge_b } => {
                write!(f, "floor polygon intersects itself (edges {edge_a} and {edge_b})")
            }
            Clockwise => write!(f, "floor polygon is clockwise, must be counter-clockwise"),
            DuplicateId { id } => write!(f, "id {id:?} is used twice"),
            EmptyMotion => write!(f, "human has no frames"),
            FrameJointCount { expected, got } => {
                write!(f, "frame has {got} joint positions, skeleton has {expected} joints")
            }
            MissingJoint { name } => write!(f, "skeleton lacks the required joint {name:?}"),
            DuplicateJoint { name } => write!(f, "joint {name:?} appears twice"),
            BoneOutOfRange { index, joints } => {
                write!(f, "bone joint index {index} out of range (skeleton has {joints} joints)")
            }
            DegenerateBone => write!(f, "bone joins a joint to itself"),
            ActionOutOfRange { start, end, frames } => {
                write!(f, "action range [{start}, {end}) is empty or outside the {frames} frames")
            }
            OverlappingActions { other } => write!(f, "action range overlaps actions[{other}]"),
            OutOfRange { value, min, max } => {
                write!(f, "{} is outside the allowed range {min} to {max}", Short(*value))
            }
            TooMany { what, count, max } => write!(f, "{count} {what}, at most {max} allowed"),
        }
    }
}
