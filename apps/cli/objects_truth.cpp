#include "cli/objects_truth.h"

#include <filesystem>
#include <regex>

#include "strata/sim/sim_setup.h"
#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/sim/world/world_paths.h"

namespace strata::apps {
namespace {

namespace fs = std::filesystem;

/// What one session's objects.json says (the fields the match needs).
struct SessionRecord {
  std::string world;
  std::uint64_t seed = 0;
  std::vector<std::pair<std::string, bool>> objects;  // name, present, in file order
};

SessionRecord readRecord(const fs::path& path) {
  const std::vector<std::uint8_t> bytes = readFile(path.string());
  const std::string text(bytes.begin(), bytes.end());
  SessionRecord r;
  std::smatch m;
  if (std::regex_search(text, m, std::regex("\"world\":\\s*\"([^\"]*)\""))) r.world = m[1];
  if (std::regex_search(text, m, std::regex("\"seed\":\\s*([0-9]+)"))) r.seed = std::stoull(m[1]);
  const std::regex object("\"name\":\\s*\"([^\"]*)\"[^}]*?\"present\":\\s*(true|false)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), object);
       it != std::sregex_iterator(); ++it) {
    r.objects.emplace_back((*it)[1], (*it)[2] == "true");
  }
  return r;
}

/// The world's session K of a folder named session_K (-1 when not so named).
int sessionIndex(const fs::path& dir) {
  std::smatch m;
  const std::string name = dir.filename().string();
  return std::regex_match(name, m, std::regex("session_([0-9]+)")) ? std::stoi(m[1]) : -1;
}

void checkAgrees(const sim::World& world, int session, const SessionRecord& record,
                 const std::string& dir) {
  const auto& objects = world.session(session).objects;
  bool same = record.seed == world.seed() && record.objects.size() == objects.size();
  for (std::size_t i = 0; same && i < objects.size(); ++i) {
    same = record.objects[i].first == objects[i].name &&
           record.objects[i].second == objects[i].present;
  }
  if (!same) {
    throw InputError("the ground truth of session folder '" + dir + "' (world '" + record.world +
                     "', seed " + std::to_string(record.seed) +
                     ") disagrees with the world loaded for it (seed " +
                     std::to_string(world.seed()) + "): give the world file with --world");
  }
}

}  // namespace

std::shared_ptr<const SimTruth> findSimTruth(const std::vector<std::string>& session_dirs,
                                             const std::string& world_path, std::string& why_not) {
  std::vector<SessionRecord> records;
  std::vector<int> indices;
  int sessions = 0;
  for (const std::string& dir : session_dirs) {
    fs::path folder = fs::path(dir).lexically_normal();
    if (folder.filename().empty()) folder = folder.parent_path();  // "sim/session_0/"
    const int k = sessionIndex(folder);
    const fs::path json =
        folder.parent_path() / "ground_truth" / ("session_" + std::to_string(k)) / "objects.json";
    if (k < 0 || !fs::is_regular_file(json)) {
      why_not = "no simulator ground truth beside '" + dir + "'";
      return nullptr;
    }
    records.push_back(readRecord(json));
    indices.push_back(k);
    sessions = std::max(sessions, k + 1);
  }
  const std::string name = world_path.empty() ? records.front().world : world_path;
  std::string path;
  try {
    path = sim::findWorld(name);
  } catch (const InputError& e) {
    why_not = std::string("the world of the ground truth does not load: ") + e.what();
    return nullptr;
  }
  auto truth = std::make_shared<SimTruth>();
  truth->world = sim::loadWorld(path, records.front().seed, sessions);
  truth->world_sessions = indices;
  for (std::size_t i = 0; i < records.size(); ++i) {
    checkAgrees(*truth->world, indices[i], records[i], session_dirs[i]);
  }
  return truth;
}

eval::ObjectDbEvaluation evaluateObjectsRun(const SimTruth& truth, const DiffResult& result,
                                            const ObjectsRun& run) {
  std::vector<std::vector<change::DiscoveredObject>> segments;
  for (const DiffSession& session : result.sessions) segments.push_back(session.objects);
  const auto identities = eval::segmentIdentities(*truth.world, segments, truth.world_sessions);
  return eval::evaluateObjectDatabase(
      identities, eval::objectDbTruth(*truth.world, truth.world_sessions), run.database.models());
}

}  // namespace strata::apps
