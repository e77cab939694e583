//! Exports: MuJoCo worlds (MJCF), and pictures (a small deterministic canvas, masks as PNG, the
//! humans' top and side views). (robosuite arenas and glTF join here.)

mod canvas;
mod humans_png;
mod mask_png;
mod mjcf;
#[cfg(feature = "mujoco")]
mod validate_mujoco;

pub use canvas::{Canvas, Color, View, png_bytes};
pub use humans_png::{action_color, render_humans, render_humans_sized};
pub use mask_png::{mask_png, save_mask_png};
pub use mjcf::{MjcfOptions, scene_mjcf};
#[cfg(feature = "mujoco")]
pub use validate_mujoco::{MAX_MOVE, MujocoValidation, validate_in_mujoco};
