#!/usr/bin/env bash
# The project's test command (README, CI): installs what the tests need — rustfmt and clippy, and
# MuJoCo 3.17.0 from its PyPI wheel (scripts/setup_mujoco.sh), robosuite 1.5.2 in its own venv
# (scripts/setup_robosuite.sh) and the Khronos glTF validator (npm) — then runs rustfmt --check, clippy
# with warnings as errors, and every test with the `mujoco` feature.
set -euo pipefail
cd "$(dirname "$0")/.."

if ! cargo fmt --version >/dev/null 2>&1 || ! cargo clippy --version >/dev/null 2>&1; then
    rustup component add rustfmt clippy
fi
echo "== MuJoCo, robosuite and the glTF validator"
bash scripts/setup_mujoco.sh
bash scripts/setup_robosuite.sh
(cd scripts/glb_viewer && npm install --silent --no-audit --no-fund gltf-validator@2.0.0-dev.3.10 --no-save >/dev/null)

echo "== cargo fmt --check"
cargo fmt --check
echo "== cargo clippy --all-targets --features mujoco -- -D warnings"
cargo clippy --locked --all-targets --features mujoco -- -D warnings
echo "== cargo test --features mujoco"
cargo test --locked --features mujoco
