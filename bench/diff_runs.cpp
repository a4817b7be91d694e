#include "diff_runs.h"

#include <cstdio>

#include "strata/sim/session/sim_session.h"
#include "summary.h"

namespace strata::bench {
namespace {

constexpr double kMinLabelAgreement = 0.999;  // target: device and reference labels

/// Fuses one simulated session into `detector`; returns the fusion device time.
double fuseSession(change::ChangeDetector& detector, int session, const Dataset& data,
                   std::size_t& frames) {
  double device_ms = 0.0;
  frames = data.size();
  for (std::size_t i = 0; i < frames; ++i) {
    const FrameStats fs = detector.integrate(session, data.load(i), data.intrinsics());
    device_ms += fs.normals_ms + fs.allocate_ms + fs.integrate_ms;
    if ((i + 1) % 100 == 0 || i + 1 == frames) {
      std::fprintf(stderr, "  session %d: frame %zu/%zu\n", session, i + 1, frames);
    }
  }
  return device_ms;
}

Json stagesJson(const change::ChangeStageTimes& t) {
  return Json::object()
      .set("neighbour_table_ms", t.neighbours_ms)
      .set("difference_ms", t.difference_ms)
      .set("erosion_ms", t.erosion_ms)
      .set("dilation_ms", t.dilation_ms)
      .set("static_update_ms", t.static_update_ms)
      .set("session_dynamic_ms", t.session_dynamic_ms)
      .set("total_ms", t.total());
}

/// Nanoseconds per voxel of the allocated blocks, per stage.
Json perVoxelJson(const change::ChangeStageTimes& t, std::uint64_t voxels) {
  const double to_ns = voxels > 0 ? 1e6 / static_cast<double>(voxels) : 0.0;
  change::ChangeStageTimes ns = t;
  ns.neighbours_ms *= to_ns;  // in total_ns
  ns.difference_ms *= to_ns;
  ns.erosion_ms *= to_ns;
  ns.dilation_ms *= to_ns;
  ns.static_update_ms *= to_ns;
  ns.session_dynamic_ms *= to_ns;
  return Json::object()
      .set("difference_ns", ns.difference_ms)
      .set("erosion_ns", ns.erosion_ms)
      .set("dilation_ns", ns.dilation_ms)
      .set("static_update_ns", ns.static_update_ms)
      .set("session_dynamic_ns", ns.session_dynamic_ms)
      .set("total_ns", ns.total());
}

template <typename Field>
std::vector<double> collect(const DiffRun& run, Field field) {
  std::vector<double> out;
  for (const DiffSessionRun& s : run.sessions) out.push_back(field(s));
  return out;
}

}  // namespace

DiffRun runDiff(const DiffRunSettings& s) {
  vk::ContextOptions options;
  options.device_selector = s.device;
  options.log_device = false;
  auto context = vk::Context::create(options);
  DiffRun run;
  run.device_name = context->deviceName();
  change::ChangeDetector device(*context, s.map, s.change);
  change::ChangeDetector reference(s.map, s.change);
  sim::SimSessionConfig session_config;
  session_config.max_frames = s.frames;
  for (int session = 0; session < s.sessions; ++session) {
    const sim::SimSessionDataset data(s.world, session, session_config);
    DiffSessionRun r;
    r.session = device.beginSession();
    r.fusion_device_ms = fuseSession(device, r.session, data, r.frames);
    r.device = device.endSession(r.session);
    std::fprintf(stderr, "  session %d: %u blocks, update %.1f ms device\n", session,
                 r.device.blocks, r.device.stages.total());
    if (s.reference) {
      reference.addSessionMap(device.sessionMap(r.session));
      r.reference = reference.endSession(r.session);
      r.label_agreement = change::labelAgreement(device.labels(), reference.labels());
      r.part_agreement = change::labelAgreement(device.sessionDynamic(r.session),
                                                reference.sessionDynamic(r.session));
      std::fprintf(stderr, "  session %d: reference %.1f ms, labels agree %.5f\n", session,
                   r.reference.stages.total(), r.label_agreement);
      run.ok = run.ok && r.label_agreement >= kMinLabelAgreement &&
               r.part_agreement >= kMinLabelAgreement;
    }
    run.ok = run.ok && r.device.blocks > 0;
    run.sessions.push_back(r);
  }
  run.device_bytes = device.deviceMap()->deviceBytes();
  return run;
}

Json diffSessionJson(const DiffSessionRun& r) {
  const change::ChangeUpdateStats& d = r.device;
  Json out = Json::object()
                 .set("session", r.session)
                 .set("frames", r.frames)
                 .set("fusion_device_ms", r.fusion_device_ms)
                 .set("blocks", d.blocks)
                 .set("voxels", d.voxels)
                 .set("device", stagesJson(d.stages))
                 .set("device_per_voxel", perVoxelJson(d.stages, d.voxels))
                 .set("device_update_wall_ms", d.wall_ms)
                 .set("dynamic_voxels", Json::object()
                                            .set("difference", d.raw_dynamic_voxels)
                                            .set("after_erosion", d.eroded_dynamic_voxels)
                                            .set("after_dilation", d.dynamic_voxels)
                                            .set("session_dynamic_part", d.session_dynamic_voxels));
  if (r.reference.session < 0) return out.set("reference", "not run (--no-reference)");
  const double total = d.stages.total();
  return out.set("reference", stagesJson(r.reference.stages))
      .set("reference_per_voxel", perVoxelJson(r.reference.stages, d.voxels))
      .set("speedup_over_reference", total > 0.0 ? r.reference.stages.total() / total : 0.0)
      .set("label_agreement", r.label_agreement)
      .set("session_dynamic_agreement", r.part_agreement)
      .set("reference_dynamic_voxels", r.reference.dynamic_voxels);
}

Json diffSummaryJson(const DiffRun& run) {
  auto device = [&](auto stage) {
    return meanMedian(collect(run, [&](const DiffSessionRun& s) { return stage(s.device); }));
  };
  auto reference = [&](auto stage) {
    return meanMedian(collect(run, [&](const DiffSessionRun& s) { return stage(s.reference); }));
  };
  auto total = [](const change::ChangeUpdateStats& u) { return u.stages.total(); };
  auto per_voxel = [](const change::ChangeUpdateStats& u) {
    return u.voxels > 0 ? u.stages.total() * 1e6 / static_cast<double>(u.voxels) : 0.0;
  };
  return Json::object()
      .set("device_update_ms", device(total))
      .set("device_update_ns_per_voxel", device(per_voxel))
      .set("device_difference_ms", device([](auto& u) { return u.stages.difference_ms; }))
      .set("device_erosion_ms", device([](auto& u) { return u.stages.erosion_ms; }))
      .set("device_dilation_ms", device([](auto& u) { return u.stages.dilation_ms; }))
      .set("device_static_update_ms", device([](auto& u) { return u.stages.static_update_ms; }))
      .set("device_session_dynamic_ms", device([](auto& u) { return u.stages.session_dynamic_ms; }))
      .set("reference_update_ms", reference(total))
      .set("device_map_mib", static_cast<double>(run.device_bytes) / (1 << 20));
}

}  // namespace strata::bench
