//! A scene as glTF 2.0 binary (`.glb`) for any glTF viewer: the floor polygon, walls, furniture
//! (one node per object, one box per template part, coloured like the MJCF world) and the
//! humans' bones as capsules whose motion is one animation ("motion", linear, per-bone
//! translation and rotation at the scene's fps). Names are the MJCF names (`o3`, `o3_seat`,
//! `h0_pelvis-spine`, `wall2`).
//!
//! glTF is y-up: the root node turns shade-sim's z-up frame by −90° about x, everything below it
//! stays in scene coordinates. Output is deterministic (sorted JSON keys, fixed order).

use super::glb::GlbBuffer;
use super::mesh::TriMesh;
use super::mjcf::{bone_name, bone_pose, part_names};
use super::palette::{MATERIALS, material, material_index};
use crate::furniture::wall_boxes;
use crate::geom::OBox;
use crate::scene::Scene;
use glam::DQuat;
use serde_json::{Value, json};

/// Capsule tessellation: segments around, rings per cap.
const CAPSULE_SEGMENTS: usize = 12;
const CAPSULE_RINGS: usize = 4;

fn f32s<const N: usize>(v: [f64; N]) -> [f32; N] {
    v.map(|x| x as f32)
}

/// `[x, y, z, w]`, glTF's quaternion order.
fn xyzw(q: DQuat) -> [f32; 4] {
    f32s([q.x, q.y, q.z, q.w])
}

/// The document being built: the buffer, meshes and nodes.
struct Builder {
    buffer: GlbBuffer,
    meshes: Vec<Value>,
    nodes: Vec<Value>,
    /// The unit-box mesh of each material, made on first use.
    box_meshes: Vec<Option<usize>>,
    /// Accessors of the unit box (positions, normals, indices).
    unit_box: Option<[usize; 3]>,
}

impl Builder {
    fn mesh(&mut self, name: &str, m: &TriMesh, material: &str) -> usize {
        let accessors = [
            self.buffer.floats(&m.positions, true),
            self.buffer.floats(&m.normals, true),
            self.buffer.indices(&m.indices),
        ];
        self.mesh_of(name, accessors, material)
    }

    fn mesh_of(&mut self, name: &str, [positions, normals, indices]: [usize; 3], material: &str) -> usize {
        self.meshes.push(json!({
            "name": name,
            "primitives": [{ "attributes": { "POSITION": positions, "NORMAL": normals }, "indices": indices, "material": material_index(material) }],
        }));
        self.meshes.len() - 1
    }

    fn box_mesh(&mut self, material: &str) -> usize {
        let k = material_index(material);
        if let Some(m) = self.box_meshes[k] {
            return m;
        }
        let accessors = match self.unit_box {
            Some(a) => a,
            None => {
                let b = TriMesh::unit_box();
                let a = [
                    self.buffer.floats(&b.positions, true),
                    self.buffer.floats(&b.normals, true),
                    self.buffer.indices(&b.indices),
                ];
                self.unit_box = Some(a);
                a
            }
        };
        let m = self.mesh_of(&format!("box_{material}"), accessors, material);
        self.box_meshes[k] = Some(m);
        m
    }

    fn node(&mut self, node: Value) -> usize {
        self.nodes.push(node);
        self.nodes.len() - 1
    }

    /// A node drawing `b` (world or parent frame) as a scaled unit box.
    fn box_node(&mut self, name: &str, b: &OBox, material: &str) -> usize {
        let mesh = self.box_mesh(material);
        self.node(json!({
            "name": name, "mesh": mesh,
            "translation": f32s(b.center.to_array()),
            "rotation": xyzw(DQuat::from_rotation_z(b.yaw)),
            "scale": f32s(b.size.to_array()),
        }))
    }
}

/// The `.glb` bytes of `scene`.
pub fn scene_glb(scene: &Scene) -> Vec<u8> {
    let mut g = Builder {
        buffer: GlbBuffer::default(),
        meshes: Vec::new(),
        nodes: Vec::new(),
        box_meshes: vec![None; MATERIALS.len()],
        unit_box: None,
    };
    let mut children = Vec::new();
    let floor = g.mesh("floor", &TriMesh::floor(&scene.floor_plan.polygon()), "floor");
    children.push(g.node(json!({ "name": "floor", "mesh": floor })));
    for (i, w) in wall_boxes(scene) {
        children.push(g.box_node(&format!("wall{i}"), &w, "wall"));
    }
    for o in &scene.objects {
        let b = o.obox();
        let parts: Vec<usize> = part_names(o)
            .into_iter()
            .map(|(name, p)| {
                let local = OBox::new(b.to_local(p.obox.center), p.obox.size, 0.0);
                g.box_node(&name, &local, material(o.category.group()))
            })
            .collect();
        children.push(g.node(json!({
            "name": o.id, "children": parts,
            "translation": f32s(b.center.to_array()),
            "rotation": xyzw(DQuat::from_rotation_z(b.yaw)),
        })));
    }
    let (humans, animation) = humans(&mut g, scene);
    children.extend(humans);
    let root = g.node(json!({
        "name": "shade-sim scene (z-up)", "children": children,
        "rotation": xyzw(DQuat::from_rotation_x(-std::f64::consts::FRAC_PI_2)),
    }));
    let materials: Vec<Value> = MATERIALS
        .iter()
        .map(|(name, rgba)| {
            let mut m = json!({
                "name": name,
                "pbrMetallicRoughness": { "baseColorFactor": f32s(*rgba), "metallicFactor": 0.0, "roughnessFactor": 0.8 },
            });
            if rgba[3] < 1.0 {
                m["alphaMode"] = json!("BLEND");
                m["doubleSided"] = json!(true);
            }
            m
        })
        .collect();
    let mut doc = json!({
        "scene": 0,
        "scenes": [{ "name": format!("shade-sim {} scene", scene.room_type), "nodes": [root] }],
        "nodes": g.nodes, "meshes": g.meshes, "materials": materials,
    });
    if let Some(a) = animation {
        doc["animations"] = json!([a]);
    }
    g.buffer.finish(doc)
}

/// One node per human with a capsule node per bone, and the animation moving the bones.
fn humans(g: &mut Builder, scene: &Scene) -> (Vec<usize>, Option<Value>) {
    let (mut nodes, mut samplers, mut channels) = (Vec::new(), Vec::new(), Vec::new());
    for (h, human) in scene.humans.iter().enumerate() {
        let times: Vec<[f32; 1]> = (0..human.frames.len()).map(|f| [(f as f64 / human.fps) as f32]).collect();
        let input = g.buffer.floats(&times, false);
        let mut bones = Vec::new();
        for (b, bone) in human.skeleton.bones.iter().enumerate() {
            let name = bone_name(scene, h, b);
            let half = human.joint_at(0, bone.a).distance(human.joint_at(0, bone.b)) * 0.5;
            let mesh = g.mesh(&name, &TriMesh::capsule(bone.radius, half, CAPSULE_SEGMENTS, CAPSULE_RINGS), "human");
            let (p0, q0) = bone_pose(scene, h, b, 0);
            let node = g.node(json!({
                "name": name, "mesh": mesh,
                "translation": f32s(p0.to_array()), "rotation": xyzw(q0),
            }));
            bones.push(node);
            if human.frames.len() < 2 {
                continue;
            }
            let mut last = q0;
            let (mut translations, mut rotations) = (Vec::new(), Vec::new());
            for f in 0..human.frames.len() {
                let (p, mut q) = bone_pose(scene, h, b, f);
                // Keep neighbouring quaternions in one hemisphere so interpolation takes the
                // short way round.
                if q.dot(last) < 0.0 {
                    q = -q;
                }
                last = q;
                translations.push(f32s(p.to_array()));
                rotations.push(xyzw(q));
            }
            for (path, output) in [
                ("translation", g.buffer.floats(&translations, false)),
                ("rotation", g.buffer.floats(&rotations, false)),
            ] {
                samplers.push(json!({ "input": input, "output": output, "interpolation": "LINEAR" }));
                channels.push(json!({ "sampler": samplers.len() - 1, "target": { "node": node, "path": path } }));
            }
        }
        nodes.push(g.node(json!({ "name": human.id, "children": bones })));
    }
    let animation =
        (!channels.is_empty()).then(|| json!({ "name": "motion", "samplers": samplers, "channels": channels }));
    (nodes, animation)
}
