#!/usr/bin/env bash
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
expect 0 "usage: ppm-render" -- -h
expect 0 "libppm" -- --version
expect 1 "no scene file given" --
expect 1 "unknown option '--frobnicate'" -- "$scene" --frobnicate
expect 1 "--passes needs a whole number" -- "$scene" --passes -3
expect 1 "--passes needs a whole number" -- "$scene" --passes many
expect 1 "--set needs KEY=VALUE" -- "$scene" --set alpha
expect 1 "unknown layer 'depth'" -- "$scene" --layers depth
expect 2 "--set warp=9: unknown" -- "$scene" --set warp=9 -q
expect 2 "--set alpha=7: alpha must be in (0, 1]" -- "$scene" --set alpha=7 -q

# --- bad scene files: a located message and exit status 2 ----------------------------------
expect 2 "missing.json" -- "$work/missing.json"
printf '{\n  "shapes": [\n    {"type": "sphere", "radius": -1}\n  ]\n}\n' >negative.json
expect 2 "negative.json:3:34: shapes[0].radius: expected a number > 0" -- negative.json
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
