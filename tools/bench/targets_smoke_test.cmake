# SPDX-License-Identifier: Apache-2.0
# ctest driver of ppm_bench_targets_smoke: runs `ppm-bench targets` on a tiny workload and
# checks that it exited 0 and printed its tables, verdict lines and CSV; then checks that a
# bad option value exits 1 with a message naming the option.
# Variables: BENCH (the executable), OUT (a scratch directory).
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
execute_process(
  COMMAND ${BENCH} targets --rays 200 --width 16 --height 16 --rounds 2 --min-time 0 --grid 8
          --csv ${OUT}/rounds.csv
  RESULT_VARIABLE status
  OUTPUT_VARIABLE output
  ERROR_VARIABLE errors)
message("${output}")
if(NOT status EQUAL 0)
  message(FATAL_ERROR "ppm-bench targets exited with '${status}':\n${errors}")
endif()
set(ratio "[0-9.]+ \\([0-9.]+-[0-9.]+ over [0-9]+ rounds\\)")
set(patterns
    "\nmachine: [0-9]+ hardware threads"
    "\n== random: 200 rays"
    "\n== camera: 256 rays"
    "\nexact-presplit-3 "
    "\nexact-presplit-12 "
    "\nembree-N8 "
    "\nrandom rays: exact-presplit-3 / embree-N8 = ${ratio}  target >= 0.5  (PASS|FAIL)\n"
    "\nrandom rays: exact-presplit-12 / embree-N8 = ${ratio}  target >= 0.5  (PASS|FAIL)\n"
    "\nmemory: embree-N8 / exact-presplit-3 = [0-9.]+ \\([^)]*\\)  target >= 1000  (PASS|FAIL)\n"
    "\ncamera rays: exact-presplit-3 / embree-N8 = ${ratio}  \\(no target\\)\n"
    "\nexact-presplit-12 meets [0-9] of [0-9] targets checked\n"
    "\ndone in ")
# The CGAL lines only where CGAL was built (the note on stderr says when it was not).
if(NOT errors MATCHES "this build has no CGAL")
  list(APPEND patterns
      "\ncgal-N8 "
      "\nrandom rays: exact-presplit-3 / cgal-N8 = ${ratio}  target >= 5  (PASS|FAIL)\n"
      "\nmemory: cgal-N8 / exact-presplit-12 = [0-9.]+ \\([^)]*\\)  target >= 1000  (PASS|FAIL)\n")
endif()
foreach(pattern ${patterns})
  if(NOT output MATCHES "${pattern}")
    message(FATAL_ERROR "ppm-bench targets output lacks '${pattern}'")
  endif()
endforeach()
file(STRINGS ${OUT}/rounds.csv rows)
list(LENGTH rows count)
# Header + 2 rounds x (3 or 4 methods) x 2 sets.
if(count LESS 13)
  message(FATAL_ERROR "${OUT}/rounds.csv has only ${count} lines")
endif()

execute_process(
  COMMAND ${BENCH} targets --rounds 0
  RESULT_VARIABLE status
  OUTPUT_VARIABLE output
  ERROR_VARIABLE errors)
if(NOT status EQUAL 1)
  message(FATAL_ERROR "ppm-bench targets --rounds 0 exited with '${status}', not 1")
endif()
if(NOT errors MATCHES "--rounds: Value 0 not in range 1 to 1000")
  message(FATAL_ERROR "ppm-bench targets --rounds 0 did not name the bad option:\n${errors}")
endif()
