#!/usr/bin/env bash
# The project's Python venv (.venv) for the Python package and its tests: robosuite 1.5.2 (it pins
# numpy < 2) with MuJoCo 3.9.0, Ray, pytest and maturin (which builds the wheel). Idempotent; about
# a minute the first time. MuJoCo 3.9.0 is the newest whose Python bindings robosuite 1.5.2's
# environments run with (measured: `robosuite.make("Lift")` stepped): 3.10 changed `mj_fullM`'s
# arguments, 3.11 dropped `MjData.qM`, and from 3.12 its enums no longer equal numpy integers in a
# tuple test, so `get_joint_qpos_addr` asserts. (The Rust side links 3.17.0 from .venv-mujoco,
# scripts/setup_mujoco.sh; both load the same MJCF.)
set -euo pipefail
cd "$(dirname "$0")/.."
want="robosuite==1.5.2 mujoco==3.9.0 ray==2.60.0 pytest==9.2.0 maturin==1.16.0"
stamp=.venv/.shade-sim-requirements
if [ -x .venv/bin/python ] && [ "$(cat "$stamp" 2>/dev/null)" = "$want" ]; then
    exit 0
fi
python3 -m venv .venv
# shellcheck disable=SC2086
.venv/bin/pip install --quiet --disable-pip-version-check "numpy<2" $want
echo "$want" > "$stamp"
echo "Python venv: $(.venv/bin/python -c 'import robosuite, ray; print("robosuite", robosuite.__version__, "ray", ray.__version__)') in .venv"
