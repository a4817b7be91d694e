// OMPL adapters of RrtPlanner (rrt_ompl_adapters.h).
#include "strata/plan/internal/rrt_ompl_adapters.h"

#include <ompl/base/spaces/RealVectorStateSpace.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace strata::plan::internal {
namespace ob = ompl::base;

Eigen::Vector3f toVector(const ob::State* s) {
  const double* v = s->as<ob::RealVectorStateSpace::StateType>()->values;
  return Eigen::Vector3d(v[0], v[1], v[2]).cast<float>();
}

void fromVector(const Eigen::Vector3f& p_W, ob::State* s) {
  double* v = s->as<ob::RealVectorStateSpace::StateType>()->values;
  for (int i = 0; i < 3; ++i) v[i] = p_W[i];
}

CapsuleStateValidity::CapsuleStateValidity(const ob::SpaceInformationPtr& si, Robot robot)
    : ob::StateValidityChecker(si), robot_(robot) {}

bool CapsuleStateValidity::isValid(const ob::State* s) const {
  const Eigen::Vector3f p = toVector(s);
  return robot_.checker->segmentFree(p, p, robot_.radius_m, robot_.unknown);
}

CapsuleMotionValidator::CapsuleMotionValidator(const ob::SpaceInformationPtr& si, Robot robot)
    : ob::MotionValidator(si), robot_(robot) {}

bool CapsuleMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2) const {
  const bool free =
      robot_.checker->segmentFree(toVector(s1), toVector(s2), robot_.radius_m, robot_.unknown);
  (free ? valid_ : invalid_)++;
  return free;
}

bool CapsuleMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2,
                                         std::pair<ob::State*, double>& last_valid) const {
  const Eigen::Vector3f a = toVector(s1);
  const Eigen::Vector3f b = toVector(s2);
  const float h = 0.5f * robot_.checker->voxelSize();
  const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / h)));
  std::vector<EsdfSegment> pieces;
  for (int k = 0; k < n; ++k) {
    pieces.push_back(
        {a + (b - a) * (static_cast<float>(k) / n), a + (b - a) * (static_cast<float>(k + 1) / n)});
  }
  const std::vector<std::uint8_t> free =
      robot_.checker->segmentsFree(pieces, robot_.radius_m, robot_.unknown);
  const auto first_blocked = std::find(free.begin(), free.end(), std::uint8_t{0});
  if (first_blocked == free.end()) {
    ++valid_;
    return true;
  }
  ++invalid_;
  last_valid.second = static_cast<double>(first_blocked - free.begin()) / n;
  if (last_valid.first != nullptr) {
    fromVector(a + (b - a) * static_cast<float>(last_valid.second), last_valid.first);
  }
  return false;
}

template <typename Draw>
void FreeSampleBuffer::refill(Draw draw) {
  std::vector<Eigen::Vector3f> drawn;
  Eigen::Vector3f p;
  while (static_cast<int>(drawn.size()) < kSampleBatch && draw(&p)) drawn.push_back(p);
  std::vector<EsdfSegment> points;  // zero-length capsules, as CapsuleStateValidity
  for (const Eigen::Vector3f& q : drawn) points.push_back({q, q});
  const std::vector<std::uint8_t> free =
      robot_.checker->segmentsFree(points, robot_.radius_m, robot_.unknown);
  buffer_.clear();
  next_ = 0;
  for (std::size_t i = 0; i < drawn.size(); ++i) {
    if (free[i] != 0) buffer_.push_back(drawn[i]);
  }
  if (buffer_.empty()) buffer_ = drawn;
}

FreeSpaceSampler::FreeSpaceSampler(const ob::StateSpace* space, Robot robot)
    : ob::StateSampler(space), uniform_(space->allocDefaultStateSampler()), buffer_(robot) {}

void FreeSpaceSampler::sampleUniform(ob::State* state) {
  if (buffer_.empty()) {
    buffer_.refill([&](Eigen::Vector3f* p) {
      uniform_->sampleUniform(state);
      *p = toVector(state);
      return true;
    });
  }
  fromVector(buffer_.pop(), state);
}

void FreeSpaceSampler::sampleUniformNear(ob::State* state, const ob::State* near, double distance) {
  uniform_->sampleUniformNear(state, near, distance);
}

void FreeSpaceSampler::sampleGaussian(ob::State* state, const ob::State* mean, double std_dev) {
  uniform_->sampleGaussian(state, mean, std_dev);
}

namespace {

/// Wraps OMPL's informed sampler: samples under one cost bound come from a FreeSampleBuffer.
class BatchedInformedSampler final : public ob::InformedSampler {
 public:
  BatchedInformedSampler(const ob::ProblemDefinitionPtr& problem, unsigned int max_calls,
                         ob::InformedSamplerPtr inner, Robot robot)
      : ob::InformedSampler(problem, max_calls), inner_(std::move(inner)), buffer_(robot) {}

  bool sampleUniform(ob::State* state, const ob::Cost& max_cost) override {
    if (buffer_.empty() || max_cost.value() != buffer_cost_) {
      buffer_cost_ = max_cost.value();
      buffer_.refill([&](Eigen::Vector3f* p) {
        if (!inner_->sampleUniform(state, max_cost)) return false;
        *p = toVector(state);
        return true;
      });
      if (buffer_.empty()) return false;  // the informed set yielded nothing
    }
    fromVector(buffer_.pop(), state);
    return true;
  }
  bool sampleUniform(ob::State* state, const ob::Cost& min_cost,
                     const ob::Cost& max_cost) override {
    return inner_->sampleUniform(state, min_cost, max_cost);
  }
  bool hasInformedMeasure() const override { return inner_->hasInformedMeasure(); }
  double getInformedMeasure(const ob::Cost& current) const override {
    return inner_->getInformedMeasure(current);
  }
  double getInformedMeasure(const ob::Cost& min_cost, const ob::Cost& max_cost) const override {
    return inner_->getInformedMeasure(min_cost, max_cost);
  }
  ob::Cost heuristicSolnCost(const ob::State* state) const override {
    return inner_->heuristicSolnCost(state);
  }

 private:
  ob::InformedSamplerPtr inner_;
  FreeSampleBuffer buffer_;
  double buffer_cost_ = 0.0;
};

}  // namespace

BatchedPathLengthObjective::BatchedPathLengthObjective(const ob::SpaceInformationPtr& si,
                                                       Robot robot)
    : ob::PathLengthOptimizationObjective(si), robot_(robot) {}

ob::InformedSamplerPtr BatchedPathLengthObjective::allocInformedStateSampler(
    const ob::ProblemDefinitionPtr& problem, unsigned int max_calls) const {
  return std::make_shared<BatchedInformedSampler>(
      problem, max_calls,
      ob::PathLengthOptimizationObjective::allocInformedStateSampler(problem, max_calls), robot_);
}

}  // namespace strata::plan::internal
