#pragma once
// The object database over a change-detection run (`strata objects`, `strata demo`): built from
// every session's discovered objects, then written as files:
//   objects.json               models (id, area, merged observations, instances with session,
//                              segment, world centroid, T_W_O as 4 rows, match score), the
//                              outcome of every segment, and with simulator truth "truth"
//   model_K.ply                each model's mesh in its model frame
//   session_K_completed.ply    session K's static mesh plus every model placed at its instances
//   objects.sodb               the database file (saveObjectDatabase)
//   objects.png                contact sheet: a shaded rendering per model, its instance count
#include <string>
#include <vector>

#include "strata/mapper/session_diff.h"
#include "strata/map/tsdf_map.h"
#include "strata/objects/object_database.h"

namespace strata::apps {

struct ObjectsRun {
  objects::ObjectDatabase database;
  std::vector<std::vector<objects::SegmentOutcome>> outcomes;  // [session][segment]
  double build_s = 0.0;
};

/// Adds every session of `result` in order (`maps[i]`: session i's own layer, as
/// DiffPipeline::finish returns them). InputError when the counts disagree.
ObjectsRun buildObjectDatabase(const DiffResult& result, const std::vector<TsdfMap>& maps,
                               const objects::DatabaseConfig& config = {});

struct ObjectsFiles {
  std::string json;
  std::string database;
  std::string contact_sheet;
  std::vector<std::string> models;     // by model, in the database's order
  std::vector<std::string> completed;  // by session
};

/// Writes the files above into `out_dir` (which must exist). `truth_json`: "" or a JSON object
/// stored under "truth". Throws Error naming a file that cannot be written.
ObjectsFiles writeObjectsFiles(const ObjectsRun& run, const DiffResult& result,
                               const std::string& out_dir, const std::string& truth_json);

/// objects.json but its "command" and "truth", as a JSON object: build time, the files
/// (database, contact sheet, completed sessions), "models" and "segments".
std::string objectsJson(const ObjectsRun& run, const ObjectsFiles& files);

/// "5 models from 14 segments (9 matched, 1 skipped) in 3.2 s".
std::string summarizeObjects(const ObjectsRun& run);

}  // namespace strata::apps
