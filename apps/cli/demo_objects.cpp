#include "cli/demo_objects.h"

#include "cli/objects_outputs.h"
#include "cli/objects_truth.h"
#include "cli/report_json.h"

namespace strata::apps {

void addDemoObjects(const DiffResult& result, const std::vector<TsdfMap>& maps,
                    const std::shared_ptr<const sim::World>& world, const std::string& out_dir,
                    DemoReport& report) {
  const ObjectsRun run = buildObjectDatabase(result, maps);
  SimTruth truth{world, {}};
  for (std::size_t s = 0; s < result.sessions.size(); ++s) {
    truth.world_sessions.push_back(static_cast<int>(s));
  }
  report.objects = evaluateObjectsRun(truth, result, run);
  const std::string truth_json = eval::objectDbEvaluationJson(*report.objects);
  const ObjectsFiles files = writeObjectsFiles(run, result, out_dir, truth_json);
  std::size_t segments = 0;
  for (const auto& session : run.outcomes) segments += session.size();
  Json json;
  json["models"] = run.database.models().size();
  json["segments"] = segments;
  json["build_s"] = run.build_s;
  json["file"] = files.json;
  json["database"] = files.database;
  json["contact_sheet"] = files.contact_sheet;
  json["truth"] = parseJson(truth_json);
  report.objects_json = jsonText(json);
  report.objects_summary = "Object database: " + summarizeObjects(run) + "; against the truth: " +
                           eval::describeObjectDbEvaluation(*report.objects) +
                           " (objects.json, objects.png).";
}

}  // namespace strata::apps
