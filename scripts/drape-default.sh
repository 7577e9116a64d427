#!/usr/bin/env bash
# README command 1: installs what Drape needs, builds it, and runs the main job on the bundled default scene.
# Output goes to out/: default.obj (the draped garment), default.png (a picture of it) and default.stats.json.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
BUILD_DIR="${DRAPE_BUILD_DIR:-build}"
mkdir -p out
"$BUILD_DIR/app/drape" --info assets/scenes/default.json
"$BUILD_DIR/app/drape" --simulate assets/scenes/default.json -o out/default.obj \
  --stats out/default.stats.json --png out/default.png
echo "drape-default: wrote out/default.obj, out/default.png and out/default.stats.json"
