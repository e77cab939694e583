#!/usr/bin/env bash
# Installs MuJoCo 3.17.0 from its PyPI wheel (a venv in .venv-mujoco) and puts its shared library
# where the `mujoco` feature links it: .mujoco/lib/libmujoco.so (see .cargo/config.toml and
# build.rs, which bakes that folder into the binaries' rpath). Idempotent; ~10 s after the download.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ -f .mujoco/lib/libmujoco.so ]; then
    exit 0
fi
python3 -m venv .venv-mujoco
.venv-mujoco/bin/pip install --quiet --disable-pip-version-check mujoco==3.17.0
lib=$(.venv-mujoco/bin/python - <<'PY'
import glob, os, mujoco
d = os.path.dirname(mujoco.__file__)
print(sorted(glob.glob(os.path.join(d, "libmujoco.so*")))[0])
PY
)
mkdir -p .mujoco/lib
cp "$lib" .mujoco/lib/
ln -sf "$(basename "$lib")" .mujoco/lib/libmujoco.so
echo "MuJoCo: $(basename "$lib") in .mujoco/lib"
