#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Fails when a C or C++ file of the repository differs from what .clang-format makes of it,
# and names the files. Run by ctest (test "format"); `clang-format -i FILE` fixes a file.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
command -v clang-format >/dev/null || { echo "clang-format not found: bash scripts/setup.sh installs it" >&2; exit 1; }
mapfile -t files < <(git ls-files '*.c' '*.cpp' '*.h' | grep -v -e '/corpus/' -e '/crashes/')
((${#files[@]} > 0)) || { echo "no C or C++ file found: not a git checkout?" >&2; exit 1; }
# In batches on every core; each batch names its files that clang-format would change.
mapfile -t unformatted < <(printf '%s\0' "${files[@]}" | xargs -0 -n 16 -P "$(nproc)" bash -c '
  for file; do clang-format --dry-run --Werror "$file" >/dev/null 2>&1 || echo "$file"; done' batch | sort)
if ((${#unformatted[@]} > 0)); then
  printf 'not formatted by .clang-format (clang-format -i FILE):\n' >&2
  printf '  %s\n' "${unformatted[@]}" >&2
  exit 1
fi
echo "all ${#files[@]} C and C++ files are formatted"
