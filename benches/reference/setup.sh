#!/usr/bin/env bash
# Installs PyTorch (CPU use) into benches/reference/.venv for the speed comparison in
# `cargo bench --bench model`. Not needed by the tests or the tool. Idempotent.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
venv="$here/.venv"
if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c "import torch" 2>/dev/null; then
    python3 -m venv "$venv"
    "$venv/bin/pip" install --quiet "torch>=2.4"
fi
"$venv/bin/python" -c "import torch; print('PyTorch', torch.__version__, 'in', '$venv')"
