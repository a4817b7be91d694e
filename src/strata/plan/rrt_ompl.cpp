// The OMPL side of RrtPlanner (rrt_ompl.h): the problem, the planner, seeding and the solve.
#include "strata/plan/internal/rrt_ompl.h"

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/SpaceInformation.h>
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

#include "strata/plan/internal/rrt_ompl_adapters.h"

namespace strata::plan::internal {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

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
  si->setStateValidityChecker(std::make_shared<CapsuleStateValidity>(si, robot));
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
  pdef->setOptimizationObjective(std::make_shared<BatchedPathLengthObjective>(si, robot));
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
