# hq_test(<module> <name> [LIBS ...]): tests/<module>/<name>.cpp becomes the
# executable test_<module>_<name>, linked with GoogleTest and hq_<module>,
# its tests registered with CTest.
function(hq_test module name)
  cmake_parse_arguments(ARG "" "" "LIBS" ${ARGN})
  set(target test_${module}_${name})
  add_executable(${target} ${name}.cpp)
  target_link_libraries(${target} PRIVATE hq_${module} hq_test_support ${ARG_LIBS} GTest::gtest_main hq_warnings)
  gtest_discover_tests(${target} TEST_PREFIX "${module}." DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 600)
endfunction()
