//! BVH (Biovision Hierarchy) reader: the hierarchy (joints, offsets, channels in any order, end
//! sites) and the motion, turned into joint positions at every frame by forward kinematics.
//!
//! Written here rather than taken from a crate: `bvh_anim` 0.4 (the one published reader, last
//! released in 2020) panics on some malformed hierarchies, and a user's truncated file must be one
//! clear line. Every error names the line of the file. Units and axes are kept as in the file
//! (`rig` detects and converts them).
//!
//! Whole rows after the frames the header announces are read and left out (some exporters write
//! one more than they count); a partial row anywhere is an error.
//!
//! Conventions, as the common writers (MotionBuilder, Blender, CMU's conversion, Axis Neuron):
//! a joint's rotation is the product of its rotation channels in the order listed (`Zrotation
//! Xrotation Yrotation` is R = Rz·Rx·Ry), degrees; its translation is its position channels where
//! it has them and its OFFSET otherwise; world position = parent's position + parent's world
//! rotation × translation.

use super::clip::{Clip, MAX_FRAMES, MAX_JOINTS, MAX_POSITIONS};
use glam::{DMat3, DVec3};

/// One channel of a joint.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Channel {
    Position(usize),
    Rotation(usize),
}

impl Channel {
    fn parse(token: &str) -> Option<Channel> {
        let axis = match token.as_bytes().first()?.to_ascii_lowercase() {
            b'x' => 0,
            b'y' => 1,
            b'z' => 2,
            _ => return None,
        };
        match token[1..].to_ascii_lowercase().as_str() {
            "position" => Some(Channel::Position(axis)),
            "rotation" => Some(Channel::Rotation(axis)),
            _ => None,
        }
    }
}

#[derive(Debug, Clone)]
struct Joint {
    name: String,
    parent: Option<usize>,
    offset: DVec3,
    channels: Vec<Channel>,
    /// Index of its first channel in a frame's row.
    first: usize,
}

/// The words of a file with their 1-based line numbers; `{` and `}` are words of their own.
struct Words<'a> {
    words: Vec<(&'a str, usize)>,
    at: usize,
}

impl<'a> Words<'a> {
    fn of(text: &'a str) -> Words<'a> {
        let mut words = Vec::new();
        for (i, line) in text.lines().enumerate() {
            for word in line.split_whitespace() {
                let mut rest = word;
                while let Some(k) = rest.find(['{', '}']) {
                    if k > 0 {
                        words.push((&rest[..k], i + 1));
                    }
                    words.push((&rest[k..k + 1], i + 1));
                    rest = &rest[k + 1..];
                }
                if !rest.is_empty() {
                    words.push((rest, i + 1));
                }
            }
        }
        Words { words, at: 0 }
    }

    /// The line of the next word (the last line at the end).
    fn line(&self) -> usize {
        self.words.get(self.at).or(self.words.last()).map_or(1, |w| w.1)
    }

    fn next(&mut self, what: &str) -> Result<&'a str, String> {
        let word = self.words.get(self.at).ok_or_else(|| format!("the file ends where {what} was expected"))?;
        self.at += 1;
        Ok(word.0)
    }

    fn peek(&self) -> Option<&'a str> {
        self.words.get(self.at).map(|w| w.0)
    }

    fn expect(&mut self, word: &str) -> Result<(), String> {
        let line = self.line();
        match self.next(&format!("`{word}`"))? {
            w if w.eq_ignore_ascii_case(word) => Ok(()),
            w => Err(format!("line {line}: expected `{word}`, found `{w}`")),
        }
    }

    fn number(&mut self, what: &str) -> Result<f64, String> {
        let line = self.line();
        let word = self.next(what)?;
        match word.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(_) => Err(format!("line {line}: {what} is not a finite number: `{word}`")),
            Err(_) => Err(format!("line {line}: expected {what}, found `{word}`")),
        }
    }

    fn offset(&mut self) -> Result<DVec3, String> {
        self.expect("OFFSET")?;
        Ok(DVec3::new(self.number("an offset")?, self.number("an offset")?, self.number("an offset")?))
    }
}

/// Reads a BVH file's text into joint positions per frame.
pub fn read_bvh(text: &str) -> Result<Clip, String> {
    let mut words = Words::of(text);
    words.expect("HIERARCHY")?;
    let joints = hierarchy(&mut words)?;
    let channels: usize = joints.iter().map(|j| j.channels.len()).sum();
    if channels == 0 {
        return Err("the hierarchy has no channels: nothing moves".into());
    }
    words.expect("MOTION")?;
    let line = words.line();
    let frames = match words.next("`Frames:`")? {
        "Frames:" => words.number("the frame count")?,
        w => match w.strip_prefix("Frames:").map(str::parse::<f64>) {
            Some(Ok(n)) => n,
            _ => return Err(format!("line {line}: expected `Frames:`, found `{w}`")),
        },
    };
    if frames < 1.0 || frames.fract() != 0.0 || frames > MAX_FRAMES as f64 {
        return Err(format!(
            "line {line}: the frame count must be a whole number from 1 to {MAX_FRAMES}, not {frames}"
        ));
    }
    let frames = frames as usize;
    if frames.saturating_mul(joints.len()) > MAX_POSITIONS {
        return Err(format!("{frames} frames of {} joints: more than {MAX_POSITIONS} positions", joints.len()));
    }
    words.expect("Frame")?;
    words.expect("Time:")?;
    let line = words.line();
    let frame_time = words.number("the frame time")?;
    if !(1e-4..=10.0).contains(&frame_time) {
        return Err(format!("line {line}: the frame time must be 0.0001 to 10 s, not {frame_time}"));
    }
    let mut rows = Vec::with_capacity(frames);
    let mut row = vec![0.0; channels];
    for f in 0..frames {
        if words.peek().is_none() {
            return Err(format!("the file ends after {f} of {frames} frames"));
        }
        read_row(&mut words, f, &mut row)?;
        rows.push(positions(&joints, &row));
    }
    // Whole rows beyond the announced count (some exporters write one more) are read and left
    // out; anything else there is an error.
    let mut f = frames;
    while words.peek().is_some() {
        read_row(&mut words, f, &mut row)?;
        f += 1;
    }
    Ok(Clip {
        names: joints.iter().map(|j| j.name.clone()).collect(),
        parents: joints.iter().map(|j| j.parent).collect(),
        fps: 1.0 / frame_time,
        frames: rows,
    })
}

/// One frame's values: one line of exactly `row.len()` numbers.
fn read_row(words: &mut Words<'_>, f: usize, row: &mut [f64]) -> Result<(), String> {
    let (line, channels) = (words.line(), row.len());
    for (c, value) in row.iter_mut().enumerate() {
        if words.peek().is_none() || words.line() != line {
            return Err(format!(
                "line {line}: frame {} has {c} values where the hierarchy has {channels} channels",
                f + 1
            ));
        }
        *value = words.number(&format!("value {} of frame {}", c + 1, f + 1))?;
    }
    if words.peek().is_some() && words.line() == line {
        return Err(format!("line {line}: frame {} has more values than the hierarchy's {channels} channels", f + 1));
    }
    Ok(())
}

/// The joints of the hierarchy, parents before children (read with a stack, not recursion, so
/// a deep file cannot overflow it).
fn hierarchy(words: &mut Words<'_>) -> Result<Vec<Joint>, String> {
    words.expect("ROOT")?;
    let mut joints: Vec<Joint> = Vec::new();
    let mut open: Vec<usize> = Vec::new();
    let mut channels = 0;
    let mut name = words.next("the root's name")?.to_string();
    loop {
        // A joint's block: `{ OFFSET x y z CHANNELS n …` then its children and `}`.
        if joints.len() >= MAX_JOINTS {
            return Err(format!("line {}: more than {MAX_JOINTS} joints", words.line()));
        }
        words.expect("{")?;
        let offset = words.offset()?;
        words.expect("CHANNELS")?;
        let line = words.line();
        let n = words.number("the channel count")?;
        if !(0.0..=6.0).contains(&n) || n.fract() != 0.0 {
            return Err(format!("line {line}: a joint has 0 to 6 channels, not {n}"));
        }
        let mut list = Vec::new();
        for _ in 0..n as usize {
            let line = words.line();
            let word = words.next("a channel")?;
            let channel = Channel::parse(word).ok_or_else(|| format!("line {line}: unknown channel `{word}`"))?;
            if list.contains(&channel) {
                return Err(format!("line {line}: channel `{word}` twice in one joint"));
            }
            list.push(channel);
        }
        if joints.iter().any(|j| j.name == name) {
            return Err(format!("line {line}: two joints are called `{name}`"));
        }
        joints.push(Joint {
            name: std::mem::take(&mut name),
            parent: open.last().copied(),
            offset,
            channels: list,
            first: channels,
        });
        channels += n as usize;
        open.push(joints.len() - 1);
        // Children and end sites until this joint's `}` (and the `}`s of parents that end with it).
        loop {
            let line = words.line();
            match words.next("`JOINT`, `End Site` or `}`")? {
                w if w.eq_ignore_ascii_case("JOINT") => {
                    name = words.next("a joint's name")?.to_string();
                    break;
                }
                w if w.eq_ignore_ascii_case("End") => {
                    words.expect("Site")?;
                    words.expect("{")?;
                    let offset = words.offset()?;
                    words.expect("}")?;
                    let parent = *open.last().expect("an open joint");
                    let end = format!("{}/end", joints[parent].name);
                    if joints.iter().any(|j| j.name == end) {
                        return Err(format!("line {line}: `{}` has two end sites", joints[parent].name));
                    }
                    joints.push(Joint {
                        name: end,
                        parent: Some(parent),
                        offset,
                        channels: Vec::new(),
                        first: channels,
                    });
                }
                "}" => {
                    open.pop();
                    if open.is_empty() {
                        return Ok(joints);
                    }
                }
                w => return Err(format!("line {line}: expected `JOINT`, `End Site` or `}}`, found `{w}`")),
            }
        }
    }
}

/// World positions of every joint for one frame's channel values.
fn positions(joints: &[Joint], row: &[f64]) -> Vec<DVec3> {
    let mut position = Vec::with_capacity(joints.len());
    let mut rotation: Vec<DMat3> = Vec::with_capacity(joints.len());
    for joint in joints {
        let mut local = DMat3::IDENTITY;
        let mut translation = joint.offset;
        let mut moved = [false; 3];
        for (k, channel) in joint.channels.iter().enumerate() {
            let value = row[joint.first + k];
            match *channel {
                Channel::Position(axis) => {
                    if !moved[axis] {
                        // Position channels replace the offset (all three, once any is given).
                        translation = DVec3::ZERO;
                        moved = [true; 3];
                    }
                    translation[axis] = value;
                }
                Channel::Rotation(axis) => {
                    let angle = value.to_radians();
                    local *= match axis {
                        0 => DMat3::from_rotation_x(angle),
                        1 => DMat3::from_rotation_y(angle),
                        _ => DMat3::from_rotation_z(angle),
                    };
                }
            }
        }
        let (p, r) = match joint.parent {
            Some(parent) => (position[parent] + rotation[parent] * translation, rotation[parent] * local),
            None => (translation, local),
        };
        position.push(p);
        rotation.push(r);
    }
    position
}

#[cfg(test)]
mod tests {
    use super::*;

    const TWO_BONES: &str = "HIERARCHY
ROOT Hips
{
  OFFSET 0 0 0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation
  JOINT Spine
  {
    OFFSET 0 10 0
    CHANNELS 3 Zrotation Xrotation Yrotation
    End Site
    {
      OFFSET 0 5 0
    }
  }
}
MOTION
Frames: 2
Frame Time: 0.5
1 2 3 0 0 0 0 0 0
0 0 0 90 0 0 0 90 0
";

    fn near(a: DVec3, b: DVec3) -> bool {
        a.distance(b) < 1e-9
    }

    #[test]
    fn forward_kinematics_by_hand() {
        let clip = read_bvh(TWO_BONES).unwrap();
        assert_eq!(clip.names, ["Hips", "Spine", "Spine/end"]);
        assert_eq!(clip.parents, [None, Some(0), Some(1)]);
        assert_eq!(clip.fps, 2.0);
        // Frame 1: translated by (1, 2, 3), no rotation.
        let f = &clip.frames[0];
        assert!(near(f[0], DVec3::new(1.0, 2.0, 3.0)) && near(f[1], DVec3::new(1.0, 12.0, 3.0)));
        assert!(near(f[2], DVec3::new(1.0, 17.0, 3.0)));
        // Frame 2: the hips turn 90° about z, so the spine (10 along y) points along −x; the
        // spine turns 90° about x, so its end (5 along y) points along +z in the spine's frame,
        // which the hips' turn leaves along +z.
        let f = &clip.frames[1];
        assert!(near(f[1], DVec3::new(-10.0, 0.0, 0.0)), "{:?}", f[1]);
        assert!(near(f[2], DVec3::new(-10.0, 0.0, 5.0)), "{:?}", f[2]);
    }

    #[test]
    fn rotation_order_is_the_channel_order() {
        // Ry(90)·Rx(90) and Rx(90)·Ry(90) send the end's offset (0 5 0) to different places.
        let yx =
            TWO_BONES.replace("CHANNELS 3 Zrotation Xrotation Yrotation", "CHANNELS 3 Yrotation Xrotation Zrotation");
        let row = "0 0 0 0 0 0 90 90 0";
        let a = read_bvh(&yx.replace("0 0 0 90 0 0 0 90 0", row)).unwrap();
        let xy =
            TWO_BONES.replace("CHANNELS 3 Zrotation Xrotation Yrotation", "CHANNELS 3 Xrotation Yrotation Zrotation");
        let b = read_bvh(&xy.replace("0 0 0 90 0 0 0 90 0", row)).unwrap();
        // Ry(90)·Rx(90)·(0,5,0): Rx sends it to (0,0,5), Ry to (5,0,0).
        assert!(near(a.frames[1][2] - a.frames[1][1], DVec3::new(5.0, 0.0, 0.0)), "{:?}", a.frames[1]);
        // Rx(90)·Ry(90)·(0,5,0): Ry leaves it, Rx sends it to (0,0,5).
        assert!(near(b.frames[1][2] - b.frames[1][1], DVec3::new(0.0, 0.0, 5.0)), "{:?}", b.frames[1]);
    }

    #[test]
    fn malformed_files_are_one_line_naming_where() {
        let cases = [
            (TWO_BONES.replace("0 0 0 90 0 0 0 90 0\n", ""), "the file ends after 1 of 2 frames"),
            (
                TWO_BONES.replace("0 0 0 90 0 0 0 90 0", "0 0 0 90 0 0 0 90"),
                "line 20: frame 2 has 8 values where the hierarchy has 9 channels",
            ),
            (TWO_BONES.replace("0 0 0 90 0 0 0 90 0", "0 0 0 90 0 0 0 90 0 1"), "line 20: frame 2 has more values"),
            (TWO_BONES.replace("1 2 3", "1 nan 3"), "line 19: value 2 of frame 1 is not a finite number"),
            (TWO_BONES.replace("Frames: 2", "Frames: 0"), "line 17: the frame count must be a whole number from 1"),
            (TWO_BONES.replace("CHANNELS 3", "CHANNELS 7"), "line 9: a joint has 0 to 6 channels"),
            (
                TWO_BONES.replace("Xrotation Yrotation\n", "Xrotation Wrotation\n"),
                "line 5: unknown channel `Wrotation`",
            ),
            (TWO_BONES.replace("JOINT Spine", "JOINT Hips"), "two joints are called `Hips`"),
            (TWO_BONES[..120].to_string(), "the file ends where"),
            ("MOTION".to_string(), "line 1: expected `HIERARCHY`, found `MOTION`"),
            (String::new(), "the file ends where `HIERARCHY` was expected"),
            (TWO_BONES.replace("Frame Time: 0.5", "Frame Time: 0"), "the frame time must be"),
        ];
        for (text, want) in cases {
            let err = read_bvh(&text).unwrap_err();
            assert!(err.contains(want), "{err:?} should say {want:?}");
        }
    }

    #[test]
    fn braces_on_the_name_s_line_and_a_deep_chain_read() {
        let mut text = String::from("HIERARCHY\nROOT a{ OFFSET 0 0 0 CHANNELS 3 Xposition Yposition Zposition\n");
        for i in 0..600 {
            text += &format!("JOINT j{i} {{ OFFSET 0 1 0 CHANNELS 0\n");
        }
        text += &"}".repeat(601);
        text += "\nMOTION\nFrames: 1\nFrame Time: 0.01\n0 0 0\n";
        let clip = read_bvh(&text).unwrap();
        assert_eq!(clip.names.len(), 601);
        assert!(near(clip.frames[0][600], DVec3::new(0.0, 600.0, 0.0)));
    }
}
