#include "cli/demo_objects.h"

#include <sstream>

#include "cli/objects_outputs.h"
#include "cli/objects_truth.h"
#include "core/json_text.h"

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
  const std::string truth_json = eval::objectDbEvaluationJson(*report.objects, 4);
  const ObjectsFiles files =
      writeObjectsFiles(run, result, out_dir, eval::objectDbEvaluationJson(*report.objects, 2));
  std::size_t segments = 0;
  for (const auto& session : run.outcomes) segments += session.size();
  std::ostringstream json;
  json << "{\"models\": " << run.database.models().size() << ", \"segments\": " << segments
       << ", \"build_s\": " << jsonNumber(run.build_s) << ", \"file\": " << jsonQuoted(files.json)
       << ", \"database\": " << jsonQuoted(files.database)
       << ", \"contact_sheet\": " << jsonQuoted(files.contact_sheet)
       << ",\n    \"truth\": " << truth_json << "}";
  report.objects_json = json.str();
  report.objects_summary = "Object database: " + summarizeObjects(run) + "; against the truth: " +
                           eval::describeObjectDbEvaluation(*report.objects) +
                           " (objects.json, objects.png).";
}

}  // namespace strata::apps
