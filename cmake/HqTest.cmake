# hq_test(<module> <name> [LIBS ...] [LABELS ...]): tests/<module>/<name>.cpp
# goes into the module's test program of those labels (hq_test_target:
# test_<module>, or test_<module>_<labels> for a labelled one), linked with
# GoogleTest, hq_<module> and LIBS, its tests registered with CTest under
# LABELS. One program per module and label set rather than one per source:
# some 90 links and test discoveries fewer in each half of CI, and the
# sources of a program can be compiled in unity batches (HQVIEW_TEST_UNITY,
# tests/CMakeLists.txt). Labels (the
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
# hq_test_target(<module> <labels> <result>): the name of the module's test
# program of those labels (for a CMakeLists that sets more on it).
function(hq_test_target module labels result)
  set(target test_${module})
  foreach(label IN LISTS labels)
    string(APPEND target _${label})
  endforeach()
  set(${result} ${target} PARENT_SCOPE)
endfunction()
function(hq_test module name)
  cmake_parse_arguments(ARG "" "" "LIBS;LABELS" ${ARGN})
  hq_test_target(${module} "${ARG_LABELS}" target)
  hq_test_built("${ARG_LABELS}" built)
  if(NOT built)
    return()
  endif()
  if(TARGET ${target})
    target_sources(${target} PRIVATE ${name}.cpp)
  else()
    add_executable(${target} ${name}.cpp)
    target_link_libraries(${target} PRIVATE hq_${module} hq_test_support GTest::gtest_main hq_warnings)
    set(properties TIMEOUT 600)
    if(ARG_LABELS)
      list(APPEND properties LABELS "${ARG_LABELS}")
    endif()
    gtest_discover_tests(${target} TEST_PREFIX "${module}." DISCOVERY_TIMEOUT 60 PROPERTIES ${properties})
  endif()
  target_link_libraries(${target} PRIVATE ${ARG_LIBS})
endfunction()
