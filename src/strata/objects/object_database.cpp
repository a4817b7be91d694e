#include "strata/core/clock.h"
#include "strata/objects/object_database.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "strata/core/error.h"
#include "strata/core/statistics.h"

namespace strata::objects {

namespace {

using Clock = std::chrono::steady_clock;

/// Segments largest first (most vertices; ties by id), so the most complete view of an object
/// founds its model and smaller pieces match against it.
std::vector<const change::DiscoveredObject*> largestFirst(
    const std::vector<change::DiscoveredObject>& segments) {
  std::vector<const change::DiscoveredObject*> order;
  for (const change::DiscoveredObject& s : segments) order.push_back(&s);
  std::stable_sort(order.begin(), order.end(), [](const auto* a, const auto* b) {
    return a->vertex_count != b->vertex_count ? a->vertex_count > b->vertex_count : a->id < b->id;
  });
  return order;
}

void appendRefusal(std::string& refused, int model_id, const std::string& why) {
  refused +=
      (refused.empty() ? "" : "; ") + std::string("model ") + std::to_string(model_id) + ": " + why;
}

/// Appends `mesh` (frame M) placed at T_W_M to `out`.
void appendPlaced(const Mesh& mesh, const Eigen::Isometry3d& T_W_M, Mesh& out) {
  const Eigen::Isometry3f T = T_W_M.cast<float>();
  const Eigen::Matrix3f R = T.linear();
  const int base = static_cast<int>(out.vertices.size());
  const bool normals = mesh.hasNormals() && (out.vertices.empty() || out.hasNormals());
  const bool colors = mesh.hasColors() && (out.vertices.empty() || out.hasColors());
  if (!normals) out.normals.clear();
  if (!colors) out.colors.clear();
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    out.vertices.push_back(T * mesh.vertices[i]);
    if (normals) out.normals.push_back(R * mesh.normals[i]);
    if (colors) out.colors.push_back(mesh.colors[i]);
  }
  for (const Eigen::Vector3i& t : mesh.triangles) {
    out.triangles.push_back(t + Eigen::Vector3i::Constant(base));
  }
}

/// The floor's height under a session: the 2nd percentile of its surface vertices' heights
/// (world z; 0 for an empty surface).
float floorHeight(const Mesh& surface) {
  std::vector<double> z;
  z.reserve(surface.vertices.size());
  for (const auto& v : surface.vertices) z.push_back(v.z());
  const double floor_z = quantile(z, 0.02);
  return std::isfinite(floor_z) ? static_cast<float>(floor_z) : 0.0f;
}

/// A vertical span and whether its top was seen (a top face: among the samples within 1.5
/// voxels of the highest, at least 5 and 30 % face up). An unseen top makes the height a lower
/// bound: the part above was hidden, not absent.
struct Span {
  float height_m = 0.0f;
  bool top_seen = false;
};

Span spanOf(const SurfaceCloud& cloud, float voxel_m) {
  Span span;
  if (cloud.empty()) return span;
  float low = cloud.points.front().z(), high = low;
  for (const Eigen::Vector3f& p : cloud.points) {
    low = std::min(low, p.z());
    high = std::max(high, p.z());
  }
  span.height_m = high - low;
  if (cloud.normals.size() != cloud.points.size()) return span;
  std::size_t near_top = 0, facing_up = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (cloud.points[i].z() < high - 1.5f * voxel_m) continue;
    ++near_top;
    facing_up += cloud.normals[i].z() > 0.7f ? 1 : 0;
  }
  span.top_seen = facing_up >= 5 && facing_up >= 0.3 * static_cast<double>(near_top);
  return span;
}

/// "" when the spans agree within the config's tolerance (or the check is off), else why not.
/// With open_top_is_lower_bound, a span whose top was not seen may be the lower of the two by
/// any amount, never the higher beyond the tolerance.
std::string heightMismatch(const Span& observation, const Span& model,
                           const DatabaseConfig& config) {
  if (config.max_height_difference_ratio <= 0.0f) return "";
  const float tolerance_m =
      std::max(config.max_height_difference_voxels * config.registration.voxel_size_m,
               config.max_height_difference_ratio * std::max(observation.height_m, model.height_m));
  const float excess_m = observation.height_m - model.height_m;  // > 0: the observation higher
  const bool lower_may_be_partial = config.open_top_is_lower_bound;
  const bool observation_open = lower_may_be_partial && !observation.top_seen;
  const bool model_open = lower_may_be_partial && !model.top_seen;
  if (std::abs(excess_m) <= tolerance_m) return "";
  if (excess_m < 0.0f && observation_open) return "";  // the observation's top was hidden
  if (excess_m > 0.0f && model_open) return "";        // the model's top was never seen
  auto describe = [](const Span& span) {
    return std::to_string(span.height_m) + " m" + (span.top_seen ? "" : " (top unseen)");
  };
  return "height " + describe(observation) + " against the model's " + describe(model) +
         " (tolerance " + std::to_string(tolerance_m) + " m)";
}

}  // namespace

void DatabaseConfig::validate() const {
  if (!(max_height_difference_ratio >= 0.0f && max_height_difference_ratio < 1.0f)) {
    throw InputError("DatabaseConfig.max_height_difference_ratio must be in [0, 1), got " +
                     std::to_string(max_height_difference_ratio));
  }
  if (!(grounded_tolerance_voxels >= 0.0f)) {
    throw InputError("DatabaseConfig.grounded_tolerance_voxels must be >= 0, got " +
                     std::to_string(grounded_tolerance_voxels));
  }
  if (!(max_height_difference_voxels >= 0.0f)) {
    throw InputError("DatabaseConfig.max_height_difference_voxels must be >= 0, got " +
                     std::to_string(max_height_difference_voxels));
  }
  if (!(min_horizontal_constraint >= 0.0f && min_horizontal_constraint <= 0.5f)) {
    throw InputError("DatabaseConfig.min_horizontal_constraint must be in [0, 0.5], got " +
                     std::to_string(min_horizontal_constraint));
  }
  if (!(min_match_score >= 0.0f && min_match_score <= 1.0f)) {
    throw InputError("DatabaseConfig.min_match_score must be in [0, 1], got " +
                     std::to_string(min_match_score));
  }
  observation.validate();
  registration.validate();
  consistency.validate();
  prefilter.validate();
  model.validate();
}

ObjectDatabase::ObjectDatabase(const DatabaseConfig& config)
    : config_(config), prefilter_(config.prefilter) {
  config_.validate();
}

const ObjectModel* ObjectDatabase::findModel(int id) const {
  for (const ObjectModel& m : models_) {
    if (m.id == id) return &m;
  }
  return nullptr;
}

std::vector<SegmentOutcome> ObjectDatabase::addSession(
    int session, const TsdfMap& session_map, const change::LabelledSurface& surface,
    const std::vector<change::DiscoveredObject>& segments) {
  if (std::find(sessions_.begin(), sessions_.end(), session) != sessions_.end()) {
    throw InputError("object database: session " + std::to_string(session) + " was already added");
  }
  const float voxel_m = session_map.config().voxel_size_m;
  if (!sessions_.empty() && voxel_m != config_.registration.voxel_size_m) {
    throw InputError("object database: session " + std::to_string(session) + " has " +
                     std::to_string(voxel_m) + " m voxels, the database " +
                     std::to_string(config_.registration.voxel_size_m) + " m");
  }
  // NOTE: registration works on samples one map voxel apart, so its radii follow the map.
  config_.registration.voxel_size_m = voxel_m;
  floor_z_m_ = floorHeight(surface.mesh);
  std::vector<SegmentOutcome> outcomes;
  for (const change::DiscoveredObject* segment : largestFirst(segments)) {
    outcomes.push_back(addSegment(session, session_map, surface, *segment));
  }
  sessions_.push_back(session);
  std::sort(sessions_.begin(), sessions_.end());
  return outcomes;
}

SegmentOutcome ObjectDatabase::addSegment(int session, const TsdfMap& session_map,
                                          const change::LabelledSurface& surface,
                                          const change::DiscoveredObject& segment) {
  const Clock::time_point start = Clock::now();
  SegmentOutcome outcome;
  outcome.session = session;
  outcome.segment_id = segment.id;
  ObjectObservation observation;
  try {
    observation = observeObject(session_map, surface, segment, session, config_.observation);
  } catch (const InputError& e) {
    outcome.skipped = e.what();
    outcome.ms = msSince(start);
    return outcome;
  }
  std::vector<Match> also_accepted;
  const Match best = bestMatch(observation, session_map, outcome, also_accepted);
  const float spacing_m =
      config_.observation.sample_spacing_voxels * config_.registration.voxel_size_m;
  ObjectInstance instance;
  instance.session = session;
  instance.segment_id = segment.id;
  instance.observed_area_m2 = observation.surface_area_m2;
  if (best.model_id != 0) {
    ObjectModel& model = *std::find_if(models_.begin(), models_.end(),
                                       [&](const ObjectModel& m) { return m.id == best.model_id; });
    const Eigen::Isometry3d T_M_O = best.registration.T_target_source;
    const bool constrained =
        best.registration.horizontal_constraint >= config_.min_horizontal_constraint;
    if (config_.merge && constrained) {
      mergeObservation(model, observation, T_M_O, config_.model);
      ++model.merged_observations;
      refreshModel(model, spacing_m, config_.model);
    }
    instance.T_W_M = observation.T_W_O * T_M_O.inverse();
    instance.match_score = best.score;
    instance.merged = config_.merge && constrained;
    instance.pose_constrained = constrained;
    model.instances.push_back(instance);
    outcome.model_id = model.id;
    outcome.score = best.score;
    outcome.registration = best.registration;
    outcome.consistency = best.consistency;
    if (config_.join_duplicates && constrained && !also_accepted.empty()) {
      joinDuplicates(best.model_id, best, also_accepted, observation, session_map, outcome);
    }
  } else {
    models_.push_back(foundModel(next_id_++, observation, config_.model));
    outcome.model_id = models_.back().id;
    outcome.new_model = true;
    outcome.score = 1.0;
  }
  const ObjectModel& changed = *findModel(outcome.model_id);
  prefilter_.upsert(changed.id, changed.extent_m, changed.mean_color);
  // Merged, founded or joined: its samples changed (joined ones are gone).
  model_features_.erase(changed.id);
  for (const int id : outcome.joined_models) model_features_.erase(id);
  outcome.ms = msSince(start);
  return outcome;
}

ObjectDatabase::Match ObjectDatabase::bestMatch(const ObjectObservation& observation,
                                                const TsdfMap& session_map, SegmentOutcome& outcome,
                                                std::vector<Match>& also_accepted) const {
  Match best;
  std::vector<Match> accepted;
  const auto scoreFitness = [this](const RegistrationResult& r) {
    return config_.score_both_ways ? std::max(r.fitness, r.target_coverage) : r.fitness;
  };
  const std::vector<int> candidates =
      prefilter_.candidates(observation.extent_m, observation.mean_color);
  outcome.candidates = static_cast<int>(candidates.size());
  std::optional<SurfaceFeatures> observed;  // prepared at the first registration, then reused
  for (const int id : candidates) {
    const ObjectModel* model = findModel(id);
    if (model == nullptr || model->surface_M.empty()) continue;
    const std::string mismatch = heightRefusal(observation.surface_O, observation.T_W_O, *model);
    if (!mismatch.empty()) {
      appendRefusal(outcome.refused, id, mismatch);
      continue;
    }
    if (!observed) {
      observed.emplace(observation.surface_O, config_.registration, "observation's cloud");
    }
    const RegistrationResult primary =
        registerSurfaces(*observed, modelFeatures(*model), config_.registration,
                         floorHeightShift(observation, *model));
    if (!primary.converged) {
      appendRefusal(outcome.refused, id, "registration: " + primary.reason);
      continue;
    }
    ++outcome.registrations;
    // The best fit, then (check_pose_alternatives) its alternatives: the best score stands.
    RegistrationResult registration = primary;
    ConsistencyResult consistency = checkConsistency(
        *model, observation, registration.T_target_source, session_map, config_.consistency);
    double fitness = scoreFitness(registration);
    if (config_.check_pose_alternatives) {
      for (const PoseAlternative& alternative : primary.alternatives) {
        RegistrationResult candidate = primary;
        candidate.T_target_source = alternative.T_target_source;
        candidate.fitness = alternative.fitness;
        candidate.target_coverage = alternative.target_coverage;
        candidate.horizontal_constraint = alternative.horizontal_constraint;
        const ConsistencyResult check = checkConsistency(
            *model, observation, candidate.T_target_source, session_map, config_.consistency);
        if (!check.accepted) continue;
        const double candidate_fitness = scoreFitness(candidate);
        if (!consistency.accepted ||
            candidate_fitness * check.agreement > fitness * consistency.agreement) {
          registration = candidate;
          consistency = check;
          fitness = candidate_fitness;
        }
      }
    }
    if (!consistency.accepted) {
      appendRefusal(outcome.refused, id, consistency.reason);
      continue;
    }
    const double score = fitness * consistency.agreement;
    if (score < config_.min_match_score) {
      appendRefusal(outcome.refused, id,
                    "score " + std::to_string(score) + " (fitness " + std::to_string(fitness) +
                        " x agreement " + std::to_string(consistency.agreement) +
                        ") < min_match_score " + std::to_string(config_.min_match_score));
      continue;
    }
    accepted.push_back({id, score, registration, consistency});
    if (score > best.score) best = accepted.back();
  }
  // Accepted but outscored candidates are reported too: two models that both accept one
  // observation are near duplicates (or identical shapes) worth knowing about.
  std::sort(accepted.begin(), accepted.end(),
            [](const Match& a, const Match& b) { return a.score > b.score; });
  also_accepted.clear();
  for (const Match& m : accepted) {
    if (m.model_id == best.model_id) continue;
    appendRefusal(outcome.refused, m.model_id,
                  "accepted but outscored (" + std::to_string(m.score) + " < " +
                      std::to_string(best.score) + ")");
    also_accepted.push_back(m);
  }
  return best;
}

void ObjectDatabase::joinDuplicates(int keep_id, const Match& best,
                                    const std::vector<Match>& others,
                                    const ObjectObservation& observation,
                                    const TsdfMap& session_map, SegmentOutcome& outcome) {
  auto byId = [this](int id) {
    return std::find_if(models_.begin(), models_.end(),
                        [id](const ObjectModel& m) { return m.id == id; });
  };
  const Eigen::Isometry3d T_K_O = best.registration.T_target_source;
  for (const Match& other : others) {
    if (other.registration.horizontal_constraint < config_.min_horizontal_constraint) {
      appendRefusal(outcome.refused, other.model_id,
                    "not joined: its registration leaves the horizontal translation open");
      continue;
    }
    const auto dup = byId(other.model_id);
    if (dup == models_.end()) continue;
    ObjectModel& keep = *byId(keep_id);
    if (dup->instances.empty()) continue;
    // As between an observation (the duplicate) and a model: spans from the floor must agree in
    // height (an ambiguous view of a crate is accepted by crates of two heights; joining them is
    // the ball of doom).
    const std::string mismatch = heightRefusal(dup->surface_M, dup->instances.front().T_W_M, keep);
    if (!mismatch.empty()) {
      appendRefusal(outcome.refused, dup->id, "not joined: " + mismatch);
      continue;
    }
    // The duplicate as an observation of this session, where the observation placed it.
    const Eigen::Isometry3d T_D_O = other.registration.T_target_source;
    const Eigen::Isometry3d T_K_D = T_K_O * T_D_O.inverse();
    ObjectObservation as_seen;
    as_seen.session = observation.session;
    as_seen.segment_id = observation.segment_id;
    as_seen.T_W_O = observation.T_W_O * T_D_O.inverse();
    as_seen.tsdf = dup->tsdf;
    as_seen.surface_O = dup->surface_M;
    as_seen.extent_m = dup->extent_m;
    as_seen.surface_area_m2 = dup->surface_area_m2;
    as_seen.mean_color = dup->mean_color;
    const ConsistencyResult check =
        checkConsistency(keep, as_seen, T_K_D, session_map, config_.consistency);
    if (!check.accepted) {
      appendRefusal(outcome.refused, dup->id, "not joined: " + check.reason);
      continue;
    }
    if (config_.merge) mergeObservation(keep, as_seen, T_K_D, config_.model);
    keep.merged_observations += dup->merged_observations;
    // T_W_K = T_W_D T_K_D^-1 for every session the duplicate stood in.
    for (ObjectInstance instance : dup->instances) {
      instance.T_W_M = instance.T_W_M * T_K_D.inverse();
      keep.instances.push_back(instance);
    }
    outcome.joined_models.push_back(dup->id);
    prefilter_.remove(dup->id);
    models_.erase(dup);
  }
  if (!outcome.joined_models.empty() && config_.merge) {
    const float spacing_m =
        config_.observation.sample_spacing_voxels * config_.registration.voxel_size_m;
    refreshModel(*byId(keep_id), spacing_m, config_.model);
  }
}

std::string ObjectDatabase::heightRefusal(const SurfaceCloud& cloud, const Eigen::Isometry3d& T_W_X,
                                          const ObjectModel& model) const {
  if (model.instances.empty()) return "";
  const Eigen::Isometry3d& T_W_M = model.instances.front().T_W_M;
  if (config_.height_check_grounded_only &&
      !(grounded(cloud, T_W_X) && grounded(model.surface_M, T_W_M))) {
    return "";
  }
  const float voxel_m = config_.registration.voxel_size_m;
  return heightMismatch(spanOf(cloud, voxel_m), spanOf(model.surface_M, voxel_m), config_);
}

void ObjectDatabase::prepareModels() const {
  for (const ObjectModel& model : models_) {
    if (!model.surface_M.empty()) modelFeatures(model);
  }
}

const SurfaceFeatures& ObjectDatabase::modelFeatures(const ObjectModel& model) const {
  auto it = model_features_.find(model.id);
  if (it == model_features_.end() || !it->second.preparedFor(config_.registration)) {
    const SurfaceFeatures prepared(model.surface_M, config_.registration,
                                   "model " + std::to_string(model.id) + "'s cloud");
    it = model_features_.insert_or_assign(model.id, prepared).first;
  }
  return it->second;
}

std::optional<double> ObjectDatabase::floorHeightShift(const ObjectObservation& observation,
                                                       const ObjectModel& model) const {
  if (!config_.floor_fixes_height || model.instances.empty()) return std::nullopt;
  const Eigen::Isometry3d& T_W_M = model.instances.front().T_W_M;
  if (!grounded(observation.surface_O, observation.T_W_O) || !grounded(model.surface_M, T_W_M)) {
    return std::nullopt;
  }
  // Both stand on the floor, so M's origin is as high in this session as at its first instance:
  // T_W_M.z = T_W_O.z - t_z (rotations about the vertical; O's axes are the world's).
  return observation.T_W_O.translation().z() - T_W_M.translation().z();
}

bool ObjectDatabase::grounded(const SurfaceCloud& cloud, const Eigen::Isometry3d& T_W_X) const {
  if (cloud.empty()) return false;
  const Eigen::Isometry3f T = T_W_X.cast<float>();
  float low_z = std::numeric_limits<float>::infinity();
  for (const Eigen::Vector3f& p : cloud.points) low_z = std::min(low_z, (T * p).z());
  return low_z <=
         floor_z_m_ + config_.grounded_tolerance_voxels * config_.registration.voxel_size_m;
}

Mesh ObjectDatabase::sessionObjects(int session) const {
  Mesh out;
  for (const ObjectModel& model : models_) {
    for (const ObjectInstance& instance : model.instances) {
      if (instance.session == session) appendPlaced(model.mesh_M, instance.T_W_M, out);
    }
  }
  return out;
}

ObjectDatabase ObjectDatabase::fromParts(const DatabaseConfig& config,
                                         std::vector<ObjectModel> models,
                                         std::vector<int> sessions) {
  ObjectDatabase database(config);
  database.models_ = std::move(models);
  std::sort(sessions.begin(), sessions.end());
  database.sessions_ = std::move(sessions);
  for (const ObjectModel& m : database.models_) {
    database.next_id_ = std::max(database.next_id_, m.id + 1);
    database.prefilter_.upsert(m.id, m.extent_m, m.mean_color);
  }
  return database;
}

}  // namespace strata::objects
