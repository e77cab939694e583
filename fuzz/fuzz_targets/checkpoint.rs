//! A model folder's two files from one input: the first line is `config.json`'s text, the rest
//! `model.safetensors`' bytes. Loading either is checked; a pair that loads is a model whose
//! config, tensors and hash all agree. Any panic or abort is a finding.
#![no_main]

use libfuzzer_sys::fuzz_target;
use shade_sim::generator::Checkpoint;
use shade_sim::generator::checkpoint::{parse_meta, read_tensors};
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let split = data.iter().position(|&b| b == b'\n').unwrap_or(data.len());
    let (config, weights) = (&data[..split], data.get(split + 1..).unwrap_or(&[]));
    let _ = read_tensors(weights, Path::new("model.safetensors"));
    let Ok(text) = std::str::from_utf8(config) else { return };
    let Ok(meta) = parse_meta(text, Path::new("config.json")) else { return };
    let _ = Checkpoint::from_parts(meta, weights, Path::new("model.safetensors"));
});
