#pragma once
// Internal to RrtPlanner (includes OMPL: only .cpp files of strata_plan include this): OMPL's
// state validity, motion validation and sampling as batched CollisionChecker calls.
// Thread safety: not thread safe (the checker); OMPL runs RRT* on the calling thread.
#include <ompl/base/MotionValidator.h>
#include <ompl/base/StateSampler.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/samplers/InformedStateSampler.h>

#include <Eigen/Core>
#include <vector>

#include "strata/plan/collision_checker.h"

namespace strata::plan::internal {

/// Samples pre-tested per batch by the samplers below: one checker call (one dispatch) each.
inline constexpr int kSampleBatch = 128;

/// What the robot is and how unknown space counts, shared by the adapters.
struct Robot {
  CollisionChecker* checker;
  float radius_m;
  UnknownPolicy unknown;
};

Eigen::Vector3f toVector(const ompl::base::State* s);
void fromVector(const Eigen::Vector3f& p_W, ompl::base::State* s);

/// Valid: the zero-length capsule at the state is free (the motion checks' sample radius).
class CapsuleStateValidity final : public ompl::base::StateValidityChecker {
 public:
  CapsuleStateValidity(const ompl::base::SpaceInformationPtr& si, Robot robot);
  bool isValid(const ompl::base::State* s) const override;

 private:
  Robot robot_;
};

/// A motion is valid when the robot's capsule along it is free: one batch per motion.
class CapsuleMotionValidator final : public ompl::base::MotionValidator {
 public:
  CapsuleMotionValidator(const ompl::base::SpaceInformationPtr& si, Robot robot);
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const override;
  /// The motion in pieces of at most half a voxel, all in one batch; the last valid state is the
  /// start of the first piece that is not free.
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                   std::pair<ompl::base::State*, double>& last_valid) const override;

 private:
  Robot robot_;
};

/// Hands out samples drawn kSampleBatch at a time and pre-tested in one call, the free ones
/// only; a batch without a free sample is handed out as drawn (a blocked map cannot stall it).
class FreeSampleBuffer {
 public:
  explicit FreeSampleBuffer(Robot robot) : robot_(robot) {}
  bool empty() const { return next_ == buffer_.size(); }
  Eigen::Vector3f pop() { return buffer_[next_++]; }
  /// `draw` fills one sample (false: the source has none).
  template <typename Draw>
  void refill(Draw draw);
  void clear() { buffer_.clear(), next_ = 0; }

 private:
  Robot robot_;
  std::vector<Eigen::Vector3f> buffer_;
  std::size_t next_ = 0;
};

/// Plain RRT*'s uniform samples, pre-tested in batches (FreeSampleBuffer).
class FreeSpaceSampler final : public ompl::base::StateSampler {
 public:
  FreeSpaceSampler(const ompl::base::StateSpace* space, Robot robot);
  void sampleUniform(ompl::base::State* state) override;
  void sampleUniformNear(ompl::base::State* state, const ompl::base::State* near,
                         double distance) override;
  void sampleGaussian(ompl::base::State* state, const ompl::base::State* mean,
                      double std_dev) override;

 private:
  ompl::base::StateSamplerPtr uniform_;
  FreeSampleBuffer buffer_;
};

/// The path-length objective whose informed sampler (direct ellipsoidal sampling) pre-tests its
/// samples in batches; a buffer drawn under a larger cost bound is dropped when the bound shrinks.
class BatchedPathLengthObjective final : public ompl::base::PathLengthOptimizationObjective {
 public:
  BatchedPathLengthObjective(const ompl::base::SpaceInformationPtr& si, Robot robot);
  ompl::base::InformedSamplerPtr allocInformedStateSampler(
      const ompl::base::ProblemDefinitionPtr& problem, unsigned int max_calls) const override;

 private:
  Robot robot_;
};

}  // namespace strata::plan::internal
