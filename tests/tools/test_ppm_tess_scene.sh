#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# ppm-tess on a scene file: every Bezier shape, placed by its to_world, in one mesh; other
# shapes skipped; scene errors located.
#
#   bash test_ppm_tess_scene.sh PPM_TESS TEAPOT_BPT
set -uo pipefail
tess=$1
teapot=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/ppm-tess-scene.XXXXXX")
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

cat >scene.json <<JSON
{ "shapes": [
    { "type": "sphere", "radius": 2 },
    { "type": "bezier", "filename": "$teapot", "to_world": { "translate": [100, 0, 0] } }
] }
JSON
"$tess" "$teapot" -o direct.obj --grid 4 2>direct.txt || fail "ppm-tess on the .bpt failed: $(cat direct.txt)"
"$tess" scene.json -o scene.obj --grid 4 2>scene.txt || fail "ppm-tess on the scene failed: $(cat scene.txt)"
direct_faces=$(grep -c '^f ' direct.obj)
scene_faces=$(grep -c '^f ' scene.obj)
[[ $direct_faces -gt 0 && $direct_faces -eq $scene_faces ]] || fail "faces: $direct_faces from .bpt, $scene_faces from the scene"
# Every vertex moved by +100 in x: the scene's smallest x is the file's plus 100.
min_x() { awk '$1 == "v" { if (!seen || $2 < m) m = $2; seen = 1 } END { printf "%.6f", m }' "$1"; }
direct_x=$(min_x direct.obj)
scene_x=$(min_x scene.obj)
shifted=$(awk -v a="$direct_x" -v b="$scene_x" 'BEGIN { d = b - a - 100; print (d < 1e-9 && d > -1e-9) ? 1 : 0 }')
[[ $shifted == 1 ]] && echo "ok: to_world applied (min x $direct_x -> $scene_x)" || fail "min x $direct_x -> $scene_x, expected +100"

echo '{ "shapes": [ { "type": "sphere" } ] }' >nopatches.json
"$tess" nopatches.json -o x.obj 2>err.txt && fail "a scene without patches was accepted"
grep -q "has no Bezier patches" err.txt && echo "ok: no patches reported" || fail "message: $(cat err.txt)"
echo '{ "shapes": [ { "type": "bezier", "filename": "none.bpt" } ] }' >missing.json
"$tess" missing.json -o x.obj 2>err.txt && fail "a missing .bpt was accepted"
grep -q "missing.json:1:.*shapes\[0\].filename: file not found" err.txt && echo "ok: located error" || fail "message: $(cat err.txt)"

echo "failures: $failures"
((failures == 0))
