#!/usr/bin/env bash
# README command 2: installs what Drape needs, builds it with the tests, and runs the whole suite.
# GUI and viewport tests need an X server: the suite runs under xvfb-run. Tests that read ../shared/data skip
# where it is absent, unless DRAPE_REQUIRE_SHARED_DATA=1 (CI) makes that a failure. -noreset: Xvfb otherwise
# resets whenever its last client disconnects, and a test connecting during the reset is refused.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh -DDRAPE_BUILD_TESTS=ON
BUILD_DIR="${DRAPE_BUILD_DIR:-build}"
xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" \
  ctest --test-dir "$BUILD_DIR" --output-on-failure --timeout 900 -j "$(nproc)"
