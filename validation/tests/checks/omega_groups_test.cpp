// checks/ocean/analysis.hpp's groups of equal ω: the resolved waves' groups made from the half
// plane's (subset_groups) are those group_by_omega makes of the resolved waves themselves.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "checks/ocean/analysis.hpp"

namespace {

using swell::validation::ocean_analysis::group_by_omega;
using swell::validation::ocean_analysis::subset_groups;
using swell::validation::ocean_analysis::Wave;

TEST(OmegaGroups, ASubsetsGroupsAreTheOnesItsOwnSortMakes) {
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> level(0, 40);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<Wave> waves(3000);
  for (Wave& w : waves) w.omega = 0.1 * level(rng);  // many waves share each ω
  for (double kept : {0.0, 0.02, 0.5, 1.0}) {
    std::vector<std::size_t> positions;
    std::vector<Wave> subset;
    for (std::size_t i = 0; i < waves.size(); ++i) {
      if (uniform(rng) < kept) {
        positions.push_back(i);
        subset.push_back(waves[i]);
      }
    }
    const auto from_all = subset_groups(group_by_omega(waves), positions);
    const auto own = group_by_omega(subset);
    EXPECT_EQ(from_all.omegas, own.omegas) << "kept " << kept;
    EXPECT_EQ(from_all.group, own.group) << "kept " << kept;
  }
}

}  // namespace
