//! With the `mujoco` feature, binaries, tests and benches find libmujoco.so in .mujoco/lib
//! (installed by scripts/setup_mujoco.sh) without LD_LIBRARY_PATH.

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
    if std::env::var_os("CARGO_FEATURE_MUJOCO").is_some() {
        let root = std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR");
        println!("cargo::rustc-link-arg=-Wl,-rpath,{root}/.mujoco/lib");
    }
}
