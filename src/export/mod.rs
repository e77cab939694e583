//! Exports: MuJoCo worlds (MJCF), and pictures (a small deterministic canvas, masks as PNG, the
//! humans' top and side views), glTF binary with the motion as an animation, and where a robot's
//! base can stand in a scene (for robosuite).

mod canvas;
mod font;
mod glb;
mod gltf;
mod humans_png;
mod loss_png;
mod mask_png;
mod mesh;
mod mjcf;
mod palette;
mod plan_png;
mod robot_spot;
#[cfg(feature = "mujoco")]
mod validate_mujoco;

pub use canvas::{Canvas, Color, View, png_bytes};
pub use font::{draw_text, text_width};
pub use gltf::scene_glb;
pub use humans_png::{action_color, render_humans, render_humans_sized};
pub use loss_png::{LossPoint, loss_canvas, render_loss_png};
pub use mask_png::{mask_png, save_mask_png};
pub use mesh::TriMesh;
pub use mjcf::{MjcfOptions, MocapMotion, PAIR_MARGIN, mocap_motion, part_names, scene_mjcf};
pub use palette::{MATERIALS, material};
pub use plan_png::{group_color, render_plan};
pub use robot_spot::robot_spot;
#[cfg(feature = "mujoco")]
pub use validate_mujoco::{MAX_MOVE, MujocoValidation, validate_in_mujoco};
