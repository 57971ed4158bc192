# SPDX-License-Identifier: Apache-2.0
# ctest driver of ppm_bench_smoke: runs `ppm-bench intersect` on a tiny workload, then checks
# that it exited 0, printed its tables and wrote the CSV and markdown files.
# Variables: BENCH (the executable), OUT (a scratch directory).
file(REMOVE_RECURSE ${OUT})
execute_process(
  COMMAND ${BENCH} intersect --rays 200 --width 16 --height 16 --angles 1e-3,1e-6
          --tolerances 1e-6,1e-9 --presplits 1,4 --grids 4,8 --cgal-grids 4 --adaptive 1e-2 --cgal-adaptive none
          --min-time 0 --threads 2 --list 2 --out ${OUT} --csv ${OUT}/smoke.csv
  RESULT_VARIABLE status
  OUTPUT_VARIABLE output
  ERROR_VARIABLE errors)
message("${output}")
if(NOT status EQUAL 0)
  message(FATAL_ERROR "ppm-bench intersect exited with '${status}':\n${errors}")
endif()
foreach(pattern
    "reference: tools/reference/reference_intersector"
    "\n== random: 200 rays"
    "\n== grazing-1e-6: 50 rays"
    "\n== leaving: "
    "\nexact-1e-9 +[0-9.e+-]+ +[0-9.e+-]+ +0 +0 "
    "\nexact-presplit-1 +[0-9.e+-]+ +[0-9.e+-]+ +0 +0 "
    "\nnewton-r16 "
    "\nembree-N8 "
    "\nembree-adaptive-1e-2 "
    "Miss rate"
    "\ndone in ")
  if(NOT output MATCHES "${pattern}")
    message(FATAL_ERROR "ppm-bench intersect output lacks '${pattern}'")
  endif()
endforeach()
foreach(file smoke.csv stability.md summary.md)
  if(NOT EXISTS ${OUT}/${file})
    message(FATAL_ERROR "ppm-bench intersect did not write ${OUT}/${file}")
  endif()
endforeach()
file(STRINGS ${OUT}/smoke.csv rows)
list(LENGTH rows count)
if(count LESS 10)
  message(FATAL_ERROR "${OUT}/smoke.csv has only ${count} lines")
endif()
