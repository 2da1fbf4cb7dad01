# Test tiers, for scripts/run_tests.sh (catkin's run_tests target still runs every test):
#   unit  the libraries' gtests and static checks (launch files, the ROS-free boundary): nothing
#         is started, no ROS master
#   cli   the built command-line tools end to end (calibrate_bag, detect_people,
#         make_synthetic_bag): no ROS master
#   ros   the rostests and the installed package: a ROS master and running nodes
# `make run_<tier>_tests` in the build directory runs one tier; with make -jN its tests run N at a
# time (the unit and CLI tests share nothing but the machine). scripts/run_tests.sh runs the ROS
# tier one test at a time beside the other two: each rostest starts its own master (on a free
# port) and nodes that keep about one core busy.
#
# A test's tier follows from how it is registered: catkin's test type, and for the gtests that
# run the built tools, tlc_cli_gtest_tier() beside their registration. tlc_make_test_tiers() runs
# after every test is registered and stops the configure step on a test type it does not know,
# so that no test drops out of run_tests.sh unnoticed.

# The gtest NAME runs the built command-line tools (the CLI tier, not the unit tier).
function(tlc_cli_gtest_tier name)
  set_property(GLOBAL APPEND PROPERTY TLC_CLI_GTESTS ${name})
endfunction()

# Makes run_unit_tests, run_cli_tests and run_ros_tests from the catkin test targets
# (run_tests_<project>_<type>_<name>) registered in the directories given.
function(tlc_make_test_tiers)
  get_property(cli_gtests GLOBAL PROPERTY TLC_CLI_GTESTS)
  foreach(tier unit cli ros)
    add_custom_target(run_${tier}_tests)
  endforeach()
  foreach(dir ${ARGN})
    get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
    foreach(target ${targets})
      if(NOT target MATCHES "^run_tests_${PROJECT_NAME}_([^_]+)_(.+)$")
        continue()  # not one test (catkin's per-project and per-type targets)
      endif()
      set(type ${CMAKE_MATCH_1})
      set(name ${CMAKE_MATCH_2})
      if(type STREQUAL "gtest" AND name IN_LIST cli_gtests)
        set(tier cli)
      elseif(type MATCHES "^(gtest|boundary|roslaunch-check|launch)$")
        set(tier unit)
      elseif(type STREQUAL "cli")
        set(tier cli)
      elseif(type MATCHES "^(rostest|install)$")
        set(tier ros)
      else()
        message(FATAL_ERROR "test/tiers.cmake: ${target} is of test type '${type}', which has no "
                            "tier: add the type to tlc_make_test_tiers()")
      endif()
      add_dependencies(run_${tier}_tests ${target})
      set_property(GLOBAL APPEND PROPERTY TLC_${tier}_TESTS ${name})
    endforeach()
  endforeach()
  foreach(name ${cli_gtests})
    get_property(cli GLOBAL PROPERTY TLC_cli_TESTS)
    if(NOT name IN_LIST cli)
      message(FATAL_ERROR "test/tiers.cmake: tlc_cli_gtest_tier(${name}) names no registered gtest")
    endif()
  endforeach()
endfunction()
