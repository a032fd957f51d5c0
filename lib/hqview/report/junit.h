#pragma once
// JUnit XML, the test report GitLab, Jenkins and GitHub's test reporters
// read: `batch` writes OUT/junit.xml (one test case per mesh, one per mesh
// and gate), `diff --junit FILE` one per gate. No times: the file is the same
// for the same results (timings.json has the times).

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hqview/report/batch_index.h"

namespace hq {

struct JunitCase {
  std::string classname;  // groups the cases in a reporter: the mesh's method, or "hqview"
  std::string name;
  enum class Outcome { passed, failed, error, skipped } outcome = Outcome::passed;
  std::string message;  // the failure, error or skip in one line
  std::string text;     // the details (the element's body)
};

// <testsuites><testsuite name=SUITE tests= failures= errors= skipped=>
// with every case in order. Text from input (paths, rules, error messages)
// is escaped for XML; characters XML 1.0 cannot hold become U+FFFD.
std::string junit_xml(std::string_view suite, const std::vector<JunitCase>& cases);

// A batch's cases, in index order: per mesh "PATH" (error: the mesh failed,
// with its error; skipped: not a hex mesh), then per gate "PATH: RULE"
// (failure: the value against the rule). A mesh whose gates are not known
// (a merged index) has only its own case, failed when a gate failed.
std::vector<JunitCase> batch_junit_cases(const std::vector<BatchEntry>& entries);

}  // namespace hq
