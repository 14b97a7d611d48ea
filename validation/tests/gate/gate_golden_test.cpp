// Golden reports of the gate: the gate was made faster on the promise of "the
// same checks and the same verdicts", and this test holds it to more — the whole JSON report
// (every check, statistic, p-value, bound and reason, and the skipped checks) of each engine
// below must stay byte for byte what the gate said before it was optimized:
//
//   catalogue/    every buggy engine of the test engine on the catalogue's seas
//                 (gate_catalogue_test.cpp), the right engines on both, and the diagnoses
//                 beyond the catalogue (another depth, an undeclared loop period, another λ)
//   calibration/  right engines as the calibration tests draw them: 64² over 400 m with s = 10
//                 and their seeds, fp32-rounded and fp64 frames, one, two and eight frames, a
//                 free scale, a non-square grid, α = 0.05, fp32 EXR frames read from disk, and
//                 two cascade sets (additive with its sum, nested)
//
// The frames come from the test engine (fp64, plain FFTW-estimate transforms), not from
// impls::Synthesizer, so that work on the synthesizer's transforms does not move them; the
// cascade sets take their amplitudes from impls::initial_amplitudes, as cascade_test.cpp does.
// Only the wall-clock field ("seconds") is left out, and "case" (a temporary path) is emptied.
//
// Exactness: the report does not depend on the thread count (the gate's groups of checks each
// run on one thread, in a fixed order), so the goldens are made and compared with 2 threads.
// The numbers do depend on the compiler and on the CPU (FFTW picks its SIMD codelets at run
// time; several statistics are themselves rounding errors, e.g. hermitian.symmetry), so each
// golden records the host it was made on ("made_on"). On that host the report must match byte
// for byte; on another, the test compares what must hold anywhere — the same checks in the same
// order with the same verdicts, the same skipped checks — and says that it did only that.
//
// A deliberate change to a check's statistics or wording changes these reports: regenerate them
// with the change, say so in the commit, and review the diff of the goldens:
//
//   SWELL_REGENERATE_GOLDENS=1 build/validation/tests/swell_gate_catalogue_tests --gtest_filter='*GateGolden*'
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "gate/gate_cases.hpp"
#include "swell/impls/synthesizer.hpp"
#include "swell/reference/fields.hpp"
#include "swell/validation/io/case_file.hpp"
#include "swell/validation/io/frame_io.hpp"
#include "swell/validation/gate/gate.hpp"
#include "swell/validation/stats/periodogram.hpp"
#include "test_engine.hpp"

namespace {

namespace fs = std::filesystem;
using swell::reference::FrameSequence;
using swell::reference::Grid;
using swell::reference::OceanCase;
using swell::test::as_case_file;
using swell::test::catalogue_case;
using swell::test::EngineBug;
using swell::test::shallow_case;
using swell::validation::CaseFile;
using swell::validation::GateOptions;
using swell::validation::GateReport;
using Complex = std::complex<double>;

GateOptions two_threads(double alpha = 1e-3) {
  GateOptions options;
  options.alpha = alpha;
  options.threads = 2;
  return options;
}

// ------------------------------------------------------------------ the host

// What the numbers depend on besides the code: the compiler, and the CPU's model and vector
// extensions (FFTW's codelets).
nlohmann::json this_host() {
  std::string model, extensions;
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (model.empty() && line.rfind("model name", 0) == 0) model = line.substr(line.find(':') + 2);
    if (extensions.empty() && line.rfind("flags", 0) == 0) {
      std::istringstream flags(line.substr(line.find(':') + 1));
      for (std::string flag; flags >> flag;) {
        if (flag == "sse2" || flag == "avx" || flag == "avx2" || flag == "fma" || flag == "avx512f") {
          extensions += (extensions.empty() ? "" : " ") + flag;
        }
      }
    }
  }
  return {{"compiler", SWELL_CXX_COMPILER}, {"cpu", model}, {"extensions", extensions}};
}

// ------------------------------------------------------------------ the reports

// The gate's JSON without what changes from run to run.
nlohmann::json comparable(const GateReport& report) {
  auto json = swell::validation::gate_json(report);
  json.erase("seconds");
  json["case"] = "";
  return json;
}

// Heights and every other field rounded to float32, as an fp32 EXR holds them.
FrameSequence as_float32(FrameSequence frames) {
  for (auto& frame : frames.frames) {
    for (auto& [field, values] : frame.fields) {
      for (double& v : values) v = double(float(v));
    }
  }
  frames.unit_roundoff = 0x1p-24;
  return frames;
}

// The calibration tests' sea: the catalogue's at 64² over 400 m with s = 10.
OceanCase calibration_case(long seed) {
  OceanCase c = catalogue_case();
  c.grid = Grid::create(64, 64, 400, 400);
  c.spreading.numbers["s"] = 10.0;
  c.seed = seed;
  return c;
}

GateReport right_engine(const OceanCase& c, bool fp32, double alpha = 1e-3,
                        bool free_scale = false) {
  CaseFile file = as_case_file(c);
  if (free_scale) file.scale = swell::validation::SpectrumScale::free;
  const auto frames = swell::test::render_surface(c);
  return swell::validation::run_gate(file, fp32 ? as_float32(frames) : frames, two_threads(alpha));
}

// The right engine's frames written as fp32 EXR with all six fields and judged from disk.
GateReport from_exr(const OceanCase& c) {
  const fs::path directory =
      fs::temp_directory_path() / ("swell_gate_golden_" + std::to_string(::getpid()));
  fs::remove_all(directory);
  CaseFile file = as_case_file(c);
  swell::validation::FrameWriteOptions write;
  write.format = swell::validation::FrameFormat::exr;
  file.input = swell::validation::write_frames(directory, swell::test::render_surface(c), write);
  swell::validation::write_case_file(directory / "case.toml", file);
  const auto report = swell::validation::run_gate(directory / "case.toml", two_threads());
  fs::remove_all(directory);
  return report;
}

// Cascade sets (cascade_test.cpp's pair and Mitchell's nested pair): heights of h̃0 from
// impls::initial_amplitudes (band weight, Δk and cascade key) at ω(|k|), fp64.
FrameSequence cascade_heights(const OceanCase& c) {
  const auto amplitudes = swell::impls::initial_amplitudes(c);
  const Grid& g = c.grid;
  FrameSequence out;
  out.grid = g;
  out.unit_roundoff = 0x1p-53;
  for (int f = 0; f < c.frames; ++f) {
    const double t = c.time(f);
    std::vector<Complex> spectrum(amplitudes.size());
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        const int n = Grid::signed_index(i, g.nx), m = Grid::signed_index(j, g.ny);
        if (!g.carries_energy(n, m)) continue;
        const std::size_t e = std::size_t(j) * g.nx + i;
        const std::size_t minus = std::size_t((g.ny - j) % g.ny) * g.nx + (g.nx - i) % g.nx;
        const double omega = c.omega(std::hypot(n * g.dkx(), m * g.dky()));
        spectrum[e] = amplitudes[e] * std::polar(1.0, -omega * t) +
                      std::conj(amplitudes[minus]) * std::polar(1.0, omega * t);
      }
    }
    swell::reference::FieldFrame frame;
    frame.time = t;
    frame.fields[swell::reference::Field::height] = swell::validation::field_from_spectrum(spectrum, g);
    out.frames.push_back(std::move(frame));
  }
  return out;
}

std::string cascade_sea() {
  return "[time]\ndt = 0.5\nframes = 8\n[spectrum]\nmodel = \"jonswap\"\nhs = 3.0\ntp = 8.0\n"
         "gamma = 3.3\n[spreading]\nmodel = \"cos2s\"\ns = 10.0\nwind_dir_deg = 30.0\n"
         "[synthesis]\nchoppiness = 1.0\nseed = 700000\n";
}

GateReport cascade_set(const std::string& cascades, bool with_sum) {
  const CaseFile c = swell::validation::parse_case_toml(cascade_sea() + cascades,
                                                        "/tmp/gate_golden/case.toml");
  std::vector<FrameSequence> frames;
  for (std::size_t i = 0; i < c.cascades.size(); ++i) frames.push_back(cascade_heights(c.cascade_case(i)));
  FrameSequence sum;
  if (with_sum) sum = cascade_heights(*c.summed_case());
  return swell::validation::run_cascade_gate(c, frames, with_sum ? &sum : nullptr, two_threads());
}

struct Golden {
  std::string suite, name;
  std::function<GateReport()> report;
};

void PrintTo(const Golden& golden, std::ostream* out) { *out << golden.suite << "/" << golden.name; }

std::vector<Golden> goldens() {
  std::vector<Golden> all;
  // The catalogue: every bug on the sea it is caught on, the complex output of the unpaired −k.
  for (EngineBug bug : swell::test::all_engine_bugs()) {
    const bool shallow = bug == EngineBug::deep_water_dispersion;
    all.push_back({"catalogue", swell::test::to_string(bug), [bug, shallow] {
                     const OceanCase c = shallow ? shallow_case() : catalogue_case();
                     return swell::validation::run_gate(as_case_file(c),
                                                        swell::test::render_surface(c, bug), two_threads());
                   }});
  }
  all.push_back({"catalogue", "independent_minus_k_real_part_complex", [] {
                   swell::test::EngineOptions options;
                   options.keep_imaginary = true;
                   return swell::validation::run_gate(
                       as_case_file(catalogue_case()),
                       swell::test::render_surface(catalogue_case(), EngineBug::independent_minus_k_real_part,
                                                   options),
                       two_threads());
                 }});
  all.push_back({"catalogue", "right_deep", [] { return right_engine(catalogue_case(), false); }});
  all.push_back({"catalogue", "right_shallow", [] { return right_engine(shallow_case(), false); }});
  // Diagnoses beyond the catalogue: frames of another depth, loop period, choppiness.
  auto rendered_as = [](const std::function<void(OceanCase&)>& change, bool shallow) {
    return [change, shallow] {
      const OceanCase declared = shallow ? shallow_case() : catalogue_case();
      OceanCase engine = declared;
      change(engine);
      return swell::validation::run_gate(as_case_file(declared), swell::test::render_surface(engine),
                                         two_threads());
    };
  };
  all.push_back({"catalogue", "depth_25_declared_10", rendered_as([](OceanCase& c) { c.depth = 25; }, true)});
  all.push_back({"catalogue", "undeclared_loop_period_40",
                 rendered_as([](OceanCase& c) { c.loop_period = 40; }, false)});
  all.push_back({"catalogue", "choppiness_1_2_declared_0_8",
                 rendered_as([](OceanCase& c) { c.choppiness = 1.2; }, false)});

  // Right engines of the calibration tests.
  for (long seed : {500000L, 500001L, 500002L, 500003L}) {
    all.push_back({"calibration", "fp32_64_seed" + std::to_string(seed),
                   [seed] { return right_engine(calibration_case(seed), true); }});
  }
  for (long seed : {500004L, 500005L}) {
    all.push_back({"calibration", "fp64_64_seed" + std::to_string(seed),
                   [seed] { return right_engine(calibration_case(seed), false); }});
  }
  all.push_back({"calibration", "fp32_64_alpha_0_05", [] { return right_engine(calibration_case(500006), true, 0.05); }});
  all.push_back({"calibration", "fp32_128_one_frame", [] {
                   OceanCase c = calibration_case(901010);
                   c.grid = Grid::create(128, 128, 800, 800);
                   c.frames = 1;
                   return right_engine(c, true);
                 }});
  all.push_back({"calibration", "fp32_64_two_frames", [] {
                   OceanCase c = calibration_case(900020);
                   c.frames = 2;
                   return right_engine(c, true);
                 }});
  all.push_back({"calibration", "fp32_64x32_non_square", [] {
                   OceanCase c = calibration_case(500007);
                   c.grid = Grid::create(64, 32, 400, 200);
                   return right_engine(c, true);
                 }});
  all.push_back({"calibration", "fp64_64_free_scale",
                 [] { return right_engine(calibration_case(500008), false, 1e-3, true); }});
  all.push_back({"calibration", "exr_64_six_fields", [] { return from_exr(calibration_case(500009)); }});
  all.push_back({"calibration", "cascades_additive_with_sum", [] {
                   return cascade_set(
                       "[cascades]\nrelation = \"additive\"\n"
                       "[[cascade]]\nn = 64\nlength = 1000.0\nband = [0.0, 0.1]\n"
                       "[[cascade]]\nn = 64\nlength = 250.0\nband = [0.1, 0.8]\n",
                       true);
                 }});
  all.push_back({"calibration", "cascades_nested", [] {
                   return cascade_set("[cascades]\nrelation = \"nested\"\n[[cascade]]\nn = 64\nlength = 1000.0\n"
                                      "[[cascade]]\nn = 256\nlength = 1000.0\n",
                                      false);
                 }});
  return all;
}

// One line per key of the report, and one per check: small files whose diffs name the check.
std::string render(const nlohmann::json& report) {
  std::string out = "{";
  for (auto it = report.begin(); it != report.end(); ++it) {
    out += (it == report.begin() ? "\n " : ",\n ") + nlohmann::json(it.key()).dump() + ": ";
    if (it.key() != "checks") {
      out += it.value().dump();
      continue;
    }
    out += "[";
    for (std::size_t c = 0; c < it.value().size(); ++c) {
      out += (c == 0 ? "\n  " : ",\n  ") + it.value()[c].dump();
    }
    out += "\n ]";
  }
  return out + "\n}";
}

fs::path golden_path(const Golden& golden) {
  return fs::path(SWELL_GOLDEN_DIR) / golden.suite / (golden.name + ".json");
}

bool regenerating() {
  const char* value = std::getenv("SWELL_REGENERATE_GOLDENS");
  return value && std::string(value) == "1";
}

// The first line where two renderings differ, with its neighbours, for the failure message.
std::string first_difference(const std::string& expected, const std::string& actual) {
  std::istringstream a(expected), b(actual);
  std::string x, y;
  for (int line = 1;; ++line) {
    const bool more_a = bool(std::getline(a, x)), more_b = bool(std::getline(b, y));
    if (!more_a && !more_b) return "(no difference)";
    if (x != y || more_a != more_b) {
      return "line " + std::to_string(line) + "\n  golden: " + (more_a ? x : "(end)") +
             "\n  now:    " + (more_b ? y : "(end)");
    }
  }
}

// What must hold on any host: the checks, their order and verdicts, the skipped checks.
nlohmann::json verdicts(const nlohmann::json& report) {
  nlohmann::json out = {{"skipped", report["skipped"]}, {"pass", report["pass"]},
                        {"statistical_checks", report["statistical_checks"]}};
  for (const auto& check : report["checks"]) {
    out["checks"].push_back({{"check", check["check"]}, {"pass", check["pass"]}});
  }
  return out;
}

// FFTW's estimate plans take any wisdom the process holds (FFTW manual §4.7), so the analysis
// transforms' rounding would depend on the wisdom file of the machine's cache. The goldens are
// made and compared with none: an empty wisdom directory, set before the process' first plan
// (ctest runs each test in its own process; run alone, filter on '*GateGolden*').
void without_fftw_wisdom() {
  static const struct EmptyDirectory {
    EmptyDirectory() {
      char pattern[] = "/tmp/swell_golden_wisdom_XXXXXX";
      if (const char* made = ::mkdtemp(pattern)) {
        path = made;
        ::setenv("SWELL_FFTW_WISDOM_DIR", made, 1);
      }
    }
    ~EmptyDirectory() {
      std::error_code ignored;
      if (!path.empty()) fs::remove_all(path, ignored);
    }
    std::string path;
  } directory;
}

class GateGolden : public ::testing::TestWithParam<Golden> {};

TEST_P(GateGolden, TheGateReportIsTheGoldenOne) {
  without_fftw_wisdom();
  const Golden& golden = GetParam();
  const nlohmann::json report = comparable(golden.report());
  const std::string rendered = render(report);
  const fs::path path = golden_path(golden);
  if (regenerating()) {
    fs::create_directories(path.parent_path());
    std::ofstream(path) << "{\"made_on\": " << this_host().dump() << ",\n\"report\": " << rendered << "}\n";
    GTEST_SKIP() << "wrote " << path;
  }
  std::ifstream in(path);
  ASSERT_TRUE(in) << path << " is missing; make it with SWELL_REGENERATE_GOLDENS=1";
  const nlohmann::json stored = nlohmann::json::parse(in);
  if (stored["made_on"] == this_host()) {
    const std::string expected = render(stored["report"]);
    EXPECT_TRUE(expected == rendered) << golden.suite << "/" << golden.name
                                  << ": the report differs from its golden at "
                                  << first_difference(expected, rendered);
  } else {
    EXPECT_EQ(verdicts(stored["report"]).dump(1), verdicts(report).dump(1))
        << golden.suite << "/" << golden.name << ": other checks or verdicts than the golden's";
    std::cout << "[ golden ] " << golden.name << ": made on " << stored["made_on"].dump()
              << ", this host is " << this_host().dump()
              << ": compared checks and verdicts only, not the numbers\n";
  }
}

INSTANTIATE_TEST_SUITE_P(Reports, GateGolden, ::testing::ValuesIn(goldens()), [](const auto& info) {
  return info.param.suite + "_" + info.param.name;
});

}  // namespace
