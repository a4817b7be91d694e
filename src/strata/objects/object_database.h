#pragma once
// The incremental object database (docs/objects.md; Furrer, Fehr et al. IROS 2018): the objects
// that moved, kept as TSDF models that grow more complete with every session they are seen in.
//
// addSession(), per discovered segment of the session, largest first:
//   observeObject -> prefilter candidates (size, colour; heights, DatabaseConfig) ->
//   registerSurfaces against each
//   candidate -> checkConsistency of the registered pose -> the candidate with the best score
//   (fitness x agreement) among those accepted takes the observation: merged into its TSDF
//   (weighted SDF average) and an instance added; none accepted: a new model. Degenerate segments
//   are skipped with the reason recorded. Several segments of one session may join one model
//   (identical shapes: the database stores shapes and their instances).
// Thread safety: not thread safe; one ObjectDatabase per thread.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "strata/change/object_discovery.h"
#include "strata/map/tsdf_map.h"
#include "strata/mesh/mesh.h"
#include "strata/objects/consistency_check.h"
#include "strata/objects/object_model.h"
#include "strata/objects/object_observation.h"
#include "strata/objects/object_prefilter.h"
#include "strata/objects/object_registration.h"

namespace strata::objects {

struct DatabaseConfig {
  ObservationConfig observation;
  RegistrationConfig registration;  // its voxel_size_m is set from the session map
  ConsistencyConfig consistency;
  PrefilterConfig prefilter;
  ObjectModelConfig model;
  /// Matches scoring lower (registration fitness x SDF agreement) are refused. 0 disables.
  /// Default 0.5: an observation with less than about half its surface on the model is more
  /// often another object that the consistency check let through than a new side of the same
  /// one (docs/objects_evaluation.md, "Settings and why").
  float min_match_score = 0.5f;
  /// The score's fitness is the larger of the registration's (share of the observation on the
  /// model) and the same share of the model's surface on the observation: a partial model (one
  /// side of a crate) and a fuller later view of it score low one way only. false: one way.
  bool score_both_ways = true;
  /// Objects stand on the floor and their tops are seen, so partial views of one object span
  /// its whole height, while boxes of one footprint but different heights pass the consistency
  /// check (its NOTE). A model whose vertical span differs from the observation's by more than
  /// max(max_height_difference_voxels voxels, max_height_difference_ratio x the taller) is not
  /// registered. NOTE: a segment that is only part of an object (a chair's seat) is refused by
  /// it too, as the size prefilter mostly does already. Ratio 0 disables. Default 8 %: keeps
  /// crates 0.5 and 0.6 m tall apart, where a looser ratio lets boxes of other heights into a
  /// model (docs/objects_evaluation.md, "Settings and why").
  float max_height_difference_ratio = 0.08f;
  float max_height_difference_voxels = 2.5f;
  /// The height check compares only spans that reach down to the floor (both the observation's
  /// and the model's at its first instance, within grounded_tolerance_voxels of the floor): a
  /// standing object's full height starts there, while a fragment off the floor (a chair's back
  /// above its thin legs) is a part whose span says nothing of the whole. NOTE: an object on a
  /// desk is not grounded either, so its height is not compared. The floor is the 2nd
  /// percentile of the session surface's heights (the world frame's z is up and shared by the
  /// sessions). false: every pair is compared. Default on, and the floor rather than up-facing
  /// supports: docs/objects_evaluation.md, "Settings and why".
  bool height_check_grounded_only = true;
  float grounded_tolerance_voxels = 4.0f;
  /// When the observation and the model both reach the floor (as above), the registration's
  /// vertical translation is not estimated but taken from the floor: M's origin stands as high
  /// over the floor in every session. false: estimated. Default on: a view whose faces are all
  /// vertical (a tall box whose top the camera did not see) otherwise fits the model slid up or
  /// down (docs/objects_evaluation.md, "Settings and why").
  bool floor_fixes_height = true;
  /// A span whose top face was not seen (none of the samples near its highest point face up:
  /// the camera at 1.2 m does not see the top of a 1.4 m stack, a crate in front hides a part)
  /// is a lower bound: it may be lower than the other span by any amount, not higher beyond the
  /// tolerance. false (the default): both spans are taken as exact. Off because it trades
  /// precision for recall: crates of 0.5 and 0.6 m join through partial views
  /// (docs/objects_evaluation.md, "Settings and why").
  bool open_top_is_lower_bound = false;
  /// A match whose overlap holds the horizontal translation less firmly than this
  /// (RegistrationResult::horizontal_constraint: one face of a box, or a cart's top, seen alone)
  /// keeps its identity but not its pose: the instance is recorded with pose_constrained =
  /// false, the observation is not merged (a face slid along itself would blur the model) and
  /// joins no models (their relative pose would be slid too). 0 disables.
  float min_horizontal_constraint = 0.02f;
  /// Merge an accepted observation into the model (false: only record the instance).
  bool merge = true;
  /// An observation that two or more models accept shows them to be one object seen in parts:
  /// each other accepted model is checked against the best one (the height check, and the same
  /// consistency check with the other model as the observation, placed by the two
  /// registrations) and, when both pass,
  /// joined into it (TSDF averaged, instances moved; its id is retired). false: they stay apart
  /// ("accepted but outscored" in the outcome).
  bool join_duplicates = true;
  /// Each registration's other upright poses (RegistrationConfig::yaw_alternatives: a quarter
  /// or half turn of a near-square footprint, another RANSAC hypothesis) go through the
  /// consistency check too, and the pose with the best score (fitness x agreement) stands for
  /// the match: the point fit alone cannot tell a 0.5 x 0.4 m crate from itself turned a
  /// quarter when the view shows two faces, the model's volume can. false: the best fit only.
  bool check_pose_alternatives = true;
  void validate() const;  // InputError naming the bad field
};

/// What happened to one segment.
struct SegmentOutcome {
  int session = 0;
  int segment_id = 0;
  int model_id = 0;  // 0: skipped
  bool new_model = false;
  std::string skipped;              // why it was skipped ("" otherwise)
  int candidates = 0;               // models the prefilter let through
  int registrations = 0;            // of those, registered
  double score = 0.0;               // of the accepted match (1 for a new model)
  RegistrationResult registration;  // of the accepted match
  ConsistencyResult consistency;    // of the accepted match
  std::string refused;              // summary of the candidates refused and why ("" when none)
  /// Models joined into model_id because this observation showed them to be the same object
  /// (DatabaseConfig::join_duplicates); their ids no longer exist.
  std::vector<int> joined_models;
  double ms = 0.0;  // observation + matching + merge
};

class ObjectDatabase {
 public:
  explicit ObjectDatabase(const DatabaseConfig& config = {});

  /// Adds one session's discovered objects. `session_map` is the session's own layer (world
  /// frame), `surface` its labelled surface (as extractObjects returns it), `segments` its
  /// discovered objects. Sessions may come in any order; a session already added is an
  /// InputError (nothing changes). Voxel sizes must agree across sessions (InputError).
  std::vector<SegmentOutcome> addSession(int session, const TsdfMap& session_map,
                                         const change::LabelledSurface& surface,
                                         const std::vector<change::DiscoveredObject>& segments);

  const std::vector<ObjectModel>& models() const { return models_; }
  const ObjectModel* findModel(int id) const;
  const DatabaseConfig& config() const { return config_; }
  std::vector<int> sessions() const { return sessions_; }

  /// Every model placed at its instances of `session`, world frame, one mesh (coloured by the
  /// model's TSDF colour).
  Mesh sessionObjects(int session) const;

  /// Prepares every model's samples for registration now (FPFH and search trees, kept until the
  /// model changes), so that the first session after a load does not pay for them; matching
  /// prepares a model at its first registration otherwise. Copies of the database share them.
  void prepareModels() const;

  /// For the file reader: a database with these models and sessions (ids kept).
  static ObjectDatabase fromParts(const DatabaseConfig& config, std::vector<ObjectModel> models,
                                  std::vector<int> sessions);

 private:
  /// The best accepted candidate of one segment (model_id 0: none).
  struct Match {
    int model_id = 0;
    double score = 0.0;
    RegistrationResult registration;
    ConsistencyResult consistency;
  };
  SegmentOutcome addSegment(int session, const TsdfMap& session_map,
                            const change::LabelledSurface& surface,
                            const change::DiscoveredObject& segment);
  /// The best accepted candidate; the other accepted ones, best first, go to `also_accepted`.
  Match bestMatch(const ObjectObservation& observation, const TsdfMap& session_map,
                  SegmentOutcome& outcome, std::vector<Match>& also_accepted) const;
  /// Joins each of `others` into model `keep_id` where the height and consistency checks pass
  /// (DatabaseConfig::join_duplicates).
  void joinDuplicates(int keep_id, const Match& best, const std::vector<Match>& others,
                      const ObjectObservation& observation, const TsdfMap& session_map,
                      SegmentOutcome& outcome);
  /// Why `cloud` (placed by T_W_X) and `model` (at its first instance) differ too much in height
  /// to be one object; "" when they agree or are not compared (height_check_grounded_only).
  std::string heightRefusal(const SurfaceCloud& cloud, const Eigen::Isometry3d& T_W_X,
                            const ObjectModel& model) const;
  /// Whether the lowest point of `cloud`, placed by T_W_X, lies within the grounded tolerance of
  /// the current session's floor.
  bool grounded(const SurfaceCloud& cloud, const Eigen::Isometry3d& T_W_X) const;
  /// T_M_O's z translation when the observation and the model both reach the floor
  /// (floor_fixes_height), else nullopt: the registration estimates it.
  std::optional<double> floorHeightShift(const ObjectObservation& observation,
                                         const ObjectModel& model) const;
  /// The model's samples prepared for registration: computed at its first registration after it
  /// changed, kept until it changes again (addSegment drops the entry of a model it merged into,
  /// founded or joined).
  const SurfaceFeatures& modelFeatures(const ObjectModel& model) const;

  DatabaseConfig config_;
  std::vector<ObjectModel> models_;
  std::vector<int> sessions_;
  ModelPrefilter prefilter_;
  int next_id_ = 1;
  mutable std::map<int, SurfaceFeatures> model_features_;  // by model id; a cache, see above
  float floor_z_m_ = 0.0f;  // of the session being added (world frame)
};

}  // namespace strata::objects
