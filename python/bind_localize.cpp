// strata.localize (bindings.h): localisation of live RGB-D frames against a prior map store
// (localize/prior_map.h, localizer.h, pose_fusion.h, session_localization.h). The GIL is released
// while a map loads, a frame is localised and a session runs; Ctrl-C stops a session between
// frames.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "bindings.h"
#include "convert.h"
#include "strata/core/error.h"
#include "strata/io/open_dataset.h"
#include "strata/localize/session_localization.h"
#include "strata/store/session_store.h"

namespace strata::python {
// Named, not anonymous: the module is a unity build, and bind_align.cpp has helpers of its own.
namespace localize_bindings {

namespace fs = std::filesystem;
using localize::PriorMap;

/// The map store at `path`, opened read-only, as a prior map (the GIL released while it loads).
std::unique_ptr<PriorMap> openPriorMap(const std::string& path, int threads) {
  if (!fs::is_regular_file(path)) throw InputError("map database '" + path + "' does not exist");
  localize::PriorMapConfig config;
  config.threads = threads;
  config.validate();
  py::gil_scoped_release release;
  store::StoreOptions options;
  options.read_only = true;
  store::Store db(path, options);
  return std::unique_ptr<PriorMap>(new PriorMap(PriorMap::fromStore(db, config)));
}

localize::Localization localizeFrame(const localize::Localizer& self, const py::object& color,
                                     const py::array& depth, const CameraIntrinsics& intrinsics,
                                     const py::object& prior, double depth_scale) {
  RgbdFrame frame;
  depthInto(depth, depth_scale, frame.depth);
  colorInto(color, frame.color);
  validateFrame(frame, intrinsics);
  std::optional<localize::PosePrior> pose_prior;
  if (!prior.is_none())
    pose_prior = localize::PosePrior{poseFrom(prior.cast<py::array>(), "prior")};
  py::gil_scoped_release release;
  return self.localize(frame.color, frame.depth, intrinsics, pose_prior);
}

/// localize_session's result as arrays.
struct PySessionLocalization {
  py::array_t<double> timestamps_s;  // N
  py::array_t<bool> placed;          // N: the frame has a map-frame pose
  py::array_t<bool> localized;       // N: its own localisation succeeded
  py::array_t<double> T_W_C;         // N x 4 x 4, NaN where not placed
  std::vector<std::string> status;   // N: uninitialised / tracking / corrected
  std::vector<std::string> notes;    // N: why not localised, why rejected, or ""
  std::size_t attempts = 0, localizations = 0, accepted = 0, rejected = 0;
  std::size_t check_frames = 0, check_localized = 0;
  bool with_odometry = false;
};

PySessionLocalization sessionFrom(const localize::SessionLocalization& s) {
  PySessionLocalization out;
  const auto n = static_cast<py::ssize_t>(s.frames.size());
  out.timestamps_s = py::array_t<double>(n);
  out.placed = py::array_t<bool>(n);
  out.localized = py::array_t<bool>(n);
  std::vector<std::optional<Eigen::Isometry3d>> poses;
  for (py::ssize_t i = 0; i < n; ++i) {
    const localize::FrameLocalization& f = s.frames[static_cast<std::size_t>(i)];
    out.timestamps_s.mutable_at(i) = f.timestamp_s;
    out.placed.mutable_at(i) = f.placed();
    out.localized.mutable_at(i) = f.attempted && f.localization.localized;
    poses.push_back(f.placed() ? std::optional<Eigen::Isometry3d>(f.fused.T_W_C) : std::nullopt);
    out.status.emplace_back(localize::fusionStatusName(f.fused.status));
    std::string note = f.fused.note;
    if (note.empty() && f.attempted && !f.localization.localized)
      note = "not localised: " + f.localization.reason;
    out.notes.push_back(note);
  }
  out.T_W_C = poseStackTo(poses);
  out.attempts = s.attempted;
  out.localizations = s.localized;
  out.accepted = s.accepted;
  out.rejected = s.rejected;
  out.check_frames = s.check_frames;
  out.check_localized = s.check_localized;
  out.with_odometry = s.with_odometry;
  return out;
}

PySessionLocalization localizeSessionOf(const std::string& session_dir, const py::object& map,
                                        int every, bool odometry, int threads) {
  if (!fs::is_directory(session_dir))
    throw InputError("session folder '" + session_dir + "' does not exist");
  std::unique_ptr<PriorMap> loaded;
  const PriorMap* prior_map = nullptr;
  if (py::isinstance<PriorMap>(map)) {
    prior_map = &map.cast<const PriorMap&>();
  } else if (py::isinstance<py::str>(map) || py::hasattr(map, "__fspath__")) {
    loaded = openPriorMap(py::str(map).cast<std::string>(), threads);
    prior_map = loaded.get();
  } else {
    throw InputError("map must be a strata.localize.PriorMap or the path of a map store");
  }
  localize::SessionLocalizationConfig config;
  config.every = every;
  config.validate();
  DatasetOptions options;
  const fs::path odometry_file = fs::path(session_dir) / "odometry.txt";
  if (odometry && fs::is_regular_file(odometry_file))
    options.trajectory_file = odometry_file.string();
  localize::SessionLocalization result;
  bool interrupted = false;
  {
    py::gil_scoped_release release;
    const std::unique_ptr<Dataset> frames = openDataset(session_dir, options);
    std::vector<Eigen::Isometry3d> T_O_C;
    if (!options.trajectory_file.empty())
      for (std::size_t i = 0; i < frames->size(); ++i) T_O_C.push_back(frames->stamp(i).T_W_C);
    // Ctrl-C: a pending signal stops the pass between frames (the GIL taken just for the check).
    result = localize::localizeSession(*frames, T_O_C, *prior_map, config,
                                       [&](std::size_t, std::size_t) {
                                         py::gil_scoped_acquire gil;
                                         interrupted = PyErr_CheckSignals() != 0;
                                         return !interrupted;
                                       });
  }
  if (interrupted) throw py::error_already_set();  // the KeyboardInterrupt the check raised
  return sessionFrom(result);
}

std::string fusedRepr(const localize::FusedPose& p) {
  std::ostringstream o;
  o << "FusedPose(" << localize::fusionStatusName(p.status) << ", sigma " << p.translation_sigma_m
    << " m" << (p.note.empty() ? "" : ", " + p.note) << ")";
  return o.str();
}

}  // namespace localize_bindings

void bindLocalize(py::module_& l) {
  using namespace localize_bindings;
  using localize::FusedPose;
  using localize::Localization;
  using localize::Localizer;
  using localize::PoseFusion;

  py::class_<PriorMap>(l, "PriorMap",
                       "The keyframes of a map store (poses in the map frame, depth, ORB features, "
                       "surface descriptions, the place index) that frames are localised against "
                       "(localize/prior_map.h).")
      .def(py::init(&openPriorMap), py::arg("path"), py::arg("threads") = 2,
           "Loads the map store at path (opened read-only; never changed) with `threads` "
           "workers; the GIL is released while it loads. InputError for a missing file, a store "
           "with no usable session, or a session whose folder is gone or changed.")
      .def_property_readonly(
          "keyframes", [](const PriorMap& m) { return m.keyframes().size(); },
          "Number of map keyframes")
      .def_property_readonly("sessions", &PriorMap::sessions, "Names of the sessions it holds")
      .def_property_readonly("skipped_sessions", &PriorMap::skipped_sessions,
                             "Names of the sessions left out (unaligned)")
      .def_property_readonly(
          "keyframe_poses",
          [](const PriorMap& m) {
            std::vector<std::optional<Eigen::Isometry3d>> poses;
            for (const auto& k : m.keyframes()) poses.emplace_back(k.T_W_C);
            return poseStackTo(poses);
          },
          "K x 4 x 4 float64: each keyframe's T_W_C in the map frame")
      .def("__repr__", [](const PriorMap& m) {
        return "PriorMap(" + std::to_string(m.keyframes().size()) + " keyframes, " +
               std::to_string(m.sessions().size()) + " sessions)";
      });

  py::class_<Localization>(l, "Localization",
                           "One frame's localisation: the pose with its covariance, or why not.")
      .def_readonly("localized", &Localization::localized)
      .def_readonly("reason", &Localization::reason, "Why not localised ('' when localised)")
      .def_property_readonly(
          "T_W_C", [](const Localization& r) { return poseTo(r.T_W_C); }, "4 x 4 camera to map")
      .def_readonly("covariance", &Localization::covariance,
                    "6 x 6 (tx ty tz rx ry rz) of a right-multiplied perturbation")
      .def_readonly("keyframe", &Localization::keyframe, "Index of the map keyframe used")
      .def_readonly("candidates", &Localization::candidates, "Candidates verified")
      .def_readonly("accepted", &Localization::accepted, "Of those, accepted by the verifier")
      .def_readonly("inliers", &Localization::inliers)
      .def_readonly("residual_m", &Localization::residual_m, "ICP RMS")
      .def_readonly("overlap", &Localization::overlap, "ICP overlap")
      .def_readonly("from_surface", &Localization::from_surface)
      .def_readonly("source", &Localization::candidate_source,
                    "'appearance', 'surface' or 'prior' ('' when not localised)")
      .def_readonly("time_ms", &Localization::time_ms, "Wall time of the call")
      .def_readonly("features_ms", &Localization::features_ms)
      .def_readonly("surface_ms", &Localization::surface_ms)
      .def_readonly("verify_ms", &Localization::verify_ms)
      .def("__repr__", [](const Localization& r) {
        return r.localized ? "Localization(localized by " + r.candidate_source + ", keyframe " +
                                 std::to_string(r.keyframe) + ")"
                           : "Localization(not localized: " + r.reason + ")";
      });

  py::class_<Localizer>(l, "Localizer", "Localises frames against a PriorMap (localizer.h).")
      .def(py::init<const PriorMap&>(), py::arg("prior_map"), py::keep_alive<1, 2>(),
           "A localiser with the default configuration; it keeps prior_map alive.")
      .def("localize", &localizeFrame, py::arg("color"), py::arg("depth"), py::arg("intrinsics"),
           py::arg("prior") = py::none(), py::arg("depth_scale") = 1000.0,
           "Localises one frame: color H x W x 3 uint8 (or None), depth float32 metres or "
           "uint16 (depth_scale units per metre), prior a 4 x 4 T_W_C the caller believes (to "
           "propose candidates) or None. Returns a Localization; InputError for images whose "
           "sizes disagree with the intrinsics. The GIL is released during the call.");

  py::class_<FusedPose>(l, "FusedPose", "The map-frame pose PoseFusion gives at a frame.")
      .def_property_readonly(
          "status", [](const FusedPose& p) { return localize::fusionStatusName(p.status); },
          "'uninitialised', 'tracking' or 'corrected'")
      .def_property_readonly(
          "T_W_C", [](const FusedPose& p) { return poseTo(p.T_W_C); },
          "4 x 4 camera to map (identity while uninitialised)")
      .def_readonly("covariance", &FusedPose::covariance, "6 x 6 of the correction (t, r)")
      .def_readonly("translation_sigma_m", &FusedPose::translation_sigma_m)
      .def_readonly("jump_m", &FusedPose::jump_m, "How far this frame's update moved the camera")
      .def_readonly("note", &FusedPose::note, "E.g. why a localisation was rejected")
      .def("__repr__", &fusedRepr);

  py::class_<PoseFusion>(l, "PoseFusion",
                         "Odometry fused with localisations: a Kalman filter on the "
                         "odometry-to-map correction T_W_O (pose_fusion.h).")
      .def(py::init<>(), "A filter with the default configuration, uninitialised.")
      .def(
          "predict",
          [](PoseFusion& self, double timestamp_s, const py::array& T_O_C) {
            return self.predict(timestamp_s, poseFrom(T_O_C, "T_O_C"));
          },
          py::arg("timestamp_s"), py::arg("T_O_C"),
          "A new odometry pose (4 x 4 camera to odometry frame); returns the FusedPose with only "
          "the odometry applied. InputError for time going backwards (nothing changes).")
      .def("correct", &PoseFusion::correct, py::arg("localization"),
           "A Localization of the frame last predicted; returns that frame's FusedPose. Refused "
           "localisations leave the correction as it was (see note).")
      .def("reset", &PoseFusion::reset, "Forgets the correction.")
      .def(
          "prior",
          [](const PoseFusion& self) -> py::object {
            const auto p = self.prior();
            return p ? py::object(poseTo(p->T_W_C)) : py::object(py::none());
          },
          "The 4 x 4 T_W_C prior for Localizer.localize at the last predicted frame, or None "
          "while uninitialised.")
      .def_property_readonly("initialised", &PoseFusion::initialised)
      .def_property_readonly(
          "T_W_O", [](const PoseFusion& self) { return poseTo(self.T_W_O()); },
          "4 x 4 odometry to map: the correction")
      .def_property_readonly("accepted", &PoseFusion::accepted, "Localisations accepted")
      .def_property_readonly("rejected", &PoseFusion::rejected, "Localisations gated out");

  py::class_<PySessionLocalization>(l, "SessionLocalization",
                                    "What localize_session gives: per-frame arrays and counts.")
      .def_readonly("timestamps_s", &PySessionLocalization::timestamps_s, "N")
      .def_readonly("placed", &PySessionLocalization::placed,
                    "N bool: the frame has a map-frame pose")
      .def_readonly("localized", &PySessionLocalization::localized,
                    "N bool: the frame's own localisation succeeded")
      .def_readonly("T_W_C", &PySessionLocalization::T_W_C, "N x 4 x 4, NaN where not placed")
      .def_readonly("status", &PySessionLocalization::status,
                    "N of uninitialised/tracking/corrected")
      .def_readonly("notes", &PySessionLocalization::notes, "N: why not localised or rejected")
      .def_readonly("attempts", &PySessionLocalization::attempts,
                    "Frames localisation was tried on")
      .def_readonly("localizations", &PySessionLocalization::localizations, "Of those, localised")
      .def_readonly("accepted", &PySessionLocalization::accepted, "Accepted by the fusion")
      .def_readonly("rejected", &PySessionLocalization::rejected, "Gated out by the fusion")
      .def_readonly("check_frames", &PySessionLocalization::check_frames,
                    "Frames of the up-front sample tried")
      .def_readonly("check_localized", &PySessionLocalization::check_localized)
      .def_readonly("with_odometry", &PySessionLocalization::with_odometry)
      .def("__repr__", [](const PySessionLocalization& s) {
        return "SessionLocalization(" + std::to_string(s.localizations) + " of " +
               std::to_string(s.attempts) + " localised, " + std::to_string(s.status.size()) +
               " frames)";
      });

  l.def("localize_session", &localizeSessionOf, py::arg("session_dir"), py::arg("map"),
        py::arg("every") = 1, py::arg("odometry") = true, py::arg("threads") = 2,
        "Localises every `every`-th frame of a TUM session folder against map (a PriorMap or "
        "the path of a map store), as `strata localize`: with odometry (the folder's "
        "odometry.txt, when present and odometry=True) every frame is fused and placed, without "
        "only the localised frames are. InputError when a sample of frames localises nowhere "
        "(a map of another place). The GIL is released while it runs; Ctrl-C (a pending "
        "signal) stops it between frames.");
}

}  // namespace strata::python
