#!/usr/bin/env bash
# The project's test command (README, CI): installs what the tests need — rustfmt and clippy,
# MuJoCo 3.17.0 from its PyPI wheel (scripts/setup_mujoco.sh), the project's Python venv .venv with
# robosuite, Ray, pytest and maturin (scripts/setup_python.sh) and the Khronos glTF validator (npm) —
# then runs rustfmt --check, clippy with warnings as errors (the crate and its Python bindings),
# every Rust test with the `mujoco` feature, builds the wheel of the Python package
# (scripts/build_python.sh), installs it in .venv and runs the Python tests (python/tests).
set -euo pipefail
cd "$(dirname "$0")/.."
# One build per run: incremental caches would add gigabytes to a clean checkout's target folder.
export CARGO_INCREMENTAL="${CARGO_INCREMENTAL:-0}"

if ! cargo fmt --version >/dev/null 2>&1 || ! cargo clippy --version >/dev/null 2>&1; then
    rustup component add rustfmt clippy
fi
echo "== MuJoCo, the Python venv (robosuite, Ray) and the glTF validator"
bash scripts/setup_mujoco.sh
bash scripts/setup_python.sh
(cd scripts/glb_viewer && npm install --silent --no-audit --no-fund gltf-validator@2.0.0-dev.3.10 --no-save >/dev/null)

echo "== cargo fmt --check"
cargo fmt --check
echo "== cargo clippy --all-targets --features mujoco -- -D warnings"
cargo clippy --locked --all-targets --features mujoco -- -D warnings
cargo clippy --locked -p shade-sim-python -- -D warnings
echo "== cargo test --features mujoco"
cargo test --locked --features mujoco
echo "== the Python package: wheel, install, pytest"
wheel=$(bash scripts/build_python.sh --dev)
.venv/bin/pip install --quiet --disable-pip-version-check --force-reinstall --no-deps "$wheel"
.venv/bin/python -m pytest -q -p no:cacheprovider python/tests
