#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# ThreadSanitizer run of the tests labelled "threads". Assumes scripts/setup.sh has run.
#
#   bash scripts/tsan.sh          (also run by bash scripts/test.sh, unless --no-tsan)
#
# 1. Once: builds libtbb from Debian's source of the installed libtbb12 (same version, so the
#    headers in /usr/include match) with -fsanitize=thread into build-tsan/tbb/. TSan sees a
#    task's hand-off from the thread that spawns it to the worker that runs it only inside an
#    instrumented TBB; with Debian's build it reports races on every task's data. The source
#    comes through `apt-get source` with a private copy of the machine's apt sources turned
#    into deb-src entries: the system's apt settings and state are not touched.
# 2. Builds libppm and the "threads" test executables with -DPPM_SANITIZE=thread into
#    build-tsan/ (tests/CMakeLists.txt points them at that libtbb and makes every report
#    fatal; tests/tsan.supp holds the third-party suppressions).
# 3. ctest -L threads in build-tsan/.
# Exits non-zero if a step fails or TSan reports anything.
#
# Environment: PPM_TSAN_BUILD_DIR (default build-tsan), PPM_JOBS (see common.sh).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
cd "$PPM_ROOT"

build_dir=$(ppm_abspath "${PPM_TSAN_BUILD_DIR:-build-tsan}")
tbb=$build_dir/tbb

# build_tbb: leaves the instrumented libtbb.so* in $tbb/lib, rebuilt only when the installed
# libtbb12 changes version.
build_tbb() {
  local package version
  package=$(dpkg-query -W -f='${source:Package}' libtbb12) || ppm_die "libtbb12 is not installed"
  version=$(dpkg-query -W -f='${source:Version}' libtbb12)
  if [[ -e "$tbb/lib/libtbb.so.12" && "$(cat "$tbb/version" 2>/dev/null)" == "$package=$version" ]]; then
    echo "instrumented $package $version is built"
    return 0
  fi
  rm -rf "$tbb"
  local apt_dir=$tbb/apt
  mkdir -p "$apt_dir/sources.list.d" "$apt_dir/lists/partial" "$apt_dir/cache/archives/partial" "$tbb/src"
  : >"$apt_dir/sources.list"
  local file
  [[ -f /etc/apt/sources.list ]] && sed -n 's/^deb /deb-src /p' /etc/apt/sources.list >"$apt_dir/sources.list"
  for file in /etc/apt/sources.list.d/*.list; do
    [[ -f "$file" ]] && sed -n 's/^deb /deb-src /p' "$file" >"$apt_dir/sources.list.d/${file##*/}"
  done
  for file in /etc/apt/sources.list.d/*.sources; do
    [[ -f "$file" ]] && sed 's/^Types:.*/Types: deb-src/' "$file" >"$apt_dir/sources.list.d/${file##*/}"
  done
  local apt=(apt-get -q -o "Dir::Etc::SourceList=$apt_dir/sources.list"
    -o "Dir::Etc::SourceParts=$apt_dir/sources.list.d" -o "Dir::State::Lists=$apt_dir/lists"
    -o "Dir::Cache=$apt_dir/cache" -o APT::Sandbox::User=root)
  # A source list without a source index (a third-party repository) only warns here.
  "${apt[@]}" update || echo "apt-get update reported errors; trying the download anyway"
  (cd "$tbb/src" && "${apt[@]}" source "$package=$version") || ppm_die "apt-get source $package=$version failed"
  local source_dir
  source_dir=$(find "$tbb/src" -mindepth 1 -maxdepth 1 -type d | head -n 1)
  [[ -n "$source_dir" ]] || ppm_die "apt-get source $package left no source folder"
  # gcc warns that TSan does not model atomic_thread_fence, which TBB's sleep/wake protocol
  # uses; no report has come from it. TBB_STRICT would make the warning an error.
  cmake -S "$source_dir" -B "$tbb/build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTBB_SANITIZE=thread \
    -DCMAKE_CXX_FLAGS=-Wno-tsan -DTBB_TEST=OFF -DTBB_STRICT=OFF -DTBBMALLOC_BUILD=OFF \
    -DTBB_DISABLE_HWLOC_AUTOMATIC_SEARCH=ON
  cmake --build "$tbb/build" --parallel "$PPM_JOBS" --target tbb
  mkdir -p "$tbb/lib"
  find "$tbb/build" -name 'libtbb.so*' -exec cp -P {} "$tbb/lib/" \;
  [[ -e "$tbb/lib/libtbb.so.12" ]] || ppm_die "the TBB build made no libtbb.so.12"
  echo "$package=$version" >"$tbb/version"
}

ppm_step "ThreadSanitizer: libtbb with -fsanitize=thread in $tbb/"
build_tbb

ppm_step "ThreadSanitizer: libppm and the thread tests in $build_dir/"
ppm_configure "$PPM_ROOT" "$build_dir" "${PPM_SANITIZER_CMAKE_ARGS[@]}" -DPPM_SANITIZE=thread \
  -DPPM_BUILD_TOOLS=OFF -DPPM_BUILD_REFERENCE=OFF -DPPM_TSAN_TBB_LIBRARY_DIR="$tbb/lib"
# Only the executables of the label: each test of ppm_add_test is named after its target.
mapfile -t tests < <(ctest --test-dir "$build_dir" -N -L threads | sed -n 's/^ *Test *#[0-9]*: *//p')
((${#tests[@]} > 0)) || ppm_die "no test is labelled 'threads'"
targets=()
for test in "${tests[@]}"; do
  if ninja -C "$build_dir" -t query "$test" >/dev/null 2>&1; then targets+=("$test"); fi
done
cmake --build "$build_dir" --parallel "$PPM_JOBS" --target "${targets[@]}"

ppm_step "ThreadSanitizer: ctest -L threads"
ctest --test-dir "$build_dir" -L threads --output-on-failure --no-tests=error --timeout 1200
ppm_step "ThreadSanitizer: no report (${SECONDS}s)"
