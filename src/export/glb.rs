//! The glTF 2.0 binary container (`.glb`): one binary buffer of accessors, a JSON document, and
//! the 12-byte header and two chunks around them. Knows nothing about scenes; `gltf.rs` fills it.

use serde_json::{Value, json};

const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;
const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;

/// Accessors and their bytes, collected before the document is written.
#[derive(Debug, Default)]
pub struct GlbBuffer {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl GlbBuffer {
    fn view(&mut self, bytes: &[u8], target: Option<u32>) -> usize {
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        self.bin.resize(self.bin.len().next_multiple_of(4), 0);
        let mut v = json!({ "buffer": 0, "byteOffset": offset, "byteLength": bytes.len() });
        if let Some(t) = target {
            v["target"] = json!(t);
        }
        self.views.push(v);
        self.views.len() - 1
    }

    /// Adds `rows` of `N` floats as an accessor of type SCALAR (N = 1), VEC3 or VEC4, with its
    /// per-component min and max (glTF requires them for positions and animation inputs);
    /// `vertex` marks vertex attributes. Returns the accessor's index.
    pub fn floats<const N: usize>(&mut self, rows: &[[f32; N]], vertex: bool) -> usize {
        let kind = match N {
            1 => "SCALAR",
            2 => "VEC2",
            3 => "VEC3",
            4 => "VEC4",
            _ => unreachable!("glTF float accessors have 1 to 4 components"),
        };
        let mut lo = [f32::INFINITY; N];
        let mut hi = [f32::NEG_INFINITY; N];
        let mut bytes = Vec::with_capacity(rows.len() * N * 4);
        for r in rows {
            for k in 0..N {
                lo[k] = lo[k].min(r[k]);
                hi[k] = hi[k].max(r[k]);
                bytes.extend_from_slice(&r[k].to_le_bytes());
            }
        }
        let view = self.view(&bytes, vertex.then_some(ARRAY_BUFFER));
        self.accessors.push(json!({
            "bufferView": view, "componentType": FLOAT, "count": rows.len(), "type": kind,
            "min": lo.to_vec(), "max": hi.to_vec(),
        }));
        self.accessors.len() - 1
    }

    /// Adds triangle indices; returns the accessor's index.
    pub fn indices(&mut self, indices: &[u32]) -> usize {
        let bytes: Vec<u8> = indices.iter().flat_map(|i| i.to_le_bytes()).collect();
        let view = self.view(&bytes, Some(ELEMENT_ARRAY_BUFFER));
        self.accessors.push(json!({
            "bufferView": view, "componentType": UNSIGNED_INT, "count": indices.len(), "type": "SCALAR",
        }));
        self.accessors.len() - 1
    }

    /// The `.glb` bytes of `document` (asset, scenes, nodes, meshes, …) with this buffer's
    /// `buffers`, `bufferViews` and `accessors` added.
    pub fn finish(self, mut document: Value) -> Vec<u8> {
        document["asset"] = json!({ "version": "2.0", "generator": concat!("shade-sim ", env!("CARGO_PKG_VERSION")) });
        document["buffers"] = json!([{ "byteLength": self.bin.len() }]);
        document["bufferViews"] = Value::Array(self.views);
        document["accessors"] = Value::Array(self.accessors);
        let mut text = serde_json::to_vec(&document).expect("a JSON value serialises");
        text.resize(text.len().next_multiple_of(4), b' ');
        let total = 12 + 8 + text.len() + 8 + self.bin.len();
        let mut out = Vec::with_capacity(total);
        out.extend_from_slice(b"glTF");
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&(total as u32).to_le_bytes());
        out.extend_from_slice(&(text.len() as u32).to_le_bytes());
        out.extend_from_slice(b"JSON");
        out.extend_from_slice(&text);
        out.extend_from_slice(&(self.bin.len() as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&self.bin);
        out
    }
}
