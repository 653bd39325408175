# Tests of tdo-avoid and tdo-sim (included from CMakeLists.txt): their nodes in-process over
# memq://, the whole chain planner + follower + simulator on Map6, and the programs themselves. The
# simulator (tdo::sim_node, tdo-sim) reads map files (mapio/, built with the apps).
add_executable(tdo_avoid_node_tests test_avoid_node.cpp)
target_link_libraries(tdo_avoid_node_tests PRIVATE tdo::avoid_node GTest::gtest_main)
tdo_set_warnings(tdo_avoid_node_tests)
gtest_discover_tests(tdo_avoid_node_tests TEST_PREFIX "apps." DISCOVERY_TIMEOUT 60
                     PROPERTIES LABELS "apps;lcm" TIMEOUT 120)
if(TARGET tdo::sim_node)
  add_executable(tdo_sim_node_tests test_sim_node.cpp)
  target_link_libraries(tdo_sim_node_tests PRIVATE tdo::sim_node GTest::gtest_main)
  target_compile_definitions(tdo_sim_node_tests PRIVATE TDO_MAPS_DIR="${PROJECT_SOURCE_DIR}/maps")
  tdo_set_warnings(tdo_sim_node_tests)
  gtest_discover_tests(tdo_sim_node_tests TEST_PREFIX "apps." DISCOVERY_TIMEOUT 60
                       PROPERTIES LABELS "apps;lcm" TIMEOUT 120)
endif()
if(TARGET tdo::sim_node)
  # The three nodes on one bus: the chain on Map6 (test_chain.cpp) and replanning, a wall
  # published across the route mid-flight and hidden columns (test_replan.cpp).
  foreach(_chain chain replan)
    add_executable(tdo_${_chain}_tests test_${_chain}.cpp)
    target_link_libraries(tdo_${_chain}_tests PRIVATE tdo::planner_node tdo::avoid_node
                                                      tdo::sim_node GTest::gtest_main)
    target_compile_definitions(tdo_${_chain}_tests PRIVATE TDO_MAPS_DIR="${PROJECT_SOURCE_DIR}/maps")
    tdo_set_warnings(tdo_${_chain}_tests)
    gtest_discover_tests(tdo_${_chain}_tests TEST_PREFIX "apps." DISCOVERY_TIMEOUT 60
                         PROPERTIES LABELS "apps;lcm" TIMEOUT 300)
  endforeach()
endif()

# The programs: --help, a bad option, a bounded memq:// run, a bad URL, SIGINT/SIGTERM.
tdo_app_run_test(tdo-avoid help 0 "--follower" --help)
tdo_app_run_test(tdo-avoid bad_option 2 "frobnicate" --frobnicate)
tdo_app_run_test(tdo-avoid bad_follower 2 "--follower" --follower potential)
tdo_app_run_test(tdo-avoid bad_rate 2 "rate" --lcm-url memq:// --rate 0)
tdo_app_run_test(tdo-avoid bad_url 2 "cannot start LCM" --lcm-url nonsense://x)
tdo_app_run_test(tdo-avoid bad_replan_lead 2 "replan lead" --lcm-url memq:// --replan-lead -1)
tdo_app_run_test(tdo-avoid memq_run 0 "stopped: 0 received, 0 setpoints"
                 --lcm-url memq:// --duration 0.3 --max-size 16 16 8 --follower apf)
tdo_app_signal_tests(tdo-avoid --lcm-url memq:// --max-size 16 16 8)
if(TARGET tdo-sim)
  tdo_app_run_test(tdo-sim help 0 "--lockstep" --help)
  tdo_app_run_test(tdo-sim bad_option 2 "frobnicate" --frobnicate)
  tdo_app_run_test(tdo-sim bad_url 2 "cannot start LCM" --lcm-url nonsense://x)
  tdo_app_run_test(tdo-sim missing_map 2 "map" --lcm-url memq:// --map ${CMAKE_CURRENT_BINARY_DIR}/none.tdomap)
  tdo_app_run_test(tdo-sim bad_map 2 "error" --lcm-url memq:// --map ${CMAKE_CURRENT_SOURCE_DIR}/run_expect.cmake)
  # No setpoints for 0.3 s: the vehicle stays at Map6's start, no collision, 12 movers.
  tdo_app_run_test(tdo-sim memq_run 0 "12 movers.*stopped: 0 received, [0-9]+ steps .[0-9]+ braking, 0 in collision.*at .2.000, 2.000, 3.000."
                   --lcm-url memq:// --duration 0.3 --map ${PROJECT_SOURCE_DIR}/maps/map6.tdomap)
  tdo_app_run_test(tdo-sim bad_unknown 2 "unknown fraction" --lcm-url memq:// --unknown 1.5
                   --map ${PROJECT_SOURCE_DIR}/maps/map6.tdomap)
  tdo_app_run_test(tdo-sim bad_sensor_range 2 "sensor range" --lcm-url memq:// --unknown 0.3
                   --sensor-range 0 --map ${PROJECT_SOURCE_DIR}/maps/map6.tdomap)
  tdo_app_run_test(tdo-sim unknown_without_map 2 "need a map file" --lcm-url memq:// --unknown 0.3)
  # 30 % of Map6's 500 columns hidden: 150, some seen from the start (in the first map).
  tdo_app_run_test(tdo-sim memq_unknown 0 "0 in collision.* [0-9]+ of 150 hidden boxes revealed"
                   --lcm-url memq:// --duration 0.3 --unknown 0.3 --sensor-range 5
                   --map ${PROJECT_SOURCE_DIR}/maps/map6.tdomap)
  tdo_app_signal_tests(tdo-sim --lcm-url memq:// --map ${PROJECT_SOURCE_DIR}/maps/map6.tdomap)
endif()
