#include "hqview/report/junit.h"

#include <cstdint>

#include "hqview/core/number_format.h"
#include "hqview/report/escape.h"

namespace hq {


std::string junit_xml(std::string_view suite, const std::vector<JunitCase>& cases) {
  int failures = 0, errors = 0, skipped = 0;
  for (const JunitCase& c : cases) {
    failures += c.outcome == JunitCase::Outcome::failed;
    errors += c.outcome == JunitCase::Outcome::error;
    skipped += c.outcome == JunitCase::Outcome::skipped;
  }
  const std::string counts = " tests=\"" + std::to_string(cases.size()) + "\" failures=\"" +
                             std::to_string(failures) + "\" errors=\"" + std::to_string(errors) + "\" skipped=\"" +
                             std::to_string(skipped) + "\"";
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<testsuites name=\"hqview\"" + counts + ">\n";
  out += "  <testsuite name=\"" + xml_escape(suite) + "\"" + counts + ">\n";
  for (const JunitCase& c : cases) {
    out += "    <testcase classname=\"" + xml_escape(c.classname) + "\" name=\"" + xml_escape(c.name) + "\"";
    if (c.outcome == JunitCase::Outcome::passed) {
      out += "/>\n";
      continue;
    }
    const char* tag = c.outcome == JunitCase::Outcome::failed  ? "failure"
                      : c.outcome == JunitCase::Outcome::error ? "error"
                                                               : "skipped";
    out += ">\n      <" + std::string(tag) + " message=\"" + xml_escape(c.message) + "\"";
    if (c.outcome != JunitCase::Outcome::skipped) out += " type=\"" + std::string(tag) + "\"";
    out += c.text.empty() ? "/>\n" : ">" + xml_escape(c.text) + "</" + tag + ">\n";
    out += "    </testcase>\n";
  }
  out += "  </testsuite>\n</testsuites>\n";
  return out;
}

std::vector<JunitCase> batch_junit_cases(const std::vector<BatchEntry>& entries) {
  std::vector<JunitCase> cases;
  for (const BatchEntry& e : entries) {
    const std::string classname = e.label.empty() ? "hqview" : "hqview." + e.label;
    JunitCase mesh{classname, e.path, JunitCase::Outcome::passed, "", ""};
    if (e.status == BatchStatus::failed) {
      mesh.outcome = JunitCase::Outcome::error;
      mesh.message = e.error;
    } else if (e.status == BatchStatus::skipped) {
      mesh.outcome = JunitCase::Outcome::skipped;
      mesh.message = e.error;
    } else if (e.gates.empty() && !e.failed_gates.empty()) {
      mesh.outcome = JunitCase::Outcome::failed;
      mesh.message = "gate failed: ";
      for (std::size_t i = 0; i < e.failed_gates.size(); ++i) mesh.message += (i ? ", " : "") + e.failed_gates[i];
    }
    cases.push_back(std::move(mesh));
    for (const GateResult& g : e.gates) {
      JunitCase gate{classname, e.path + ": " + g.rule, JunitCase::Outcome::passed, "", ""};
      if (!g.passed) {
        gate.outcome = JunitCase::Outcome::failed;
        gate.message = "gate failed: " + g.rule + " (value " + format_double(g.value) + ")";
        gate.text = "mesh: " + e.path + "\nrule: " + g.rule + "\nvalue: " + format_double(g.value) + "\n";
      }
      cases.push_back(std::move(gate));
    }
  }
  return cases;
}

}  // namespace hq
