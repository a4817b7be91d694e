// Store: pose-graph edges and keyframe features.
#include "strata/core/error.h"
#include "strata/store/internal/store_sql.h"
#include "strata/store/session_store.h"

namespace strata::store {

using detail::bindPose;
using detail::placeholders;
using detail::poseColumns;
using detail::readPose;

namespace {

bool keyframeExists(Statement& lookup, std::int64_t id) {
  lookup.bind(1, id);
  const bool found = lookup.step();
  lookup.reset();
  return found;
}

void checkEdgeShape(const EdgeRecord& e, const std::string& what) {
  if ((e.kind == EdgeKind::kPrior) != !e.to_keyframe) {
    throw InputError(what + (e.kind == EdgeKind::kPrior ? ": a prior has no 'to' keyframe"
                                                        : ": needs a 'to' keyframe"));
  }
  if ((e.kind == EdgeKind::kLoop) != e.loop.has_value()) {
    throw InputError(what + (e.kind == EdgeKind::kLoop ? ": a loop edge needs its statistics"
                                                       : ": loop statistics on a non-loop edge"));
  }
  if (!e.T_from_to.matrix().allFinite() || !e.information.allFinite()) {
    throw InputError(what + ": non-finite pose or information");
  }
  if (e.loop && !(e.loop->inlier_ratio >= 0.0 && e.loop->inlier_ratio <= 1.0)) {
    throw InputError(what + ": inlier ratio " + std::to_string(e.loop->inlier_ratio) +
                     " outside [0, 1]");
  }
}

}  // namespace

std::vector<std::int64_t> Store::addEdges(const std::vector<EdgeRecord>& edges) {
  Transaction transaction(*db_);
  Statement lookup(*db_, "SELECT 1 FROM keyframes WHERE id = ?");
  Statement insert(*db_, "INSERT INTO edges (kind, from_keyframe, to_keyframe, " +
                             poseColumns("T_from_to") +
                             ", information, loop_inliers, loop_inlier_ratio, loop_residual, "
                             "loop_accepted) VALUES (" +
                             placeholders(15) + ")");
  std::vector<std::int64_t> ids;
  ids.reserve(edges.size());
  for (const EdgeRecord& e : edges) {
    const std::string what = "map database '" + path() + "': " + edgeKindName(e.kind) +
                             " edge from keyframe " + std::to_string(e.from_keyframe);
    checkEdgeShape(e, what);
    for (std::optional<std::int64_t> id :
         {std::optional<std::int64_t>(e.from_keyframe), e.to_keyframe}) {
      if (id && !keyframeExists(lookup, *id)) {
        throw InputError(what + ": no keyframe " + std::to_string(*id));
      }
    }
    insert.bind(1, std::string(edgeKindName(e.kind))).bind(2, e.from_keyframe);
    insert.bind(3, e.to_keyframe);
    bindPose(insert, 4, e.T_from_to);
    insert.bindBlob(11, matrixToBlob(e.information));
    if (e.loop) {
      insert.bind(12, e.loop->inliers).bind(13, e.loop->inlier_ratio).bind(14, e.loop->residual);
      insert.bind(15, std::int64_t{e.loop->accepted ? 1 : 0});
    } else {
      for (int i = 12; i <= 15; ++i) insert.bindNull(i);
    }
    insert.run();
    ids.push_back(db_->lastInsertId());
  }
  transaction.commit();
  return ids;
}

std::vector<EdgeRecord> Store::edges(std::optional<EdgeKind> kind) {
  Statement s(*db_, "SELECT id, kind, from_keyframe, to_keyframe, " + poseColumns("T_from_to") +
                        ", information, loop_inliers, loop_inlier_ratio, loop_residual, "
                        "loop_accepted FROM edges WHERE ? IS NULL OR kind = ? ORDER BY id");
  if (kind) {
    s.bind(1, std::string(edgeKindName(*kind))).bind(2, std::string(edgeKindName(*kind)));
  }
  std::vector<EdgeRecord> out;
  while (s.step()) {
    EdgeRecord e;
    e.id = s.getInt(0);
    const std::string what = "map database '" + path() + "': edge " + std::to_string(e.id);
    e.kind = parseEdgeKind(s.getText(1), what);
    e.from_keyframe = s.getInt(2);
    if (!s.isNull(3)) e.to_keyframe = s.getInt(3);
    e.T_from_to = *readPose(s, 4, what);
    e.information = matrixFromBlob(s.getBlob(11), what + " information");
    if (!s.isNull(15)) {
      e.loop = LoopStats{s.getInt(12), s.getDouble(13), s.getDouble(14), s.getInt(15) != 0};
    }
    out.push_back(std::move(e));
  }
  return out;
}

void Store::setFeatures(std::int64_t keyframe_id, const FeatureSet& features) {
  const std::vector<std::uint8_t> blob = featuresToBlob(features);
  Transaction transaction(*db_);
  Statement lookup(*db_, "SELECT 1 FROM keyframes WHERE id = ?");
  if (!keyframeExists(lookup, keyframe_id)) {
    throw InputError("map database '" + path() + "': setFeatures: no keyframe " +
                     std::to_string(keyframe_id));
  }
  Statement insert(*db_,
                   "INSERT OR REPLACE INTO features (keyframe_id, format, count, "
                   "descriptor_bytes, data) VALUES (?, ?, ?, ?, ?)");
  insert.bind(1, keyframe_id).bind(2, features.format);
  insert.bind(3, static_cast<std::int64_t>(features.keypoints_px.size()));
  insert.bind(4, static_cast<std::int64_t>(features.descriptor_bytes)).bindBlob(5, blob).run();
  transaction.commit();
}

std::optional<FeatureSet> Store::features(std::int64_t keyframe_id) {
  Statement s(*db_,
              "SELECT format, descriptor_bytes, count, data FROM features "
              "WHERE keyframe_id = ?");
  s.bind(1, keyframe_id);
  if (!s.step()) return std::nullopt;
  return featuresFromBlob(
      s.getText(0), static_cast<std::uint32_t>(s.getInt(1)), static_cast<std::size_t>(s.getInt(2)),
      s.getBlob(3),
      "map database '" + path() + "': features of keyframe " + std::to_string(keyframe_id));
}

}  // namespace strata::store
