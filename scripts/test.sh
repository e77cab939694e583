#!/usr/bin/env bash
# The project's test command (README, CI): installs what the tests need, then runs
# rustfmt --check, clippy with warnings as errors, and every test.
#
# Today the tests need only the Rust toolchain's rustfmt and clippy; the MuJoCo / robosuite
# installs join here with the physics and export work (behind the `mujoco` feature).
set -euo pipefail
cd "$(dirname "$0")/.."

if ! cargo fmt --version >/dev/null 2>&1 || ! cargo clippy --version >/dev/null 2>&1; then
    rustup component add rustfmt clippy
fi

echo "== cargo fmt --check"
cargo fmt --check
echo "== cargo clippy --all-targets -- -D warnings"
cargo clippy --locked --all-targets -- -D warnings
echo "== cargo test"
cargo test --locked
