#!/usr/bin/env bash
# The project's test command (README, CI): installs what the tests need — rustfmt and clippy, and
# MuJoCo 3.17.0 from its PyPI wheel (scripts/setup_mujoco.sh) and robosuite 1.5.2 in its own venv
# (scripts/setup_robosuite.sh) — then runs rustfmt --check, clippy
# with warnings as errors, and every test with the `mujoco` feature.
set -euo pipefail
cd "$(dirname "$0")/.."

if ! cargo fmt --version >/dev/null 2>&1 || ! cargo clippy --version >/dev/null 2>&1; then
    rustup component add rustfmt clippy
fi
echo "== MuJoCo and robosuite"
bash scripts/setup_mujoco.sh
bash scripts/setup_robosuite.sh

echo "== cargo fmt --check"
cargo fmt --check
echo "== cargo clippy --all-targets --features mujoco -- -D warnings"
cargo clippy --locked --all-targets --features mujoco -- -D warnings
echo "== cargo test --features mujoco"
cargo test --locked --features mujoco
