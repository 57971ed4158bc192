#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# ppm-render end to end: options, exit statuses, located scene errors, atomic outputs,
# interrupt-and-resume equal to an uninterrupted render, and the --time budget.
#
#   bash test_ppm_render_tool.sh PPM_RENDER TEST_DATA_DIR EXAMPLE_SCENES_DIR
set -uo pipefail
render=$1
data=$2
examples=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/ppm-render-test.XXXXXX")
trap 'rm -rf "$work"' EXIT
cd "$work"
scene="$data/scenes/small_box.json"
failures=0

fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

# expect STATUS FRAGMENT -- ARGS...: runs ppm-render, checks exit status and stderr.
expect() {
  local status=$1 fragment=$2
  shift 3
  "$render" "$@" >out.txt 2>err.txt
  local got=$?
  if [[ $got -ne $status ]]; then
    fail "ppm-render $* exited $got, expected $status; stderr: $(cat err.txt)"
  elif [[ -n "$fragment" ]] && ! grep -qF -- "$fragment" err.txt out.txt; then
    fail "ppm-render $*: output lacks '$fragment': $(cat err.txt out.txt)"
  else
    echo "ok: ppm-render $* -> $got"
  fi
}

# Images are compared pixel for pixel (idiff from openimageio-tools).
same_image() {
  if idiff -fail 0 -warn 0 "$1" "$2" >idiff.txt 2>&1; then
    echo "ok: $1 and $2 are identical"
  else
    fail "$1 and $2 differ: $(cat idiff.txt)"
  fi
}

# --- the command line: usage errors exit 1 ----------------------------------------------------------------------
expect 0 "Usage: ppm-render" -- -h
expect 0 "--size WxH" -- --help
expect 0 "$(sed -n 's/.*project(ppm VERSION \([0-9.]*\).*/\1/p' "$data/../../CMakeLists.txt")" -- --version
expect 1 "SCENE is required" --
expect 1 "--frobnicate" -- "$scene" --frobnicate
expect 1 "--passes: Value -3 not in range" -- "$scene" --passes -3
expect 1 "--passes: Value many" -- "$scene" --passes many
expect 1 "--set needs KEY=VALUE" -- "$scene" --set alpha
expect 1 "--layers: depth not in {radius,photons}" -- "$scene" --layers depth
expect 1 "--size needs WIDTHxHEIGHT" -- "$scene" --size 64
expect 1 "--size needs whole numbers" -- "$scene" --size 64x0
expect 1 "--crop 8,4,8,9 is empty" -- "$scene" --crop 8,4,8,9
expect 1 "--crop needs X0,Y0,X1,Y1" -- "$scene" --crop 1,2,3
expect 1 "-D needs NAME=VALUE" -- "$scene" -D spp
expect 2 "--set warp=9: unknown" -- "$scene" --set warp=9 -q
expect 2 "(did you mean 'photons_per_pass'?)" -- "$scene" --set photons_per_pas=9 -q
expect 2 "--set alpha=7: alpha must be in (0, 1]" -- "$scene" --set alpha=7 -q
expect 2 "apply to Mitsuba XML scene files only" -- "$scene" -D spp=4 -q
# Outputs are checked before anything is rendered: no pass runs for an unwritable image.
expect 2 "the folder $work/nowhere cannot be used" -- "$scene" -o "$work/nowhere/image.png"
mkdir readonly && chmod a-w readonly
if [[ -w readonly ]]; then
  echo "ok: (running as root: a read-only folder is writable, not tested)"
else
  expect 2 "cannot write into the folder readonly" -- "$scene" -o readonly/image.png
fi
if grep -q "passes" err.txt; then fail "a pass ran before the output was refused: $(cat err.txt)"; fi

# --- bad scene files: a located message and exit status 2 ----------------------------------
expect 2 "missing.json" -- "$work/missing.json"
printf '{\n  "shapes": [\n    {"type": "sphere", "radius": -1}\n  ]\n}\n' >negative.json
expect 2 "negative.json:3:34: shapes[0].radius: sphere shape: parameter 'radius' must be > 0, not -1" -- negative.json
printf '{"shapes": [{"type": "sphere"}], "sensor": {"film": {"width": 100000, "height": 100000}}}' >huge.json
expect 2 "exceeds the limit" -- huge.json
printf '{"shapes": [{"type": "sphere"}' >cut.json
expect 2 "cut.json:1:" -- cut.json
printf '{"shapes": [{"type": "obj", "filename": "nowhere.obj"}]}' >noobj.json
expect 2 "file not found" -- noobj.json

# --- what the banner says before rendering -------------------------------------------------
printf '{"shapes": [{"type": "sphere"}], "sensor": {"film": {"width": 8, "height": 6}}}' >dark.json
expect 0 "dark.json has no light source" -- dark.json --passes 1 --photons 100 -o dark.png
expect 0 "3 passes or 60.0 s, whichever ends first" -- "$scene" --passes 3 --time 60 --photons 100 -o both.png
if grep -q "no light source" < <("$render" "$scene" --passes 1 --photons 100 -o lit.png 2>&1); then
  fail "a scene with a light was warned about"
else
  echo "ok: no warning for a lit scene"
fi

# --- image size and crop window --------------------------------------------------------------
expect 0 "64 x 48, " -- "$scene" --size 64x48 --passes 1 --photons 100 -o sized.exr
expect 0 "32 x 24 (crop 16,12,48,36)" -- "$scene" --size 64x48 --crop 16,12,48,36 --passes 1 --photons 100 -o cropped.exr
if iinfo sized.exr | grep -q "64 x   48" && iinfo cropped.exr | grep -q "32 x   24"; then
  echo "ok: --size and --crop set the image size"
else
  fail "image sizes: $(iinfo sized.exr cropped.exr)"
fi
expect 2 "--crop 0,0,65,10 reaches beyond the image of 64 x 48 pixels" -- "$scene" --size 64x48 --crop 0,0,65,10

# --- Mitsuba XML: parameters (-D) and lenient reading ------------------------------------------
cat >ball.xml <<'XML'
<scene version="3.0.0">
  <default name="res" value="40"/>
  <sensor type="perspective">
    <transform name="to_world"><lookat origin="0, -5, 1" target="0, 0, 1" up="0, 0, 1"/></transform>
    <film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="30"/></film>
  </sensor>
  <shape type="sphere"><bsdf type="hair"/></shape>
  <emitter type="point"><point name="position" x="0" y="-2" z="3"/></emitter>
</scene>
XML
expect 2 "ball.xml:7:" -- ball.xml -q -o ball.png
expect 0 "warning" -- ball.xml --lenient --passes 1 --photons 100 -o ball.png
expect 0 "24 x 30, " -- ball.xml --lenient -D res=24 --passes 1 --photons 100 -o ball.png
expect 0 "parameter 'rez' (-D rez=24) is not used by the scene (did you mean 'res'?)" -- ball.xml --lenient -D rez=24 -q -o ball.png

# --- a render: every output format, layers, nothing temporary left ---------------------------
expect 0 "4 passes" -- "$scene" -o box.png -o box.exr -o box.jpg -o box.tif --layers radius,photons
for f in box.png box.exr box.jpg box.tif; do
  [[ -s $f ]] || fail "$f was not written"
done
if ls -a | grep -q '\.tmp-'; then fail "temporary files left: $(ls -a)"; fi
if iinfo -v box.exr | grep -q 'radius'; then echo "ok: EXR has the radius layer"; else fail "no radius layer in box.exr: $(iinfo -v box.exr)"; fi
expect 1 "no file extension" -- "$scene" -o noextension -q
expect 1 "cannot write" -- "$scene" -o image.xyz -q

# --- same seed, same image; interrupted and resumed = uninterrupted --------------------------
"$render" "$scene" --passes 6 -o whole.exr -q || fail "uninterrupted render failed"
"$render" "$scene" --passes 3 -o part.exr --checkpoint part.ppmckpt -q || fail "first half failed"
"$render" "$scene" --passes 6 -o part.exr --resume part.ppmckpt -q || fail "resume failed"
same_image whole.exr part.exr
expect 2 "--resume" -- "$scene" --resume part.ppmckpt --seed 3 -o x.exr
expect 2 "not a libppm checkpoint" -- "$scene" --resume "$scene" -o x.exr

# SIGINT during a long render: exit 0, an image and a checkpoint; resuming to the end gives the
# uninterrupted image.
# Under the sanitizers (PPM_TEST_QUICK=1) everything is slower: fewer photons, same steps.
photons=200000
[[ "${PPM_TEST_QUICK:-0}" == 1 ]] && photons=40000
long_args=("$scene" --photons "$photons" --passes 40 --write-interval 0)
"$render" "${long_args[@]}" -o long.exr -q || fail "long uninterrupted render failed"
"$render" "${long_args[@]}" -o stopped.exr 2>stopped.txt &
pid=$!
for _ in $(seq 100); do
  [[ -s stopped.exr ]] && break
  sleep 0.1
done
kill -INT "$pid"
wait "$pid"
status=$?
if [[ $status -eq 0 ]] && grep -q "interrupted" stopped.txt && [[ -s stopped.ppmckpt ]]; then
  echo "ok: SIGINT wrote the image and stopped.ppmckpt, exit 0 ($(grep -o 'ppm-render: [0-9]* passes' stopped.txt))"
  "$render" "${long_args[@]}" -o stopped.exr --resume stopped.ppmckpt -q || fail "resume after SIGINT failed"
  same_image long.exr stopped.exr
else
  fail "SIGINT: exit $status, stderr: $(cat stopped.txt)"
fi

# --time: the time budget, not the pass count, ends the render (no bound on wall-clock time is
# asserted: a loaded machine may take longer for everything).
"$render" "$scene" --photons "$photons" --passes 100000 --time 0.5 -o timed.png 2>timed.txt || fail "--time render failed"
timed_passes=$(sed -n 's/^ppm-render: \([0-9]*\) passes .*/\1/p' timed.txt | tail -n 1)
if [[ -n "$timed_passes" ]] && ((timed_passes >= 1 && timed_passes < 100000)) && [[ -s timed.png ]]; then
  echo "ok: --time 0.5 stopped after $timed_passes passes"
else
  fail "--time 0.5: $(cat timed.txt)"
fi

# --- every example scene renders (one cheap pass) ---------------------------------------------
for example in "$examples"/*.json; do
  expect 0 "1 passes" -- "$example" --passes 1 --photons 1000 -o "example.png"
done

echo "failures: $failures"
((failures == 0))
