#pragma once
// Decoding of what strata-view receives over LCM, never trusting the payload: every length field
// is checked against the bytes that follow it before lcm-gen's decoder allocates for it, so a
// corrupt or hostile message costs at most its own size. The output types of strata-mapper
// (mesh_update_t, esdf_slice_t, map_stats_t, change_event_t, object_update_t) are checked here;
// pose_t and camera_info_t by strata::lcm's decodePayload.
//
// Errors: InputError naming the type and the problem (short, wrong type, a length past the end,
// bytes left over). Pure functions; thread safe.
#include <cstdint>
#include <optional>

#include "strata/change_event_t.hpp"
#include "strata/esdf_slice_t.hpp"
#include "strata/map_stats_t.hpp"
#include "strata/mesh_update_t.hpp"
#include "strata/object_update_t.hpp"
#include "strata/pose_t.hpp"

namespace strata::view {

mesh_update_t decodeMeshUpdate(const void* data, int size);
esdf_slice_t decodeEsdfSlice(const void* data, int size);
map_stats_t decodeMapStats(const void* data, int size);
change_event_t decodeChangeEvent(const void* data, int size);
object_update_t decodeObjectUpdate(const void* data, int size);

/// The pose inside an rgbd_frame_t payload (its utime and T_W_C as sent), read without decoding
/// the images; nullopt when the frame carries none (has_pose false).
std::optional<pose_t> framePose(const void* data, int size);

}  // namespace strata::view
