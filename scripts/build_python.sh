#!/usr/bin/env bash
# Builds the Python package `shade_sim` (python/: PyO3 + maturin) into one abi3 wheel for CPython
# >= 3.9 in target/wheels/. `bash scripts/build_python.sh` builds the release profile (what users
# install); `--dev` builds the dev profile (the tests' build, sharing their compiled dependencies).
# maturin comes from the project's venv (scripts/setup_python.sh). Prints the wheel's path.
set -euo pipefail
cd "$(dirname "$0")/.."
profile=release
if [ "${1:-}" = "--dev" ]; then
    profile=dev
fi
[ -x .venv/bin/maturin ] || bash scripts/setup_python.sh
rm -f target/wheels/shade_sim-*.whl
.venv/bin/maturin build --quiet --manifest-path python/Cargo.toml --profile "$profile" --strip \
    --out target/wheels >&2
ls target/wheels/shade_sim-*.whl
