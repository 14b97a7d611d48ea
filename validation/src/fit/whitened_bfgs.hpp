#pragma once
// What both JONSWAP fits (jonswap_fit.cpp, buoy_fit.cpp) minimize with: Ceres's dense BFGS over
// whitened coordinates u, φ = φ0 + M u with M = L⁻ᵀ from the information F = L Lᵀ of the free
// coordinates (docs/fit.md §3). There the Hessian of the cost is ≈ the identity, so BFGS starts
// well scaled, and the gradient in u is the distance to the optimum in standard errors: the
// gradient tolerance is a statement about statistics, not units. And the level both fits' 95 %
// profile-likelihood intervals are cut at.
#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <array>
#include <string>

namespace swell::validation::fit_detail {

// χ²₁(0.95) = z²_0.975: the likelihood-ratio interval {ψ : 2(ℓ(θ̂) − ℓ_p(ψ)) ≤ 3.8415}
// (e.g. Pawitan 2001, "In All Likelihood", §3.4 and §10.6).
inline constexpr double kZ975 = 1.959963984540054;

// M = L⁻ᵀ for the M free coordinates (all N but `fixed`; fixed = −1: none) embedded in N rows;
// the identity on the free coordinates if F is not positive definite there.
template <int N, int M>
Eigen::Matrix<double, N, M> whitening(const Eigen::Matrix<double, N, N>& f, int fixed) {
  std::array<int, M> free{};
  for (int i = 0, j = 0; i < N; ++i) {
    if (i != fixed) free[j++] = i;
  }
  Eigen::Matrix<double, M, M> f_free;
  for (int a = 0; a < M; ++a) {
    for (int b = 0; b < M; ++b) f_free(a, b) = f(free[a], free[b]);
  }
  Eigen::Matrix<double, M, M> l_inverse_t = Eigen::Matrix<double, M, M>::Identity();
  const Eigen::LLT<Eigen::Matrix<double, M, M>> llt(f_free);
  if (llt.info() == Eigen::Success) {
    const Eigen::Matrix<double, M, M> l = llt.matrixL();
    const Eigen::Matrix<double, M, M> inv =
        l.template triangularView<Eigen::Lower>().solve(Eigen::Matrix<double, M, M>::Identity());
    if (inv.allFinite()) l_inverse_t = inv.transpose();
  }
  Eigen::Matrix<double, N, M> out = Eigen::Matrix<double, N, M>::Zero();
  for (int a = 0; a < M; ++a) out.row(free[a]) = l_inverse_t.row(a);
  return out;
}

struct BfgsRun {
  int iterations = 0;
  bool converged = false;
  std::string report;  // Ceres's brief report
};

// Minimizes `cost` (a Ceres autodiff first-order functor of M whitened coordinates, owned by the
// problem) from u = 0, leaving the minimizer in u. Stops where the gradient in u is below
// `gradient_tolerance` standard errors. The relative cost change is not a useful criterion (the
// cost is relative to the start and may be tiny), so function_tolerance is effectively off, and
// parameter_tolerance only stops steps below rounding.
template <typename Cost, int M>
BfgsRun minimize_bfgs(Cost* cost, double (&u)[M], double gradient_tolerance) {
  ceres::GradientProblem problem(new ceres::AutoDiffFirstOrderFunction<Cost, M>(cost));
  ceres::GradientProblemSolver::Options options;
  options.line_search_direction_type = ceres::BFGS;
  options.max_num_iterations = 500;
  options.gradient_tolerance = gradient_tolerance;
  options.function_tolerance = 1e-15;
  options.parameter_tolerance = 1e-13;
  options.logging_type = ceres::SILENT;
  ceres::GradientProblemSolver::Summary summary;
  ceres::Solve(options, problem, u, &summary);
  return {int(summary.iterations.size()) - 1, summary.termination_type == ceres::CONVERGENCE,
          summary.BriefReport()};
}

}  // namespace swell::validation::fit_detail
