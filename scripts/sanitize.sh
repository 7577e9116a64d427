#!/usr/bin/env bash
# The sanitizer tier: builds Drape with AddressSanitizer and UndefinedBehaviorSanitizer (-DDRAPE_SANITIZE=ON) into
# build-sanitize/ (or $DRAPE_BUILD_DIR) and runs the fast test tier (ctest -LE slow) under Xvfb. Any sanitizer
# report fails its test: undefined behaviour aborts (-fno-sanitize-recover), and leaks are reported for Drape's own
# allocations (sanitize.supp suppresses the system libraries' one-time allocations: Mesa, fontconfig, Qt's plugins).
# Extra arguments go to ctest (e.g. -R Pattern).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export DRAPE_BUILD_DIR="${DRAPE_BUILD_DIR:-build-sanitize}"
bash scripts/build.sh -DDRAPE_BUILD_TESTS=ON -DDRAPE_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:detect_stack_use_after_return=1"
export LSAN_OPTIONS="suppressions=$PWD/scripts/sanitize.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" \
  ctest --test-dir "$DRAPE_BUILD_DIR" -LE slow --output-on-failure --timeout 1800 -j "$(nproc)" "$@"
