#!/usr/bin/env bash
# Installs every Debian 12 package Drape needs to build, test and run. Idempotent: packages already
# present are left alone, and apt is only asked when something is missing.
set -euo pipefail

PACKAGES=(
  # toolchain
  build-essential cmake ninja-build pkg-config git
  # engine
  libeigen3-dev libsuitesparse-dev libmetis-dev libtbb-dev libassimp-dev
  nlohmann-json3-dev libyaml-cpp-dev libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  # DXF-AAMA pattern files: libdxflib in the engine; ezdxf, an independent DXF writer, for the tests
  libdxflib-dev python3-ezdxf
  # renderer (headless EGL on Mesa llvmpipe, OSMesa fallback) and PNG output
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri libosmesa6-dev libpng-dev
  # GUI
  qt6-base-dev libqt6opengl6-dev qt6-charts-dev qt6-svg-dev
  # tests
  libgtest-dev xvfb xauth
  # drape --batch --slurm and its test against a one-node Slurm (scripts/slurm-local.sh)
  slurm-wlm munge
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages already installed"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
