#include "hqview/report/junit.h"

#include <cstdint>

#include "hqview/core/number_format.h"

namespace hq {
namespace {

// One UTF-8 sequence starting at text[i] (its length), 0 when malformed.
std::size_t utf8_length(std::string_view text, std::size_t i) {
  const auto c = static_cast<unsigned char>(text[i]);
  std::size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
  if (n == 0 || i + n > text.size()) return 0;
  for (std::size_t k = 1; k < n; ++k)
    if ((static_cast<unsigned char>(text[i + k]) >> 6) != 0x2) return 0;
  return n;
}

std::string xml_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    const std::size_t n = utf8_length(text, i);
    if (n == 0) {
      out += "\xEF\xBF\xBD";  // not UTF-8
      ++i;
      continue;
    }
    if (n == 1) {
      switch (c) {
        case '&': out += "&amp;"; break;
        case '<': out += "&lt;"; break;
        case '>': out += "&gt;"; break;
        case '"': out += "&quot;"; break;
        case '\'': out += "&apos;"; break;
        case '\t': out += "&#9;"; break;
        case '\n': out += "&#10;"; break;
        case '\r': out += "&#13;"; break;
        default:
          if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F)
            out += "\xEF\xBF\xBD";  // not allowed in XML 1.0
          else
            out += c;
      }
    } else {
      out.append(text.substr(i, n));
    }
    i += n;
  }
  return out;
}

}  // namespace

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
