#include "strata/io/euroc_dataset.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "strata/core/error.h"
#include "strata/core/file_limits.h"
#include "strata/core/pose_interpolation.h"
#include "strata/io/euroc_parse.h"
#include "strata/io/internal/image_header.h"
#include "strata/io/image_io.h"

namespace strata::euroc {
namespace {

namespace fs = std::filesystem;

constexpr FileSizeLimit kMaxEurocCsvBytes{"kMaxEurocCsvBytes", kMaxCsvBytes};
constexpr FileSizeLimit kMaxEurocYamlBytes{"kMaxEurocYamlBytes", kMaxYamlBytes};
// Only the header is needed to check a size; the whole file is read (PNGs are small), bounded.
constexpr FileSizeLimit kMaxEurocImageBytes{"kMaxEurocImageBytes", std::uint64_t{256} << 20};

std::string readText(const fs::path& path, const FileSizeLimit& limit, const char* what) {
  return readTextBounded(path.string(), limit, what);
}

void requireFolder(const fs::path& path, const char* what) {
  if (!fs::is_directory(path)) throw InputError(path.string() + ": " + what + " folder not found");
}

struct CameraFiles {
  CameraCalibration calibration;
  std::vector<ImageRow> rows;
  fs::path data_dir;
};

CameraFiles readCamera(const fs::path& dir, const std::string& name, ReaderStats* stats) {
  requireFolder(dir, "camera");
  CameraFiles camera;
  const fs::path yaml = dir / "sensor.yaml";
  camera.calibration =
      parseCameraYaml(readText(yaml, kMaxEurocYamlBytes, "camera sensor.yaml"), yaml.string());
  camera.calibration.name = name;
  const fs::path csv = dir / "data.csv";
  camera.rows = parseImageCsv(readText(csv, kMaxEurocCsvBytes, "camera data.csv"), csv.string());
  if (camera.rows.empty()) throw InputError(csv.string() + ": no image rows");
  camera.data_dir = dir / "data";
  requireFolder(camera.data_dir, "image");
  // NOTE: rows whose image is absent are dropped and counted rather than refused: excerpts and
  // trimmed copies of EuRoC sequences keep the full data.csv (the shared micro excerpt does).
  std::vector<ImageRow> present;
  for (ImageRow& row : camera.rows) {
    const fs::path image = camera.data_dir / row.filename;
    if (fs::is_regular_file(image)) {
      present.push_back(std::move(row));
    } else {
      if (stats->missing_images++ == 0) stats->first_missing_image = image.string();
    }
  }
  if (present.empty()) {
    throw InputError(csv.string() + ": none of its " + std::to_string(camera.rows.size()) +
                     " images is in " + camera.data_dir.string() + " (first: " +
                     (camera.data_dir / camera.rows.front().filename).string() + " not found)");
  }
  camera.rows = std::move(present);
  return camera;
}

/// Refuses an image whose header disagrees with the camera's resolution (open() checks the first
/// frame this way, without decoding).
void checkHeaderSize(const std::string& path, const CameraCalibration& camera) {
  const std::vector<std::uint8_t> bytes = readFileBounded(path, kMaxEurocImageBytes, "grey image");
  const detail::ImageHeader header = detail::readImageHeader(bytes, path);
  if (header.width_px != camera.width_px || header.height_px != camera.height_px) {
    throw InputError(path + ": image is " + std::to_string(header.width_px) + "x" +
                     std::to_string(header.height_px) + " but " + camera.name +
                     "/sensor.yaml resolution is " + std::to_string(camera.width_px) + "x" +
                     std::to_string(camera.height_px));
  }
}

/// Merges two sorted rows lists: pairs within the tolerance, counts the rest.
std::vector<StereoFrame> pairFrames(const CameraFiles& left, const CameraFiles& right,
                                    std::int64_t tolerance_ns, ReaderStats* stats) {
  std::vector<StereoFrame> frames;
  std::size_t i = 0, j = 0;
  while (i < left.rows.size() && j < right.rows.size()) {
    const std::int64_t tl = left.rows[i].timestamp_ns;
    const std::int64_t tr = right.rows[j].timestamp_ns;
    if (std::llabs(tl - tr) <= tolerance_ns) {
      frames.push_back({tl, (left.data_dir / left.rows[i].filename).string(),
                        (right.data_dir / right.rows[j].filename).string()});
      ++i;
      ++j;
    } else if (tl < tr) {
      ++stats->unpaired_left;
      ++i;
    } else {
      ++stats->unpaired_right;
      ++j;
    }
  }
  stats->unpaired_left += left.rows.size() - i;
  stats->unpaired_right += right.rows.size() - j;
  return frames;
}

void countImuGaps(const std::vector<ImuSample>& imu, double rate_hz, ReaderStats* stats) {
  const double period_ns = 1e9 / rate_hz;
  for (std::size_t k = 1; k < imu.size(); ++k) {
    const double dt_ns = static_cast<double>(imu[k].timestamp_ns - imu[k - 1].timestamp_ns);
    if (dt_ns > 1.5 * period_ns) {
      ++stats->imu_gaps;
      stats->imu_missing_samples += static_cast<std::size_t>(std::llround(dt_ns / period_ns)) - 1;
    }
  }
}

}  // namespace

bool isEurocFolder(const std::string& folder) {
  const fs::path path(folder);
  return fs::is_directory(path / "mav0" / "cam0") ||
         (path.filename() == "mav0" && fs::is_directory(path / "cam0"));
}

Calibration readCalibration(const std::string& folder, bool use_right_camera) {
  const fs::path root(folder);
  requireFolder(root, "EuRoC session");
  const fs::path mav0 = fs::is_directory(root / "mav0") ? root / "mav0" : root;
  Calibration calibration;
  const auto camera = [&](const char* name) {
    const fs::path yaml = mav0 / name / "sensor.yaml";
    CameraCalibration c =
        parseCameraYaml(readText(yaml, kMaxEurocYamlBytes, "camera sensor.yaml"), yaml.string());
    c.name = name;  // as open() names them
    return c;
  };
  calibration.cameras.push_back(camera("cam0"));
  if (use_right_camera && fs::exists(mav0 / "cam1" / "sensor.yaml")) {
    calibration.cameras.push_back(camera("cam1"));
  }
  const fs::path imu_yaml = mav0 / "imu0" / "sensor.yaml";
  calibration.imu =
      parseImuYaml(readText(imu_yaml, kMaxEurocYamlBytes, "IMU sensor.yaml"), imu_yaml.string());
  return calibration;
}

EurocDataset EurocDataset::open(const std::string& folder, const ReaderOptions& options) {
  if (options.stereo_tolerance_ns < 0) {
    throw InputError("EuRoC reader: stereo_tolerance_ns must be >= 0");
  }
  const fs::path root(folder);
  requireFolder(root, "EuRoC session");
  fs::path mav0 = root / "mav0";
  fs::path session = root;
  if (!fs::is_directory(mav0) && fs::is_directory(root / "cam0")) {
    mav0 = root;  // opened at mav0/ itself
    session = fs::absolute(root).parent_path();
  }
  requireFolder(mav0, "EuRoC mav0");
  EurocDataset d;
  d.folder_ = folder;
  d.mav0_ = mav0.string();

  const CameraFiles left = readCamera(mav0 / "cam0", "cam0", &d.stats_);
  d.calibration_.cameras.push_back(left.calibration);
  d.stats_.left_frames = left.rows.size();
  checkHeaderSize((left.data_dir / left.rows.front().filename).string(), left.calibration);
  if (options.use_right_camera && fs::exists(mav0 / "cam1")) {
    const CameraFiles right = readCamera(mav0 / "cam1", "cam1", &d.stats_);
    d.calibration_.cameras.push_back(right.calibration);
    d.stats_.right_frames = right.rows.size();
    checkHeaderSize((right.data_dir / right.rows.front().filename).string(), right.calibration);
    d.frames_ = pairFrames(left, right, options.stereo_tolerance_ns, &d.stats_);
    d.stats_.stereo_pairs = d.frames_.size();
    if (d.frames_.empty()) {
      throw InputError(mav0.string() + ": no cam0/cam1 rows pair within " +
                       std::to_string(options.stereo_tolerance_ns) + " ns");
    }
  } else {
    for (const ImageRow& row : left.rows) {
      d.frames_.push_back({row.timestamp_ns, (left.data_dir / row.filename).string(), ""});
    }
  }

  const fs::path imu_dir = mav0 / "imu0";
  requireFolder(imu_dir, "IMU");
  const fs::path imu_yaml = imu_dir / "sensor.yaml";
  d.calibration_.imu =
      parseImuYaml(readText(imu_yaml, kMaxEurocYamlBytes, "IMU sensor.yaml"), imu_yaml.string());
  const fs::path imu_csv = imu_dir / "data.csv";
  ImuCsv imu = parseImuCsv(readText(imu_csv, kMaxEurocCsvBytes, "IMU data.csv"), imu_csv.string());
  if (imu.samples.empty()) throw InputError(imu_csv.string() + ": no finite IMU sample");
  d.imu_ = std::move(imu.samples);
  d.stats_.imu_rows = imu.rows;
  d.stats_.imu_nonfinite_skipped = imu.nonfinite_skipped;
  countImuGaps(d.imu_, d.calibration_.imu.rate_hz, &d.stats_);

  const fs::path gt_csv = mav0 / "state_groundtruth_estimate0" / "data.csv";
  const fs::path gt_tum = session / "groundtruth_body.txt";
  if (fs::exists(gt_csv)) {
    d.ground_truth_ = parseGroundTruthCsv(
        readText(gt_csv, kMaxEurocCsvBytes, "ground truth data.csv"), gt_csv.string());
    d.ground_truth_file_ = gt_csv.string();
  } else if (fs::exists(gt_tum)) {
    d.ground_truth_ = parseGroundTruthTum(readText(gt_tum, kMaxEurocCsvBytes, "TUM ground truth"),
                                          gt_tum.string());
    d.ground_truth_file_ = gt_tum.string();
  }
  d.stats_.ground_truth_states = d.ground_truth_.size();
  return d;
}

std::vector<Event> EurocDataset::events() const {
  std::vector<Event> events;
  events.reserve(imu_.size() + frames_.size());
  std::size_t i = 0, f = 0;
  while (i < imu_.size() || f < frames_.size()) {
    const bool take_imu =
        f == frames_.size() || (i < imu_.size() && imu_[i].timestamp_ns <= frames_[f].timestamp_ns);
    if (take_imu) {
      events.push_back({imu_[i].timestamp_ns, Event::Kind::kImu, i});
      ++i;
    } else {
      events.push_back({frames_[f].timestamp_ns, Event::Kind::kFrame, f});
      ++f;
    }
  }
  return events;
}

std::optional<Eigen::Isometry3d> interpolateGroundTruth(const std::vector<GroundTruthState>& truth,
                                                        std::int64_t timestamp_ns,
                                                        std::int64_t max_gap_ns) {
  return interpolateStamped(
      truth, timestamp_ns, max_gap_ns, [](const GroundTruthState& s) { return s.timestamp_ns; },
      [](const GroundTruthState& s) { return s.T_W_B; });
}

GreyImage loadGreyImage(const std::string& path, const CameraCalibration& camera) {
  GreyImage image = readGreyImage(path);
  if (image.width_px != camera.width_px || image.height_px != camera.height_px) {
    throw InputError(path + ": image is " + std::to_string(image.width_px) + "x" +
                     std::to_string(image.height_px) + " but " + camera.name +
                     "/sensor.yaml resolution is " + std::to_string(camera.width_px) + "x" +
                     std::to_string(camera.height_px));
  }
  return image;
}

StereoImages EurocDataset::loadImages(std::size_t index) const {
  if (index >= frames_.size()) {
    throw InputError(folder_ + ": frame " + std::to_string(index) + " out of range (" +
                     std::to_string(frames_.size()) + " frames)");
  }
  const StereoFrame& frame = frames_[index];
  StereoImages images;
  images.left = loadGreyImage(frame.left_path, calibration_.cameras[0]);
  if (stereo()) images.right = loadGreyImage(frame.right_path, calibration_.cameras[1]);
  return images;
}

}  // namespace strata::euroc
