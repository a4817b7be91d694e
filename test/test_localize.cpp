// Localisation against a prior map on real data: the 7-Scenes redkitchen excerpt split in two,
// a map from frames 0-74 (its reference poses as the odometry, so the map frame is the
// dataset's), the other half in an odometry frame of its own with drift, localised against it
// by the library and by `strata localize`; a map of another place refused; the map read only.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli/localize_command.h"
#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/core/pose_interpolation.h"
#include "strata/io/open_dataset.h"
#include "strata/io/tum_format.h"
#include "strata/localize/session_localization.h"
#include "strata/store/session_import.h"
#include "split_kitchen.h"
#include "store_test_helpers.h"
#include "test_utils.h"

namespace strata::localize {
namespace {

namespace fs = std::filesystem;

struct Split {
  fs::path root, map_session, live_session, db;
};

Split splitKitchen(const std::string& kitchen, const std::string& name) {
  // The second half drifts 3 cm per sqrt(m): more than the alignment tests' default.
  const test::SplitKitchen split =
      test::splitKitchen(kitchen, name, "kitchen_map", "kitchen_live", 0.03);
  Split out{split.root, split.first, split.second, {}};
  out.db = out.root / "map.sqlite";
  store::Store db(out.db.string());
  store::ImportOptions import;
  import.keyframe_every = 3;
  store::importTumSession(db, out.map_session.string(), import);
  return out;
}

TEST(Localize, TheSecondHalfOfRedkitchenLocalisesAgainstAMapOfTheFirst) {
  STRATA_REQUIRE_DATA("redkitchen", kitchen);
  const Split split = splitKitchen(kitchen, "localize_kitchen");
  store::StoreOptions read_only;
  read_only.read_only = true;
  store::Store db(split.db.string(), read_only);
  const PriorMap map = PriorMap::fromStore(db);
  EXPECT_EQ(map.keyframes().size(), 25u);
  DatasetOptions options;
  options.trajectory_file = (split.live_session / "odometry.txt").string();
  const std::unique_ptr<Dataset> live = openDataset(split.live_session.string(), options);
  std::vector<Eigen::Isometry3d> odometry;
  for (std::size_t i = 0; i < live->size(); ++i) odometry.push_back(live->stamp(i).T_W_C);
  SessionLocalizationConfig config;
  config.every = 3;
  const SessionLocalization result = localizeSession(*live, odometry, map, config);
  const std::vector<tum::TimedPose> truth =
      tum::readTrajectory((split.live_session / "groundtruth.txt").string());
  std::size_t placed = 0, wrong = 0;
  std::vector<double> errors, raw;
  double early = 0.0;  // largest error over the first 15 frames (75-89)
  for (const FrameLocalization& f : result.frames) {
    if (!f.placed()) continue;
    ++placed;
    const auto T = interpolateStamped(
        truth, f.timestamp_s, 0.1, [](const tum::TimedPose& p) { return p.timestamp_s; },
        [](const tum::TimedPose& p) { return p.T_W_C; });
    ASSERT_TRUE(T);
    const double e = (T->translation() - f.fused.T_W_C.translation()).norm();
    errors.push_back(e);
    if (f.frame < 15) early = std::max(early, e);
    if (f.attempted && f.localization.localized)
      raw.push_back((T->translation() - f.localization.T_W_C.translation()).norm());
    wrong += e > 0.5 ? 1 : 0;
  }
  std::sort(errors.begin(), errors.end());
  std::sort(raw.begin(), raw.end());
  const double median = errors.empty() ? 1e9 : errors[errors.size() / 2];
  std::printf("redkitchen 75-149 against a map of 0-74: %zu of %zu localisations, %zu of %zu "
              "frames placed, median error %.1f mm, largest %.1f mm (the localisations alone: median %.1f mm)\n",
              result.localized, result.attempted, placed, result.frames.size(), 1e3 * median,
              errors.empty() ? 0.0 : 1e3 * errors.back(), raw.empty() ? 0.0 : 1e3 * raw[raw.size() / 2]);
  EXPECT_GE(result.localized * 10, result.attempted * 6);  // >= 60 % of the attempts
  EXPECT_GE(placed * 10, result.frames.size() * 8);
  // The reference poses disagree with the images from about frame 90 on by 2-5 cm (docs/align.md,
  // measured with pairs whose measurements chain consistently), so the truth bounds what can be
  // asserted here: within 2 cm while it holds (the first frames), 8 cm at the median.
  EXPECT_LT(early, 0.025);
  EXPECT_LT(median, 0.08);
  EXPECT_EQ(wrong, 0u);
  fs::remove_all(split.root);
}

TEST(Localize, CommandWritesPosesAndSummaryAndLeavesTheMapUntouched) {
  STRATA_REQUIRE_DATA("redkitchen", kitchen);
  const Split split = splitKitchen(kitchen, "localize_cli");
  const std::uint32_t before = [&] {
    const std::vector<std::uint8_t> bytes = readFile(split.db.string());
    return crc32(bytes.data(), bytes.size());
  }();
  apps::LocalizeOptions o;
  o.session_dir = split.live_session.string();
  o.db_path = split.db.string();
  o.out_path = (split.root / "out" / "trajectory.txt").string();
  o.truth_path = (split.live_session / "groundtruth.txt").string();
  o.every = 5;
  o.quiet = true;
  fs::create_directories(split.root / "out");
  ASSERT_EQ(apps::runLocalize(o), 0);
  const std::vector<tum::TimedPose> poses = tum::readTrajectory(o.out_path);
  EXPECT_GT(poses.size(), 50u);
  std::ifstream in(split.root / "out" / "trajectory.json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  EXPECT_EQ(summary["frames"].get<std::size_t>(), 75u);
  EXPECT_EQ(summary["per_frame"].size(), 75u);
  EXPECT_EQ(summary["truth"]["wrong"].get<std::size_t>(), 0u);
  EXPECT_LT(summary["truth"]["median_error_m"].get<double>(), 0.08);
  const std::vector<std::uint8_t> bytes = readFile(split.db.string());
  EXPECT_EQ(crc32(bytes.data(), bytes.size()), before) << "localize wrote to the map";

  // The output may not be an input; a missing map is named; both before any work.
  apps::LocalizeOptions same = o;
  same.out_path = o.truth_path;
  EXPECT_EQ(apps::runLocalize(same), 2);
  apps::LocalizeOptions missing = o;
  missing.db_path = (split.root / "nothing.sqlite").string();
  missing.out_path = (split.root / "out" / "other.txt").string();
  EXPECT_EQ(apps::runLocalize(missing), 2);
  EXPECT_FALSE(fs::exists(missing.out_path));
  // A corrupt map database: refused, named, left as it was.
  apps::LocalizeOptions corrupt = missing;
  corrupt.db_path = (split.root / "corrupt.sqlite").string();
  test::writeRandomFile(corrupt.db_path, 64 * 1024, 5);
  const std::vector<std::uint8_t> corrupt_bytes = readFile(corrupt.db_path);
  EXPECT_EQ(apps::runLocalize(corrupt), 2);
  EXPECT_EQ(readFile(corrupt.db_path), corrupt_bytes);
  EXPECT_FALSE(fs::exists(corrupt.out_path));
  fs::remove_all(split.root);
}

TEST(Localize, AMapOfAnotherPlaceIsRefusedAndNothingIsWritten) {
  STRATA_REQUIRE_DATA("redkitchen", kitchen);
  STRATA_REQUIRE_DATA("sun3d_studyroom/fragment_2", study);
  const Split split = splitKitchen(kitchen, "localize_other");
  apps::LocalizeOptions o;
  o.session_dir = study;
  o.db_path = split.db.string();
  o.out_path = (split.root / "study.txt").string();
  o.no_odometry = true;
  o.quiet = true;
  EXPECT_EQ(apps::runLocalize(o), 2);
  EXPECT_FALSE(fs::exists(o.out_path));
  EXPECT_FALSE(fs::exists(split.root / "study.json"));
  fs::remove_all(split.root);
}

}  // namespace
}  // namespace strata::localize
