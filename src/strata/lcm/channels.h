#pragma once
// LCM channel names of the Strata processes (the table in README.md). Processes take them as
// defaults; each can be renamed on the command line.
namespace strata::lcm_io {

inline constexpr const char* kRgbdChannel = "STRATA_RGBD";                // rgbd_frame_t, in
inline constexpr const char* kCameraInfoChannel = "STRATA_CAMERA_INFO";   // camera_info_t, in
inline constexpr const char* kPoseChannel = "STRATA_POSE";                // pose_t T_W_C, in
inline constexpr const char* kImuChannel = "STRATA_IMU";                  // imu_t, in (recorded)
inline constexpr const char* kStereoChannel = "STRATA_STEREO";            // stereo_image_t (VIO)
inline constexpr const char* kCommandChannel = "STRATA_COMMAND";          // command_t, in
inline constexpr const char* kMeshChannel = "STRATA_MESH_UPDATE";         // mesh_update_t, out
inline constexpr const char* kEsdfChannel = "STRATA_ESDF_SLICE";          // esdf_slice_t, out
inline constexpr const char* kStatsChannel = "STRATA_MAP_STATS";          // map_stats_t, out
inline constexpr const char* kChangeChannel = "STRATA_CHANGE_EVENT";      // change_event_t, out
inline constexpr const char* kObjectsChannel = "STRATA_OBJECTS";         // object_update_t, out
inline constexpr const char* kKeyframeChannel = "STRATA_KEYFRAME_SCORE";  // keyframe_score_t, out
inline constexpr const char* kMapPoseChannel = "STRATA_MAP_POSE";  // pose_t T_W_C, map frame
inline constexpr const char* kLocalizationChannel = "STRATA_LOCALIZATION";  // localization_status_t

/// Multicast on the host only (ttl=0): nothing leaves the machine. A 4 MiB receive buffer holds
/// a few 640x480 frames (the kernel default of 208 KiB holds none; net.core.rmem_max caps it).
inline constexpr const char* kDefaultUrl = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304";

}  // namespace strata::lcm_io
