#!/usr/bin/env bash
# README command 1: installs what Drape needs, builds it, and runs the main job on the bundled default scene.
# Output goes to out/: default.obj (the garment) and default.stats.json.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
BUILD_DIR="${DRAPE_BUILD_DIR:-build}"
mkdir -p out
"$BUILD_DIR/app/drape" --info assets/scenes/default.json
"$BUILD_DIR/app/drape" --simulate assets/scenes/default.json --solver none -o out/default.obj \
  --stats out/default.stats.json
echo "drape-default: wrote out/default.obj and out/default.stats.json"
