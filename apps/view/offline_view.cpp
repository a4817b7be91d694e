#include "view/offline_view.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <regex>
#include <fstream>
#include <sstream>

#include "strata/core/error.h"
#include "strata/map/map_file.h"
#include "strata/mapper/mapper.h"
#include "strata/io/tum_format.h"
#include "strata/mesh/ply.h"
#include "strata/vk/vk.h"
#include "view/scene_items.h"

namespace strata::view {
namespace fs = std::filesystem;
namespace {

// Slices are at most this many cells a side (the resolution grows for larger maps).
constexpr int kMaxSliceCells = 400;

bool hasExtension(const fs::path& p, const char* ext) { return p.extension() == ext; }

// The page's title: the file or folder's own name ("strata_out" for "strata_out/").
std::string title(const fs::path& p) {
  fs::path name = p.lexically_normal().filename();
  if (name.empty()) name = p.lexically_normal().parent_path().filename();
  return name.empty() ? p.string() : name.string();
}

// strata plan's path.csv ("x,y,z" and one point a line).
bool isPathFile(const std::string& name) { return name == "path.csv"; }
// A TUM trajectory: strata align's trajectory.txt, or a name ending in _trajectory.txt.
bool isTrajectoryFile(const std::string& name) {
  const std::string suffix = "_trajectory.txt";
  return name == "trajectory.txt" ||
         (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0);
}

std::vector<Eigen::Vector3f> readPathCsv(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError("cannot read '" + file.string() + "'");
  std::string line;
  std::getline(in, line);
  if (line.rfind("x,y,z", 0) != 0) throw InputError("'" + file.string() + "': a path file starts with the header x,y,z");
  std::vector<Eigen::Vector3f> points;
  int row = 1;
  while (std::getline(in, line)) {
    ++row;
    if (line.empty()) continue;
    std::istringstream fields(line);
    Eigen::Vector3f p;
    char comma1 = 0, comma2 = 0;
    if (!(fields >> p.x() >> comma1 >> p.y() >> comma2 >> p.z()) || comma1 != ',' || comma2 != ',' || !p.allFinite() ||
        p.cwiseAbs().maxCoeff() > 1e6f) {
      throw InputError("'" + file.string() + "' line " + std::to_string(row) + ": not three finite numbers x,y,z");
    }
    points.push_back(p);
  }
  return points;
}

}  // namespace

OfflineView::OfflineView(const std::string& path, const std::string& device, Scene& scene)
    : scene_(scene) {
  std::error_code ec;
  const fs::path root(path);
  if (!fs::exists(root, ec)) throw InputError("'" + path + "' does not exist");
  std::vector<fs::path> plys, maps, lines;
  if (fs::is_directory(root, ec)) {
    // The folder's own files, and those of its folders one level down: strata align writes
    // session_<s>/trajectory.txt, strata explore one folder per planner.
    std::vector<fs::path> folders = {root};
    for (const auto& entry : fs::directory_iterator(root, ec)) {
      if (entry.is_directory()) folders.push_back(entry.path());
    }
    std::sort(folders.begin() + 1, folders.end());
    for (const fs::path& folder : folders) {
      std::vector<fs::path> folder_plys, folder_maps;
      for (const auto& entry : fs::directory_iterator(folder, ec)) {
        if (!entry.is_regular_file()) continue;
        const std::string name = entry.path().filename().string();
        if (hasExtension(entry.path(), ".ply")) folder_plys.push_back(entry.path());
        if (hasExtension(entry.path(), ".strata")) folder_maps.push_back(entry.path());
        if (isPathFile(name) || isTrajectoryFile(name)) lines.push_back(entry.path());
      }
      // Meshes and maps from the first folder that has any (the top one before its folders):
      // strata explore --compare's planners each mapped the same world.
      if (plys.empty() && maps.empty()) {
        plys = std::move(folder_plys);
        maps = std::move(folder_maps);
      }
    }
    std::sort(plys.begin(), plys.end());
    std::sort(maps.begin(), maps.end());
    std::sort(lines.begin(), lines.end());
  } else if (hasExtension(root, ".strata")) {
    maps.push_back(root);
  } else if (hasExtension(root, ".ply")) {
    plys.push_back(root);
  } else {
    throw InputError("'" + path + "' is neither a map (.strata), a mesh (.ply) nor a folder");
  }

  // Read everything before anything is shown: a bad file fails the command, not half a scene.
  struct Item {
    std::string id, group, label;
    int session = -1;
    Mesh mesh;
  };
  std::vector<Item> items;
  std::vector<ObjectBox> boxes;
  const std::regex object_name(R"(session_(\d+)_object_(\d+)\.ply)");
  const std::regex session_name(R"(session_(\d+)_mesh\.ply)");
  const std::regex skipped_name(R"((model_\d+|session_\d+_completed|session_\d+_truth)\.ply)");
  for (const fs::path& p : plys) {
    const std::string name = p.filename().string();
    std::smatch m;
    if (std::regex_match(name, skipped_name)) continue;
    Item item;
    item.mesh = readPly(p.string());
    if (std::regex_match(name, m, object_name)) {
      item.group = "object";
      item.session = std::stoi(m[1]);
      item.id = "object:" + m[1].str() + ":" + m[2].str();
      item.label = "session " + m[1].str() + " object " + m[2].str();
      ObjectBox box;
      box.id = std::stoi(m[2]);
      box.session = item.session;
      box.label = item.label;
      box.min_W = Eigen::Vector3f::Constant(std::numeric_limits<float>::max());
      box.max_W = -box.min_W;
      for (const auto& v : item.mesh.vertices) {
        box.min_W = box.min_W.cwiseMin(v);
        box.max_W = box.max_W.cwiseMax(v);
      }
      if (!item.mesh.vertices.empty()) boxes.push_back(box);
    } else if (std::regex_match(name, m, session_name)) {
      item.group = "session";
      item.session = std::stoi(m[1]);
      item.id = "session:" + m[1].str();
      item.label = "session " + m[1].str();
    } else {
      item.group = "map";
      item.id = "mesh:" + p.stem().string();
    }
    items.push_back(std::move(item));
  }
  struct Line {
    std::string type, id;
    std::vector<Eigen::Vector3f> points;
  };
  std::vector<Line> polylines;
  for (const fs::path& file : lines) {
    const std::string relative = fs::relative(file, root, ec).string();
    Line line;
    if (isPathFile(file.filename().string())) {
      line.type = "path";
      line.points = readPathCsv(file);
    } else {
      line.type = "trajectory";
      for (const tum::TimedPose& pose : tum::readTrajectory(file.string())) {
        line.points.push_back(pose.T_W_C.translation().cast<float>());
      }
    }
    line.id = relative;
    if (line.points.size() >= 2) polylines.push_back(std::move(line));
  }
  std::optional<TsdfMap> map;
  if (!maps.empty()) {
    MapFileContents contents = loadMapFile(maps.front().string());
    map = std::move(contents.map);
  }
  if (items.empty() && !map && polylines.empty()) throw InputError("nothing to show in '" + path + "' (no .ply mesh, .strata map, trajectory.txt or path.csv, nor in its folders)");

  if (map) {
    vk::ContextOptions options;
    options.device_selector = device;
    context_ = vk::Context::create(options);
    MapperConfig config;
    config.map = map->config();
    config.esdf = true;
    voxel_size_m_ = map->config().voxel_size_m;
    mapper_ = Mapper::fromMap(*map, *context_, config);
    mapper_->updateEsdf();
    // The map's own surface unless the folder has its mesh already.
    const bool has_static = std::any_of(items.begin(), items.end(), [](const Item& i) { return i.group == "map"; });
    if (!has_static) {
      Item item;
      item.group = "map";
      item.id = "mesh:" + maps.front().stem().string();
      item.mesh = mapper_->mesh();
      items.push_back(std::move(item));
    }
  }

  min_x_ = min_y_ = std::numeric_limits<float>::max();
  max_x_ = max_y_ = -std::numeric_limits<float>::max();
  std::size_t triangles = 0;
  int meshes = 0;
  for (const Item& item : items) {
    for (const auto& v : item.mesh.vertices) {
      min_x_ = std::min(min_x_, v.x());
      max_x_ = std::max(max_x_, v.x());
      min_y_ = std::min(min_y_, v.y());
      max_y_ = std::max(max_y_, v.y());
    }
    triangles += item.mesh.triangles.size();
    ++meshes;
  }
  std::ostringstream s;
  s << meshes << " meshes (" << triangles << " triangles), " << boxes.size() << " objects, "
    << polylines.size() << " trajectories and paths"
    << (mapper_ ? ", ESDF from " + maps.front().filename().string() : ", no ESDF (no .strata map)");
  summary_ = s.str();

  scene_.put("hello", encodeMessage({{"type", "hello"},
                                     {"title", title(root)},
                                     {"mode", "offline"},
                                     {"esdf", mapper_ != nullptr}}));
  for (const Item& item : items) scene_.put(item.id, meshMessage(item.id, item.group, item.mesh, item.session, item.label));
  if (!boxes.empty()) scene_.put("objects", objectsMessage(boxes));
  for (const Line& line : polylines) {
    scene_.put(line.type + ":" + line.id, polylineMessage(line.type, line.id, line.points));
  }
  nlohmann::json stats = {{"meshes", meshes}, {"triangles", triangles}, {"objects", boxes.size()}};
  if (mapper_) stats["blocks"] = mapper_->blockCount();
  scene_.put("stats", encodeMessage({{"type", "stats"}, {"values", stats}}));
}

OfflineView::~OfflineView() = default;

Message OfflineView::answer(const nlohmann::json& request) {
  const std::string type = request.value("type", "");
  if (type != "query" && type != "slice") throw InputError("unknown request type '" + type + "'");
  if (!mapper_) return encodeMessage({{"type", "error"}, {"message", "no ESDF: the view has no .strata map"}});
  if (type == "query") {
    const auto& p = request.at("point");
    if (!p.is_array() || p.size() != 3 || !p[0].is_number() || !p[1].is_number() || !p[2].is_number())
      throw InputError("query: point must be [x, y, z] in metres");
    const Eigen::Vector3f point(p[0].get<float>(), p[1].get<float>(), p[2].get<float>());
    if (!point.allFinite()) throw InputError("query: point must be finite");
    const EsdfSample sample = mapper_->distances({point}).front();
    return answerMessage(request.value("id", 0), point, sample.status == EsdfStatus::kKnown, sample.distance_m);
  }
  const auto& zj = request.at("z");
  if (!zj.is_number()) throw InputError("slice: z must be a number (metres)");
  const float z = zj.get<float>();
  if (!std::isfinite(z)) throw InputError("slice: z must be finite");
  EsdfSliceImage slice;
  slice.z_m = z;
  const float extent = std::max(max_x_ - min_x_, max_y_ - min_y_);
  slice.resolution_m = std::max(voxel_size_m_, extent / kMaxSliceCells);
  slice.origin_x_m = min_x_;
  slice.origin_y_m = min_y_;
  slice.width = std::max(1, static_cast<int>(std::ceil((max_x_ - min_x_) / slice.resolution_m)));
  slice.height = std::max(1, static_cast<int>(std::ceil((max_y_ - min_y_) / slice.resolution_m)));
  std::vector<Eigen::Vector3f> points;
  points.reserve(static_cast<std::size_t>(slice.width) * slice.height);
  for (int r = 0; r < slice.height; ++r) {
    for (int c = 0; c < slice.width; ++c) {
      points.emplace_back(slice.origin_x_m + (c + 0.5f) * slice.resolution_m,
                          slice.origin_y_m + (r + 0.5f) * slice.resolution_m, z);
    }
  }
  const std::vector<EsdfSample> samples = mapper_->distances(points);
  slice.distances_m.resize(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const bool known = samples[i].status == EsdfStatus::kKnown;
    slice.distances_m[i] = known ? samples[i].distance_m : std::numeric_limits<float>::quiet_NaN();
    if (known) slice.max_m = std::max(slice.max_m, samples[i].distance_m);
  }
  scene_.put("esdf", esdfSliceMessage(slice));
  return nullptr;
}

}  // namespace strata::view
