#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Builds the libFuzzer targets of tests/fuzz/ with clang (ASan + UBSan) and fuzzes them.
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
cd "$PPM_ROOT"

TARGETS=(scene_json bpt obj checkpoint texture ply serialized)
FUZZ_DIR=${PPM_FUZZ_BUILD_DIR:-build-fuzz}

usage() {
  cat <<EOF
usage: bash scripts/fuzz.sh [-h] [--build-only|--no-build] [TARGET|all] [SECONDS] [-- LIBFUZZER_ARGS...]

Builds the fuzz targets of tests/fuzz/ with clang and -fsanitize=fuzzer,address,undefined in
$FUZZ_DIR/ (installs clang with apt-get when it is missing: root or sudo), then runs TARGET
(default: all, one after the other) for SECONDS each (default 60). Targets: ${TARGETS[*]}.

Each run starts from the committed seeds (tests/fuzz/TARGET/corpus) and the corpus grown by
earlier runs ($FUZZ_DIR/corpus/TARGET/, kept between runs, not committed), with the
target's dictionary and limits. Inputs that crash, leak, time out or run out of memory are
written to $FUZZ_DIR/findings/TARGET/; the log of each run is $FUZZ_DIR/logs/TARGET.log.
At the end a table gives per target: executions, exec/s, coverage (cov: edges, ft:
features), corpus size, findings.

To fuzz two targets at once (one per core), build first and start each with --no-build:
  bash scripts/fuzz.sh --build-only && (bash scripts/fuzz.sh --no-build obj 600 &) &&
  bash scripts/fuzz.sh --no-build bpt 600

To keep a finding as a reproducer, copy it into tests/fuzz/TARGET/crashes/ with a name that
says what it is (see tests/fuzz/README.md); ctest then replays it in every build.

Arguments after -- go to libFuzzer, e.g. -- -fork=1 -ignore_crashes=1 to keep fuzzing past
known failures.

Environment: PPM_FUZZ_BUILD_DIR (default build-fuzz), PPM_FUZZ_RSS_MB (default 2048),
PPM_JOBS (compile jobs).
EOF
}

build_only=0
no_build=0
positional=()
extra=()
while (($#)); do
  case $1 in
  -h | --help)
    usage
    exit 0
    ;;
  --build-only) build_only=1 ;;
  --no-build) no_build=1 ;;
  --)
    shift
    extra=("$@")
    break
    ;;
  -*)
    usage >&2
    exit 1
    ;;
  *) positional+=("$1") ;;
  esac
  shift
done
target=${positional[0]:-all}
seconds=${positional[1]:-60}
if ((${#positional[@]} > 2)) || ! [[ "$seconds" =~ ^[0-9]+$ ]]; then
  usage >&2
  exit 1
fi
if [[ "$target" == all ]]; then
  selected=("${TARGETS[@]}")
elif [[ " ${TARGETS[*]} " == *" $target "* ]]; then
  selected=("$target")
else
  echo "unknown target '$target'; targets: ${TARGETS[*]}" >&2
  exit 1
fi

# Per target: longest input in bytes (the seeds are well below it).
declare -A MAX_LEN=([scene_json]=8192 [bpt]=16384 [obj]=4096 [checkpoint]=4096 [texture]=4096 [ply]=4096 [serialized]=4096)
rss_mb=${PPM_FUZZ_RSS_MB:-2048}

# ---------------------------------------------------------------------------------------------
if ((!no_build)); then
  ppm_step "clang and libFuzzer"
  if ! command -v clang >/dev/null 2>&1 || ! command -v clang++ >/dev/null 2>&1 ||
    ! echo 'extern "C" int LLVMFuzzerTestOneInput(const char *, unsigned long) { return 0; }' |
    clang++ -fsanitize=fuzzer,address,undefined -x c++ - -o /dev/null 2>/dev/null; then
    sudo=()
    if ((EUID != 0)); then
      command -v sudo >/dev/null 2>&1 || ppm_die "installing clang needs root: run as root or install sudo"
      sudo=(sudo)
    fi
    apt=("${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=600 -o Dpkg::Use-Pty=0 -y -q)
    "${apt[@]}" update </dev/null
    # libclang-rt-dev: the sanitizer and libFuzzer runtimes of Debian's default clang.
    "${apt[@]}" install --no-install-recommends clang libclang-rt-dev </dev/null ||
      ppm_die "apt-get could not install clang and its libFuzzer runtime"
  fi
  clang --version | head -n 1

  # ---------------------------------------------------------------------------------------------
  ppm_step "Build the fuzz targets in $FUZZ_DIR/"
  # The whole library is instrumented for coverage (fuzzer-no-link); only the targets link
  # libFuzzer's main. Tools are not needed.
  if [[ -f "$FUZZ_DIR/CMakeCache.txt" ]] && ! grep -q '^CMAKE_CXX_COMPILER:.*clang++' "$FUZZ_DIR/CMakeCache.txt"; then
    ppm_die "$FUZZ_DIR/ was configured with another compiler; remove it and run again"
  fi
  CC=clang CXX=clang++ ppm_configure "$PPM_ROOT" "$FUZZ_DIR" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DPPM_SANITIZE=ON -DPPM_FUZZ_LIBFUZZER=ON -DPPM_BUILD_TOOLS=OFF \
    -DCMAKE_C_FLAGS=-fsanitize=fuzzer-no-link -DCMAKE_CXX_FLAGS=-fsanitize=fuzzer-no-link >/dev/null ||
    ppm_die "configuring $FUZZ_DIR/ failed"
  cmake --build "$FUZZ_DIR" --parallel "$PPM_JOBS" --target "${selected[@]/#/fuzz_}" ||
    ppm_die "building the fuzz targets failed"
fi
((build_only)) && exit 0

# ---------------------------------------------------------------------------------------------
# Third-party leaks the suite accepts (each with its reason) are in tests/lsan.supp.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:symbolize=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1:report_error_type=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PPM_ROOT/tests/lsan.supp:print_suppressions=0}

summary=()
total_findings=0
for name in "${selected[@]}"; do
  ppm_step "Fuzz $name for ${seconds}s"
  corpus="$FUZZ_DIR/corpus/$name"
  findings="$FUZZ_DIR/findings/$name"
  log="$FUZZ_DIR/logs/$name.log"
  mkdir -p "$corpus" "$findings" "$(dirname "$log")"
  before=$(find "$findings" -type f | wc -l)
  # The targets' temporary files, including those of processes that crashed.
  scratch="$FUZZ_DIR/tmp/$name"
  mkdir -p "$scratch"
  # New inputs go to the first folder (the grown corpus); the committed seeds are only read.
  TMPDIR="$(ppm_abspath "$scratch")" "$FUZZ_DIR/tests/fuzz/fuzz_$name" -max_total_time="$seconds" -max_len="${MAX_LEN[$name]}" \
    -rss_limit_mb="$rss_mb" -malloc_limit_mb="$rss_mb" -timeout=10 -print_final_stats=1 \
    -dict="tests/fuzz/$name.dict" -artifact_prefix="$findings/" "${extra[@]}" \
    "$corpus" "tests/fuzz/$name/corpus" >"$log" 2>&1
  status=$?
  rm -rf "$scratch"
  tail -n 12 "$log"
  after=$(find "$findings" -type f | wc -l)
  new=$((after - before))
  total_findings=$((total_findings + new))
  # "#123456<TAB>DONE   cov: 2345 ft: 6789 corp: 321/45Kb lim: ... exec/s: 12 rss: 345Mb", or
  # in -fork mode "#123456: cov: 2345 ft: 6789 corp: 321 exec/s 12 ..." and no stat:: lines.
  last=$(grep -E '^#[0-9]+[:[:space:]]' "$log" | tail -n 1)
  cov=$(sed -nE 's/.* cov: ([0-9]+).*/\1/p' <<<"$last")
  ft=$(sed -nE 's/.* ft: ([0-9]+).*/\1/p' <<<"$last")
  runs=$(sed -nE 's/^stat::number_of_executed_units: *([0-9]+).*/\1/p' "$log" | tail -n 1)
  speed=$(sed -nE 's/^stat::average_exec_per_sec: *([0-9]+).*/\1/p' "$log" | tail -n 1)
  [[ -n "$runs" ]] || runs=$(sed -nE 's/^#([0-9]+).*/\1/p' <<<"$last")
  [[ -n "$speed" || -z "$runs" ]] || speed=$((runs / (seconds > 0 ? seconds : 1)))
  files=$(find "$corpus" -type f | wc -l)
  summary+=("$(printf '%-11s %10s %7s %6s %7s %7s %8s  %s' "$name" "${runs:-?}" "${speed:-?}" \
    "${cov:-?}" "${ft:-?}" "$files" "$new" "exit $status")")
  if ((new > 0)); then
    echo "new findings in $findings/:"
    ls -t "$findings" | head -n "$new" | sed "s|^|  $findings/|"
  fi
done

ppm_step "Summary (${seconds}s per target)"
printf '%-11s %10s %7s %6s %7s %7s %8s\n' target executions exec/s cov ft corpus findings
printf '%s\n' "${summary[@]}"
echo "findings are in $FUZZ_DIR/findings/<target>/; replay one with" \
  "$FUZZ_DIR/tests/fuzz/fuzz_<target> FILE"
((total_findings == 0))
