#include "strata/io/open_dataset.h"

#include <filesystem>

#include "strata/core/error.h"
#include "strata/io/seven_scenes_dataset.h"
#include "strata/io/internal/tum_dataset.h"

namespace strata {

std::unique_ptr<Dataset> openDataset(const std::string& path, const DatasetOptions& options) {
  namespace fs = std::filesystem;
  if (!fs::exists(path)) throw InputError(path + ": no such folder");
  if (!fs::is_directory(path))
    throw InputError(path + ": not a folder (expected a dataset folder)");
  if (options.format == "tum") return openTumDataset(path, options);
  if (options.format == "7scenes") return open7ScenesDataset(path, options);
  if (options.format != "auto") {
    throw InputError("unknown dataset format '" + options.format +
                     "' (expected auto, tum or 7scenes)");
  }
  if (fs::is_regular_file(fs::path(path) / "depth.txt")) return openTumDataset(path, options);
  if (looksLike7Scenes(path)) return open7ScenesDataset(path, options);
  throw InputError(path + ": not a TUM RGB-D folder (no depth.txt) nor a 7-Scenes folder " +
                   "(no frame-*.depth.png)");
}

}  // namespace strata
