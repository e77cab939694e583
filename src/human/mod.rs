//! Human bodies: the default skeleton, poses (stand, walk, sit, lie, touch), motions, body-surface
//! points and the conditioning the generator reads from humans.
//!
//! Bodies are capsules between named joints. Poses are geometric (inverse kinematics and gait
//! rules), not simulated; physics replays them in `sim`.

mod conditions;
mod gait;
mod meetings;
mod motion;
mod pose;
mod seats_in_the_way;
mod skeleton;
mod surface;

pub use conditions::{
    Conditions, ContactBox, FLOOR_REST, FloorPoint, KNEE_BOX_SIDE, SUPPORT_DEPTH, TOUCH_SIDE, body_yaw, contact_boxes,
    floor_points, free_space_mask, knee_box, knees_of, palm_of,
};
pub use gait::Gait;
pub use meetings::{Meeting, inside_each_other_at_once, meets_anyone, people_meeting};
pub use motion::Motion;
pub use pose::{BODY_BONES, KNEE_OVERHANG, Pose, SEAT_BONES, lie, sit, stand, stand_local, touch, two_bone_ik};
pub use seats_in_the_way::{SeatInTheWay, seats_in_the_way};
pub use skeleton::{Body, JOINT_NAMES, Joint, Side, round_mm};
pub use surface::{SurfaceSampler, segment_distance_3d};
