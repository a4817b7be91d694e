#pragma once
// Marginalisation of parameter blocks into a linear prior (Schur complement), as in sliding-window
// visual-inertial estimators (Leutenegger et al. OKVIS, Qin et al. VINS-Mono):
// the factors touching the dropped blocks are linearised at the current estimate, the dropped
// blocks are eliminated from the Gauss-Newton system, and what remains is kept as
//     r(x) = r0 + J (x [-] x0)
// over the kept blocks, with J fixed at x0 (the first estimate) while the other factors on those
// blocks are re-linearised at every solve (NOTE: not first-estimate Jacobians, so the prior may
// make yaw and position weakly observable where they are not: the usual, accepted inconsistency).
#include <ceres/cost_function.h>
#include <ceres/loss_function.h>
#include <ceres/manifold.h>

#include <Eigen/Core>
#include <map>
#include <memory>
#include <set>
#include <vector>

namespace strata::odometry {

/// A parameter block as the prior sees it; manifold nullptr: Euclidean.
struct PriorBlock {
  double* data = nullptr;
  int size = 0;
  const ceres::Manifold* manifold = nullptr;
  int tangentSize() const { return manifold ? manifold->TangentSize() : size; }
};

/// r = r0 + J dx with dx_b = Minus(x_b, x0_b) per block. Its ambient Jacobian is J_b times the
/// manifold's MinusJacobian at x_b, so Ceres' product with the PlusJacobian gives J_b back.
/// Not thread safe to evaluate concurrently with a change of the blocks it points to.
class LinearPrior final : public ceres::CostFunction {
 public:
  /// x0 is read from the blocks now. J: rows x (sum of tangent sizes), r0: rows.
  LinearPrior(std::vector<PriorBlock> blocks, Eigen::MatrixXd J, Eigen::VectorXd r0);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

  const std::vector<PriorBlock>& blocks() const { return blocks_; }
  std::vector<double*> blockPointers() const;
  const Eigen::MatrixXd& jacobian() const { return J_; }

 private:
  std::vector<PriorBlock> blocks_;
  std::vector<std::vector<double>> x0_;
  Eigen::MatrixXd J_;
  Eigen::VectorXd r0_;
};

/// A prior with diagonal information: r = (x [-] x_now) / sigma per tangent coordinate.
std::unique_ptr<LinearPrior> makeDiagonalPrior(const std::vector<PriorBlock>& blocks,
                                               const Eigen::VectorXd& sigmas);

/// One factor to linearise: not owned; loss may be nullptr.
struct LinearisedFactor {
  const ceres::CostFunction* cost = nullptr;
  const ceres::LossFunction* loss = nullptr;
  std::vector<double*> blocks;
};

/// Eliminates `marginalised` from the factors' Gauss-Newton system and returns the prior on the
/// other blocks they touch (nullptr if none remain). `manifolds` names the non-Euclidean blocks.
/// Robust losses are applied by reweighting with sqrt(rho'(s)) (Triggs' first-order correction
/// without the curvature term). The pseudo-inverse of the eliminated block drops eigenvalues below
/// 1e-8 times the largest, so unobservable directions add no information.
/// Throws Error when a factor fails to evaluate.
std::unique_ptr<LinearPrior> marginalise(
    const std::vector<LinearisedFactor>& factors, const std::set<double*>& marginalised,
    const std::map<double*, const ceres::Manifold*>& manifolds);

}  // namespace strata::odometry
