# hq_test(<module> <name> [LIBS ...] [LABELS ...]): tests/<module>/<name>.cpp
# becomes the executable test_<module>_<name>, linked with GoogleTest and
# hq_<module>, its tests registered with CTest under LABELS. Labels (the
# sanitizer run of scripts/test skips them but for a small subset): slow
# (long runs over real data), fault (hostile inputs and mutations), browser,
# workflow.
# A program whose label is in HQVIEW_UNBUILT_TEST_LABELS is not built (nor
# registered): scripts/test --sanitize sets it to `slow`, the label that run
# leaves out whole (hq_test_built tells the test's CMakeLists).
set(HQVIEW_UNBUILT_TEST_LABELS "" CACHE STRING
    "Labels whose test programs are not built (scripts/test --sanitize: slow, which that run never runs)")
function(hq_test_built labels result)
  set(built TRUE)
  foreach(label IN LISTS labels)
    if(label IN_LIST HQVIEW_UNBUILT_TEST_LABELS)
      set(built FALSE)
    endif()
  endforeach()
  set(${result} ${built} PARENT_SCOPE)
endfunction()
function(hq_test module name)
  cmake_parse_arguments(ARG "" "" "LIBS;LABELS" ${ARGN})
  set(target test_${module}_${name})
  hq_test_built("${ARG_LABELS}" built)
  if(NOT built)
    return()
  endif()
  add_executable(${target} ${name}.cpp)
  target_link_libraries(${target} PRIVATE hq_${module} hq_test_support ${ARG_LIBS} GTest::gtest_main hq_warnings)
  set(properties TIMEOUT 600)
  if(ARG_LABELS)
    list(APPEND properties LABELS "${ARG_LABELS}")
  endif()
  gtest_discover_tests(${target} TEST_PREFIX "${module}." DISCOVERY_TIMEOUT 60 PROPERTIES ${properties})
endfunction()
