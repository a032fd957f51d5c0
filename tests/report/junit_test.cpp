#include "hqview/report/junit.h"

#include <gtest/gtest.h>

#include <string>

namespace HQ_TEST_UNIT {

hq::BatchEntry entry(const std::string& path, hq::BatchStatus status) {
  hq::BatchEntry e;
  e.path = path;
  e.status = status;
  return e;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(Junit, OneCasePerMeshAndGateWithTheCounts) {
  hq::BatchEntry ok = entry("a/ok.mesh", hq::BatchStatus::ok);
  ok.label = "polycube";
  ok.gates = {{"quality.scaled_jacobian.min>=0.2", 0.31, true}};
  hq::BatchEntry bad = entry("a/bad.mesh", hq::BatchStatus::gate_failed);
  bad.gates = {{"quality.scaled_jacobian.min>=0.2", -0.5, false}, {"quality.num_inverted==0", 3, false}};
  hq::BatchEntry failed = entry("b/broken.mesh", hq::BatchStatus::failed);
  failed.error = "b/broken.mesh:7: expected 8 vertex ids";
  hq::BatchEntry skipped = entry("b/surface.off", hq::BatchStatus::skipped);
  skipped.error = "not a hex mesh";
  const std::string xml = hq::junit_xml("hqview batch", hq::batch_junit_cases({ok, bad, failed, skipped}));
  // 4 meshes + 3 gates; 2 gate failures, 1 error, 1 skipped; on both elements.
  EXPECT_EQ(count(xml, "tests=\"7\" failures=\"2\" errors=\"1\" skipped=\"1\""), 2u) << xml;
  EXPECT_EQ(count(xml, "<testcase "), 7u);
  EXPECT_NE(xml.find("<testcase classname=\"hqview.polycube\" name=\"a/ok.mesh\"/>"), std::string::npos) << xml;
  EXPECT_NE(xml.find("name=\"a/bad.mesh: quality.scaled_jacobian.min&gt;=0.2\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<failure message=\"gate failed: quality.scaled_jacobian.min&gt;=0.2 (value -0.5)\""),
            std::string::npos)
      << xml;
  EXPECT_NE(xml.find("<error message=\"b/broken.mesh:7: expected 8 vertex ids\" type=\"error\"/>"), std::string::npos)
      << xml;
  EXPECT_NE(xml.find("<skipped message=\"not a hex mesh\"/>"), std::string::npos) << xml;
}

TEST(Junit, InputTextIsEscapedForXml) {
  hq::BatchEntry e = entry("odd/<a href=\"x\">&'\x01\xff\x1b\xef\xbf\xbe.mesh", hq::BatchStatus::failed);
  e.error = "line\nbreak";
  const std::string xml = hq::junit_xml("s<&>", hq::batch_junit_cases({e}));
  // Control characters and bytes that are not UTF-8 as \xhh (message_text);
  // U+FFFE, valid UTF-8 but not an XML 1.0 character, as its bytes.
  EXPECT_NE(xml.find("name=\"odd/&lt;a href=&quot;x&quot;&gt;&amp;&apos;\\x01\\xff\\x1b\\xef\\xbf\\xbe.mesh\""),
            std::string::npos)
      << xml;
  EXPECT_NE(xml.find("message=\"line&#10;break\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<testsuite name=\"s&lt;&amp;&gt;\""), std::string::npos) << xml;
  EXPECT_EQ(xml.find('\x01'), std::string::npos);
}

TEST(Junit, AMergedIndexWithoutGateValuesStillFailsTheMesh) {
  hq::BatchEntry e = entry("m.mesh", hq::BatchStatus::gate_failed);
  e.failed_gates = {"quality.num_inverted==0"};
  const std::string xml = hq::junit_xml("hqview batch", hq::batch_junit_cases({e}));
  EXPECT_NE(xml.find("<failure message=\"gate failed: quality.num_inverted==0\" type=\"failure\"/>"),
            std::string::npos)
      << xml;
}

}  // namespace
