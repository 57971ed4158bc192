#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Fails when a source file of libppm (C, C++, Python, shell, CMake) lacks its SPDX licence line
# near the top. Run by ctest (test "spdx").
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

status=0
count=0
while IFS= read -r -d '' file; do
  count=$((count + 1))
  if ! head -n 3 "$file" | grep -q 'SPDX-License-Identifier: Apache-2.0'; then
    echo "$file: no 'SPDX-License-Identifier: Apache-2.0' in its first three lines" >&2
    status=1
  fi
done < <(find CMakeLists.txt cmake include lib tools tests bindings examples scripts \
  \( -path tests/data -o -path tests/fuzz/corpus -o -name 'build*' -o -name __pycache__ \
  -o -path 'tests/fuzz/*/*' \) -prune -o -type f \
  \( -name '*.c' -o -name '*.h' -o -name '*.cpp' -o -name '*.py' -o -name '*.sh' \
  -o -name '*.cmake' -o -name CMakeLists.txt -o -name '*.in' \) -print0)
((status == 0)) && echo "all $count source files carry the SPDX licence line"
exit $status
