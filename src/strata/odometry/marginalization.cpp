#include "strata/odometry/marginalization.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "strata/core/error.h"

namespace strata::odometry {
namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Ambient Jacobian (rows x size, row-major as Ceres wants) times the PlusJacobian.
Eigen::MatrixXd toTangent(const RowMajor& J_ambient, const PriorBlock& block) {
  if (!block.manifold) return J_ambient;
  RowMajor plus(block.size, block.manifold->TangentSize());
  block.manifold->PlusJacobian(block.data, plus.data());
  return J_ambient * plus;
}

struct Linearisation {
  Eigen::MatrixXd H;
  Eigen::VectorXd g;
};

}  // namespace

LinearPrior::LinearPrior(std::vector<PriorBlock> blocks, Eigen::MatrixXd J, Eigen::VectorXd r0)
    : blocks_(std::move(blocks)), J_(std::move(J)), r0_(std::move(r0)) {
  set_num_residuals(static_cast<int>(r0_.size()));
  for (const PriorBlock& b : blocks_) {
    mutable_parameter_block_sizes()->push_back(b.size);
    x0_.emplace_back(b.data, b.data + b.size);
  }
}

std::vector<double*> LinearPrior::blockPointers() const {
  std::vector<double*> pointers;
  for (const PriorBlock& b : blocks_) pointers.push_back(b.data);
  return pointers;
}

bool LinearPrior::Evaluate(double const* const* parameters, double* residuals,
                           double** jacobians) const {
  Eigen::Map<Eigen::VectorXd> r(residuals, num_residuals());
  r = r0_;
  int col = 0;
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    const PriorBlock& b = blocks_[i];
    const int t = b.tangentSize();
    Eigen::VectorXd dx(t);
    if (b.manifold) {
      if (!b.manifold->Minus(parameters[i], x0_[i].data(), dx.data())) return false;
    } else {
      for (int k = 0; k < b.size; ++k) dx[k] = parameters[i][k] - x0_[i][static_cast<size_t>(k)];
    }
    r += J_.middleCols(col, t) * dx;
    if (jacobians && jacobians[i]) {
      Eigen::Map<RowMajor> out(jacobians[i], num_residuals(), b.size);
      if (b.manifold) {
        RowMajor minus(t, b.size);
        if (!b.manifold->MinusJacobian(parameters[i], minus.data())) return false;
        out = J_.middleCols(col, t) * minus;
      } else {
        out = J_.middleCols(col, t);
      }
    }
    col += t;
  }
  return true;
}

std::unique_ptr<LinearPrior> makeDiagonalPrior(const std::vector<PriorBlock>& blocks,
                                               const Eigen::VectorXd& sigmas) {
  const Eigen::VectorXd information_sqrt = sigmas.cwiseInverse();
  return std::make_unique<LinearPrior>(blocks, Eigen::MatrixXd(information_sqrt.asDiagonal()),
                                       Eigen::VectorXd::Zero(sigmas.size()));
}

std::unique_ptr<LinearPrior> marginalise(
    const std::vector<LinearisedFactor>& factors, const std::set<double*>& marginalised,
    const std::map<double*, const ceres::Manifold*>& manifolds) {
  // Order: marginalised blocks first, then kept ones, each at a tangent offset.
  std::vector<PriorBlock> order;
  std::map<double*, int> offset;
  auto add = [&](double* data, int size, bool want_marginalised) {
    if (offset.count(data) || (marginalised.count(data) > 0) != want_marginalised) return;
    PriorBlock b{data, size, nullptr};
    const auto m = manifolds.find(data);
    if (m != manifolds.end()) b.manifold = m->second;
    offset[data] = 0;
    order.push_back(b);
  };
  for (bool first : {true, false}) {
    for (const LinearisedFactor& f : factors) {
      for (std::size_t i = 0; i < f.blocks.size(); ++i) {
        add(f.blocks[i], f.cost->parameter_block_sizes()[i], first);
      }
    }
  }
  int n = 0, m = 0;
  for (const PriorBlock& b : order) {
    offset[b.data] = n;
    if (marginalised.count(b.data)) m += b.tangentSize();
    n += b.tangentSize();
  }
  Linearisation lin{Eigen::MatrixXd::Zero(n, n), Eigen::VectorXd::Zero(n)};
  for (const LinearisedFactor& f : factors) {
    const int rows = f.cost->num_residuals();
    const std::size_t nb = f.blocks.size();
    std::vector<RowMajor> J(nb);
    std::vector<double*> jac_ptrs(nb);
    for (std::size_t i = 0; i < nb; ++i) {
      J[i].resize(rows, f.cost->parameter_block_sizes()[i]);
      jac_ptrs[i] = J[i].data();
    }
    Eigen::VectorXd r(rows);
    if (!f.cost->Evaluate(f.blocks.data(), r.data(), jac_ptrs.data())) {
      throw Error("marginalise: a factor failed to evaluate at the current estimate");
    }
    double weight = 1.0;
    if (f.loss) {
      double rho[3];
      f.loss->Evaluate(r.squaredNorm(), rho);
      weight = std::sqrt(std::max(rho[1], 0.0));
    }
    r *= weight;
    std::vector<Eigen::MatrixXd> Jt(nb);
    std::vector<int> cols(nb);
    for (std::size_t i = 0; i < nb; ++i) {
      const PriorBlock& b = order[static_cast<std::size_t>(
          std::find_if(order.begin(), order.end(),
                       [&](const PriorBlock& o) { return o.data == f.blocks[i]; }) -
          order.begin())];
      Jt[i] = weight * toTangent(J[i], b);
      cols[i] = offset[b.data];
    }
    for (std::size_t a = 0; a < nb; ++a) {
      lin.g.segment(cols[a], Jt[a].cols()) += Jt[a].transpose() * r;
      for (std::size_t b = 0; b < nb; ++b) {
        lin.H.block(cols[a], cols[b], Jt[a].cols(), Jt[b].cols()) += Jt[a].transpose() * Jt[b];
      }
    }
  }
  const int k = n - m;
  if (k == 0) return nullptr;
  // Schur complement with a pseudo-inverse of H_mm.
  Eigen::MatrixXd Hmm = 0.5 * (lin.H.topLeftCorner(m, m) + lin.H.topLeftCorner(m, m).transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig_m(Hmm);
  const double max_m = std::max(eig_m.eigenvalues().maxCoeff(), 0.0);
  const Eigen::VectorXd inv_m =
      (eig_m.eigenvalues().array() > 1e-8 * max_m).select(eig_m.eigenvalues().cwiseInverse(), 0.0);
  const Eigen::MatrixXd Hmm_inv =
      eig_m.eigenvectors() * inv_m.asDiagonal() * eig_m.eigenvectors().transpose();
  const Eigen::MatrixXd Hkm = lin.H.bottomLeftCorner(k, m);
  Eigen::MatrixXd Hs = lin.H.bottomRightCorner(k, k) - Hkm * Hmm_inv * Hkm.transpose();
  Hs = 0.5 * (Hs + Hs.transpose());
  const Eigen::VectorXd gs = lin.g.tail(k) - Hkm * Hmm_inv * lin.g.head(m);
  // Back to a residual: J^T J = Hs, J^T r0 = gs.
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Hs);
  const double max_s = std::max(eig.eigenvalues().maxCoeff(), 0.0);
  const Eigen::ArrayXd s = eig.eigenvalues().array();
  const Eigen::ArrayXd keep = (s > 1e-8 * max_s).cast<double>();
  const Eigen::VectorXd sqrt_s = (s.max(0.0).sqrt() * keep).matrix();
  const Eigen::VectorXd inv_sqrt_s = ((s.max(1e-300).sqrt().inverse()) * keep).matrix();
  Eigen::MatrixXd J = sqrt_s.asDiagonal() * eig.eigenvectors().transpose();
  Eigen::VectorXd r0 = inv_sqrt_s.asDiagonal() * eig.eigenvectors().transpose() * gs;
  std::vector<PriorBlock> kept;
  for (const PriorBlock& b : order) {
    if (!marginalised.count(b.data)) kept.push_back(b);
  }
  return std::make_unique<LinearPrior>(std::move(kept), std::move(J), std::move(r0));
}

}  // namespace strata::odometry
