#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# README command 1: prepares a Debian bookworm machine and shows libppm working.
#
#   sudo bash scripts/setup.sh      (or, as root: bash scripts/setup.sh)
#
# 1. installs the Debian packages that are missing (none on a prepared machine: then no
#    apt-get runs at all and no root is needed),
# 2. configures and builds the Release library, tests and tools in build/,
# 3. renders the example scene examples/scenes/teapot-cornell.json into teapot-cornell.png.
# Safe to run again: every step only does what is not done yet.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
cd "$PPM_ROOT"

ppm_step "Debian packages"
mapfile -t missing < <(ppm_missing_packages)
if ((${#missing[@]} == 0)); then
  echo "all ${#PPM_DEBIAN_PACKAGES[@]} packages are installed"
else
  echo "missing: ${missing[*]}"
  sudo=()
  if ((EUID != 0)); then
    command -v sudo >/dev/null 2>&1 ||
      ppm_die "installing packages needs root: run 'sudo bash scripts/setup.sh' or run it as root"
    sudo=(sudo)
  fi
  # No questions (CI has no stdin); wait for another apt run (e.g. unattended-upgrades)
  # instead of failing on its lock. Recommends are left out: the list above is complete.
  apt=("${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=600 -o Dpkg::Use-Pty=0 -y -q)
  "${apt[@]}" update </dev/null
  "${apt[@]}" install --no-install-recommends "${missing[@]}" </dev/null
  mapfile -t still_missing < <(ppm_missing_packages)
  ((${#still_missing[@]} == 0)) || ppm_die "apt-get did not install: ${still_missing[*]}"
fi

ppm_step "Configure and build Release in $PPM_BUILD_DIR/"
ppm_build_release

ppm_step "Build the examples/ consumer against $PPM_BUILD_DIR/ (find_package(ppm))"
ppm_configure examples "$PPM_BUILD_DIR/examples" -DCMAKE_BUILD_TYPE=Release \
  -Dppm_DIR="$(ppm_abspath "$PPM_BUILD_DIR")"
cmake --build "$PPM_BUILD_DIR/examples" --parallel "$PPM_JOBS"

ppm_step "Demo: the teapot in a Cornell box -> teapot-cornell.png"
"$PPM_BUILD_DIR/tools/render/ppm-render" examples/scenes/teapot-cornell.json -o teapot-cornell.png -o teapot-cornell.exr

ppm_step "Done in ${SECONDS}s. The image is teapot-cornell.png (linear radiance: teapot-cornell.exr). Next: bash scripts/test.sh"
