#!/usr/bin/env bash
# Installs robosuite 1.5.2 in its own venv (.venv-robosuite: robosuite pins numpy < 2) with
# MuJoCo 3.17.0, for the tests that load shade-sim's arenas in robosuite. Idempotent; ~25 s.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ -x .venv-robosuite/bin/python ] && .venv-robosuite/bin/python -c "import robosuite" 2>/dev/null; then
    exit 0
fi
python3 -m venv .venv-robosuite
.venv-robosuite/bin/pip install --quiet --disable-pip-version-check "numpy<2" robosuite==1.5.2 mujoco==3.17.0
echo "robosuite: $(.venv-robosuite/bin/python -c 'import robosuite; print(robosuite.__version__)') in .venv-robosuite"
