//! Joint-position arrays: `.npy` (T × J × 3, float) and `.npz` archives holding such an array
//! with, optionally, its joint names and frame rate — what people export after running SMPL-X or
//! AMASS fits through their own body model.
//!
//! In an `.npz`, the positions are the array `joints` (or `positions`, `joint_positions`), the
//! names the string array `names` (or `joint_names`), the frame rate the scalar `fps` (or AMASS's
//! `mocap_framerate`). Without names, an array of 22, 24, 52 or 55 joints is taken to be in SMPL /
//! SMPL-H / SMPL-X order, whose first 22 joints are the body's, and one of 19 in ours
//! (`JOINT_NAMES`: a shade-scene human's `frames` saved as an array). Units and axes are kept as in the
//! file (`rig` detects and converts them).

use super::clip::{Clip, MAX_JOINTS, MAX_POSITIONS};
use crate::scene::JOINT_NAMES;
use glam::DVec3;
use npyz::NpyFile;
use npyz::npz::NpzArchive;
use std::io::{Cursor, Read};

/// The 22 body joints of SMPL, SMPL-H and SMPL-X, in their order.
pub const SMPL_BODY_JOINTS: [&str; 22] = [
    "pelvis",
    "left_hip",
    "right_hip",
    "spine1",
    "left_knee",
    "right_knee",
    "spine2",
    "left_ankle",
    "right_ankle",
    "spine3",
    "left_foot",
    "right_foot",
    "neck",
    "left_collar",
    "right_collar",
    "head",
    "left_shoulder",
    "right_shoulder",
    "left_elbow",
    "right_elbow",
    "left_wrist",
    "right_wrist",
];

/// Joint counts read as SMPL-family arrays when no names come with them.
const SMPL_SIZES: [usize; 4] = [22, 24, 52, 55];

/// Most bytes one array of an `.npz` may hold once decompressed: the most positions a clip may
/// have, as float64, and its header.
const MAX_ARRAY_BYTES: u64 = MAX_POSITIONS as u64 * 3 * 8 + (1 << 16);

/// Reads a `.npy` file's bytes; `fps` is the clip's frame rate (a `.npy` has none).
pub fn read_npy(bytes: &[u8], fps: f64) -> Result<Clip, String> {
    let (frames, joints) = positions(npy_file(bytes)?, "the array")?;
    clip(frames, joints, None, fps)
}

/// An array's bytes as an `NpyFile`, once its header is known to lie within them (the header's
/// length is read from the file and `npyz` allocates it before reading: a corrupt one asked for
/// 4 GB — found by the `motion` fuzz target) and to be shallow enough to parse quickly.
fn npy_file(bytes: &[u8]) -> Result<NpyFile<&[u8]>, String> {
    let not = |what: &str| format!("not a .npy array: {what}");
    if bytes.len() < 10 || &bytes[..6] != b"\x93NUMPY" {
        return Err(not("no NUMPY magic"));
    }
    let (prefix, header) = match bytes[6] {
        1 => (10, u16::from_le_bytes([bytes[8], bytes[9]]) as usize),
        2 | 3 if bytes.len() >= 12 => (12, u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize),
        v => return Err(not(&format!("format version {v}"))),
    };
    if prefix + header > bytes.len() {
        return Err(not(&format!("its header ({header} bytes) runs past the end of the file")));
    }
    // npyz parses the header with a backtracking parser whose time doubles with each level of
    // brackets (20 nested lists took 1.4 s; found by the `motion` fuzz target). A plain array's
    // header nests two deep, `{… (2, 22, 3) …}`: more than four is not an array of numbers.
    let mut depth = 0usize;
    for &b in &bytes[prefix..prefix + header] {
        match b {
            b'(' | b'[' | b'{' => depth += 1,
            b')' | b']' | b'}' => depth = depth.saturating_sub(1),
            _ => {}
        }
        if depth > MAX_HEADER_DEPTH {
            return Err(not(&format!("its header nests brackets more than {MAX_HEADER_DEPTH} deep")));
        }
    }
    // npyz multiplies the shape's dimensions without checking (a shape of 22 × 5.5e16 × 3
    // overflowed; found by the `motion` fuzz target): a shape whose size does not fit is refused.
    let text = String::from_utf8_lossy(&bytes[prefix..prefix + header]);
    if let Some(shape) = text.split("'shape'").nth(1).and_then(|t| t.split(')').next()) {
        let dims = shape.trim_start_matches([':', ' ', '(']).split(',').map(str::trim).filter(|d| !d.is_empty());
        let size = dims.map(|d| d.parse::<u64>().ok()).try_fold(1u64, |size, d| size.checked_mul(d?));
        if size.is_none() {
            return Err(not("its shape's size is too large to count"));
        }
    }
    NpyFile::new(bytes).map_err(|e| not(&e.to_string()))
}

/// Deepest nesting of brackets an array's header may have.
const MAX_HEADER_DEPTH: usize = 4;

/// Reads a `.npz` archive's bytes; `fps` is the frame rate where the archive has none.
pub fn read_npz(bytes: &[u8], fps: f64) -> Result<Clip, String> {
    let mut archive = NpzArchive::new(Cursor::new(bytes)).map_err(|e| format!("not a .npz archive: {e}"))?;
    let names: Vec<String> = archive.array_names().map(str::to_string).collect();
    let pick = |wanted: &[&str]| wanted.iter().find(|w| names.iter().any(|n| n == *w)).map(|w| w.to_string());
    let key = pick(&["joints", "positions", "joint_positions"]).ok_or_else(|| {
        format!("no array `joints` (or `positions`, `joint_positions`) among its arrays: {}", names.join(", "))
    })?;
    let bytes = entry(&mut archive, &key)?;
    let (frames, joints) = positions(array_file(&bytes, &key)?, &format!("array `{key}`"))?;
    let joint_names = match pick(&["names", "joint_names"]) {
        Some(k) => Some(strings(array_file(&entry(&mut archive, &k)?, &k)?, &k)?),
        None => None,
    };
    let fps = match pick(&["fps", "mocap_framerate"]) {
        Some(k) => scalar(array_file(&entry(&mut archive, &k)?, &k)?, &k)?,
        None => fps,
    };
    clip(frames, joints, joint_names, fps)
}

/// The `.npz` array `name`'s bytes as an `NpyFile`.
fn array_file<'a>(bytes: &'a [u8], name: &str) -> Result<NpyFile<&'a [u8]>, String> {
    npy_file(bytes).map_err(|e| format!("array `{name}`: {e}"))
}

/// The bytes of the array `name` (decompressed, at most [`MAX_ARRAY_BYTES`]).
fn entry(archive: &mut NpzArchive<Cursor<&[u8]>>, name: &str) -> Result<Vec<u8>, String> {
    let file = npyz::npz::file_name_from_array_name(name);
    let entry = archive.zip_archive().by_name(&file).map_err(|e| format!("array `{name}`: {e}"))?;
    let mut bytes = Vec::new();
    entry.take(MAX_ARRAY_BYTES + 1).read_to_end(&mut bytes).map_err(|e| format!("array `{name}`: {e}"))?;
    if bytes.len() as u64 > MAX_ARRAY_BYTES {
        return Err(format!("array `{name}`: more than {MAX_ARRAY_BYTES} bytes"));
    }
    Ok(bytes)
}

/// The frames (T × J positions) of a T × J × 3 float array.
fn positions(npy: NpyFile<impl Read>, what: &str) -> Result<(usize, Vec<DVec3>), String> {
    let shape = npy.shape().to_vec();
    let [t, j, 3] = shape[..] else {
        return Err(format!("{what} has shape {shape:?}; joint positions are frames × joints × 3"));
    };
    if t == 0 || j == 0 {
        return Err(format!("{what} has shape {shape:?}: no frames or no joints"));
    }
    if j > MAX_JOINTS as u64 || t.saturating_mul(j) > MAX_POSITIONS as u64 {
        return Err(format!("{what} has shape {shape:?}: more than {MAX_JOINTS} joints or {MAX_POSITIONS} positions"));
    }
    if npy.order() == npyz::Order::Fortran {
        return Err(format!("{what} is stored in Fortran order; save it with numpy.ascontiguousarray"));
    }
    let values = numbers(npy).map_err(|e| format!("{what}: {e}"))?;
    if let Some(k) = values.iter().position(|v| !v.is_finite()) {
        let (frame, joint) = (k / (3 * j as usize), k / 3 % j as usize);
        return Err(format!("{what}: frame {} joint {joint} is not a finite number", frame + 1));
    }
    Ok((j as usize, values.chunks_exact(3).map(|c| DVec3::new(c[0], c[1], c[2])).collect()))
}

fn strings(npy: NpyFile<impl Read>, name: &str) -> Result<Vec<String>, String> {
    if npy.shape().len() != 1 {
        return Err(format!("array `{name}` has shape {:?}; joint names are one string per joint", npy.shape()));
    }
    if npy.shape()[0] > MAX_JOINTS as u64 {
        return Err(format!("array `{name}`: more than {MAX_JOINTS} names"));
    }
    match npy.try_data::<String>() {
        Ok(names) => names.collect::<Result<_, _>>().map_err(|e| format!("array `{name}` cannot be read: {e}")),
        Err(npy) => Err(format!("array `{name}` holds {}, not strings", npy.dtype().descr())),
    }
}

fn scalar(npy: NpyFile<impl Read>, name: &str) -> Result<f64, String> {
    if npy.shape().iter().product::<u64>() != 1 {
        return Err(format!("array `{name}` has shape {:?}; a frame rate is one number", npy.shape()));
    }
    numbers(npy).map(|v| v[0]).map_err(|e| format!("array `{name}`: {e}"))
}

/// The values of a float or integer array as f64.
fn numbers(npy: NpyFile<impl Read>) -> Result<Vec<f64>, String> {
    let read = |e: std::io::Error| format!("cannot be read: {e}");
    let npy = match npy.try_data::<f64>() {
        Ok(values) => return values.collect::<Result<_, _>>().map_err(read),
        Err(npy) => npy,
    };
    let npy = match npy.try_data::<f32>() {
        Ok(values) => return values.map(|v| v.map(f64::from)).collect::<Result<_, _>>().map_err(read),
        Err(npy) => npy,
    };
    match npy.try_data::<i64>() {
        Ok(values) => values.map(|v| v.map(|x| x as f64)).collect::<Result<_, _>>().map_err(read),
        Err(npy) => Err(format!("holds {}, not numbers", npy.dtype().descr())),
    }
}

fn clip(joints: usize, flat: Vec<DVec3>, names: Option<Vec<String>>, fps: f64) -> Result<Clip, String> {
    let names = match names {
        Some(names) if names.len() == joints => names,
        Some(names) => return Err(format!("{} joint names for {joints} joints", names.len())),
        None if SMPL_SIZES.contains(&joints) => {
            (0..joints).map(|i| SMPL_BODY_JOINTS.get(i).map_or(format!("joint_{i}"), |s| s.to_string())).collect()
        }
        None if joints == JOINT_NAMES.len() => JOINT_NAMES.map(str::to_string).to_vec(),
        None => {
            return Err(format!(
                "unknown rig: {joints} joints without names (name them in an .npz array `names`, or use SMPL's order \
                 of 22, 24, 52 or 55 joints, or ours of 19)"
            ));
        }
    };
    if !(fps.is_finite() && (1.0..=1000.0).contains(&fps)) {
        return Err(format!("the frame rate must be 1 to 1000 per second, not {fps}"));
    }
    Ok(Clip {
        parents: vec![None; joints],
        names,
        fps,
        frames: flat.chunks_exact(joints).map(<[DVec3]>::to_vec).collect(),
    })
}
