#include "sim/calib/levenberg_marquardt.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

namespace petra::calib {

LmReport minimise(const LmProblem& problem, Eigen::VectorXd& x, const LmOptions& options) {
  LmReport report;
  // The step lives in the problem's free-parameter space, which may be
  // smaller than the state (fixed parameters) when the problem supplies plus().
  Eigen::MatrixXd jtj;
  Eigen::VectorXd jtr;
  double cost = 0;
  if (!problem.linearise(x, jtj, jtr, cost) || !std::isfinite(cost)) return report;
  report.valid = true;
  report.initial_cost = cost;
  double lambda = options.initial_lambda;
  for (int it = 0; it < options.max_iterations; ++it) {
    report.iterations = it + 1;
    const double diag_floor = 1e-12 * std::max(1e-300, jtj.diagonal().maxCoeff());
    bool accepted = false;
    bool converged = false;
    while (lambda < 1e16) {
      Eigen::MatrixXd a = jtj;
      for (Eigen::Index k = 0; k < jtj.rows(); ++k)
        a(k, k) += lambda * std::max(jtj(k, k), diag_floor);
      const Eigen::VectorXd delta = a.ldlt().solve(-jtr);
      if (!delta.allFinite()) {
        lambda *= 10;
        continue;
      }
      const Eigen::VectorXd trial =
          problem.plus ? problem.plus(x, delta) : Eigen::VectorXd(x + delta);
      double trial_cost = 0;
      if (problem.cost(trial, trial_cost) && std::isfinite(trial_cost) && trial_cost <= cost) {
        converged = cost - trial_cost <= options.cost_tolerance * cost;
        x = trial;
        lambda = std::max(lambda / 3, 1e-12);
        accepted = true;
        break;
      }
      lambda *= 4;
    }
    if (!accepted) break;  // no step lowers the cost: a minimum
    if (!problem.linearise(x, jtj, jtr, cost)) break;
    if (converged) break;
  }
  report.final_cost = cost;
  report.jtj = jtj;
  return report;
}

}  // namespace petra::calib
