# hq_test(<module> <name> [LIBS ...] [LABELS ...]): tests/<module>/<name>.cpp
# becomes the executable test_<module>_<name>, linked with GoogleTest and
# hq_<module>, its tests registered with CTest under LABELS. Labels (the
# sanitizer run of scripts/test skips them but for a small subset): slow
# (long runs over real data), fault (hostile inputs and mutations), browser,
# workflow.
function(hq_test module name)
  cmake_parse_arguments(ARG "" "" "LIBS;LABELS" ${ARGN})
  set(target test_${module}_${name})
  add_executable(${target} ${name}.cpp)
  target_link_libraries(${target} PRIVATE hq_${module} hq_test_support ${ARG_LIBS} GTest::gtest_main hq_warnings)
  set(properties TIMEOUT 600)
  if(ARG_LABELS)
    list(APPEND properties LABELS "${ARG_LABELS}")
  endif()
  gtest_discover_tests(${target} TEST_PREFIX "${module}." DISCOVERY_TIMEOUT 60 PROPERTIES ${properties})
endfunction()
