// Levenberg-Marquardt over a state vector with a problem-defined update (so
// rotations can be updated multiplicatively). The problem supplies the
// normal equations J^T J, J^T r and the cost 0.5 |r|^2 at a state, the cost
// alone at a trial state, and how a step is applied. Damping is Marquardt's
// (lambda times the diagonal of J^T J), so parameters of any unit mix.
// Ground code: dynamic Eigen, std::function.
#pragma once

#include <Eigen/Core>
#include <functional>

namespace petra::calib {

struct LmProblem {
  // False when x is outside the model's domain (e.g. a point behind a camera).
  std::function<bool(const Eigen::VectorXd& x, Eigen::MatrixXd& jtj, Eigen::VectorXd& jtr,
                     double& cost)>
      linearise;
  std::function<bool(const Eigen::VectorXd& x, double& cost)> cost;
  // x (+) delta, delta in the space of J^T J (the free parameters); plain
  // addition when empty (then J^T J must be x.size() square).
  std::function<Eigen::VectorXd(const Eigen::VectorXd& x, const Eigen::VectorXd& delta)> plus;
};

struct LmOptions {
  int max_iterations = 200;
  double cost_tolerance = 1e-14;  // relative decrease that counts as converged
  double initial_lambda = 1e-3;
};

struct LmReport {
  bool valid = false;  // the start point was inside the domain
  int iterations = 0;
  double initial_cost = 0;
  double final_cost = 0;
  Eigen::MatrixXd jtj;  // at the solution, for covariances
};

LmReport minimise(const LmProblem& problem, Eigen::VectorXd& x, const LmOptions& options = {});

}  // namespace petra::calib
