#!/usr/bin/env bash
# The fuzz tier: installs clang and libFuzzer (Debian's clang-14, libclang-rt-14-dev), builds the loaders' libFuzzer
# harnesses with ASan and UBSan into build-fuzz/ (or $DRAPE_FUZZ_BUILD_DIR; engine and harnesses only), and runs each
# for 60 s from its seeds (ctest -L fuzz_slow: Fuzz.pattern, Fuzz.scene, Fuzz.measurements, Fuzz.avatar). A finding
# fails its test and is kept as build-fuzz/fuzz/finding_<harness>-*; reproduce it with
# build-fuzz/fuzz/drape_fuzz_<harness> FILE, then keep it in tests/data/bad with the error it must give.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
missing=()
for p in clang-14 libclang-rt-14-dev; do dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p"); done
if [ ${#missing[@]} -gt 0 ]; then
  $SUDO apt-get update -q
  $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
BUILD_DIR="${DRAPE_FUZZ_BUILD_DIR:-build-fuzz}"
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang-14 \
  -DCMAKE_CXX_COMPILER=clang++-14 -DDRAPE_FUZZ=ON -DDRAPE_BUILD_GUI=OFF -DDRAPE_BUILD_TESTS=OFF "$@"
cmake --build "$BUILD_DIR" -j "$(nproc)" --target drape_fuzz_pattern drape_fuzz_dxf drape_fuzz_scene drape_fuzz_measurements \
  drape_fuzz_avatar
ctest --test-dir "$BUILD_DIR" -L fuzz_slow --output-on-failure -j "$(nproc)"
