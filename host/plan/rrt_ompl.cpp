// The OMPL side of RrtPlanner (rrt_ompl.h): adapters from OMPL's state validity, motion
// validation and sampling to batched CollisionChecker calls.
#include "plan/rrt_ompl.h"

#include <ompl/base/MotionValidator.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateSampler.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/rrt/InformedRRTstar.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <sstream>

namespace strata::plan::internal {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

// Samples pre-tested per batch by FreeSpaceSampler: one checker call (one dispatch) per batch.
constexpr int kSampleBatch = 128;

Eigen::Vector3f toVector(const ob::State* s) {
  const double* v = s->as<ob::RealVectorStateSpace::StateType>()->values;
  return Eigen::Vector3d(v[0], v[1], v[2]).cast<float>();
}

void fromVector(const Eigen::Vector3f& p, ob::State* s) {
  double* v = s->as<ob::RealVectorStateSpace::StateType>()->values;
  for (int i = 0; i < 3; ++i) v[i] = p[i];
}

/// What the robot is and how unknown space counts, shared by the adapters.
struct Robot {
  CollisionChecker* checker;
  float radius_m;
  UnknownPolicy unknown;
};

class SphereValidity final : public ob::StateValidityChecker {
 public:
  SphereValidity(const ob::SpaceInformationPtr& si, Robot robot)
      : ob::StateValidityChecker(si), robot_(robot) {}
  bool isValid(const ob::State* s) const override {
    return robot_.checker->spheresFree({toVector(s)}, robot_.radius_m, robot_.unknown)[0] != 0;
  }

 private:
  Robot robot_;
};

/// A motion is valid when the robot's capsule along it is free: one batch per motion.
class CapsuleMotionValidator final : public ob::MotionValidator {
 public:
  CapsuleMotionValidator(const ob::SpaceInformationPtr& si, Robot robot)
      : ob::MotionValidator(si), robot_(robot) {}

  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    const bool free =
        robot_.checker->segmentFree(toVector(s1), toVector(s2), robot_.radius_m, robot_.unknown);
    (free ? valid_ : invalid_)++;
    return free;
  }

  /// The motion cut in pieces of at most half a voxel, all tested in one batch; the last valid
  /// state is the start of the first piece that is not free.
  bool checkMotion(const ob::State* s1, const ob::State* s2,
                   std::pair<ob::State*, double>& last_valid) const override {
    const Eigen::Vector3f a = toVector(s1);
    const Eigen::Vector3f b = toVector(s2);
    const float h = 0.5f * robot_.checker->voxelSize();
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / h)));
    std::vector<EsdfSegment> pieces;
    for (int k = 0; k < n; ++k) {
      pieces.push_back({a + (b - a) * (static_cast<float>(k) / n),
                        a + (b - a) * (static_cast<float>(k + 1) / n)});
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

 private:
  Robot robot_;
};

/// Uniform samples in the bounds, pre-tested in batches of kSampleBatch (one checker call each)
/// and handed out only when the robot's sphere is free there; a batch without a free sample is
/// handed out as it is (so a blocked map cannot stall the planner).
class FreeSpaceSampler final : public ob::StateSampler {
 public:
  FreeSpaceSampler(const ob::StateSpace* space, Robot robot)
      : ob::StateSampler(space), robot_(robot), uniform_(space->allocDefaultStateSampler()) {}

  void sampleUniform(ob::State* state) override {
    if (next_ == buffer_.size()) refill();
    fromVector(buffer_[next_++], state);
  }
  void sampleUniformNear(ob::State* state, const ob::State* near, double distance) override {
    uniform_->sampleUniformNear(state, near, distance);
  }
  void sampleGaussian(ob::State* state, const ob::State* mean, double std_dev) override {
    uniform_->sampleGaussian(state, mean, std_dev);
  }

 private:
  void refill() {
    std::vector<Eigen::Vector3f> samples(kSampleBatch);
    ob::State* s = space_->allocState();
    for (Eigen::Vector3f& p : samples) {
      uniform_->sampleUniform(s);
      p = toVector(s);
    }
    space_->freeState(s);
    const std::vector<std::uint8_t> free =
        robot_.checker->spheresFree(samples, robot_.radius_m, robot_.unknown);
    buffer_.clear();
    for (std::size_t i = 0; i < samples.size(); ++i) {
      if (free[i] != 0) buffer_.push_back(samples[i]);
    }
    if (buffer_.empty()) buffer_ = samples;
    next_ = 0;
  }

  Robot robot_;
  ob::StateSamplerPtr uniform_;
  std::vector<Eigen::Vector3f> buffer_;
  std::size_t next_ = 0;
};

/// While alive, OMPL's messages go here: information is dropped, warnings and errors pass on to
/// the previous handler, except the notice that re-seeding happens after the first draw (plan()
/// re-seeds on purpose and builds every generator afterwards).
class ScopedOmplLog final : public ompl::msg::OutputHandler {
 public:
  ScopedOmplLog() : previous_(ompl::msg::getOutputHandler()) { ompl::msg::useOutputHandler(this); }
  ~ScopedOmplLog() override { ompl::msg::useOutputHandler(previous_); }
  ScopedOmplLog(const ScopedOmplLog&) = delete;
  ScopedOmplLog& operator=(const ScopedOmplLog&) = delete;

  void log(const std::string& text, ompl::msg::LogLevel level, const char* filename,
           int line) override {
    if (level < ompl::msg::LOG_WARN || previous_ == nullptr) return;
    if (text.find("Changing seed now") != std::string::npos) return;
    previous_->log(text, level, filename, line);
  }

 private:
  ompl::msg::OutputHandler* previous_;
};

std::uint_fast32_t omplSeed(std::uint64_t seed) {
  const auto folded = static_cast<std::uint32_t>(seed ^ (seed >> 32));
  return folded != 0 ? folded : 0x9e3779b9u;  // OMPL ignores a zero seed
}

ob::PlannerPtr makePlanner(const ob::SpaceInformationPtr& si, const RrtOptions& options) {
  std::shared_ptr<og::RRTstar> planner;
  if (options.kind == RrtKind::kInformedRrtStar) {
    planner = std::make_shared<og::InformedRRTstar>(si);
  } else {
    planner = std::make_shared<og::RRTstar>(si);
  }
  if (options.range_m > 0.0f) planner->setRange(options.range_m);
  planner->setGoalBias(options.goal_bias);
  return planner;
}

ob::SpaceInformationPtr makeSpace(const RrtOptions& options, Robot robot) {
  auto space = std::make_shared<ob::RealVectorStateSpace>(3);
  ob::RealVectorBounds bounds(3);
  for (int i = 0; i < 3; ++i) {
    bounds.setLow(i, options.bounds_W.min()[i]);
    bounds.setHigh(i, options.bounds_W.max()[i]);
  }
  space->setBounds(bounds);
  space->setStateSamplerAllocator([robot](const ob::StateSpace* s) -> ob::StateSamplerPtr {
    return std::make_shared<FreeSpaceSampler>(s, robot);
  });
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker(std::make_shared<SphereValidity>(si, robot));
  si->setMotionValidator(std::make_shared<CapsuleMotionValidator>(si, robot));
  si->setup();
  return si;
}

std::vector<Eigen::Vector3f> toPath(const og::PathGeometric& path) {
  std::vector<Eigen::Vector3f> out;
  for (std::size_t i = 0; i < path.getStateCount(); ++i) out.push_back(toVector(path.getState(i)));
  return out;
}

}  // namespace

OmplSolution solveWithOmpl(CollisionChecker& checker, const RrtOptions& options,
                           const PlanRequest& request) {
  ScopedOmplLog log;
  // Before any OMPL object exists: every generator made below draws its seed from this.
  ompl::RNG::setSeed(omplSeed(request.seed));
  const Robot robot{&checker, request.radius_m, request.unknown};
  const ob::SpaceInformationPtr si = makeSpace(options, robot);
  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  ob::ScopedState<> start(si->getStateSpace()), goal(si->getStateSpace());
  fromVector(request.start_W, start.get());
  fromVector(request.goal_W, goal.get());
  pdef->setStartAndGoalStates(start, goal, options.goal_tolerance_m);
  pdef->setOptimizationObjective(std::make_shared<ob::PathLengthOptimizationObjective>(si));
  const ob::PlannerPtr planner = makePlanner(si, options);
  planner->setProblemDefinition(pdef);
  planner->setup();

  OmplSolution out;
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(request.time_budget_s));
  const std::uint64_t cap = options.max_iterations;
  const ob::PlannerTerminationCondition ptc([&] {
    ++out.iterations;
    return (cap > 0 && out.iterations > cap) || std::chrono::steady_clock::now() >= deadline;
  });
  planner->solve(ptc);
  out.motions_checked = si->getMotionValidator()->getValidMotionCount() +
                        si->getMotionValidator()->getInvalidMotionCount();
  if (!pdef->hasExactSolution()) {
    std::ostringstream msg;
    msg << "no path from start to goal found within " << request.time_budget_s << " s ("
        << out.iterations << " iterations, " << planner->as<og::RRTstar>()->numIterations()
        << " samples)";
    out.message = msg.str();
    return out;
  }
  out.solved = true;
  out.path_W = toPath(*pdef->getSolutionPath()->as<og::PathGeometric>());
  return out;
}

}  // namespace strata::plan::internal
