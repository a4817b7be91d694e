#include "soak_report.h"

#include <cstdio>

namespace strata::bench {
namespace {

/// The first sample at or after `t_s` (the last one when none is).
const SoakSample& sampleAt(const SoakRun& run, double t_s) {
  for (const SoakSample& x : run.samples) {
    if (x.elapsed_s >= t_s) return x;
  }
  return run.samples.back();
}

template <typename Field>
Json column(const SoakRun& run, Field field) {
  Json values = Json::array();
  for (const SoakSample& x : run.samples) values.push(x.*field);
  return values;
}

Json samplesJson(const SoakRun& run) {
  return Json::object()
      .set("elapsed_s", column(run, &SoakSample::elapsed_s))
      .set("rss_mib", column(run, &SoakSample::rss_mib))
      .set("hwm_mib", column(run, &SoakSample::hwm_mib))
      .set("device_mib", column(run, &SoakSample::device_mib))
      .set("blocks", column(run, &SoakSample::blocks))
      .set("frames_sent", column(run, &SoakSample::frames_sent))
      .set("frames_received", column(run, &SoakSample::frames_received))
      .set("frames_fused", column(run, &SoakSample::frames_fused))
      .set("frames_dropped", column(run, &SoakSample::frames_dropped))
      .set("frames_rejected", column(run, &SoakSample::frames_rejected))
      .set("sessions_completed", column(run, &SoakSample::sessions_completed));
}

Json totalsJson(const SoakRun& run) {
  const SoakSample& end = run.samples.back();
  return Json::object()
      .set("seconds", end.elapsed_s)
      .set("sessions_completed", end.sessions_completed)
      .set("play_failures", run.play_failures)
      .set("mapper_exit_code", run.mapper_exit_code)
      .set("frames_sent", end.frames_sent)
      .set("frames_received", end.frames_received)
      .set("frames_fused", end.frames_fused)
      .set("frames_dropped", end.frames_dropped)
      .set("frames_rejected", end.frames_rejected)
      .set("frames_per_s", end.elapsed_s > 0 ? end.frames_fused / end.elapsed_s : 0.0);
}

Json memoryJson(const SoakRun& run) {
  const SoakSample& start = run.samples.front();
  const SoakSample& warm = sampleAt(run, run.first_loop_end_s);
  const SoakSample& end = run.samples.back();
  return Json::object()
      .set("rss_start_mib", start.rss_mib)
      .set("rss_at_warmup_end_mib", warm.rss_mib)
      .set("rss_end_mib", end.rss_mib)
      .set("hwm_end_mib", end.hwm_mib)
      .set("device_start_mib", start.device_mib)
      .set("device_at_warmup_end_mib", warm.device_mib)
      .set("device_end_mib", end.device_mib)
      .set("blocks_end", end.blocks);
}

Json plateauJson(const PlateauVerdict& v) {
  return Json::object()
      .set("warmup_end_s", v.warmup_end_s)
      .set("rss_slope_last_half_mib_per_min", v.rss_slope_last_half_mib_per_min)
      .set("rss_first_third_after_warmup_mib", v.rss_first_third_mib)
      .set("rss_last_third_mib", v.rss_last_third_mib)
      .set("rss_growth_thirds_mib", v.rss_growth_thirds_mib)
      .set("map_stable_since_s", v.map_stable_since_s)
      .set("map_blocks_max", v.map_blocks_max)
      .set("device_at_map_stable_mib", v.device_at_map_stable_mib)
      .set("device_end_mib", v.device_end_mib)
      .set("device_growth_after_map_stable_mib", v.device_growth_after_map_stable_mib)
      .set("device_slope_after_map_stable_mib_per_min", v.device_slope_after_map_stable_mib_per_min)
      .set("plateau", v.plateau)
      .set("plateau_rule",
           "|RSS slope, second half| < 1 MiB/min and |device growth after the "
           "map stopped growing| < 1 MiB (a reading aid, not asserted)");
}

}  // namespace

SoakSeries soakSeries(const SoakRun& run) {
  SoakSeries s;
  for (const SoakSample& x : run.samples) {
    s.t_s.push_back(x.elapsed_s);
    s.rss_mib.push_back(x.rss_mib);
    s.hwm_mib.push_back(x.hwm_mib);
    s.device_mib.push_back(x.device_mib);
    s.blocks.push_back(x.blocks);
  }
  return s;
}

Json soakResults(const SoakRun& run, const PlateauVerdict& verdict) {
  return Json::object()
      .set("totals", totalsJson(run))
      .set("memory", memoryJson(run))
      .set("plateau", plateauJson(verdict))
      .set("session_ends_s", Json::numbers(run.session_ends_s))
      .set("samples", samplesJson(run));
}

std::string describeSoak(const SoakRun& run, const PlateauVerdict& v) {
  const SoakSample& start = run.samples.front();
  const SoakSample& end = run.samples.back();
  char text[512];
  std::snprintf(
      text, sizeof(text),
      "%.0f s, %lld sessions: %lld frames sent, %lld received, %lld fused (%.1f/s), "
      "%lld dropped, %lld rejected. Mapper RSS %.1f MiB at the start, %.1f at warm-up "
      "end, %.1f at the end (peak %.1f); device memory %.1f -> %.1f MiB. ",
      end.elapsed_s, static_cast<long long>(end.sessions_completed),
      static_cast<long long>(end.frames_sent), static_cast<long long>(end.frames_received),
      static_cast<long long>(end.frames_fused),
      end.elapsed_s > 0 ? end.frames_fused / end.elapsed_s : 0.0,
      static_cast<long long>(end.frames_dropped), static_cast<long long>(end.frames_rejected),
      start.rss_mib, sampleAt(run, run.first_loop_end_s).rss_mib, end.rss_mib, end.hwm_mib,
      start.device_mib, end.device_mib);
  return text + describePlateau(v);
}

}  // namespace strata::bench
