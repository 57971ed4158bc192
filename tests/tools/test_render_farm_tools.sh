#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# ppm-render --pass-range/--partial and ppm-merge end to end: a render split into ranges
# (different thread counts, merged in any order) gives the image of one process rendering all
# passes, bit for bit; a partial resumes; foreign, overlapping, corrupt and incomplete sets and
# bad options get the documented messages and exit statuses.
#
#   bash test_render_farm_tools.sh PPM_RENDER PPM_MERGE TEST_DATA_DIR
set -uo pipefail
render=$1
merge=$2
data=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/ppm-farm-test.XXXXXX")
trap 'rm -rf "$work"' EXIT
cd "$work"
scene="$data/scenes/small_box.json"
failures=0
common=(--passes 6 --photons 3000 -q)

fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

# expect STATUS FRAGMENT TOOL ARGS...: runs TOOL, checks its exit status and stderr.
expect() {
  local status=$1 fragment=$2 tool=$3
  shift 3
  "$tool" "$@" >out.txt 2>err.txt
  local got=$?
  if [[ $got -ne $status ]]; then
    fail "$(basename "$tool") $* exited $got, expected $status; stderr: $(cat err.txt)"
  elif [[ -n "$fragment" ]] && ! grep -qF -- "$fragment" err.txt out.txt; then
    fail "$(basename "$tool") $*: output lacks '$fragment': $(cat err.txt out.txt)"
  else
    echo "ok: $(basename "$tool") $* -> $got"
  fi
}

same_image() {
  if idiff -fail 0 -warn 0 "$1" "$2" >idiff.txt 2>&1; then
    echo "ok: $1 and $2 are identical"
  else
    fail "$1 and $2 differ: $(tail -n 3 idiff.txt)"
  fi
}

# One process, all passes, in the pass-independent mode.
expect 0 "" "$render" "$scene" "${common[@]}" --set mode=pppm -o whole.exr
# Three ranges, on different thread counts, merged in two orders.
expect 0 "" "$render" "$scene" "${common[@]}" --pass-range 0:2 --partial a.ppmpart --threads 1
expect 0 "" "$render" "$scene" "${common[@]}" --pass-range 2:5 --partial b.ppmpart --threads 2
expect 0 "" "$render" "$scene" "${common[@]}" --pass-range 5:6 --partial c.ppmpart
[[ ! -e small_box.png ]] || fail "a partial render wrote an image without -o"
expect 0 "passes 0-5 (6 in all)" "$merge" c.ppmpart a.ppmpart b.ppmpart -o merged.exr -o merged.png \
  --save-partial all.ppmpart
same_image merged.exr whole.exr
expect 0 "" "$merge" b.ppmpart c.ppmpart a.ppmpart -o reordered.exr -q
same_image reordered.exr whole.exr
expect 0 "" "$merge" all.ppmpart -o again.exr -q
same_image again.exr whole.exr
# The whole render as one partial is the merged partial, byte for byte.
expect 0 "" "$render" "$scene" "${common[@]}" --partial whole.ppmpart
cmp -s whole.ppmpart all.ppmpart || fail "the partial of one process differs from the merged partials"

# The bidirectional modes split and merge the same way.
expect 0 "" "$render" "$scene" "${common[@]}" --set mode=vcm -o vcm-whole.exr
expect 0 "" "$render" "$scene" "${common[@]}" --set mode=vcm --pass-range 0:4 --partial vcm-a.ppmpart --threads 1
expect 0 "" "$render" "$scene" "${common[@]}" --set mode=vcm --pass-range 4:6 --partial vcm-b.ppmpart
expect 0 "passes 0-5 (6 in all)" "$merge" vcm-b.ppmpart vcm-a.ppmpart -o vcm-merged.exr
same_image vcm-merged.exr vcm-whole.exr
expect 2 "its mode is pppm, the other's is vcm" "$merge" vcm-a.ppmpart c.ppmpart -o x.exr

# A range resumed from its partial renders only the missing passes.
expect 0 "" "$render" "$scene" "${common[@]}" --pass-range 0:2 --partial early.ppmpart
cp early.ppmpart resumed.ppmpart
expect 0 "4 to render" "$render" "$scene" --passes 6 --photons 3000 --pass-range 0:6 \
  --partial resumed.ppmpart --resume resumed.ppmpart
expect 0 "" "$merge" resumed.ppmpart -o resumed.exr -q
same_image resumed.exr whole.exr

# Incomplete, overlapping, foreign, corrupt.
expect 0 "passes 2-4 of the render's 6 are missing" "$merge" a.ppmpart c.ppmpart -o gap.exr
[[ -s gap.exr ]] || fail "the incomplete merge wrote no image"
expect 2 "passes 2-4 of the render's 6 are missing" "$merge" a.ppmpart c.ppmpart -o strict.exr \
  --require-complete
[[ ! -e strict.exr ]] || fail "--require-complete wrote an image"
expect 2 "both hold pass" "$merge" a.ppmpart all.ppmpart -o x.exr
expect 0 "" "$render" "$scene" "${common[@]}" --pass-range 2:5 --partial seeded.ppmpart --seed 99
expect 2 "seed is 99" "$merge" a.ppmpart seeded.ppmpart -o x.exr
cp a.ppmpart cut.ppmpart
truncate -s 300 cut.ppmpart
expect 2 "cut.ppmpart" "$merge" cut.ppmpart -o x.exr
expect 2 "not a libppm partial render" "$merge" "$scene" -o x.exr
expect 2 "missing.ppmpart" "$merge" missing.ppmpart -o x.exr
[[ ! -e x.exr ]] || fail "a refused merge wrote an image"

# Usage errors: exit 1.
expect 1 "needs --partial" "$render" "$scene" --pass-range 0:2
expect 1 "goes beyond --passes 6" "$render" "$scene" --passes 6 --pass-range 4:8 --partial p.ppmpart
expect 1 "is empty" "$render" "$scene" --passes 6 --pass-range 3:3 --partial p.ppmpart
expect 1 "not --set mode=sppm" "$render" "$scene" --passes 6 --partial p.ppmpart --set mode=sppm
expect 1 "no partial render given" "$merge" -o x.exr
expect 1 "no output given" "$merge" a.ppmpart
expect 1 "--frobnicate" "$merge" a.ppmpart -o x.exr --frobnicate
expect 1 "--layers" "$merge" a.ppmpart -o x.exr --layers radius,colour
expect 2 "cannot write this format" "$merge" a.ppmpart -o x.unknownformat

if ((failures > 0)); then
  echo "$failures failures"
  exit 1
fi
echo "all render farm tool checks passed"
