//! - With the `mujoco` feature, binaries, tests and benches find libmujoco.so in .mujoco/lib
//!   (installed by scripts/setup_mujoco.sh) without LD_LIBRARY_PATH.
//! - The shipped models in models/<room>/ (config.json + model.safetensors), and the low-noise
//!   experts in models/<room>-expert/, are embedded into the library, so `generate` and `demo`
//!   work from any folder; rooms without a model (or an expert) are left out.

use std::fmt::Write;
use std::path::Path;

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rerun-if-changed=models");
    let root = std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR");
    if std::env::var_os("CARGO_FEATURE_MUJOCO").is_some() {
        println!("cargo::rustc-link-arg=-Wl,-rpath,{root}/.mujoco/lib");
    }
    let mut code = String::new();
    // The whole-chain models in models/<room>/, and the low-noise experts in models/<room>-expert/.
    for (table, suffix, what) in [("SHIPPED", "", "models"), ("SHIPPED_EXPERTS", "-expert", "low-noise experts")] {
        writeln!(code, "/// Shipped {what}: (room, config.json, model.safetensors).").expect("writing to a String");
        writeln!(code, "pub static {table}: &[(&str, &str, &[u8])] = &[").expect("writing to a String");
        for room in ["bedroom", "living", "dining"] {
            let dir = Path::new(&root).join("models").join(format!("{room}{suffix}"));
            let (config, weights) = (dir.join("config.json"), dir.join("model.safetensors"));
            println!("cargo::rerun-if-changed={}", dir.display());
            if config.is_file() && weights.is_file() {
                writeln!(
                    code,
                    "    ({room:?}, include_str!({:?}), include_bytes!({:?})),",
                    config.display().to_string(),
                    weights.display().to_string()
                )
                .expect("writing to a String");
            }
        }
        code.push_str("];\n");
    }
    let out = Path::new(&std::env::var("OUT_DIR").expect("cargo sets OUT_DIR")).join("shipped_models.rs");
    std::fs::write(out, code).expect("OUT_DIR is writable");
}
