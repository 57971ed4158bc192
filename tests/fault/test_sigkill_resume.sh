#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# ppm-render killed with SIGKILL at reproducible random moments of a checkpointed render:
# after each kill the image and the checkpoint on disk load, and resuming from that checkpoint
# (or starting over when none was written yet) gives the image of an uninterrupted render, bit
# for bit, on another thread count.
#
#   bash test_sigkill_resume.sh PPM_RENDER FAULT_SHIM TEST_DATA_DIR [PRELOAD_FIRST]
#
# The moments: files can only be torn while they are written, so the kills land on the file
# system calls (through the fault shim in kill mode), chosen at random (seeded) among all the
# write, fsync, close and rename calls of the run, or in the middle of a write at a random
# byte of all the bytes written. A kill between two calls leaves the files as a kill at the
# next call does. 30 kills; 10 under PPM_TEST_QUICK=1 (sanitizer builds, 3x slower).
set -uo pipefail
render=$1
shim=$2
data=$3
preload_first=${4:-}
work=$(mktemp -d "${TMPDIR:-/tmp}/ppm-sigkill.XXXXXX")
trap 'rm -rf "$work"' EXIT
work=$(cd "$work" && pwd -P) # the shim matches paths with symbolic links resolved
cd "$work"
preload="$shim"
[[ -n "$preload_first" ]] && preload="$preload_first:$shim"
kills=30
[[ "${PPM_TEST_QUICK:-0}" == 1 ]] && kills=10
RANDOM=20261204 # the kill moments are the same on every run
failures=0

fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

# A tiny film, few photons per pass, many passes: each pass rewrites the image and the
# checkpoint (--write-interval 0, a checkpoint interval shorter than any pass).
sed 's/"width": 64, "height": 48/"width": 32, "height": 24/' "$data/scenes/small_box.json" >scene.json
args=("$work/scene.json" --passes 10 --photons 300 -q)
run_args=("${args[@]}" --threads 2 --write-interval 0 --checkpoint-interval 0.000001
  -o run.exr --checkpoint run.ppmckpt)

"$render" "${args[@]}" --threads 1 -o reference.exr || fail "the uninterrupted render failed"

# One run with the shim counting: how many calls and bytes there are to choose from.
mkdir count
(cd count && env LD_PRELOAD="$preload" PPM_FAULT_PATH="$work/count/" PPM_FAULT_OPS=write,fsync,close,rename \
  PPM_FAULT_LOG="$work/count.log" "$render" "${run_args[@]}") || fail "the counted run failed"
calls=$(wc -l <count.log)
bytes=$(awk '$2 == "write" { sum += $4 } END { print sum + 0 }' count.log)
echo "a checkpointed render makes $calls counted calls and writes $bytes bytes"
((calls > 0 && bytes > 0)) || fail "the counted run wrote nothing"

# The images are checked together at the end, by one iinfo: each one after a kill must load
# completely (a torn EXR fails when its pixels are read), each final one must have the
# pixels of the uninterrupted render.
mkdir images
for ((k = 1; k <= kills; ++k)); do
  trial="$work/trial$k"
  mkdir "$trial"
  cd "$trial"
  if ((k % 2 == 1)); then
    n=$((1 + RANDOM % calls))
    moment="call $n of $calls"
    fault="PPM_FAULT_NTH=$n"
  else
    n=$(((RANDOM << 15 | RANDOM) % bytes))
    moment="byte $n of $bytes"
    fault="PPM_FAULT_BYTES=$n"
  fi
  echo "kill $k at $moment" >"$work/images/moment-$k.txt"
  # (The outer redirection silences the shell's own "Killed" notice.)
  {
    env LD_PRELOAD="$preload" PPM_FAULT_PATH="$trial/" PPM_FAULT_OPS=write,fsync,close,rename PPM_FAULT_ACTION=kill \
      "$fault" "$render" "${run_args[@]}" 2>err.txt
    status=$?
  } 2>/dev/null
  if [[ $status -ne 137 ]]; then
    fail "kill $k at $moment: exit status $status, expected 137 (SIGKILL): $(cat err.txt)"
    cd "$work"
    continue
  fi
  [[ -e run.exr ]] && cp run.exr "$work/images/killed-$k.exr"
  if [[ -e run.ppmckpt ]]; then
    "$render" "${run_args[@]}" --resume run.ppmckpt 2>err.txt ||
      fail "kill $k at $moment: resuming from the checkpoint failed: $(cat err.txt)"
    echo "ok: kill $k at $moment: resumed from the checkpoint"
  else
    "$render" "${run_args[@]}" 2>err.txt || fail "kill $k at $moment: the new render failed: $(cat err.txt)"
    echo "ok: kill $k at $moment: no checkpoint yet, started over"
  fi
  cp run.exr "$work/images/final-$k.exr"
  cd "$work"
  rm -rf "$trial"
done

# "name.exr :  32 x 24, ..." then "    SHA-1: <hash or error>", for each file.
iinfo --hash reference.exr images/*.exr 2>&1 |
  awk '/^[^ ].* : / { name = $1 } /SHA-1:/ { sub(/.*SHA-1: /, ""); print name, $0 }' >hashes.txt
reference=$(awk '$1 == "reference.exr" { print $2 }' hashes.txt)
[[ $reference =~ ^[0-9A-F]{40}$ ]] || fail "the reference image does not load: $(cat hashes.txt)"
for ((k = 1; k <= kills; ++k)); do
  moment=$(cat "images/moment-$k.txt")
  if [[ -e images/killed-$k.exr ]]; then
    hash=$(awk -v f="images/killed-$k.exr" '$1 == f { print $2 }' hashes.txt)
    [[ $hash =~ ^[0-9A-F]{40}$ ]] ||
      fail "$moment: the image left on disk does not load: $(grep "killed-$k.exr" hashes.txt)"
  fi
  hash=$(awk -v f="images/final-$k.exr" '$1 == f { print $2 }' hashes.txt)
  [[ $hash == "$reference" ]] ||
    fail "$moment: the final image differs from the uninterrupted render ($hash, not $reference)"
done
echo "checked $kills kills: every image left on disk loads, every resumed render equals the uninterrupted one"

echo "failures: $failures"
((failures == 0))
