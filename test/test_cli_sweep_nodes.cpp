// Bad input to the LCM programs (`strata-mapper`, `strata-vio`, `strata-play`, `strata-localizer`),
// each run as its own process on memq:// (nothing on the network): each row names the command
// line, the exit code (2: bad input, whether the parser or the program refuses it), the words the
// message must hold, the inputs that must stay byte for byte as they were and the outputs that
// must not exist afterwards. Every row must be refused before any work: the fixture's calibration
// is a skeleton whose files are not EuRoC files, its TUM folder lacks its truth, its map file is
// not a map.
// A child that hangs is ended by SIGALRM after 30 s (and the row fails on its exit code).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_sweep.h"
#include "strata/map/map_file.h"
#include "test_utils.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

using Row = test::SweepRow;
using test::writeText;

/// Runs `program` with `args` (stdout and stderr those of this process, so the sweep captures
/// them); its exit code, or 128 + the signal that ended it.
int runProgram(const std::string& program, const std::vector<std::string>& args);

/// `defaults` (option-value pairs, or flags: an option followed by another option) with `args`
/// after them, leaving out each default option that `args` gives again (the parser refuses an
/// option given twice).
std::vector<std::string> withArgs(const std::vector<std::string>& defaults,
                                  const std::vector<std::string>& args) {
  auto given = [&](const std::string& option) {
    return std::find(args.begin(), args.end(), option) != args.end();
  };
  std::vector<std::string> all;
  for (std::size_t i = 0; i < defaults.size(); ++i) {
    const bool has_value = i + 1 < defaults.size() && defaults[i + 1].rfind("--", 0) != 0;
    if (!given(defaults[i])) {
      all.push_back(defaults[i]);
      if (has_value) all.push_back(defaults[i + 1]);
    }
    if (has_value) ++i;
  }
  all.insert(all.end(), args.begin(), args.end());
  return all;
}

int runProgram(const std::string& program, const std::vector<std::string>& args) {
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    alarm(30);  // survives execv: a child that hangs is ended
    std::vector<std::string> copies = args;
    std::vector<char*> argv;
    std::string name = program;
    argv.push_back(name.data());
    for (std::string& a : copies) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(name.c_str(), argv.data());
    std::perror(("execv " + program).c_str());
    _exit(127);
  }
  if (pid < 0) return -1;
  int status = 0;
  if (waitpid(pid, &status, 0) != pid) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

class NodeSweep : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::freshTempDir("cli_sweep_nodes");
    // An EuRoC layout whose files are not EuRoC files: read, they fail.
    for (const char* file : {"mav0/cam0/sensor.yaml", "mav0/cam1/sensor.yaml",
                             "mav0/imu0/sensor.yaml"}) {
      writeText(path("calib") / file, std::string("not read: ") + file + "\n");
    }
    // A TUM folder whose files are not TUM files, one without groundtruth.txt, a "map" that is
    // not a map, a mapper state with a change-detection session open.
    for (const char* file : {"tum/depth.txt", "tum/rgb.txt", "tum/groundtruth.txt",
                             "no_truth/depth.txt", "no_truth/rgb.txt"}) {
      writeText(path(file), "not read\n");
    }
    writeText(path("map.strata"), "not a Strata map\n");
    MapSessionRecord record;
    record.session_open = true;
    record.session_frames = 1;
    record.frames = 1;
    const TsdfMap empty{MapConfig{}};
    saveMapFile(MapFileContents{empty, empty, record}, str("open_session.strata"));
    test::makeCommonFixtures(dir_);
  }

  void TearDown() override { test::removeFixtures(dir_); }

  fs::path path(const std::string& name) const { return dir_ / name; }
  std::string str(const std::string& name) const { return path(name).string(); }

  // The programs with the fixture's defaults and `args` after them.
  std::function<int()> mapper(const std::vector<std::string>& args) const {
    const auto all = withArgs({"--url", "memq://", "--map", str("mapped.strata")}, args);
    return [all] { return runProgram(STRATA_MAPPER_BIN, all); };
  }
  std::function<int()> vio(const std::vector<std::string>& args) const {
    const auto all = withArgs(
        {"--url", "memq://", "--calib", str("calib"), "--summary", str("vio.json")}, args);
    return [all] { return runProgram(STRATA_VIO_BIN, all); };
  }
  std::function<int()> play(const std::vector<std::string>& args) const {
    const auto all = withArgs({"--url", "memq://", "--quiet", "--mapper-timeout", "1"}, args);
    return [all] { return runProgram(STRATA_PLAY_BIN, all); };
  }

  fs::path dir_;
};

TEST_F(NodeSweep, StrataMapper) {
  const fs::path map = path("map.strata"), open = path("open_session.strata");
  const fs::path mapped = path("mapped.strata"), objects = path("mapped.objects");
  const std::vector<Row> rows = {
      {"--voxel-size 0", mapper({"--voxel-size", "0"}), 2, {"voxel"}, {}, {mapped, objects}},
      {"--voxel-size nan", mapper({"--voxel-size", "nan"}), 2,
       {"--voxel-size", "not a finite number"}, {}, {mapped}},
      {"--max-depth -1", mapper({"--max-depth", "-1"}), 2, {"depth"}, {}, {mapped}},
      {"--max-depth inf", mapper({"--max-depth", "inf"}), 2, {"--max-depth", "not a finite"},
       {}, {mapped}},
      {"--esdf-rate -1", mapper({"--esdf-rate", "-1"}), 2, {"--esdf-rate", ">= 0"}, {}, {mapped}},
      {"--stats-rate 0", mapper({"--stats-rate", "0"}), 2, {"--stats-rate", "> 0"}, {}, {mapped}},
      {"--queue 0", mapper({"--queue", "0"}), 2, {"--queue must be 1 to 10000"}, {}, {mapped}},
      {"--queue 1000000000", mapper({"--queue", "1000000000"}), 2,
       {"--queue must be 1 to 10000", "not 1000000000"}, {}, {mapped}},
      {"--queue -5", mapper({"--queue", "-5"}), 2, {"--queue"}, {}, {mapped}},
      {"--slice-z nan", mapper({"--slice-z", "nan"}), 2, {"--slice-z", "not a finite number"},
       {}, {mapped}},
      {"--save-every -5", mapper({"--save-every", "-5"}), 2, {"--save-every", ">= 0"}, {},
       {mapped}},
      {"--change-threshold 0", mapper({"--change-threshold", "0"}), 2,
       {"--change-threshold must be a finite number > 0 (voxels)"}, {}, {mapped}},
      {"--change-min-weight -1", mapper({"--change-min-weight", "-1"}), 2,
       {"--change-min-weight must be a finite number > 0 (frames)"}, {}, {mapped}},
      {"--map in a folder that does not exist",
       mapper({"--map", str("no/such/folder/m.strata")}), 2, {"--map", "does not exist"}, {},
       {path("no")}},
      {"--map is a folder", mapper({"--map", str("a_folder")}), 2, {"--map", "a_folder"},
       {path("a_folder")}, {mapped}},
      {"--objects is --map", mapper({"--objects", str("mapped.strata")}), 2,
       {"--objects", "--map"}, {}, {mapped}},
      {"--map is not a map file: refused, left as it is", mapper({"--map", map.string()}), 2,
       {"cannot resume from the map file", "not a Strata map"}, {map}, {}},
      {"--map holds an open change session, --no-change",
       mapper({"--map", open.string(), "--no-change"}), 2,
       {"change-detection session still open", "without --no-change"}, {open}, {}},
      {"--url of no LCM provider", mapper({"--url", "bogus://"}), 2,
       {"LCM input 'bogus://' could not be opened"}, {}, {mapped}},
      {"an unknown option", mapper({"--voxels", "0.05"}), 2, {"--voxels"}, {}, {mapped}},
      {"--map in a read-only folder", mapper({"--map", str("readonly/m.strata")}), 2,
       {"--map", "not writable"}, {path("readonly")}, {}, true},
  };
  EXPECT_GE(test::sweepRows("strata-mapper", rows, dir_), rows.size() - 1);
}

TEST_F(NodeSweep, StrataVio) {
  const fs::path calib = path("calib"), summary = path("vio.json");
  const std::vector<Row> rows = {
      {"no --calib", [] { return runProgram(STRATA_VIO_BIN, {"--url", "memq://"}); }, 2,
       {"--calib is required"}, {}, {}},
      {"--calib that does not exist", vio({"--calib", str("nowhere")}), 2, {"nowhere"}, {},
       {summary}},
      {"--calib whose files are not EuRoC files", vio({}), 2, {"sensor.yaml"}, {calib},
       {summary}},
      {"--queue 0", vio({"--queue", "0"}), 2, {"--queue must be 1 to 10000"}, {calib},
       {summary}},
      {"--queue 1000000", vio({"--queue", "1000000"}), 2, {"--queue must be 1 to 10000"},
       {calib}, {summary}},
      {"--queue -5", vio({"--queue", "-5"}), 2, {"--queue"}, {calib}, {summary}},
      {"--max-idle-s nan", vio({"--max-idle-s", "nan"}), 2,
       {"--max-idle-s", "not a finite number"}, {calib}, {summary}},
      {"--max-idle-s -1", vio({"--max-idle-s", "-1"}), 2, {"--max-idle-s must be 0 to 86400"},
       {calib}, {summary}},
      {"--status-period 1e9", vio({"--status-period", "1e9"}), 2,
       {"--status-period must be 0 to 86400"}, {calib}, {summary}},
      {"--summary in a folder that does not exist",
       vio({"--summary", str("no/such/folder/v.json")}), 2, {"--summary", "does not exist"},
       {calib}, {path("no")}},
      {"--summary over the calibration it reads",
       vio({"--summary", str("calib/mav0/imu0/sensor.yaml")}), 2,
       {"--summary", "would overwrite a file of the input --calib"}, {calib}, {}},
      {"--summary is a folder", vio({"--summary", str("a_folder")}), 2, {"--summary", "a_folder"},
       {calib, path("a_folder")}, {}},
      {"--stereo-channel ''", vio({"--stereo-channel", ""}), 2, {"channel names must not be empty"},
       {calib}, {summary}},
      {"an unknown option", vio({"--calibration", str("calib")}), 2, {"--calibration"}, {calib},
       {summary}},
      {"--summary in a read-only folder", vio({"--summary", str("readonly/v.json")}), 2,
       {"--summary", "not writable"}, {calib, path("readonly")}, {}, true},
  };
  EXPECT_GE(test::sweepRows("strata-vio", rows, dir_), rows.size() - 1);
}

TEST_F(NodeSweep, StrataPlay) {
  const fs::path tum = path("tum");
  const std::vector<Row> rows = {
      {"no dataset", play({}), 2, {"dataset is required"}, {}, {}},
      {"a folder that does not exist", play({str("nowhere")}), 2, {"nowhere", "no such folder"},
       {}, {}},
      {"a file, not a folder", play({str("a_file")}), 2, {"a_file", "not a folder"},
       {path("a_file")}, {}},
      {"a TUM folder without its truth", play({str("no_truth")}), 2, {"groundtruth.txt"},
       {path("no_truth")}, {}},
      {"a TUM folder whose files are not TUM files", play({tum.string()}), 2, {"tum"}, {tum}, {}},
      {"sim: of a world that does not exist", play({"sim:nowhere"}), 2,
       {"world 'nowhere' not found"}, {}, {}},
      {"sim:room:99", play({"sim:room:99"}), 2, {"sessions 0..4"}, {}, {}},
      {"--sim-frames 1000000000", play({"sim:room:0", "--sim-frames", "1000000000"}), 2,
       {"--sim-frames must be 0 to 1000000", "not 1000000000"}, {}, {}},
      {"--frames past the end of the session",
       play({"sim:room:0", "--sim-frames", "5", "--first", "100"}), 2, {"no frames to send"}, {},
       {}},
      {"--rate nan", play({"sim:room:0", "--rate", "nan"}), 2, {"--rate", "not a finite number"},
       {}, {}},
      {"--rate -1", play({"sim:room:0", "--rate", "-1"}), 2, {"--rate must be 0 to 1000"}, {},
       {}},
      {"--rate 1e9", play({"sim:room:0", "--rate", "1e9"}), 2, {"--rate must be 0 to 1000"}, {},
       {}},
      {"--window 0", play({"sim:room:0", "--window", "0"}), 2, {"--window must be 1 to 10000"},
       {}, {}},
      {"--stride 0", play({"sim:room:0", "--stride", "0"}), 2, {"--stride must be 1 to"}, {}, {}},
      {"--frames -5", play({"sim:room:0", "--frames", "-5"}), 2, {"--frames must be 0 to"}, {},
       {}},
      {"--first -1", play({"sim:room:0", "--first", "-1"}), 2, {"--first must be 0 to"}, {}, {}},
      {"--frames 10^12 (beyond an int)", play({"sim:room:0", "--frames", "1000000000000"}), 2,
       {"--frames"}, {}, {}},
      {"--depth-encoding jpg", play({"sim:room:0", "--depth-encoding", "jpg"}), 2,
       {"depth16 or depth32f"}, {}, {}},
      {"--mapper-timeout 0", play({"sim:room:0", "--mapper-timeout", "0"}), 2,
       {"--mapper-timeout must be a finite number > 0"}, {}, {}},
      {"--mapper-timeout inf", play({"sim:room:0", "--mapper-timeout", "inf"}), 2,
       {"--mapper-timeout", "not a finite number"}, {}, {}},
      {"--with-stereo with --rate 0", play({"sim:room:0", "--with-stereo", "--rate", "0"}), 2,
       {"--with-stereo needs --rate > 0"}, {}, {}},
      {"--with-stereo with --imu", play({"sim:room:0", "--with-stereo", "--imu"}), 2,
       {"drop --imu"}, {}, {}},
      {"--with-stereo on a folder without mav0/", play({tum.string(), "--with-stereo"}), 2,
       {"has no mav0/"}, {tum}, {}},
      {"--url of no LCM provider", play({"sim:room:0", "--url", "bogus://"}), 2,
       {"LCM URL 'bogus://' could not be opened"}, {}, {}},
      {"an unknown option", play({"sim:room:0", "--speed", "2"}), 2, {"--speed"}, {}, {}},
  };
  EXPECT_EQ(test::sweepRows("strata-play", rows, dir_), rows.size());
}

#ifdef STRATA_LOCALIZER_BIN
TEST_F(NodeSweep, StrataLocalizer) {
  const fs::path db = path("map.strata"), report = path("localizer.json");  // db: not a map
  auto localizer = [&](const std::vector<std::string>& args) {
    const auto all = withArgs({"--url", "memq://", "--db", db.string(), "--report",
                               report.string()}, args);
    return std::function<int()>([all] { return runProgram(STRATA_LOCALIZER_BIN, all); });
  };
  const std::vector<Row> rows = {
      {"no --db", [] { return runProgram(STRATA_LOCALIZER_BIN, {"--url", "memq://"}); }, 2,
       {"--db is required"}, {}, {}},
      {"--db that does not exist", localizer({"--db", str("nowhere.sqlite")}), 2,
       {"nowhere.sqlite", "does not exist"}, {}, {report, path("nowhere.sqlite")}},
      {"--db that is not a map database: refused, left as it is", localizer({}), 2,
       {"cannot use the prior map", "not a database"}, {db}, {report}},
      {"--every 0", localizer({"--every", "0"}), 2, {"--every must be 1 to 10000"}, {db},
       {report}},
      {"--every 1000000", localizer({"--every", "1000000"}), 2, {"--every must be 1 to 10000"},
       {db}, {report}},
      {"--max-odometry-gap 0", localizer({"--max-odometry-gap", "0"}), 2,
       {"--max-odometry-gap must be"}, {db}, {report}},
      {"--max-idle-s nan", localizer({"--max-idle-s", "nan"}), 2,
       {"--max-idle-s", "not a finite number"}, {db}, {report}},
      {"--report over the --db", localizer({"--report", db.string()}), 2,
       {"--report", "the input --db"}, {db}, {}},
      {"--report in a folder that does not exist",
       localizer({"--report", str("no/such/folder/l.json")}), 2, {"--report", "does not exist"},
       {db}, {path("no")}},
      {"--pose-channel is the odometry's", localizer({"--pose-channel", "STRATA_POSE"}), 2,
       {"both an input and an output"}, {db}, {report}},
      {"--status-channel ''", localizer({"--status-channel", ""}), 2,
       {"channel names must not be empty"}, {db}, {report}},
      {"--url of no LCM provider", localizer({"--url", "bogus://"}), 2,
       {"LCM input 'bogus://' could not be opened"}, {db}, {report}},
      {"an unknown option", localizer({"--map", db.string()}), 2, {"--map"}, {db}, {report}},
  };
  EXPECT_EQ(test::sweepRows("strata-localizer", rows, dir_), rows.size());
}
#endif

}  // namespace
}  // namespace strata
