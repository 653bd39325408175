# Smoke test of tdo-bench-scale (CTest bench_scale_smoke): a short run on Map1 and the first 20
# MovingAI Simple queries must exit 0, print a row for every workload and planner with the success
# counts known by construction (Map1 is solvable at 0.5 m, every MovingAI query is solvable at
# clearance 0, and RRTConnect + simplify solves these short queries with seed 1), the goals block,
# and no planner may miss a query A* solved. Not timed.
#   cmake -DBENCH=<tdo-bench-scale> -P scale_smoke.cmake
execute_process(COMMAND ${BENCH} --workload map1 --workload simple --limit 20 --warmup 1
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "tdo-bench-scale exited with ${rc}\n${out}\n${err}")
endif()
set(rows
  "| map1 | tdo | 1/1 |"
  "| map1 | astar | 1/1 |"
  "| map1 | rrtconnect-simplify | 1/1 |"
  "| map1 | textbook-astar | 1/1 |"
  "| simple | tdo | 20/20 |"
  "| simple | astar | 20/20 |"
  "| simple | rrtconnect-simplify | 20/20 |"
  "| simple | textbook-astar | 20/20 |"
  "| map1 | 1 | 1 | "
  "| simple | 20 | 20 | "
  "\ngoals\n"
  "\ngoal simple: tdo median "
  "\ngoal simple: tdo mean "
  "\ngoal simple: tdo arena "
  "\ngoal map1: tdo turns "
  "\ncheck map1 tdo: solved every query astar solved (1)\n"
  "\ncheck map1 rrtconnect-simplify: solved every query astar solved (1)\n"
  "\ncheck map1 astar: cost equals textbook-astar's on 1 of 1 queries both solved\n"
  "\ncheck simple tdo: solved every query astar solved (20)\n"
  "\ncheck simple rrtconnect-simplify: solved every query astar solved (20)\n"
  "\ncheck simple astar: cost equals textbook-astar's on 20 of 20 queries both solved\n")
foreach(row IN LISTS rows)
  string(FIND "${out}" "${row}" pos)
  if(pos EQUAL -1)
    message(FATAL_ERROR "missing in the output: '${row}'\n${out}")
  endif()
endforeach()
# Every planner row of both workloads: 13 columns, numbers where a planner ran.
string(REGEX MATCHALL "\n\\| (map1|simple) \\| [a-z-]+ \\| [0-9]+/[0-9]+ \\| [0-9.]+ \\| [0-9.]+ \\| [0-9.]+ \\| [0-9.]+ \\| [0-9.]+ \\| [0-9-]+ \\| [0-9.-]+ \\| [0-9.-]+ \\| [0-9-]+ \\| [0-9.-]+ \\|" full "${out}")
list(LENGTH full n)
if(NOT n EQUAL 8)
  message(FATAL_ERROR "expected 8 complete planner rows, found ${n}\n${out}")
endif()
if(out MATCHES "MISSED")
  message(FATAL_ERROR "a planner missed a query A* solved\n${out}")
endif()
# --depth search: tdo's search alone, its grid path checked as A*'s (every Simple query solved);
# an unknown depth is refused with exit status 2.
execute_process(COMMAND ${BENCH} --workload simple --limit 20 --warmup 1 --no-rrt-movingai
                        --depth search
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "tdo-bench-scale --depth search exited with ${rc}\n${out}\n${err}")
endif()
foreach(row IN ITEMS "| simple | tdo | 20/20 |" "| simple | astar | 20/20 |" "depth search"
                     "check simple tdo: solved every query astar solved (20)")
  string(FIND "${out}${err}" "${row}" pos)
  if(pos EQUAL -1)
    message(FATAL_ERROR "--depth search: missing in the output: '${row}'\n${out}\n${err}")
  endif()
endforeach()
execute_process(COMMAND ${BENCH} --workload simple --limit 1 --depth smooth
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 2)
  message(FATAL_ERROR "--depth smooth: expected exit 2, got ${rc}\n${out}\n${err}")
endif()
