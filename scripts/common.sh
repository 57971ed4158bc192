# SPDX-License-Identifier: Apache-2.0
# Sourced by scripts/setup.sh, scripts/test.sh and .ci/run: the Debian packages the project
# needs and the one way the Release build is configured, so that setup.sh and test.sh share
# build/ without reconfiguring it.
#
# Environment (all optional):
#   PPM_BUILD_DIR       Release build directory (default: build)
#   PPM_ASAN_BUILD_DIR  sanitizer build directory used by test.sh (default: build-asan)
#   PPM_JOBS            parallel compile jobs (default: number of cores)

PPM_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
PPM_BUILD_DIR=${PPM_BUILD_DIR:-build}
PPM_ASAN_BUILD_DIR=${PPM_ASAN_BUILD_DIR:-build-asan}
PPM_JOBS=${PPM_JOBS:-$(nproc 2>/dev/null || echo 2)}

# Everything the library, tests, tools and (planned) renderer and Python bindings build
# with, as Debian bookworm names them.
PPM_DEBIAN_PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libembree-dev libtbb-dev libcmocka-dev clang-format
  libopenimageio-dev libopenexr-dev openimageio-tools
  libcgal-dev libgmp-dev libmpfr-dev libnanoflann-dev libjsoncpp-dev zlib1g-dev libpugixml-dev libcli11-dev
  python3 python3-venv python3-pip python3-dev python3-numpy python3-pytest python3-matplotlib
)

# Prints the packages of PPM_DEBIAN_PACKAGES that are not installed, one per line. Prints
# nothing on a system without dpkg (not Debian): there the build reports what it lacks.
ppm_missing_packages() {
  command -v dpkg-query >/dev/null 2>&1 || return 0
  local package
  for package in "${PPM_DEBIAN_PACKAGES[@]}"; do
    if [[ "$(dpkg-query -W -f='${db:Status-Status}' "$package" 2>/dev/null)" != installed ]]; then
      echo "$package"
    fi
  done
}

# Step banners with the time since the script started, so logs show where time goes.
ppm_step() {
  printf '\n==> [%4ds] %s\n' "$SECONDS" "$*"
}

ppm_die() {
  printf '\nerror: %s\n' "$*" >&2
  exit 1
}

# Absolute form of a path given relative to the repository.
ppm_abspath() {
  if [[ "$1" == /* ]]; then echo "$1"; else echo "$PPM_ROOT/$1"; fi
}

# ppm_configure SOURCE_DIR BUILD_DIR [cmake args...]: configures with Ninja, or with whatever
# generator BUILD_DIR was first configured with (cmake refuses to switch generators in place).
ppm_configure() {
  local source_dir=$1 build_dir=$2
  shift 2
  local generator=()
  [[ -f "$build_dir/CMakeCache.txt" ]] || generator=(-G Ninja)
  cmake -S "$source_dir" -B "$build_dir" "${generator[@]}" "$@"
}

# Configures and builds the Release library, tests and tools in PPM_BUILD_DIR. The tools are
# unity builds (PPM_UNITY_BUILD): the same code in fewer translation units, which compile
# their shared headers (CLI11 above all) once per batch instead of once per file.
ppm_build_release() {
  ppm_configure "$PPM_ROOT" "$PPM_BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DPPM_SANITIZE=OFF -DPPM_UNITY_BUILD=ON &&
    cmake --build "$PPM_BUILD_DIR" --parallel "$PPM_JOBS"
}

# The sanitizer builds (test.sh's ASan + UBSan build, tsan.sh's ThreadSanitizer build) compile
# at -O1 with line tables only (-g1), the level the sanitizers' documentation recommends: every
# check is the same and reports keep their file:line stacks, while the build takes about half
# the compile time of -O2 -g (CLI11 and the test files above all). The library is a unity build
# there (PPM_UNITY_BUILD_LIBRARY), which halves its share again.
PPM_SANITIZER_CMAKE_ARGS=(-DCMAKE_BUILD_TYPE=RelWithDebInfo
  "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG"
  -DPPM_UNITY_BUILD=ON -DPPM_UNITY_BUILD_LIBRARY=ON)
