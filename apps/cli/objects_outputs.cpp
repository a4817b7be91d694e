#include "cli/objects_outputs.h"

#include <chrono>
#include <filesystem>
#include <sstream>

#include "cli/objects_sheet.h"
#include "cli/report_json.h"
#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/io/image_io.h"
#include "strata/mesh/ply.h"
#include "strata/objects/object_database_file.h"

namespace strata::apps {
namespace {

namespace fs = std::filesystem;

/// `b` appended to `a`; a mesh without colours is painted grey when the other has them.
Mesh concatenate(Mesh a, const Mesh& b) {
  const bool colors = a.hasColors() || b.hasColors();
  const bool normals = a.hasNormals() && b.hasNormals() && !a.vertices.empty();
  const std::array<std::uint8_t, 3> grey = {180, 180, 180};
  if (colors && !a.hasColors()) a.colors.assign(a.vertices.size(), grey);
  if (!normals) a.normals.clear();
  const int base = static_cast<int>(a.vertices.size());
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  if (normals) a.normals.insert(a.normals.end(), b.normals.begin(), b.normals.end());
  if (colors) {
    if (b.hasColors()) {
      a.colors.insert(a.colors.end(), b.colors.begin(), b.colors.end());
    } else {
      a.colors.insert(a.colors.end(), b.vertices.size(), grey);
    }
  }
  for (const Eigen::Vector3i& t : b.triangles)
    a.triangles.push_back(t + Eigen::Vector3i::Constant(base));
  return a;
}

}  // namespace

ObjectsRun buildObjectDatabase(const DiffResult& result, const std::vector<TsdfMap>& maps,
                               const objects::DatabaseConfig& config) {
  if (maps.size() != result.sessions.size()) {
    throw InputError("object database: " + std::to_string(maps.size()) + " session maps for " +
                     std::to_string(result.sessions.size()) + " sessions");
  }
  const auto start = std::chrono::steady_clock::now();
  ObjectsRun run{objects::ObjectDatabase(config), {}, 0.0};
  for (std::size_t s = 0; s < maps.size(); ++s) {
    const DiffSession& session = result.sessions[s];
    run.outcomes.push_back(
        run.database.addSession(static_cast<int>(s), maps[s], session.surface, session.objects));
  }
  run.build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

ObjectsFiles writeObjectsFiles(const ObjectsRun& run, const DiffResult& result,
                               const std::string& out_dir, const std::string& truth_json) {
  const fs::path out(out_dir);
  ObjectsFiles files;
  for (const objects::ObjectModel& model : run.database.models()) {
    files.models.push_back((out / ("model_" + std::to_string(model.id) + ".ply")).string());
    writePly(files.models.back(), model.mesh_M);
  }
  for (std::size_t s = 0; s < result.sessions.size(); ++s) {
    files.completed.push_back((out / ("session_" + std::to_string(s) + "_completed.ply")).string());
    writePly(files.completed.back(),
             concatenate(result.static_mesh, run.database.sessionObjects(static_cast<int>(s))));
  }
  files.database = (out / "objects.sodb").string();
  objects::saveObjectDatabase(run.database, files.database);
  files.contact_sheet = (out / "objects.png").string();
  writeColorPng(files.contact_sheet, renderModelSheet(run.database.models()));
  files.json = (out / "objects.json").string();
  Json json;
  json["command"] = "objects";
  json.update(parseJson(objectsJson(run, files)));
  if (!truth_json.empty()) json["truth"] = parseJson(truth_json);
  writeTextAtomically(files.json, jsonFileText(json));
  return files;
}

std::string summarizeObjects(const ObjectsRun& run) {
  std::size_t segments = 0, matched = 0, skipped = 0;
  for (const auto& session : run.outcomes) {
    for (const objects::SegmentOutcome& o : session) {
      ++segments;
      skipped += o.model_id == 0;
      matched += o.model_id != 0 && !o.new_model;
    }
  }
  std::ostringstream text;
  text.precision(3);
  text << run.database.models().size() << " object models from " << segments << " segments ("
       << matched << " matched to a model, " << skipped << " skipped) in " << run.build_s << " s";
  return text.str();
}

}  // namespace strata::apps
