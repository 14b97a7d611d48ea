// The gate's report as JUnit XML for CI systems (docs/gate.md §3).
#include "swell/validation/gate/render.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "gate/report_text.hpp"
#include "swell/validation/results/report.hpp"
#include "swell/validation/results/text.hpp"

namespace swell::validation {

using namespace gate_text;

std::string gate_junit(const GateReport& report) {
  const int failed = failed_count(report);
  const int tests = int(report.results.size() + report.skipped.size());
  const std::string time = fmt::format("{:.3f}", report.seconds);
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  // The one suite and its envelope carry the same counts.
  const std::string counts =
      xml_attribute("name", "swell gate") + xml_attribute("tests", std::to_string(tests)) +
      xml_attribute("failures", std::to_string(failed)) + xml_attribute("errors", "0") +
      xml_attribute("skipped", std::to_string(report.skipped.size())) + xml_attribute("time", time);
  out += "<testsuites" + counts + ">\n";
  out += "  <testsuite" + counts + ">\n";
  out += "    <properties>\n";
  auto property = [&](const std::string& name, const std::string& value) {
    out += "      <property" + xml_attribute("name", name) + xml_attribute("value", value) + "/>\n";
  };
  property("case", report.case_path);
  property("subject", report.subject);
  property("frames", fmt::format("{} of {}x{}", report.frames, report.nx, report.ny));
  property("alpha", fmt::format("{:g}", report.alpha));
  property("alpha_per_check", fmt::format("{:g}", report.alpha_per_check));
  property("statistical_checks", std::to_string(report.statistical_checks));
  out += "    </properties>\n";
  for (const auto& r : report.results) {
    const std::string group = r.check.substr(0, r.check.find('.'));
    out += "    <testcase" + xml_attribute("classname", "swell.gate." + group) +
           xml_attribute("name", r.check) + xml_attribute("time", "0");
    if (r.passed) {
      out += ">\n      <system-out>" + xml_escape(r.reason + " (" + r.criterion + ")", false) +
             "</system-out>\n    </testcase>\n";
      continue;
    }
    const std::string message = failure_message(r);
    out += ">\n      <failure" + xml_attribute("message", message) + xml_attribute("type", r.check) + ">" +
           xml_escape(fmt::format("{}\nsubject: {}\nmeasured: {}\nexpected: {}\ncriterion: {}\n"
                                  "p-value: {}\nalpha: {}\nreason: {}",
                                  r.check, r.subject, table_number(r.measured), table_number(r.expected),
                                  r.criterion, table_number(r.p_value), table_number(r.alpha), r.reason),
                      false) +
           "</failure>\n    </testcase>\n";
  }
  for (const auto& entry : report.skipped) {
    const std::string &check = entry.check, &why = entry.why;
    const std::string group = check.substr(0, check.find('.'));
    out += "    <testcase" + xml_attribute("classname", "swell.gate." + group) +
           xml_attribute("name", check) + xml_attribute("time", "0") + ">\n      <skipped" +
           xml_attribute("message", why) + "/>\n    </testcase>\n";
  }
  out += "  </testsuite>\n</testsuites>\n";
  return out;
}

std::string gate_junit_error(const std::string& case_path, const std::string& message) {
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  const std::string counts = xml_attribute("tests", "1") + xml_attribute("failures", "0") +
                             xml_attribute("errors", "1") + xml_attribute("skipped", "0") +
                             xml_attribute("time", "0");
  out += "<testsuites" + xml_attribute("name", "swell gate") + counts + ">\n";
  out += "  <testsuite" + xml_attribute("name", "swell gate") + counts + ">\n";
  out += "    <properties>\n      <property" + xml_attribute("name", "case") +
         xml_attribute("value", case_path) + "/>\n    </properties>\n";
  out += "    <testcase" + xml_attribute("classname", "swell.gate") + xml_attribute("name", "input") +
         xml_attribute("time", "0") + ">\n      <error" + xml_attribute("message", message) +
         xml_attribute("type", "bad input") + ">" + xml_escape(message, false) +
         "</error>\n    </testcase>\n";
  out += "  </testsuite>\n</testsuites>\n";
  return out;
}

}  // namespace swell::validation
