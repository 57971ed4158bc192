#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Fails when a file under lib/ includes a header of a room above its own, or when the headers
# of lib/ include each other in a cycle (docs/architecture.md draws the rooms). A room is a
# folder (integrator/vcm is a room of its own, above integrator). Run by ctest (test "layers").
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../lib"

# What each room may include besides itself: the rooms below it.
declare -A allowed=(
  [math]=""
  [core]="math"
  [geometry]="core math"
  [io]="geometry core math"
  [scene]="geometry core math"
  [photon]="core math"
  [material]="core math"
  [camera]="core math"
  [settings]="core math"
  [light]="material geometry core math"
  [shading]="light material scene photon geometry core math"
  [film]="settings photon io core math"
  [integrator]="film shading light material camera settings photon scene io geometry core math"
  [integrator/vcm]="integrator film shading light material camera settings photon scene io geometry core math"
  [renderer]="integrator/vcm integrator film shading light material camera settings photon scene io geometry core math"
  [scenefile]="renderer film material camera settings io geometry core math"
  [api]="scenefile renderer integrator/vcm integrator film shading light material camera settings photon scene io geometry core math"
)

status=0
while IFS= read -r room; do
  if [[ -z "${allowed[$room]+set}" ]]; then
    echo "lib/$room/ has no place in the rooms: add it to scripts/check-layers.sh and docs/architecture.md" >&2
    status=1
    continue
  fi
  while IFS=: read -r file line text; do
    header=$(sed -E 's/.*#include "([a-z_/]+\.h)".*/\1/' <<<"$text")
    target=$(dirname "$header")
    [[ "$target" == "$room" ]] && continue
    if [[ " ${allowed[$room]} " != *" $target "* ]]; then
      echo "lib/$room/$file:$line: $room/ may not include $target/ (${text})" >&2
      status=1
    fi
  done < <(cd "$room" && find . -maxdepth 1 -type f \( -name '*.h' -o -name '*.cpp' \) -printf '%P\0' |
    xargs -0 -r grep -HnE '^#include "[a-z_/]+\.h"' || true)
done < <(find . -mindepth 1 -type d -printf '%P\n' | sort)

# Include cycles among headers (inside a room too): tsort fails on a loop and names it.
edges=$(grep -rnoE '^#include "[a-z_/]+\.h"' --include='*.h' . |
  sed -E 's#^\./([^:]+):[0-9]+:\#include "([^"]+)"#\1 \2#')
if ! tsort <<<"$edges" >/dev/null 2>"${TMPDIR:-/tmp}/check-layers.$$"; then
  echo "headers of lib/ include each other in a cycle:" >&2
  grep -v '^tsort: -: input contains a loop:' "${TMPDIR:-/tmp}/check-layers.$$" | sed 's/^tsort: /  /' >&2
  status=1
fi
rm -f "${TMPDIR:-/tmp}/check-layers.$$"

((status == 0)) && echo "every include of lib/ points to its own room or one below, and no headers include each other in a cycle"
exit $status
