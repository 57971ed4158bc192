#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# ppm-render when writing fails: a full disk, I/O errors at each step of the atomic write
# (write, fsync, close, rename; through the fault shim), a file size limit (ulimit -f) and a
# read-only folder. Each time for EXR and PNG images and for the checkpoint: exit status 2, a
# message naming the file, the previous file byte for byte, and no temporary file. Also: a
# film too large for the address space (ulimit -v) fails with a message naming the film.
#
#   bash test_fault_ppm_render.sh PPM_RENDER FAULT_SHIM TEST_DATA_DIR [PRELOAD_FIRST]
#
# PRELOAD_FIRST is the sanitizer runtime of a sanitized ppm-render (absent otherwise): it must
# come first in LD_PRELOAD, and the shim after it, so the runtime's wrappers call the shim's.
set -uo pipefail
render=$1
shim=$2
data=$3
preload_first=${4:-}
work=$(mktemp -d "${TMPDIR:-/tmp}/ppm-fault-render.XXXXXX")
trap 'chmod -R u+w "$work"; rm -rf "$work"' EXIT
work=$(cd "$work" && pwd -P) # the shim matches paths with symbolic links resolved
cd "$work"
scene="$data/scenes/small_box.json"
preload="$shim"
[[ -n "$preload_first" ]] && preload="$preload_first:$shim"
failures=0

fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

# The previous outputs: each failing run below must leave these bytes.
"$render" "$scene" --passes 1 --photons 2000 -o old.exr -o old.png --checkpoint old.ppmckpt -q ||
  fail "the first render failed"
mkdir previous
cp old.exr old.png old.ppmckpt previous/

# check_failed LABEL TARGET FRAGMENT: the last run's exit status ($status) is 2, its stderr
# (err.txt) names TARGET and FRAGMENT, the outputs are unchanged and no temporary file is left.
check_failed() {
  local label=$1 target=$2 fragment=$3 f
  if [[ $status -ne 2 ]]; then
    fail "$label: exit status $status, expected 2; stderr: $(cat err.txt)"
  elif ! grep -qF -- "$target" err.txt || ! grep -qF -- "$fragment" err.txt; then
    fail "$label: the message does not name '$target' and '$fragment': $(cat err.txt)"
  else
    echo "ok: $label -> $(tail -n 1 err.txt)"
  fi
  for f in old.exr old.png old.ppmckpt; do
    cmp -s "$f" "previous/$f" || fail "$label: $f changed"
  done
  local left
  left=$(find . -maxdepth 1 -name '*tmp*')
  [[ -z "$left" ]] || fail "$label: temporary files left: $left"
}

# faulty LABEL MATCH TARGET FRAGMENT FAULT_VARS... -- RENDER_ARGS...: a render with the shim,
# only the files whose path contains MATCH affected (the other outputs are written normally).
faulty() {
  local label=$1 match=$2 target=$3 fragment=$4
  shift 4
  local vars=()
  while [[ $1 != -- ]]; do
    vars+=("$1")
    shift
  done
  shift
  env LD_PRELOAD="$preload" PPM_FAULT_PATH="$work/$match" "${vars[@]}" \
    "$render" "$scene" --passes 1 --photons 2000 --seed 5 -q "$@" 2>err.txt
  status=$?
  check_failed "$label" "$target" "$fragment"
}

# --- images: every step of the write fails (EXR); PNG goes through the same writer -----------
# The shim sees the temporary file beside the image: "old.exr.tmp-XXXXXX".
faulty "old.exr: disk full at once" old.exr old.exr "No space left on device" \
  PPM_FAULT_BYTES=0 -- -o old.exr
faulty "old.exr: disk full after 100 bytes" old.exr old.exr "No space left on device" \
  PPM_FAULT_BYTES=100 -- -o old.exr
faulty "old.exr: write I/O error" old.exr old.exr "Input/output error" \
  PPM_FAULT_OPS=write PPM_FAULT_NTH=1 PPM_FAULT_ERRNO=EIO -- -o old.exr
faulty "old.exr: fsync I/O error" old.exr old.exr "Input/output error" \
  PPM_FAULT_OPS=fsync PPM_FAULT_NTH=1 PPM_FAULT_ERRNO=EIO -- -o old.exr
faulty "old.exr: close I/O error" old.exr old.exr "Input/output error" \
  PPM_FAULT_OPS=close PPM_FAULT_NTH=1 PPM_FAULT_ERRNO=EIO -- -o old.exr
faulty "old.exr: rename fails" old.exr old.exr "Disk quota exceeded" \
  PPM_FAULT_OPS=rename PPM_FAULT_NTH=1 PPM_FAULT_ERRNO=EDQUOT -- -o old.exr
faulty "old.png: disk full after 100 bytes" old.png old.png "No space left on device" \
  PPM_FAULT_BYTES=100 -- -o old.png
faulty "old.png: close I/O error" old.png old.png "Input/output error" \
  PPM_FAULT_OPS=close PPM_FAULT_NTH=1 PPM_FAULT_ERRNO=EIO -- -o old.png

# --- the checkpoint, written at the end (the images before it succeed) -----------------------
for spec in "PPM_FAULT_BYTES=5000|No space left on device" \
  "PPM_FAULT_OPS=fsync PPM_FAULT_NTH=1 PPM_FAULT_ERRNO=EIO|Input/output error" \
  "PPM_FAULT_OPS=close PPM_FAULT_NTH=1 PPM_FAULT_ERRNO=EIO|Input/output error" \
  "PPM_FAULT_OPS=rename PPM_FAULT_NTH=1 PPM_FAULT_ERRNO=EIO|Input/output error"; do
  read -ra vars <<<"${spec%|*}"
  faulty "checkpoint: ${spec%|*}" old.ppmckpt old.ppmckpt "${spec#*|}" "${vars[@]}" -- \
    -o new.exr --checkpoint old.ppmckpt
  rm -f new.exr
done
# The previous checkpoint still resumes.
if "$render" "$scene" --passes 2 --photons 2000 -o resumed.exr --resume old.ppmckpt -q 2>err.txt; then
  echo "ok: the intact checkpoint resumes"
else
  fail "resuming the intact checkpoint failed: $(cat err.txt)"
fi
rm -f resumed.exr

# --- a file size limit: writes past 4 KB fail with EFBIG (SIGXFSZ ignored, as a shell can) ----
for target in old.exr; do
  (
    trap '' XFSZ
    ulimit -f 4
    exec "$render" "$scene" --passes 1 --photons 2000 --seed 5 -q -o "$target" 2>err.txt
  )
  status=$?
  check_failed "$target: ulimit -f 4" "$target" "File too large"
done
(
  # Room for the PNG (about 5 KB), not for the checkpoint (about 200 KB).
  trap '' XFSZ
  ulimit -f 16
  exec "$render" "$scene" --passes 1 --photons 2000 --seed 5 -q -o new.png --checkpoint old.ppmckpt 2>err.txt
)
status=$?
check_failed "checkpoint: ulimit -f 16" "old.ppmckpt" "File too large"
rm -f new.png

# --- a read-only folder (as root, the render runs as nobody: root may write anywhere) ---------
mkdir readonly writable
cp previous/old.exr previous/old.png previous/old.ppmckpt readonly/
as_user=()
if [[ $(id -u) -eq 0 ]]; then
  as_user=(setpriv --reuid=65534 --regid=65534 --clear-groups)
  chmod 755 "$work"
  chmod 644 readonly/*
fi
chmod 555 readonly
chmod 777 writable
for target in readonly/old.exr readonly/old.png; do
  "${as_user[@]}" "$render" "$scene" --passes 1 --photons 2000 --seed 5 -q -o "$target" 2>err.txt
  status=$?
  check_failed "$target: read-only folder" "$target" "Permission denied"
done
"${as_user[@]}" "$render" "$scene" --passes 1 --photons 2000 --seed 5 -q -o writable/new.exr \
  --checkpoint readonly/old.ppmckpt 2>err.txt
status=$?
check_failed "readonly/old.ppmckpt: read-only folder" "readonly/old.ppmckpt" "Permission denied"
for f in old.exr old.png old.ppmckpt; do
  cmp -s "readonly/$f" "previous/$f" || fail "read-only folder: readonly/$f changed"
done
[[ -z $(find readonly -name '*tmp*') ]] || fail "read-only folder: temporary files in it"
chmod 755 readonly

# --- out of memory: a 2^28-pixel film under a 3 GB address-space limit -----------------------
if [[ -n "$preload_first" ]]; then
  echo "skipped: ulimit -v (sanitizer runtimes reserve terabytes of address space)"
else
  sed 's/"width": 64, "height": 48/"width": 16384, "height": 16384/' "$scene" >huge_film.json
  (
    ulimit -v 3000000
    exec "$render" huge_film.json --passes 1 -o huge.exr -q 2>err.txt
  )
  status=$?
  expected="pass 1: out of memory for the film of 16384 x 16384 pixels: [0-9]* bytes"
  if [[ $status -eq 2 ]] && grep -q "$expected" err.txt; then
    echo "ok: ulimit -v -> $(cat err.txt)"
  else
    fail "ulimit -v: exit status $status, stderr: $(cat err.txt)"
  fi
  [[ -z $(find . -maxdepth 1 -name '*tmp*') ]] || fail "ulimit -v: temporary files left"
fi

echo "failures: $failures"
((failures == 0))
