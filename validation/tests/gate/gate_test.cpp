// The gate (docs/gate.md): its renderings (the terminal table, JSON, JUnit XML that parses as
// XML 1.0 whatever the reasons hold), the family-wise α shared by the statistical checks, the
// same verdict whether frames are judged in memory or read from disk on any number of threads,
// `swell gate` end to end with its exit codes (0 pass, 1 fail, 2 bad input), and the example
// case files under data/cases/. The catalogue of buggy engines and the false-alarm calibration
// are in gate_catalogue_test.cpp.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <complex>
#include <cstdlib>
#include <fmt/format.h>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "swell/reference/errors.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/validation/io/frame_io.hpp"
#include "swell/validation/gate/gate.hpp"
#include "swell/validation/io/npy.hpp"
#include "swell/validation/checks/ocean_checks.hpp"
#include "gate_cases.hpp"
#include "test_engine.hpp"

namespace {

namespace fs = std::filesystem;
using swell::InvalidInput;
using swell::reference::Field;
using swell::reference::FrameSequence;
using swell::reference::Grid;
using swell::reference::OceanCase;
using swell::test::EngineBug;
using swell::validation::CaseFile;
using swell::validation::CheckResult;
using swell::validation::FrameFormat;
using swell::validation::GateOptions;
using swell::validation::GateReport;
using swell::validation::SpectrumScale;
using CliRun = swell::test::Run;  // (inside a fixture, Run is testing::Test::Run)
using swell::test::swell;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool contains(const std::string& text, const std::string& fragment) {
  return text.find(fragment) != std::string::npos;
}

std::string read_text(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// A small sea the checks resolve well: JONSWAP toward 30° in deep water, 64² over 400 m (the
// peak at 4 Δk), 8 frames 0.5 s apart, λ = 0.8 — the built-in jonswap_deep case of
// `swell check ocean`.
OceanCase small_case(int frames = 8) { return swell::test::small_gate_case(frames); }

CaseFile as_case_file(const OceanCase& c, SpectrumScale scale = SpectrumScale::absolute) {
  CaseFile file;
  file.ocean = c;
  file.scale = scale;
  return file;
}

std::string failures(const GateReport& report) {
  std::string out;
  for (const auto& r : report.results) {
    if (!r.passed) out += "\n  FAIL " + r.check + ": " + r.reason;
  }
  return out;
}

// ------------------------------------------------------------------ XML through Python

bool have_python() {
  static const bool found = std::system("python3 -c pass >/dev/null 2>&1") == 0;
  return found;
}

// Runs a Python snippet with argv[1] = path; returns its exit code and output.
CliRun python(const std::string& code, const fs::path& path) {
  const fs::path script = fs::path(path).concat(".py");
  write_text(script, code);
  const std::string command = "python3 '" + script.string() + "' '" + path.string() + "' 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return {-1, "popen failed"};
  std::string output;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
  const int status = pclose(pipe);
  fs::remove(script);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

// Parses the file with Python's XML parser (expat, strict XML 1.0); "" when well-formed.
std::string xml_error(const fs::path& path) {
  const auto run = python("import sys, xml.dom.minidom\nxml.dom.minidom.parse(sys.argv[1])\n", path);
  return run.exit_code == 0 ? "" : run.output.empty() ? "parse failed" : run.output;
}

// Characters XML 1.0 cannot hold at all: C0 controls other than tab, newline, return.
bool has_forbidden_bytes(const std::string& text) {
  return std::any_of(text.begin(), text.end(), [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return u < 0x20 && u != '\t' && u != '\n' && u != '\r';
  });
}

// ------------------------------------------------------------------ a report by hand

CheckResult result(std::string check, bool passed, double measured, double expected,
                   double tolerance, double p, double alpha, std::string reason) {
  CheckResult r;
  r.check = std::move(check);
  r.subject = "jonswap hs=3, 64×64 over 400×400 m";
  r.measured = measured;
  r.expected = expected;
  r.tolerance = tolerance;
  r.criterion = std::isnan(alpha) ? "≤ bound" : "p ≥ α";
  r.passed = passed;
  r.p_value = p;
  r.alpha = alpha;
  r.reason = std::move(reason);
  return r;
}

// Everything that must be escaped or dropped: markup, quotes, C0 controls (NUL, ESC), a lone
// continuation byte and 0xFF (not UTF-8), U+FFFE (not an XML character), and valid UTF-8.
const std::string kNasty = std::string("a & b < c > d \"e\" 'f' \x01\x1b[31mred\x1b[0m ") +
                           std::string("nul\0here ", 9) + "\x80\xff bad \xEF\xBF\xBE ok: ω ≤ λ";
// What an XML parser gives back for it: the markup as itself, controls and U+FFFE gone, each
// malformed byte replaced by U+FFFD.
const std::string kNastyParsed =
    "a & b < c > d \"e\" 'f' [31mred[0m nulhere \xEF\xBF\xBD\xEF\xBF\xBD bad  ok: ω ≤ λ";

GateReport sample_report() {
  GateReport report;
  report.case_path = "cases/engine & co <1>.toml";
  report.subject = "jonswap \"quoted\" 'single', 64×64 over 400×400 m";
  report.frames = 8;
  report.nx = 64;
  report.ny = 64;
  report.fields = {"height", "disp_x"};
  report.alpha = 1e-3;
  report.unit_roundoff = 0x1p-24;
  report.statistical_checks = 5;
  report.alpha_per_check = 2e-4;
  report.seconds = 0.25;
  report.results = {
      result("energy", true, 0.5225, 0.5619, 2e-4, 0.3, 2e-4, "mean h² is 0.930× the band-limited m0"),
      result("dispersion.residual", false, 0.03, 0, 4.7e-9, kNaN, kNaN,
             "fit leaves 3e-2 — the waves do not evolve <as> the case's & \"dispersion\" says"),
      result("spectrum.shape", false, 1.9, 1, 1e-4, 1e-12, 1e-4, kNasty)};
  report.skipped = {{"direction", swell::validation::SkipReason::too_few_frames,
                     "needs ≥ 2 frames (one frame cannot tell k from −k)"},
                    {"derived", swell::validation::SkipReason::no_field,
                     "no slope, displacement or Jacobian field given"}};
  return report;
}

class GateFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "_" + info->name();
    for (auto& c : name) c = (c == '/') ? '_' : c;
    dir_ = fs::temp_directory_path() / ("swell_gate_test_" + std::to_string(::getpid()) + "_" + name);
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

// ==================================================================== renderings

TEST(GateRender, OneLinePerCheckTheSkippedOnesAndAVerdict) {
  const std::string text = swell::validation::render_gate(sample_report());
  std::istringstream lines(text);
  int pass = 0, fail = 0, skip = 0;
  for (std::string line; std::getline(lines, line);) {
    pass += line.rfind("PASS  ", 0) == 0;
    fail += line.rfind("FAIL  ", 0) == 0;
    skip += line.rfind("SKIP  ", 0) == 0;
    if (line.rfind("FAIL  dispersion.residual", 0) == 0) {
      EXPECT_TRUE(contains(line, "0.03")) << line;              // measured
      EXPECT_TRUE(contains(line, "> 4.7e-09")) << line;         // the bound it exceeds
      EXPECT_TRUE(contains(line, "do not evolve")) << line;     // the reason
    }
    if (line.rfind("FAIL  spectrum.shape", 0) == 0) {
      EXPECT_TRUE(contains(line, "1.9")) << line;
      EXPECT_TRUE(contains(line, "p 1e-12 < α 1.0e-04")) << line;
    }
    if (line.rfind("PASS  energy", 0) == 0) {
      EXPECT_TRUE(contains(line, "0.5225")) << line;
      EXPECT_TRUE(contains(line, "0.5619")) << line;
      EXPECT_TRUE(contains(line, "p 0.3 ≥ α 2.0e-04")) << line;
    }
    if (line.rfind("SKIP  direction", 0) == 0) {
      EXPECT_TRUE(contains(line, "needs ≥ 2 frames")) << line;
    }
  }
  EXPECT_EQ(pass, 1) << text;
  EXPECT_EQ(fail, 2) << text;
  EXPECT_EQ(skip, 2) << text;
  EXPECT_TRUE(contains(text, "verdict: FAIL — 2 of 3 checks failed (dispersion.residual, "
                             "spectrum.shape), 2 skipped; family-wise α = 0.001"))
      << text;
  EXPECT_TRUE(contains(text, "shared by 5 statistical checks: each at α = 0.0002")) << text;
}

TEST(GateRender, APassingReportSaysPass) {
  GateReport report = sample_report();
  report.results.resize(1);
  report.skipped.clear();
  const std::string text = swell::validation::render_gate(report);
  EXPECT_TRUE(contains(text, "verdict: PASS — 1 check passed; family-wise α = 0.001")) << text;
  EXPECT_TRUE(contains(text, "unit roundoff 6e-08")) << text;  // 2⁻²⁴, the floor judged by
  EXPECT_TRUE(report.passed());
}

TEST(GateJson, CarriesWhatTheTableShows) {
  const auto report = sample_report();
  const auto json = swell::validation::gate_json(report);
  for (const char* key : {"case", "subject", "frames", "nx", "ny", "fields", "alpha",
                          "alpha_per_check", "statistical_checks", "fitted_scale",
                          "unit_roundoff", "checks", "skipped", "passed", "failed", "seconds",
                          "pass"}) {
    EXPECT_TRUE(json.contains(key)) << key;
  }
  EXPECT_EQ(json["case"], report.case_path);
  EXPECT_EQ(json["pass"], false);
  EXPECT_EQ(json["passed"], 1);
  EXPECT_EQ(json["failed"], 2);
  EXPECT_EQ(json["statistical_checks"], 5);
  EXPECT_EQ(json["alpha"].get<double>(), 1e-3);
  EXPECT_EQ(json["unit_roundoff"].get<double>(), 0x1p-24);
  ASSERT_EQ(json["checks"].size(), 3u);
  const auto& dispersion = json["checks"][1];
  EXPECT_EQ(dispersion["check"], "dispersion.residual");
  EXPECT_EQ(dispersion["pass"], false);
  EXPECT_EQ(dispersion["measured"].get<double>(), 0.03);
  EXPECT_EQ(dispersion["tolerance"].get<double>(), 4.7e-9);
  EXPECT_TRUE(dispersion["p_value"].is_null());  // exact check: no p-value (NaN → null)
  EXPECT_EQ(json["checks"][2]["p_value"].get<double>(), 1e-12);
  EXPECT_EQ(json["checks"][2]["alpha"].get<double>(), 1e-4);
  ASSERT_EQ(json["skipped"].size(), 2u);
  EXPECT_EQ(json["skipped"][0]["check"], "direction");
  EXPECT_EQ(json["skipped"][0]["reason"], "needs ≥ 2 frames (one frame cannot tell k from −k)");
  // Every string is valid UTF-8 (malformed bytes became U+FFFD): the JSON dumps and parses.
  std::string text;
  ASSERT_NO_THROW(text = json.dump(2));
  EXPECT_EQ(nlohmann::json::parse(text)["checks"][2]["reason"],
            "a & b < c > d \"e\" 'f' \x01\x1b[31mred\x1b[0m " + std::string("nul\0here ", 9) +
                "\xEF\xBF\xBD\xEF\xBF\xBD bad \xEF\xBF\xBE ok: ω ≤ λ");
}

TEST_F(GateFiles, JunitIsWellFormedXmlWithOneTestcasePerCheck) {
  const std::string xml = swell::validation::gate_junit(sample_report());
  EXPECT_FALSE(has_forbidden_bytes(xml));
  EXPECT_TRUE(contains(xml, "<testsuite name=\"swell gate\" tests=\"5\" failures=\"2\" errors=\"0\" "
                            "skipped=\"2\""))
      << xml;
  EXPECT_TRUE(contains(xml, "<testcase classname=\"swell.gate.dispersion\" "
                            "name=\"dispersion.residual\""))
      << xml;
  // The failure message carries measured, expected and the bound (or p against α).
  EXPECT_TRUE(contains(xml, "message=\"dispersion.residual: measured 0.03, expected 0, bound "
                            "4.7e-09: fit leaves"))
      << xml;
  EXPECT_TRUE(contains(xml, "message=\"spectrum.shape: measured 1.9, expected 1, p = 1e-12 &lt; "
                            "α = 0.0001"))
      << xml;
  EXPECT_TRUE(contains(xml, "<skipped message=\"needs ≥ 2 frames")) << xml;
  EXPECT_TRUE(contains(xml, "&lt;as&gt; the case&apos;s &amp; &quot;dispersion&quot;")) << xml;
  if (!have_python()) GTEST_SKIP() << "python3 not found: XML not parsed";
  write_text(dir_ / "junit.xml", xml);
  EXPECT_EQ(xml_error(dir_ / "junit.xml"), "") << xml;
}

TEST_F(GateFiles, JunitEscapesMarkupAndDropsWhatXmlCannotHold) {
  if (!have_python()) GTEST_SKIP() << "python3 not found: XML not parsed";
  write_text(dir_ / "junit.xml", swell::validation::gate_junit(sample_report()));
  // What a CI system reads back: the spectrum.shape failure's message, and the case property.
  const auto run = python(R"(import sys, json, xml.dom.minidom
doc = xml.dom.minidom.parse(sys.argv[1])
for case in doc.getElementsByTagName("testcase"):
    if case.getAttribute("name") == "spectrum.shape":
        failure = case.getElementsByTagName("failure")[0]
        print(json.dumps({"message": failure.getAttribute("message"),
                          "text": failure.firstChild.data}))
for p in doc.getElementsByTagName("property"):
    if p.getAttribute("name") == "case":
        print(json.dumps({"case": p.getAttribute("value")}))
)",
                          dir_ / "junit.xml");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  std::istringstream lines(run.output);
  std::string first, second;
  std::getline(lines, first);
  std::getline(lines, second);
  const auto failure = nlohmann::json::parse(first);
  const std::string message = failure["message"];
  EXPECT_TRUE(contains(message, kNastyParsed)) << message;
  EXPECT_TRUE(contains(failure["text"].get<std::string>(), "reason: " + kNastyParsed));
  EXPECT_EQ(nlohmann::json::parse(second)["case"], "cases/engine & co <1>.toml");
}

TEST_F(GateFiles, JunitOfBadInputIsAnError) {
  const std::string xml = swell::validation::gate_junit_error(
      "case.toml", "frame_0002.exr: missing frame file (frame 2 of 3) <&>");
  EXPECT_TRUE(contains(xml, "errors=\"1\"")) << xml;
  EXPECT_TRUE(contains(xml, "<error message=\"frame_0002.exr: missing frame file (frame 2 of 3) "
                            "&lt;&amp;&gt;\""))
      << xml;
  if (!have_python()) GTEST_SKIP() << "python3 not found: XML not parsed";
  write_text(dir_ / "error.xml", xml);
  EXPECT_EQ(xml_error(dir_ / "error.xml"), "") << xml;
}

// ==================================================================== one α for the gate

struct AlphaCase {
  std::string name;
  int frames;
  SpectrumScale scale;
  int statistical;  // checks sharing α
};

void PrintTo(const AlphaCase& c, std::ostream* os) { *os << c.name; }

class GateAlpha : public ::testing::TestWithParam<AlphaCase> {};

// The statistical checks that run share α: each at α / (their number), and their parts split
// that again, so the α of all statistical results together is at most the gate's.
TEST_P(GateAlpha, IsSharedByTheStatisticalChecksThatRun) {
  const auto& p = GetParam();
  const OceanCase c = small_case(p.frames);
  GateOptions options;
  options.alpha = 0.01;
  const auto report =
      swell::validation::run_gate(as_case_file(c, p.scale), swell::test::render_surface(c), options);
  EXPECT_TRUE(report.passed()) << failures(report);
  EXPECT_EQ(report.statistical_checks, p.statistical);
  EXPECT_DOUBLE_EQ(report.alpha_per_check * report.statistical_checks, options.alpha);
  EXPECT_EQ(report.alpha, options.alpha);
  double total = 0;
  std::vector<std::string> groups;
  for (const auto& r : report.results) {
    if (std::isnan(r.alpha)) continue;  // exact checks, judged against rounding bounds
    EXPECT_LE(r.alpha, report.alpha_per_check * (1 + 1e-12)) << r.check;
    total += r.alpha;
    const std::string group = r.check.substr(0, r.check.find('.'));
    if (std::find(groups.begin(), groups.end(), group) == groups.end()) groups.push_back(group);
    if (r.check == "energy") {
      EXPECT_EQ(r.alpha, report.alpha_per_check);
    }
  }
  EXPECT_LE(total, options.alpha * (1 + 1e-12));
  EXPECT_EQ(int(groups.size()), p.statistical) << "statistical checks that ran";
}

INSTANTIATE_TEST_SUITE_P(
    Gate, GateAlpha,
    ::testing::Values(AlphaCase{"eight_frames", 8, SpectrumScale::absolute, 6},
                      AlphaCase{"two_frames", 2, SpectrumScale::absolute, 6},
                      AlphaCase{"one_frame", 1, SpectrumScale::absolute, 5},
                      AlphaCase{"free_scale", 8, SpectrumScale::free, 5},
                      AlphaCase{"free_scale_one_frame", 1, SpectrumScale::free, 4}),
    [](const auto& info) { return info.param.name; });

TEST(GateAlpha, OutsideZeroOneIsBadInput) {
  const OceanCase c = small_case(2);
  const auto frames = swell::test::render_surface(c);
  for (double alpha : {0.0, 1.0, -0.1, 2.0, kNaN}) {
    GateOptions options;
    options.alpha = alpha;
    EXPECT_THROW((void)swell::validation::run_gate(as_case_file(c), frames, options), InvalidInput)
        << alpha;
  }
}

// ==================================================================== the same verdict

void expect_same_results(const std::vector<CheckResult>& got, const std::vector<CheckResult>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(got[i].check, want[i].check) << i;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(got[i].measured),
              std::bit_cast<std::uint64_t>(want[i].measured))
        << want[i].check;
    EXPECT_EQ(got[i].passed, want[i].passed) << want[i].check;
    EXPECT_EQ(got[i].reason, want[i].reason) << want[i].check;
  }
}

// The gate runs groups of checks on several threads and merges them: the results are those of
// run_ocean_checks at α / (number of statistical checks), in its order, on any thread count.
TEST(GateVerdict, EqualsTheOceanChecksAtTheSharedAlphaOnAnyNumberOfThreads) {
  for (SpectrumScale scale : {SpectrumScale::absolute, SpectrumScale::free}) {
    const OceanCase c = small_case(8);
    const auto frames = swell::test::render_surface(c, EngineBug::omega_equals_gk);
    swell::validation::OceanCheckOptions direct;
    direct.free_scale = scale == SpectrumScale::free;
    direct.alpha = 1e-3 / (direct.free_scale ? 4 : 5);
    const auto want = swell::validation::run_ocean_checks(c, frames, direct);
    for (int threads : {1, 2, 5}) {
      SCOPED_TRACE(threads);
      GateOptions options;
      options.threads = threads;
      const auto report = swell::validation::run_gate(as_case_file(c, scale), frames, options);
      expect_same_results(report.results, want.results);
      EXPECT_EQ(report.skipped, want.skipped);
      EXPECT_EQ(report.fitted_scale, want.fitted_scale);
      EXPECT_FALSE(report.passed());  // ω = g k
    }
  }
}

// Frames written to disk and judged from there — the gate keeps every frame's height and the
// other fields of the first and last frames only — give the verdict of the frames in memory.
TEST_F(GateFiles, FromDiskEqualsInMemory) {
  for (FrameFormat format : {FrameFormat::exr, FrameFormat::npy}) {
    SCOPED_TRACE(swell::validation::to_string(format));
    const OceanCase c = small_case(6);
    swell::validation::FrameWriteOptions write;
    write.format = format;
    const fs::path out = dir_ / swell::validation::to_string(format);
    CaseFile case_file = as_case_file(c);
    case_file.input = swell::validation::write_frames(out, swell::test::render_surface(c), write);
    swell::validation::write_case_file(out / "case.toml", case_file);

    const auto read_back = swell::validation::read_case_file(out / "case.toml");
    const auto in_memory = swell::validation::run_gate(
        read_back, swell::validation::read_frames(read_back), GateOptions{});
    for (int threads : {1, 2}) {
      GateOptions options;
      options.threads = threads;
      const auto from_disk = swell::validation::run_gate(out / "case.toml", options);
      EXPECT_TRUE(from_disk.passed()) << failures(from_disk);
      expect_same_results(from_disk.results, in_memory.results);
      EXPECT_EQ(from_disk.skipped, in_memory.skipped);
      EXPECT_EQ(from_disk.fields, (std::vector<std::string>{"height", "slope_x", "slope_y",
                                                            "disp_x", "disp_y", "jacobian"}));
      EXPECT_EQ(from_disk.frames, 6);
      EXPECT_EQ(from_disk.case_path, (out / "case.toml").string());
      EXPECT_GT(from_disk.read_seconds, 0);
      EXPECT_GE(from_disk.seconds, from_disk.read_seconds);
    }
  }
}

// The files the gate does not read are still required: a missing .npy of a middle frame is
// named, as read_frames names it.
TEST_F(GateFiles, AMissingFileOfAMiddleFrameIsNamed) {
  const OceanCase c = small_case(4);
  swell::validation::FrameWriteOptions write;
  write.format = FrameFormat::npy;
  CaseFile case_file = as_case_file(c);
  case_file.input = swell::validation::write_frames(dir_, swell::test::render_surface(c), write);
  swell::validation::write_case_file(dir_ / "case.toml", case_file);
  fs::remove(dir_ / "frame_0002_dx.npy");
  try {
    (void)swell::validation::run_gate(dir_ / "case.toml");
    ADD_FAILURE() << "no error";
  } catch (const InvalidInput& e) {
    EXPECT_TRUE(contains(e.what(), "frame_0002_dx.npy: missing frame file (frame 2 of 4, disp_x)"))
        << e.what();
  }
}

// Every field of every frame is read and checked, though only the heights of the frames
// between the ends are kept: a NaN in a middle frame's displacement is bad input, named.
TEST_F(GateFiles, ANonFiniteValueInAMiddleFramesFieldIsNamed) {
  for (FrameFormat format : {FrameFormat::exr, FrameFormat::npy}) {
    SCOPED_TRACE(swell::validation::to_string(format));
    const OceanCase c = small_case(5);
    auto frames = swell::test::render_surface(c);
    frames.frames[2].fields.at(Field::disp_x)[17 * 64 + 9] = std::numeric_limits<double>::quiet_NaN();
    swell::validation::FrameWriteOptions write;
    write.format = format;
    const fs::path out = dir_ / swell::validation::to_string(format);
    CaseFile case_file = as_case_file(c);
    case_file.input = swell::validation::write_frames(out, frames, write);
    swell::validation::write_case_file(out / "case.toml", case_file);
    try {
      (void)swell::validation::run_gate(out / "case.toml");
      ADD_FAILURE() << "no error";
    } catch (const InvalidInput& e) {
      const std::string file = format == FrameFormat::exr ? "frame_0002.exr" : "frame_0002_dx.npy";
      EXPECT_TRUE(contains(e.what(), file)) << e.what();
      EXPECT_TRUE(contains(e.what(), "disp_x")) << e.what();
      EXPECT_TRUE(contains(e.what(), "NaN at (i, j) = (9, 17)")) << e.what();
    }
  }
}

// PNG frames (integers through [input] value_range): a right engine passes at 16 bits and an
// engine with its energy doubled fails `energy`, diagnosed. At 8 bits the quantization noise
// (conventions §Tolerances: u = q/√(12 mean v²), here about 1 %) buries every wave vector
// under the checks' rounding floor: bad input, saying so, not a verdict.
TEST_F(GateFiles, PngFramesAreJudgedThroughTheirValueRange) {
  struct Run {
    int bits;
    EngineBug bug;
  };
  for (const Run run : {Run{16, EngineBug::none}, Run{16, EngineBug::energy_doubled},
                        Run{8, EngineBug::none}}) {
    const bool right = run.bug == EngineBug::none;
    SCOPED_TRACE(fmt::format("{} bits, {}", run.bits, right ? "right" : "energy doubled"));
    const OceanCase c = small_case(6);
    auto frames = swell::test::render_surface(c, run.bug);
    const double largest = swell::test::keep_rgb_fields(frames);
    swell::validation::FrameWriteOptions write;
    write.format = FrameFormat::png;
    write.png_bits = run.bits;
    write.png_range = {-1.05 * largest, 1.05 * largest};
    const fs::path out = dir_ / fmt::format("png{}_{}", run.bits, right);
    CaseFile case_file = as_case_file(c);
    case_file.input = swell::validation::write_frames(out, frames, write);
    swell::validation::write_case_file(out / "case.toml", case_file);
    if (run.bits == 8) {
      try {
        (void)swell::validation::run_gate(out / "case.toml");
        ADD_FAILURE() << "no error";
      } catch (const InvalidInput& e) {
        EXPECT_TRUE(contains(e.what(), "rounding")) << e.what();
        EXPECT_TRUE(contains(e.what(), "16-bit")) << e.what();
      }
      continue;
    }
    const auto report = swell::validation::run_gate(out / "case.toml");
    EXPECT_EQ(report.fields, (std::vector<std::string>{"height", "disp_x", "disp_y"}));
    EXPECT_EQ(report.passed(), right) << failures(report);
    if (right) continue;
    const auto energy = std::find_if(report.results.begin(), report.results.end(),
                                     [](const CheckResult& r) { return r.check == "energy"; });
    ASSERT_NE(energy, report.results.end());
    EXPECT_FALSE(energy->passed);
    EXPECT_TRUE(contains(energy->reason, "energy off by a factor 2")) << energy->reason;
  }
}

// ==================================================================== swell gate

class GateCli : public GateFiles {
 protected:
  // Frames of the small case rendered by the test engine (with a bug, or right) into dir_, and
  // the case file that names them.
  fs::path write_engine_frames(EngineBug bug, FrameFormat format = FrameFormat::exr,
                               int frames = 8) {
    return write_engine_frames(bug, small_case(frames), format);
  }
  fs::path write_engine_frames(EngineBug bug, const OceanCase& c, FrameFormat format) {
    swell::validation::FrameWriteOptions write;
    write.format = format;
    CaseFile case_file = as_case_file(c);
    case_file.input = swell::validation::write_frames(dir_ / "frames", swell::test::render_surface(c, bug),
                                                      write);
    case_file.input.files = "frames/" + case_file.input.files;
    swell::validation::write_case_file(dir_ / "case.toml", case_file);
    return dir_ / "case.toml";
  }
};

TEST_F(GateCli, TheRightEnginePassesWithExitZero) {
  const auto case_path = write_engine_frames(EngineBug::none);
  const CliRun run = swell("gate --case " + case_path.string() + " --junit " + path("junit.xml") +
                           " --json " + path("gate.json"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "verdict: PASS")) << run.output;
  EXPECT_TRUE(contains(run.output, "PASS  dispersion.residual")) << run.output;
  EXPECT_TRUE(contains(run.output, "PASS  derived.jacobian")) << run.output;
  const auto json = nlohmann::json::parse(read_text(path("gate.json")));
  EXPECT_EQ(json["pass"], true);
  EXPECT_EQ(json["frames"], 8);
  EXPECT_EQ(json["statistical_checks"], 6);
  const std::string xml = read_text(path("junit.xml"));
  EXPECT_TRUE(contains(xml, "failures=\"0\"")) << xml;
  if (have_python()) {
    EXPECT_EQ(xml_error(path("junit.xml")), "") << xml;
  }
}

TEST_F(GateCli, ABuggyEngineFailsWithExitOneAndTheJunitNamesTheCheck) {
  const auto case_path = write_engine_frames(EngineBug::energy_doubled);
  const CliRun run = swell("gate --case " + case_path.string() + " --junit " + path("junit.xml"));
  ASSERT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "FAIL  energy")) << run.output;
  EXPECT_TRUE(contains(run.output, "verdict: FAIL")) << run.output;
  const std::string xml = read_text(path("junit.xml"));
  EXPECT_TRUE(contains(xml, "<failure message=\"energy: measured ")) << xml;
  EXPECT_TRUE(contains(xml, "energy off by a factor 2")) << xml;
  if (have_python()) {
    EXPECT_EQ(xml_error(path("junit.xml")), "") << xml;
  }
}

// EXR frames are written and judged through OpenEXRCore alone: with swell's OpenImageIO module
// made unloadable, `swell synth` writes EXR and `swell gate` passes it, while a TIFF needs the
// module and is refused (exit 2) naming it and the variable that points to it.
TEST_F(GateCli, ExrFramesNeedNoOpenImageIO) {
  ASSERT_EQ(setenv("SWELL_OPENIMAGEIO_MODULE", "/nonexistent/libswell_openimageio.so", 1), 0);
  const std::string synth = "synth --model jonswap --hs 2 --tp 7 --impl fftw --n 32 --length 300 "
                            "--frames 4 --dt 0.5 --out ";
  const CliRun exr = swell(synth + path("exr"));
  const CliRun gate = swell("gate --case " + path("exr/case.toml"));
  const CliRun tiff = swell(synth + path("tiff") + " --format tiff");
  unsetenv("SWELL_OPENIMAGEIO_MODULE");
  ASSERT_EQ(exr.exit_code, 0) << exr.output;
  EXPECT_EQ(gate.exit_code, 0) << gate.output;
  EXPECT_TRUE(contains(gate.output, "verdict: PASS")) << gate.output;
  EXPECT_EQ(tiff.exit_code, 2) << tiff.output;
  EXPECT_TRUE(contains(tiff.output, "needs OpenImageIO")) << tiff.output;
  EXPECT_TRUE(contains(tiff.output, "/nonexistent/libswell_openimageio.so")) << tiff.output;
}

// A PNG's quantization is judged over every frame, by synth as by the gate: here frame 0's
// rounding leaves waves the gate can judge, frame 1's does not (a drawn case of the soak
// property test, which synth had accepted and the gate refused). One frame is accepted and
// judged; two are refused by synth, naming the rule, with nothing left on disk.
TEST_F(GateCli, SynthRefusesAPngWhoseLaterFrameTheGateWouldRefuse) {
  const std::string synth =
      "synth --model jonswap --hs 0.127381 --tp 7.03813 --gamma 3.5451 --spreading donelan-banner "
      "--wind-dir -92.6847 --n 16 --length 26.8104 --choppiness 1.06091 --dt 1.36372 --seed 872668 "
      "--precision fp32 --impl radix2 --format png --value-range -6.21506,6.21506";
  const CliRun one = swell(synth + " --frames 1 --out " + path("one"));
  ASSERT_EQ(one.exit_code, 0) << one.output;
  const CliRun gate = swell("gate --case " + path("one/case.toml"));
  EXPECT_TRUE(gate.exit_code == 0 || gate.exit_code == 1) << gate.output;
  const CliRun two = swell(synth + " --frames 2 --out " + path("two"));
  EXPECT_EQ(two.exit_code, 2) << two.output;
  EXPECT_TRUE(contains(two.output, "hides every wave vector")) << two.output;
  EXPECT_FALSE(fs::exists(path("two/frame_0000.png")));
}

// The gate's analysis transforms are FFTW estimate plans, and FFTW gives an estimate plan any
// wisdom the process holds: the user's cache of MEASURE-class wisdom (left by swell bench or
// swell fft) once changed the report's last digits; impls/src/backends/fftw.cpp now loads the cache only
// for plans that measure. The same report with and without such wisdom on disk.
TEST_F(GateCli, TheReportDoesNotDependOnTheFftwWisdomCache) {
  OceanCase c = small_case();
  c.grid = Grid::create(128, 128, 800, 800);  // (at 64² the patient plan rounds as the estimate one)
  const auto case_path = write_engine_frames(EngineBug::none, c, FrameFormat::exr);
  std::vector<std::complex<double>> values(128 * 128);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = {std::sin(0.1 * double(i)), std::cos(0.37 * double(i))};
  swell::validation::write_npy(path("noise.npy"), swell::validation::NpyArray::from_values<std::complex<double>>(
                                                      {128, 128}, values));
  auto with_wisdom_directory = [&](const std::string& directory, const std::string& arguments) {
    fs::create_directories(directory);
    const char* before = std::getenv("SWELL_FFTW_WISDOM_DIR");
    const std::string saved = before ? before : "";
    ::setenv("SWELL_FFTW_WISDOM_DIR", directory.c_str(), 1);
    const CliRun run = swell(arguments);
    if (before) {
      ::setenv("SWELL_FFTW_WISDOM_DIR", saved.c_str(), 1);
    } else {
      ::unsetenv("SWELL_FFTW_WISDOM_DIR");
    }
    return run;
  };
  // Patient wisdom for the analysis transform of the 128² frames (c2c forward in fp64).
  const CliRun planned = with_wisdom_directory(
      path("wisdom"), "fft --impl fftw:planner=patient --in " + path("noise.npy") + " --out " + path("out.npy"));
  ASSERT_EQ(planned.exit_code, 0) << planned.output;
  ASSERT_TRUE(fs::exists(dir_ / "wisdom" / "fftw-wisdom-fftw3"));
  const CliRun with = with_wisdom_directory(path("wisdom"), "gate --case " + case_path.string() + " --json " + path("with.json"));
  const CliRun without = with_wisdom_directory(path("empty"), "gate --case " + case_path.string() + " --json " + path("without.json"));
  ASSERT_EQ(with.exit_code, 0) << with.output;
  ASSERT_EQ(without.exit_code, 0) << without.output;
  auto report = [&](const std::string& name) {
    auto json = nlohmann::json::parse(read_text(path(name)));
    json.erase("seconds");  // the only value that may differ between two runs
    return json;
  };
  EXPECT_EQ(report("with.json"), report("without.json"));
}

TEST_F(GateCli, NumpyFramesThroughAnInputPattern) {
  write_engine_frames(EngineBug::none, FrameFormat::npy, 4);
  // The case's own [input] files pattern is replaced by --input (relative to the current
  // directory, here absolute); the channels still come from the case.
  fs::rename(dir_ / "frames", dir_ / "elsewhere");
  const CliRun run = swell("gate --case " + path("case.toml") + " --input " +
                           path("elsewhere/frame_%04d.npy") + " --json -");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto json = nlohmann::json::parse(run.output);  // JSON alone on standard output
  EXPECT_EQ(json["pass"], true);
  EXPECT_EQ(json["frames"], 4);
}

// The options are judged before anything is read: a bad α or thread count is named even when
// the case's frames are missing (it was found only after every frame had been read), and the
// JUnit file then carries the error.
TEST_F(GateCli, BadOptionsAreFoundBeforeAnyFrameIsRead) {
  write_engine_frames(EngineBug::none, FrameFormat::exr, 3);
  fs::remove_all(dir_ / "frames");
  for (const std::string option : {"--alpha 0", "--alpha nan", "--threads -2"}) {
    fs::remove(path("gate.json"));
    const CliRun run = swell("gate --case " + path("case.toml") + " " + option + " --junit " +
                             path("junit.xml") + " --json " + path("gate.json"));
    EXPECT_EQ(run.exit_code, 2) << option << ": " << run.output;
    EXPECT_FALSE(contains(run.output, "missing frame file")) << option << ": " << run.output;
    EXPECT_TRUE(contains(run.output, option.substr(2, option.find(' ') - 2))) << run.output;
    EXPECT_TRUE(contains(read_text(path("junit.xml")), "<error message=")) << option;
    // The JSON report carries the error too, with the exit code.
    const auto json = nlohmann::json::parse(read_text(path("gate.json")));
    EXPECT_EQ(json["pass"], false) << option;
    EXPECT_EQ(json["exit_code"], 2) << option;
    EXPECT_TRUE(contains(json["error"].get<std::string>(), option.substr(2, option.find(' ') - 2))) << option;
  }
  swell::validation::GateOptions options;
  options.alpha = 2;
  try {
    swell::validation::run_gate(dir_ / "case.toml", options);
    ADD_FAILURE() << "alpha 2 accepted";
  } catch (const swell::InvalidInput& e) {
    EXPECT_TRUE(contains(e.what(), "alpha")) << e.what();
  }
}

// --power prints the table from the case alone: its frames need not exist. It refuses the
// options that read frames.
TEST_F(GateCli, PowerPrintsTheTableWithoutFrames) {
  write_engine_frames(EngineBug::none, FrameFormat::exr, 3);
  fs::remove_all(dir_ / "frames");
  const CliRun run = swell("gate --power --case " + path("case.toml") + " --json " + path("power.json"));
  EXPECT_EQ(run.exit_code, 0) << run.output;
  for (const char* line : {"energy factor", "ω, relative, on every wave", "mean direction offset", "spreading s",
                           "JONSWAP γ", "choppiness λ", "time step"}) {
    EXPECT_TRUE(contains(run.output, line)) << line << ": " << run.output;
  }
  const auto json = nlohmann::json::parse(read_text(path("power.json")));
  EXPECT_EQ(json["lines"].size(), 7u);
  EXPECT_EQ(json["precision"], "float");
  const CliRun refused = swell("gate --power --case " + path("case.toml") + " --junit " + path("junit.xml"));
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_TRUE(contains(refused.output, "--power reads no frames")) << refused.output;
}

TEST_F(GateCli, AMissingFrameIsBadInputWithExitTwoAndAJunitError) {
  write_engine_frames(EngineBug::none, FrameFormat::exr, 3);
  fs::remove(dir_ / "frames" / "frame_0002.exr");
  const CliRun run = swell("gate --case " + path("case.toml") + " --junit " + path("junit.xml"));
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, "frame_0002.exr: missing frame file (frame 2 of 3)")) << run.output;
  const std::string xml = read_text(path("junit.xml"));
  EXPECT_TRUE(contains(xml, "<error message=")) << xml;
  EXPECT_TRUE(contains(xml, "frame_0002.exr")) << xml;
  if (have_python()) {
    EXPECT_EQ(xml_error(path("junit.xml")), "") << xml;
  }
}

TEST_F(GateCli, BadCasesAndOptionsExitTwo) {
  write_engine_frames(EngineBug::none, FrameFormat::exr, 2);
  const std::string good = read_text(path("case.toml"));
  struct Bad {
    std::string name, arguments, says;
  };
  write_text(path("unknown_key.toml"), good + "\n[grid2]\nsize = 3\n");
  std::string jpeg = good;
  jpeg.replace(jpeg.find("frame_%04d.exr"), 14, "frame_%04d.jpg");
  write_text(path("jpeg.toml"), jpeg);
  const std::vector<Bad> cases = {
      {"no such case", "--case " + path("nothing.toml"), "nothing.toml"},
      {"unknown section", "--case " + path("unknown_key.toml"), "grid2"},
      {"jpeg in the case", "--case " + path("jpeg.toml"), "'.jpg'"},
      {"jpeg pattern", "--case " + path("case.toml") + " --input " + path("x_%04d.jpg"), "'.jpg'"},
      {"missing --case", "", "--case"},
      {"alpha 0", "--case " + path("case.toml") + " --alpha 0", "alpha"},
      {"alpha 1.5", "--case " + path("case.toml") + " --alpha 1.5", "alpha"},
      {"negative threads", "--case " + path("case.toml") + " --threads -1", "threads"},
      {"unwritable junit", "--case " + path("case.toml") + " --junit " + path("no/such/dir/j.xml"),
       "cannot write JUnit XML"},
  };
  for (const auto& bad : cases) {
    const CliRun run = swell("gate " + bad.arguments);
    EXPECT_EQ(run.exit_code, 2) << bad.name << ": " << run.output;
    EXPECT_TRUE(contains(run.output, bad.says)) << bad.name << ": " << run.output;
  }
}

// ==================================================================== data/cases

// Every example case file reads, and a right engine rendering it (its first 8 frames) passes
// the gate: the examples the docs point to are judged as they stand.
TEST(DataCases, EveryExampleReadsAndARightEnginePassesIt) {
  const fs::path cases = fs::path(SWELL_TEST_DATA_DIR) / "cases";
  ASSERT_TRUE(fs::is_directory(cases)) << cases;
  int count = 0;
  for (const auto& entry : fs::directory_iterator(cases)) {
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().filename().string());
    ++count;
    CaseFile case_file;
    ASSERT_NO_THROW(case_file = swell::validation::read_case_file(entry.path()));
    if (case_file.is_cascade_set()) {
      // A set: every cascade names its frames; the test engine renders each (its band, its
      // random numbers) and the gate judges the set.
      case_file.ocean.frames = std::min(case_file.ocean.frames, 8);
      std::vector<swell::reference::FrameSequence> cascades;
      for (std::size_t c = 0; c < case_file.cascades.size(); ++c) {
        EXPECT_FALSE(case_file.cascades[c].input.files.empty()) << "cascade " << c;
        EXPECT_TRUE(case_file.cascades[c].input.channels.count(Field::height)) << "cascade " << c;
        cascades.push_back(swell::test::render_surface(case_file.cascade_case(c)));
      }
      const auto report = swell::validation::run_cascade_gate(case_file, cascades, nullptr);
      EXPECT_TRUE(report.passed()) << failures(report);
      continue;
    }
    EXPECT_FALSE(case_file.input.files.empty()) << "an example for the gate names its frames";
    EXPECT_TRUE(case_file.input.channels.count(Field::height));
    case_file.ocean.frames = std::min(case_file.ocean.frames, 8);
    auto frames = swell::test::render_surface(case_file.ocean);
    if (case_file.input.value_ranges.empty()) {
      const auto report = swell::validation::run_gate(case_file, frames);
      EXPECT_TRUE(report.passed()) << failures(report);
      continue;
    }
    // Integer frames: quantized as the case says (one range for every field; the fields the
    // case lists, in R, G, B order) and judged from disk.
    const auto range = case_file.input.value_ranges.begin()->second;
    for (auto& frame : frames.frames) {
      for (Field field : swell::reference::kAllFields) {
        if (!case_file.input.channels.count(field)) frame.fields.erase(field);
      }
    }
    swell::validation::FrameWriteOptions write;
    write.format = FrameFormat::png;
    write.png_range = range;
    const fs::path directory = fs::temp_directory_path() /
                               ("swell_data_cases_" + std::to_string(::getpid()));
    fs::remove_all(directory);
    const auto written = swell::validation::write_frames(directory / "frames", frames, write);
    EXPECT_EQ(written.channels, case_file.input.channels);
    EXPECT_EQ(written.value_ranges, case_file.input.value_ranges);
    case_file.input.files = (directory / case_file.input.files).string();
    swell::validation::write_case_file(directory / "case.toml", case_file);
    const auto report = swell::validation::run_gate(directory / "case.toml");
    EXPECT_TRUE(report.passed()) << failures(report);
    // 16 bits over ±3 m: q/√12 over the rms of disp_y (0.2 m, the smallest field) ≈ 1.3·10⁻⁴.
    EXPECT_LT(report.unit_roundoff, 2e-4);
    fs::remove_all(directory);
  }
  EXPECT_GE(count, 3);
}

}  // namespace
