#!/usr/bin/env bash
# Checks an exported .glb in real consumers: the Khronos glTF validator, then a three.js page in
# headless Chromium (software WebGL) that plays the motion to T seconds and saves a screenshot.
# Installs Debian's chromium (apt-get) and the page's npm packages on first use.
#   bash scripts/view_glb.sh room.glb room_view.png [T]
set -euo pipefail
glb=$(realpath "$1"); png=$(realpath -m "$2"); t=${3:-1.0}
dir="$(cd "$(dirname "$0")" && pwd)/glb_viewer"
if ! command -v chromium >/dev/null; then
    (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium) >/dev/null
fi
if [ ! -d "$dir/node_modules/three" ] || [ ! -d "$dir/node_modules/gltf-validator" ]; then
    (cd "$dir" && npm install --silent --no-audit --no-fund)
fi
node "$dir/validate.mjs" "$glb"
serve=$(mktemp -d)
trap 'kill $server 2>/dev/null; rm -rf "$serve"' EXIT
ln -s "$dir/index.html" "$serve/index.html"
ln -s "$dir/node_modules" "$serve/node_modules"
cp "$glb" "$serve/scene.glb"
port=$((20000 + RANDOM % 20000))
python3 -m http.server "$port" --bind 127.0.0.1 --directory "$serve" >/dev/null 2>&1 &
server=$!
sleep 1
chromium --headless --no-sandbox --disable-gpu --use-angle=swiftshader --enable-unsafe-swiftshader \
    --disable-quic --no-first-run --disable-background-networking --disable-component-update --disable-sync \
    --user-data-dir="$serve/profile" --window-size=1200,900 --virtual-time-budget=20000 \
    --screenshot="$png" "http://127.0.0.1:$port/index.html?file=scene.glb&t=$t" 2>/dev/null
echo "$png: screenshot of $1 at t = $t s"
