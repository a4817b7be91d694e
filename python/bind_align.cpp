// strata.store and strata.align (bindings.h): the session store (one SQLite map of many
// sessions), the import of recorded session folders into it, and the multi-session alignment
// that registers them into one world frame, as `strata align --db` runs it. The GIL is released
// during imports and the alignment.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "bindings.h"
#include "convert.h"
#include "strata/align/alignment_eval.h"
#include "strata/align/store_alignment.h"
#include "strata/core/error.h"
#include "strata/core/pose_interpolation.h"
#include "strata/io/tum_format.h"
#include "strata/store/session_import.h"
#include "strata/store/session_store.h"

namespace strata::python {
namespace {

namespace fs = std::filesystem;

/// A Store that can be closed (later calls raise InputError).
class PyStore {
 public:
  PyStore(const std::string& path, bool create, bool read_only) {
    store::StoreOptions options;
    options.create = create;
    options.read_only = read_only;
    py::gil_scoped_release release;
    store_ = std::make_unique<store::Store>(path, options);
  }
  store::Store& get() {
    if (!store_) throw InputError("the store is closed");
    return *store_;
  }
  void close() { store_.reset(); }

 private:
  std::unique_ptr<store::Store> store_;
};

py::object optionalPose(const std::optional<Eigen::Isometry3d>& T) {
  return T ? py::object(poseTo(*T)) : py::object(py::none());
}

py::dict keyframesOf(PyStore& self, std::int64_t session_id) {
  const std::vector<store::KeyframeRecord> keyframes = self.get().keyframes(session_id);
  py::array_t<double> t(static_cast<py::ssize_t>(keyframes.size()));
  std::vector<std::optional<Eigen::Isometry3d>> T_S_C, T_W_C;
  for (std::size_t k = 0; k < keyframes.size(); ++k) {
    t.mutable_at(k) = keyframes[k].timestamp_s;
    T_S_C.emplace_back(keyframes[k].T_S_C);
    T_W_C.push_back(keyframes[k].T_W_C);
  }
  std::vector<std::int64_t> ids;
  for (const auto& k : keyframes) ids.push_back(k.id);
  py::dict out;
  out["id"] = ids;
  out["timestamp_s"] = t;
  out["T_S_C"] = poseStackTo(T_S_C);
  out["T_W_C"] = poseStackTo(T_W_C);
  return out;
}

/// One session of an alignment as arrays.
struct PyAlignedSession {
  std::int64_t id = 0;
  std::string name;
  bool aligned = false;
  py::object T_W_S;                    // 4 x 4 or None
  py::array_t<double> trajectory;      // N x 8 (t, x, y, z, qx, qy, qz, qw), T_W_C; 0 x 8 unaligned
  py::array_t<double> odometry;        // N x 8, T_S_C as given
  py::array_t<double> keyframe_T_W_C;  // K x 4 x 4
};

struct PyAlignment {
  std::vector<PyAlignedSession> sessions;
  std::size_t candidates = 0, loops_verified = 0, loops_accepted = 0;
  py::dict times;
  std::optional<align::AlignmentScore> score;
};

PyAlignment alignmentFrom(const align::StoreAlignment& a,
                          const std::optional<align::AlignmentScore>& score) {
  PyAlignment out;
  for (std::size_t s = 0; s < a.sessions.size(); ++s) {
    const align::AlignedSession& r = a.result.sessions[s];
    PyAlignedSession session;
    session.id = a.sessions[s].id;
    session.name = a.sessions[s].name;
    session.aligned = r.aligned;
    session.T_W_S = optionalPose(r.T_W_S);
    std::vector<std::pair<double, Eigen::Isometry3d>> world, odometry;
    for (std::size_t i = 0; i < r.frame_timestamps_s.size(); ++i) {
      if (i < r.frame_T_W_C.size()) world.emplace_back(r.frame_timestamps_s[i], r.frame_T_W_C[i]);
      if (i < r.frame_T_S_C.size())
        odometry.emplace_back(r.frame_timestamps_s[i], r.frame_T_S_C[i]);
    }
    session.trajectory = tumArray(world);
    session.odometry = tumArray(odometry);
    session.keyframe_T_W_C = poseStackTo({r.keyframe_T_W_C.begin(), r.keyframe_T_W_C.end()});
    out.sessions.push_back(std::move(session));
  }
  out.candidates = a.result.candidates;
  out.loops_verified = a.result.loops.size();
  for (const align::AlignLoop& l : a.result.loops) out.loops_accepted += l.accepted ? 1 : 0;
  const align::AlignStageTimes& t = a.result.times;
  out.times["features_s"] = t.features_s;
  out.times["retrieval_s"] = t.retrieval_s;
  out.times["verification_s"] = t.verification_s;
  out.times["graph_s"] = t.graph_s;
  out.score = score;
  return out;
}

PyAlignment alignStoreOf(PyStore& self, std::size_t candidates, double intra_gap_s,
                         bool intra_session_loops, int threads, bool truth) {
  align::AlignConfig config;
  config.candidates_per_keyframe = candidates;
  config.min_intra_session_gap_s = intra_gap_s;
  config.intra_session_loops = intra_session_loops;
  config.threads = threads;
  config.graph.threads = threads;
  config.validate();
  store::Store& db = self.get();
  align::StoreAlignment a;
  std::optional<align::AlignmentScore> score;
  {
    py::gil_scoped_release release;
    a = align::alignStore(db, config);
    if (truth) {
      if (const auto t = align::loadStoreTruth(a)) score = align::scoreAlignment(a.result, *t, config);
    }
  }
  return alignmentFrom(a, score);
}

}  // namespace

void bindStore(py::module_& s) {
  py::class_<store::SessionRecord>(s, "Session", "A session (mission) of a store.")
      .def_readonly("id", &store::SessionRecord::id)
      .def_readonly("name", &store::SessionRecord::name)
      .def_readonly("source_folder", &store::SessionRecord::source_folder,
                    "The folder it was imported from (absolute)")
      .def_readonly("aligned", &store::SessionRecord::aligned)
      .def_property_readonly(
          "T_W_S", [](const store::SessionRecord& r) { return optionalPose(r.T_W_S); },
          "4 x 4 session-to-world once aligned, else None")
      .def("__repr__", [](const store::SessionRecord& r) {
        return "Session(id=" + std::to_string(r.id) + ", name='" + r.name +
               "', aligned=" + (r.aligned ? "True" : "False") + ")";
      });

  py::class_<store::ImportResult>(s, "ImportResult", "What import_session did.")
      .def_readonly("skipped", &store::ImportResult::skipped,
                    "The folder was in the store already; nothing was written")
      .def_readonly("session_id", &store::ImportResult::session_id)
      .def_readonly("name", &store::ImportResult::name)
      .def_readonly("odometry_file", &store::ImportResult::odometry_file)
      .def_readonly("frames", &store::ImportResult::frames)
      .def_readonly("keyframes", &store::ImportResult::keyframes)
      .def_readonly("edges", &store::ImportResult::edges)
      .def_readonly("resources", &store::ImportResult::resources)
      .def("__repr__", [](const store::ImportResult& r) {
        return "ImportResult(session_id=" + std::to_string(r.session_id) + ", '" + r.name + "', " +
               std::to_string(r.keyframes) + " keyframes of " + std::to_string(r.frames) +
               " frames" + (r.skipped ? ", skipped" : "") + ")";
      });

  py::class_<PyStore>(s, "Store",
                      "A map database (store/session_store.h): one SQLite file holding many "
                      "sessions, each in its own odometry frame, their keyframes, edges and "
                      "alignment.")
      .def(py::init<const std::string&, bool, bool>(), py::arg("path"), py::arg("create") = true,
           py::arg("read_only") = false,
           "Opens (or, with create, makes) the store at path; InputError for a file that is not "
           "a usable map.")
      .def_property_readonly(
          "path", [](PyStore& self) { return self.get().path(); }, "The database file")
      .def(
          "import_session",
          [](PyStore& self, const std::string& folder, int keyframe_every,
             double keyframe_distance_m) {
            store::ImportOptions options;
            options.keyframe_every = keyframe_every;
            options.keyframe_distance_m = keyframe_distance_m;
            store::Store& db = self.get();
            py::gil_scoped_release release;
            return store::importTumSession(db, folder, options);
          },
          py::arg("folder"), py::arg("keyframe_every") = 10, py::arg("keyframe_distance_m") = 0.0,
          "Imports a recorded session folder (TUM layout; odometry.txt, else groundtruth.txt, as "
          "its odometry) in one transaction, as `strata align` does: a keyframe every N frames "
          "and/or after keyframe_distance_m of motion. A folder already in the store is skipped.")
      .def(
          "sessions", [](PyStore& self) { return self.get().sessions(); },
          "The sessions, in id order.")
      .def("keyframes", &keyframesOf, py::arg("session_id"),
           "A session's keyframes in time order: dict(id list, timestamp_s N, T_S_C N x 4 x 4 "
           "(odometry), T_W_C N x 4 x 4 (optimised; NaN where not aligned)).")
      .def(
          "loop_count",
          [](PyStore& self) { return self.get().edges(store::EdgeKind::kLoop).size(); },
          "Loop edges the last alignment stored.")
      .def("close", &PyStore::close, "Closes the database; later calls raise.")
      .def("__repr__", [](PyStore& self) { return "Store(" + self.get().path() + ")"; });
}

void bindAlign(py::module_& a) {
  py::class_<PyAlignedSession>(a, "AlignedSession", "One session of an alignment.")
      .def_readonly("id", &PyAlignedSession::id, "The session's id in the store")
      .def_readonly("name", &PyAlignedSession::name)
      .def_readonly("aligned", &PyAlignedSession::aligned,
                    "Whether verified loops join it to the anchor")
      .def_readonly("T_W_S", &PyAlignedSession::T_W_S,
                    "4 x 4 session-to-world, or None when unaligned")
      .def_readonly("trajectory", &PyAlignedSession::trajectory,
                    "N x 8 (t, x, y, z, qx, qy, qz, qw): each frame's T_W_C, corrected by its "
                    "keyframes (0 x 8 when unaligned)")
      .def_readonly("odometry", &PyAlignedSession::odometry, "N x 8: the odometry T_S_C as given")
      .def_readonly("keyframe_T_W_C", &PyAlignedSession::keyframe_T_W_C,
                    "K x 4 x 4: the relaxed keyframe poses")
      .def("__repr__", [](const PyAlignedSession& s) {
        return "AlignedSession('" + s.name + "', " + (s.aligned ? "aligned" : "unaligned") + ")";
      });

  py::class_<align::AlignmentScore>(a, "AlignmentScore",
                                    "An alignment against the sessions' groundtruth.txt "
                                    "(align/alignment_eval.h).")
      .def_readonly("aligned_sessions", &align::AlignmentScore::aligned_sessions)
      .def_readonly("ate_before_rmse_m", &align::AlignmentScore::ate_before_rmse_m,
                    "The odometry in its own frames, one rigid fit for all sessions")
      .def_readonly("ate_after_rmse_m", &align::AlignmentScore::ate_after_rmse_m,
                    "The aligned frames, one rigid fit")
      .def_readonly("ate_after_max_m", &align::AlignmentScore::ate_after_max_m)
      .def_readonly("accepted_true", &align::AlignmentScore::accepted_true,
                    "Loops kept by the graph that are true")
      .def_readonly("accepted_false", &align::AlignmentScore::accepted_false)
      .def_readonly("loop_precision", &align::AlignmentScore::loop_precision)
      .def_readonly("loop_recall", &align::AlignmentScore::loop_recall,
                    "Keyframes with a loop opportunity that got an accepted true loop")
      .def("__repr__", [](const align::AlignmentScore& s) {
        std::ostringstream o;
        o << "AlignmentScore(ate_after_rmse_m=" << s.ate_after_rmse_m
          << ", ate_before_rmse_m=" << s.ate_before_rmse_m
          << ", loop_precision=" << s.loop_precision << ")";
        return o.str();
      });

  py::class_<PyAlignment>(a, "Alignment", "What align_store found (and wrote into the store).")
      .def_readonly("sessions", &PyAlignment::sessions, "[AlignedSession], in id order")
      .def_readonly("candidates", &PyAlignment::candidates, "Loop candidates verified")
      .def_readonly("loops_verified", &PyAlignment::loops_verified,
                    "Candidates that passed verification")
      .def_readonly("loops_accepted", &PyAlignment::loops_accepted, "Loops kept by the graph")
      .def_readonly("times", &PyAlignment::times,
                    "dict of stage wall times: features_s, retrieval_s, verification_s, graph_s")
      .def_readonly("score", &PyAlignment::score,
                    "AlignmentScore against the folders' groundtruth.txt, or None without it")
      .def("__repr__", [](const PyAlignment& r) {
        return "Alignment(" + std::to_string(r.sessions.size()) + " sessions, " +
               std::to_string(r.loops_accepted) + " loops kept of " +
               std::to_string(r.loops_verified) + " verified)";
      });

  a.def("align_store", &alignStoreOf, py::arg("store"), py::arg("candidates") = 4,
        py::arg("intra_gap_s") = 15.0, py::arg("intra_session_loops") = true,
        py::arg("threads") = 2, py::arg("truth") = true,
        "Aligns every session of the store (the first by id anchors the world frame) and writes "
        "the result into it, replacing an earlier one, as `strata align --db`: features per "
        "keyframe, verified loops, the multi-session pose graph. Each session's frames are read "
        "from the folder it was imported from (InputError naming a session whose folder is gone "
        "or changed; the store is unchanged then). With truth, scored against the folders' "
        "groundtruth.txt when every session has one. The GIL is released while it runs.");
}

}  // namespace strata::python
