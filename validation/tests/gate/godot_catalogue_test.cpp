// The Godot ocean's conventions (support/godot_engine.hpp), each named by the check that fails
// on it — alone, and all together with half-precision storage — and the right engine in half
// passing.
#include <gtest/gtest.h>

#include <iostream>
#include <string>

#include "gate/gate_cases.hpp"
#include "godot_engine.hpp"
#include "swell/validation/gate/gate.hpp"

namespace {

using swell::test::GodotConventions;
using swell::validation::GateOptions;
using swell::validation::GateReport;

struct Expected {
  std::string check, naming;
};

std::string failures(const GateReport& report) {
  std::string out;
  for (const auto& r : report.results) {
    if (!r.passed) out += "\n  FAIL " + r.check + ": " + r.reason;
  }
  return out;
}

void expect_named(const GateReport& report, const Expected& e, const std::string& what) {
  for (const auto& r : report.results) {
    if (r.check != e.check) continue;
    EXPECT_FALSE(r.passed) << what << ": " << r.check << " passed: " << r.reason;
    EXPECT_NE(r.reason.find(e.naming), std::string::npos) << what << ": '" << e.naming << "' not in " << r.reason;
    std::cout << "[ godot ] " << what << " → " << r.check << ": " << r.reason << "\n";
    return;
  }
  ADD_FAILURE() << what << ": no result " << e.check << failures(report);
}

GateReport judge(const GodotConventions& godot) {
  const auto c = swell::test::catalogue_case();
  return swell::validation::run_gate(swell::test::as_case_file(c), swell::test::render_godot(c, godot),
                                     GateOptions{});
}

const Expected kEnergy{"energy", "× 8 = 2 × 2 × 2"};
const Expected kWind{"direction.distribution", "against the wind"};
const Expected kNyquist{"spectrum.empty_energy", "the Nyquist row and column carry"};
const Expected kLeak{"derived.disp_y", "on the Nyquist row and column"};
const Expected kNormalMap{"derived.slope_x", "1 + |∂Dx/∂x|"};

TEST(GodotCatalogue, EachConventionAloneIsNamedByItsCheck) {
  GodotConventions energy, wind, nyquist, leak, normal_map;
  energy.energy_times_8 = true;
  wind.against_wind = true;
  nyquist.nyquist_filled = true;
  leak.packed_leak = true;
  normal_map.normal_map = true;
  expect_named(judge(energy), kEnergy, "energy × 8");
  expect_named(judge(wind), kWind, "against the wind");
  expect_named(judge(nyquist), kNyquist, "Nyquist filled");
  expect_named(judge(leak), kLeak, "packed leak");
  expect_named(judge(normal_map), kNormalMap, "normal map");
  GodotConventions half;
  half.half = true;
  const auto right = judge(half);
  EXPECT_TRUE(right.passed()) << "half alone" << failures(right);
}

TEST(GodotCatalogue, AllTogetherInHalfEachIsStillNamed) {
  GodotConventions all;
  all.energy_times_8 = all.against_wind = all.nyquist_filled = all.packed_leak = all.normal_map = all.half = true;
  const auto report = judge(all);
  EXPECT_FALSE(report.passed());
  for (const Expected& e : {kEnergy, kWind, kNyquist, kNormalMap}) expect_named(report, e, "all together");
  // disp_y carries both Nyquist energies (the row and column filled, and the packed leak): named.
  expect_named(report, {"derived.disp_y", "on the Nyquist row and column"}, "all together");
}

}  // namespace
