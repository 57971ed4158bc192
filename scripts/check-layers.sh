#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Fails when a file under lib/ includes a header of a layer above its own (docs/architecture.md
# draws the layers). Run by ctest (test "layers").
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../lib"

# What each folder may include besides itself: the layers below it.
declare -A allowed=(
  [math]=""
  [core]="math"
  [geometry]="core math"
  [io]="geometry core math"
  [scene]="geometry core math"
  [photon]="core math"
  [render]="photon scene io geometry core math"
  [scenefile]="render photon scene io geometry core math"
  [api]="scenefile render photon scene io geometry core math"
)

status=0
for folder in */; do
  folder=${folder%/}
  if [[ -z "${allowed[$folder]+set}" ]]; then
    echo "lib/$folder/ has no place in the layers: add it to scripts/check-layers.sh and docs/architecture.md" >&2
    status=1
    continue
  fi
  while IFS=: read -r file line text; do
    target=$(sed -E 's/.*#include "([a-z_]+)\/.*/\1/' <<<"$text")
    [[ "$target" == "$folder" ]] && continue
    if [[ " ${allowed[$folder]} " != *" $target "* ]]; then
      echo "lib/$file:$line: $folder/ may not include $target/ (${text})" >&2
      status=1
    fi
  done < <(grep -rnE '^#include "[a-z_]+/' "$folder" --include='*.h' --include='*.cpp' || true)
done
((status == 0)) && echo "every include of lib/ points to its own layer or one below"
exit $status
