#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# README command 2: builds and tests everything. Assumes scripts/setup.sh has run.
#
#   bash scripts/test.sh [--full] [--no-tsan]
#
# 1. Release build in build/, every ctest test.
# 2. ASan + UBSan build (-DPPM_SANITIZE=ON, -O1 -g1) in build-asan/, ctest with
#    PPM_TEST_QUICK=1 and sanitizer errors and leaks fatal. Without ppm-bench and the reference
#    intersector (their tests ran in step 1), and without the tests labelled "slow" (the long
#    statistical and convergence runs, which also ran in step 1). --full (CI) builds and runs
#    them all under the sanitizers too.
# 3. Installs the Release build into a temporary prefix and checks the package: files, SONAME,
#    exported symbols, and the examples/ consumer built against the installed library with
#    find_package(ppm) and with pkg-config.
# 4. Python: builds the package libppm (the extension against the library installed in step 3;
#    with --full the wheel, with `pip wheel .`), installs it into a temporary venv with Dask,
#    Ray and mypy, checks that libppm.so.0 sits beside the extension, and runs the pytest
#    tests (each test counts in the summary; a failed build counts as one).
# 5. scripts/tsan.sh: the ThreadSanitizer build in build-tsan/ and the tests labelled
#    "threads" under it, every report fatal (counts as one check); --no-tsan skips it.
# Exits non-zero if anything failed; the last line sums up ctest tests and package checks.
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
cd "$PPM_ROOT"

run_tsan=1
full=0
for arg in "$@"; do
  case "$arg" in
  --tsan) run_tsan=1 ;;
  --no-tsan) run_tsan=0 ;;
  --full) full=1 ;;
  *) ppm_die "unknown option '$arg' (usage: bash scripts/test.sh [--full] [--no-tsan])" ;;
  esac
done

passed=0
failed=0
failures=()

pass() {
  passed=$((passed + 1))
  echo "PASS: $*"
}

fail() {
  failed=$((failed + 1))
  failures+=("$*")
  echo "FAIL: $*"
}

# step NAME: a banner, and the time of the previous step into the summary.
step_names=()
step_seconds=()
step_started=$SECONDS
step() {
  if ((${#step_names[@]} > 0)); then step_seconds+=($((SECONDS - step_started))); fi
  step_names+=("$1")
  step_started=$SECONDS
  ppm_step "$1"
}

finish() {
  step_seconds+=($((SECONDS - step_started)))
  ppm_step "Summary (${SECONDS}s)"
  local i failure
  for i in "${!step_names[@]}"; do printf '  %5d s  %s\n' "${step_seconds[$i]}" "${step_names[$i]}"; done
  for failure in "${failures[@]}"; do echo "  failed: $failure"; done
  echo "summary: $passed passed, $failed failed"
  ((failed == 0))
  exit
}

# run_ctest LABEL BUILD_DIR [ctest options...] [-- VAR=value...]: runs the tests of BUILD_DIR
# (all of them unless the options select), adds their counts.
run_ctest() {
  local label=$1 dir=$2
  shift 2
  local options=() environment=()
  while (($# > 0)) && [[ "$1" != -- ]]; do
    options+=("$1")
    shift
  done
  (($# > 0)) && shift
  environment=("$@")
  local log="$dir/ctest-summary.log"
  env "${environment[@]}" ctest --test-dir "$dir" --output-on-failure --parallel "$PPM_JOBS" --no-tests=error \
    --timeout 1200 "${options[@]}" 2>&1 | tee "$log"
  local status=${PIPESTATUS[0]}
  # "100% tests passed, 0 tests failed out of 6"
  local line
  line=$(grep -E '^[0-9]+% tests passed, [0-9]+ tests? failed out of [0-9]+' "$log" | tail -n 1)
  if [[ -z "$line" ]]; then
    fail "$label: ctest ran no test or did not finish (exit status $status)"
    return
  fi
  local total failed_here
  total=$(sed -E 's/.* out of ([0-9]+).*/\1/' <<<"$line")
  failed_here=$(sed -E 's/.* ([0-9]+) tests? failed.*/\1/' <<<"$line")
  passed=$((passed + total - failed_here))
  failed=$((failed + failed_here))
  if ((failed_here > 0)); then
    failures+=("$label: $failed_here of $total ctest tests")
  elif ((status != 0)); then
    fail "$label: ctest exited with status $status"
  fi
  echo "$label: $((total - failed_here)) of $total ctest tests passed"
}

# ---------------------------------------------------------------------------------------------
step "Dependencies"
mapfile -t missing < <(ppm_missing_packages)
if ((${#missing[@]} > 0)); then
  ppm_die "missing Debian packages: ${missing[*]}
Install them (and build once) with README command 1:  bash scripts/setup.sh"
fi
for tool in cmake ninja pkg-config cc c++ nm readelf ldd; do
  command -v "$tool" >/dev/null 2>&1 ||
    ppm_die "'$tool' not found; README command 1 (bash scripts/setup.sh) installs it"
done
echo "all ${#PPM_DEBIAN_PACKAGES[@]} Debian packages and the build tools are there"

# ---------------------------------------------------------------------------------------------
step "Release build in $PPM_BUILD_DIR/"
if ! ppm_build_release; then
  fail "Release build"
  finish
fi

step "Release tests"
run_ctest "Release" "$PPM_BUILD_DIR"

# ---------------------------------------------------------------------------------------------
step "ASan + UBSan build in $PPM_ASAN_BUILD_DIR/"
# ppm-bench (CGAL, CLI11: a third of this build's compile time) and the reference intersector
# only with --full: their tests ran in the Release build.
asan_options=("${PPM_SANITIZER_CMAKE_ARGS[@]}" -DPPM_SANITIZE=ON -DPPM_BUILD_BENCH=OFF -DPPM_BUILD_REFERENCE=OFF)
asan_ctest=(-LE slow)
if ((full)); then
  asan_options=("${PPM_SANITIZER_CMAKE_ARGS[@]}" -DPPM_SANITIZE=ON -DPPM_BUILD_BENCH=ON -DPPM_BUILD_REFERENCE=ON)
  asan_ctest=()
fi
if ppm_configure "$PPM_ROOT" "$PPM_ASAN_BUILD_DIR" "${asan_options[@]}" &&
  cmake --build "$PPM_ASAN_BUILD_DIR" --parallel "$PPM_JOBS"; then
  if ((full)); then
    step "ASan + UBSan tests, all of them (PPM_TEST_QUICK=1)"
  else
    step "ASan + UBSan tests but those labelled slow (PPM_TEST_QUICK=1)"
  fi
  # Any report ends the test with a non-zero status; leaks are reported at exit, except the
  # third-party ones listed with their reasons in tests/lsan.supp.
  run_ctest "ASan+UBSan" "$PPM_ASAN_BUILD_DIR" "${asan_ctest[@]}" -- PPM_TEST_QUICK=1 \
    ASAN_OPTIONS=detect_leaks=1:halt_on_error=1:abort_on_error=0:detect_stack_use_after_return=1:strict_string_checks=1:check_initialization_order=1:strict_init_order=1 \
    UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1:report_error_type=1 \
    LSAN_OPTIONS=suppressions=$PPM_ROOT/tests/lsan.supp:print_suppressions=0
else
  fail "ASan + UBSan build"
fi

# ---------------------------------------------------------------------------------------------
step "Install into a temporary prefix and use the installed package"
work=$(mktemp -d "${TMPDIR:-/tmp}/ppm-test.XXXXXX")
trap 'rm -rf "$work"' EXIT
prefix="$work/prefix"

check_install() {
  cmake --install "$PPM_BUILD_DIR" --prefix "$prefix" || return 1
  local file status=0
  for file in include/ppm/ppm.h include/ppm/config.h lib/libppm.so lib/libppm.so.0 \
    lib/cmake/ppm/ppmConfig.cmake lib/cmake/ppm/ppmConfigVersion.cmake \
    lib/cmake/ppm/ppmTargets.cmake lib/cmake/ppm/ppmTargets-release.cmake lib/pkgconfig/ppm.pc; do
    [[ -e "$prefix/$file" ]] || {
      echo "not installed: $file"
      status=1
    }
  done
  return $status
}
if check_install; then
  pass "install: headers, libppm.so*, CMake package and ppm.pc are in place"
else
  fail "install"
  finish
fi

# Relocatable: a copy of the prefix elsewhere runs its tools with no loader path set, each
# loading the copy's libppm (RUNPATH $ORIGIN/../lib).
moved="$work/moved-prefix"
cp -a "$prefix" "$moved"
for tool in ppm-render ppm-merge ppm-tess ppm-bench; do
  binary="$moved/bin/$tool"
  loaded=$(env -u LD_LIBRARY_PATH ldd "$binary" 2>/dev/null | awk '$1 == "libppm.so.0" { print $3 }')
  if [[ "$(readlink -f "$loaded")" == "$(readlink -f "$moved/lib/libppm.so.0")" ]] &&
    env -u LD_LIBRARY_PATH "$binary" --version >/dev/null 2>&1; then
    pass "relocated install: $tool runs and loads the copied prefix's libppm"
  else
    fail "relocated install: $tool loads libppm.so.0 from '$loaded' or does not run"
  fi
done

# The installed tools at work from the copied prefix, on the data it ships (share/ppm/), with
# no loader path and nothing from the repository.
data="$moved/share/ppm"
installed_run() { env -u LD_LIBRARY_PATH "$@" >>"$work/installed-tools.log" 2>&1; }
if [[ -f "$data/teapot.bpt" && -f "$data/scenes/teapot-cornell.json" ]] && (
  cd "$work" &&
    installed_run "$moved/bin/ppm-render" "$data/scenes/teapot-cornell.json" --size 32x24 --passes 2 \
      --photons 2000 -o installed.exr -q &&
    installed_run "$moved/bin/ppm-render" "$data/scenes/teapot-cornell.json" --size 32x24 --passes 2 \
      --photons 2000 --pass-range 0:2 --partial installed.ppmpart -q &&
    installed_run "$moved/bin/ppm-merge" installed.ppmpart -o merged.exr -q &&
    installed_run "$moved/bin/ppm-tess" "$data/teapot.bpt" -o teapot.obj &&
    installed_run "$moved/bin/ppm-bench" targets --rays 200 --width 16 --height 16 --rounds 1 --min-time 0 --grid 4 &&
    [[ -s installed.exr && -s merged.exr && -s teapot.obj ]]
); then
  pass "installed tools: ppm-render, ppm-merge, ppm-tess and ppm-bench run on share/ppm/ from the copied prefix"
else
  cat "$work/installed-tools.log"
  fail "installed tools on share/ppm/ (log above)"
fi

library="$prefix/lib/libppm.so"
soname=$(readelf -d "$library" | sed -n 's/.*Library soname: \[\(.*\)\].*/\1/p')
if [[ "$soname" == libppm.so.0 ]]; then
  pass "SONAME is $soname"
else
  fail "SONAME is '$soname', expected libppm.so.0"
fi

# Exported symbols: exactly the functions ppm.h declares with PPM_API. The version script's
# node (PPM_0, an absolute symbol) is not a function and is left out.
exported=$(nm -D --defined-only "$library" | awk '$2 != "A" { sub(/@.*/, "", $3); print $3 }' |
  sort -u)
# Each declaration contributes its first "name(": the function, not a parameter type.
declared=$(tr '\n' ' ' <"$prefix/include/ppm/ppm.h" | grep -oE 'PPM_API[^;]*' |
  sed -E 's/^[^(]*[^A-Za-z0-9_](ppm_[A-Za-z0-9_]+) *\(.*/\1/' | sort -u)
not_prefixed=$(grep -v '^ppm_' <<<"$exported")
not_exported=$(comm -23 <(echo "$declared") <(echo "$exported"))
not_declared=$(comm -13 <(echo "$declared") <(echo "$exported"))
if [[ -z "$not_prefixed$not_exported$not_declared" && -n "$exported" ]]; then
  pass "exports exactly the $(wc -l <<<"$exported") ppm_* functions of ppm.h"
else
  [[ -z "$not_prefixed" ]] || echo "exported without the ppm_ prefix:" $not_prefixed
  [[ -z "$not_exported" ]] || echo "declared in ppm.h but not exported:" $not_exported
  [[ -z "$not_declared" ]] || echo "exported but not declared in ppm.h:" $not_declared
  fail "exported symbols"
fi

# run_consumer LABEL BINARY: runs the example on the teapot and checks that it loaded the
# installed libppm, not the one in the build tree.
run_consumer() {
  local label=$1 binary=$2
  local loaded
  loaded=$(ldd "$binary" | awk '$1 == "libppm.so.0" { print $3 }')
  if [[ "$(readlink -f "$loaded")" != "$(readlink -f "$prefix/lib/libppm.so.0")" ]]; then
    fail "$label: loads libppm.so.0 from '$loaded', not from the install prefix"
    return
  fi
  if "$binary" tests/data/teapot.bpt >"$work/$label.out" 2>&1 &&
    grep -q '^first hit' "$work/$label.out"; then
    pass "$label: examples/teapot_rays built against the installed library and ran"
  else
    cat "$work/$label.out"
    fail "$label: examples/teapot_rays failed"
  fi
}

# find_package(ppm) through CMAKE_PREFIX_PATH; warnings are errors so that ppm.h stays clean.
consumer="$work/consumer-cmake"
if cmake -S examples -B "$consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_C_FLAGS=-Werror >"$work/consumer-cmake.log" 2>&1 &&
  cmake --build "$consumer" >>"$work/consumer-cmake.log" 2>&1; then
  found=$(sed -n 's/^ppm_DIR:PATH=//p' "$consumer/CMakeCache.txt")
  if [[ "$(readlink -f "$found")" == "$(readlink -f "$prefix/lib/cmake/ppm")" ]]; then
    run_consumer find_package "$consumer/teapot_rays"
  else
    fail "find_package: found ppm in '$found', not in the install prefix"
  fi
else
  cat "$work/consumer-cmake.log"
  fail "find_package: configuring or building examples/ against the install failed"
fi

# pkg-config, compiled by hand as a Makefile user would.
export PKG_CONFIG_PATH="$prefix/lib/pkgconfig"
if version=$(pkg-config --modversion ppm) && cflags=$(pkg-config --cflags ppm) &&
  libs=$(pkg-config --libs ppm) && libdir=$(pkg-config --variable=libdir ppm); then
  # shellcheck disable=SC2086 # the flags are lists of words
  if cc -std=c99 -Wall -Wextra -pedantic -Werror $cflags examples/teapot_rays.c \
    -o "$work/teapot_rays-pkgconfig" $libs -lm -Wl,-rpath,"$libdir"; then
    run_consumer pkg-config "$work/teapot_rays-pkgconfig"
  else
    fail "pkg-config: compiling examples/teapot_rays.c with ppm.pc ($version) failed"
  fi
  # The header is C99 for C and must also compile cleanly as C++.
  # shellcheck disable=SC2086
  if printf '#include <ppm/ppm.h>\nint main() { return ppm_version() == PPM_VERSION ? 0 : 1; }\n' |
    c++ -std=c++17 -Wall -Wextra -pedantic -Werror $cflags -x c++ - -o "$work/header-cxx" $libs \
      -Wl,-rpath,"$libdir" && "$work/header-cxx"; then
    pass "ppm.h compiles as C++17 and PPM_VERSION matches ppm_version()"
  else
    fail "ppm.h as C++17, or PPM_VERSION differs from ppm_version()"
  fi
else
  fail "pkg-config does not find ppm.pc in the install prefix"
fi

# ---------------------------------------------------------------------------------------------
# The package is installed into a fresh venv in one of two ways, then checked and tested:
# - default: the extension alone (cmake -S bindings/python) against the library installed in
#   the step above, with the package's own install rules, so the library is not compiled again;
# - --full (CI): the wheel, as a user's `pip wheel .` builds it (build requirements from PyPI
#   in an isolated environment, the C library compiled with it, no -march=native).
# Either way the render-farm engines (the [dask] and [ray] extras) and mypy come from PyPI; a
# test whose engine or checker cannot be installed is skipped and says why.
if ((full)); then
  step "Python: pip wheel . (libppm with its extension), installed into a fresh venv, pytest"
else
  step "Python: the extension against the installed libppm, in a fresh venv, pytest"
fi
# Debian's interpreter, not whichever python3 comes first in PATH (e.g. pyenv's): the venv sees
# Debian's numpy, pytest and matplotlib through --system-site-packages.
python=${PPM_PYTHON:-/usr/bin/python3}
venv="$work/venv"

# install_wheel: builds the wheel with pip and installs it into the venv.
install_wheel() {
  CMAKE_BUILD_PARALLEL_LEVEL="$PPM_JOBS" "$venv/bin/pip" wheel --no-deps -w "$work/wheel" . &&
    "$venv/bin/pip" install "$work"/wheel/libppm-*.whl || return 1
  local wheel
  wheel=$(ls "$work"/wheel/libppm-*.whl)
  echo "wheel: $(basename "$wheel"), $(($(stat -c %s "$wheel") / 1024)) KiB" >&2
}

# install_against_prefix: builds the extension against the library in $prefix and installs the
# package (its Python files, and the extension, stubs and libppm.so.0 by the "python" install
# component that the wheel uses too) into the venv's site-packages.
install_against_prefix() {
  local build="$work/python-build" site nanobind
  "$venv/bin/pip" install "nanobind>=2.0" || return 1
  nanobind=$("$venv/bin/python" -m nanobind --cmake_dir) &&
    site=$("$venv/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])') &&
    cmake -S bindings/python -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$prefix;$nanobind" -DPython_EXECUTABLE="$venv/bin/python" &&
    cmake --build "$build" --parallel "$PPM_JOBS" &&
    cmake --install "$build" --component python --prefix "$site" &&
    cp -r bindings/python/libppm/. "$site/libppm/"
}

if ((full)); then install_package=install_wheel; else install_package=install_against_prefix; fi
if "$python" -m venv --system-site-packages "$venv" && $install_package >"$work/pip.log" 2>&1 &&
  { "$venv/bin/pip" install -q "dask[distributed]" tqdm ray mypy ||
    echo "warning: the render-farm engines (dask, ray) or mypy could not be installed"; }; then
  grep '^wheel: ' "$work/pip.log" || true
  site=$("$venv/bin/python" -c 'import libppm, os; print(os.path.dirname(libppm.__file__))')
  module=$(ls "$site"/_core*.so)
  if [[ -f "$site/libppm.so.0" ]] && readelf -d "$module" | grep -q 'R.*PATH.*\[\$ORIGIN\]' &&
    ! readelf -d "$module" | grep -q "$PPM_ROOT"; then
    pass "python package: libppm.so.0 beside the extension, found through \$ORIGIN"
  else
    fail "python package: libppm.so.0 missing beside the extension, or an rpath other than \$ORIGIN"
  fi
  # From the repository root (the tests read its data), with no loader path.
  env -u LD_LIBRARY_PATH "$venv/bin/python" -m pytest -p no:cacheprovider -q -rs bindings/python/tests 2>&1 |
    tee "$work/pytest.log"
  # "3 failed, 48 passed, 5 skipped in 4.12s"
  line=$(grep -E '^[0-9]+ [a-z]+.* in [0-9.]+s' "$work/pytest.log" | tail -n 1)
  count() { grep -oE "[0-9]+ $1" <<<"$line" | grep -oE '^[0-9]+' || echo 0; }
  if [[ -z "$line" ]]; then
    fail "python: pytest did not finish"
  else
    py_failed=$(($(count failed) + $(count 'errors?')))
    passed=$((passed + $(count passed)))
    failed=$((failed + py_failed))
    ((py_failed == 0)) || failures+=("python: $py_failed pytest tests failed")
  fi
else
  tail -n 40 "$work/pip.log" 2>/dev/null
  fail "python: venv, building the package ($install_package) or installing it"
fi

# ---------------------------------------------------------------------------------------------
if ((run_tsan)); then
  step "ThreadSanitizer (scripts/tsan.sh)"
  if bash scripts/tsan.sh; then
    pass "ThreadSanitizer: the threads tests ran without a report"
  else
    fail "ThreadSanitizer: scripts/tsan.sh (a build step, a test, or a TSan report)"
  fi
fi

finish
