#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Compiles and runs every ```c block of a Markdown file against the built libppm, so that the
# README's C examples cannot drift from the API. Each block must be a whole program; it runs
# from the repository root (its example paths are relative to it) and must exit 0.
#
# usage: run_c_blocks.sh MARKDOWN INCLUDE_DIR... -- LIBRARY_DIR COMPILER
set -euo pipefail

markdown=$1
shift
include_flags=()
while [[ $1 != -- ]]; do
  include_flags+=("-I$1")
  shift
done
shift
library_dir=$1 compiler=$2
repository=$(cd "$(dirname "$markdown")" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/ppm-readme.XXXXXX")
trap 'rm -rf "$work"' EXIT

# Each block into block-N.c, with the line in the Markdown file where it starts.
awk -v dir="$work" '
  /^```c$/ { inside = 1; n += 1; file = sprintf("%s/block-%d.c", dir, n); print NR + 1 > (dir "/lines-" n); next }
  /^```/ && inside { inside = 0; close(file); next }
  inside { print > file }
' "$markdown"

blocks=$(find "$work" -name 'block-*.c' | sort -V)
[[ -n "$blocks" ]] || { echo "no \`\`\`c block in $markdown"; exit 1; }
status=0
for block in $blocks; do
  n=${block##*block-}
  n=${n%.c}
  where="$markdown:$(cat "$work/lines-$n")"
  if ! "$compiler" -std=c99 -Wall -Wextra -pedantic -Werror "${include_flags[@]}" "$block" \
    -o "$work/program-$n" -L"$library_dir" -Wl,-rpath,"$library_dir" -lppm -lm; then
    echo "FAIL: the C block at $where does not compile"
    status=1
    continue
  fi
  if (cd "$repository" && "$work/program-$n" >"$work/out-$n" 2>&1); then
    echo "ok: the C block at $where ran: $(head -n 1 "$work/out-$n")"
  else
    cat "$work/out-$n"
    echo "FAIL: the C block at $where exited non-zero"
    status=1
  fi
done
exit $status
