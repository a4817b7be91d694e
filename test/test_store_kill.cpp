// Crash safety of the session store: a child process imports big sessions one transaction each
// and is SIGKILLed while it writes one; the reopened database passes SQLite's integrity and
// foreign-key checks and holds exactly the sessions that committed, each whole. A second Store
// reading the file meanwhile sees committed batches only.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <random>
#include <thread>

#include "strata/store/session_store.h"
#include "store_test_helpers.h"

namespace strata::test {
namespace {

namespace fs = std::filesystem;

constexpr int kKeyframesPerSession = 5000;
constexpr int kTrials = 5;

/// The child: sessions of kKeyframesPerSession keyframes and their odometry edges, each in one
/// transaction, reporting 'b' before it begins one and 'c' once its commit returned.
[[noreturn]] void importForever(const fs::path& db, int report_fd) {
  try {
    store::Store store(db.string());
    for (int i = 0; i < 1000; ++i) {
      const char begin = 'b', committed = 'c';
      if (::write(report_fd, &begin, 1) != 1) ::_exit(4);
      auto transaction = store.beginTransaction();
      const std::int64_t s =
          store.addSession("session_" + std::to_string(i), "/virtual/session_" + std::to_string(i));
      std::vector<store::KeyframeRecord> keyframes(kKeyframesPerSession);
      for (int k = 0; k < kKeyframesPerSession; ++k) {
        keyframes[k].session_id = s;
        keyframes[k].timestamp_s = k * 0.1;
        keyframes[k].T_S_C = samplePose(k % 50);
      }
      const auto ids = store.addKeyframes(keyframes);
      std::vector<store::EdgeRecord> edges(ids.size() - 1);
      for (std::size_t e = 0; e + 1 < ids.size(); ++e) {
        edges[e].from_keyframe = ids[e];
        edges[e].to_keyframe = ids[e + 1];
      }
      store.addEdges(edges);
      transaction.commit();
      if (::write(report_fd, &committed, 1) != 1) ::_exit(4);
    }
  } catch (...) {
    ::_exit(3);
  }
  ::_exit(0);
}

struct Reports {
  int begun = 0, committed = 0;
};

void count(char c, Reports& r) { (c == 'b' ? r.begun : r.committed) += 1; }

TEST(StoreKill, KilledImportLeavesExactlyTheCommittedSessions) {
  const fs::path dir = freshStoreDir("kill");
  std::mt19937 rng(20261204u);
  int killed_mid_write = 0;
  for (int trial = 0; trial < kTrials; ++trial) {
    const fs::path db = dir / ("map_" + std::to_string(trial) + ".sqlite");
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      ::close(fds[0]);
      importForever(db, fds[1]);
    }
    ::close(fds[1]);
    // Kill once the third session (or, in later trials, a later one) has begun, after a random
    // delay of up to 40 ms into its write.
    const int kill_after_begins = 3 + trial % 2;
    Reports reports;
    char c = 0;
    while (reports.begun < kill_after_begins && ::read(fds[0], &c, 1) == 1) count(c, reports);
    ASSERT_EQ(reports.begun, kill_after_begins) << "the child stopped early";
    std::this_thread::sleep_for(std::chrono::milliseconds(rng() % 40));
    ::kill(child, SIGKILL);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "child status " << status;
    while (::read(fds[0], &c, 1) == 1) count(c, reports);
    ::close(fds[0]);

    store::Store store(db.string());  // quick_check runs on open
    store::Database raw(db.string(), false);
    EXPECT_EQ(raw.queryInt("SELECT COUNT(*) FROM pragma_foreign_key_check", "fk check"), 0);
    const auto sessions = store.sessions();
    // A commit can return just before the kill, its report unsent: one more than reported.
    EXPECT_GE(static_cast<int>(sessions.size()), reports.committed) << trial;
    EXPECT_LE(static_cast<int>(sessions.size()), reports.committed + 1) << trial;
    EXPECT_LE(static_cast<int>(sessions.size()), reports.begun) << trial;
    if (static_cast<int>(sessions.size()) < reports.begun) ++killed_mid_write;
    for (std::size_t i = 0; i < sessions.size(); ++i) {
      EXPECT_EQ(sessions[i].name, "session_" + std::to_string(i));
      EXPECT_EQ(store.keyframes(sessions[i].id).size(), std::size_t{kKeyframesPerSession});
    }
    EXPECT_EQ(store.edges().size(), sessions.size() * (kKeyframesPerSession - 1));
    std::printf("trial %d: %d begun, %d reported committed, %zu in the database\n", trial,
                reports.begun, reports.committed, sessions.size());
  }
  // Sessions of 5000 keyframes take far longer to write than the delay before the kill.
  EXPECT_GT(killed_mid_write, 0);
  fs::remove_all(dir);
}

TEST(StoreKill, ReaderSeesOnlyCommittedBatchesWhileAWriterWorks) {
  const fs::path dir = freshStoreDir("reader");
  const fs::path db = dir / "map.sqlite";
  store::Store writer(db.string());
  store::Store reader(db.string());
  writer.addSession("first", "/virtual/first");
  {
    auto transaction = writer.beginTransaction();
    const std::int64_t s = writer.addSession("second", "/virtual/second");
    writer.addKeyframes({store::KeyframeRecord{0, s, 1.0, samplePose(1), {}, {}}});
    EXPECT_EQ(reader.sessions().size(), 1u);  // the open batch is invisible
    transaction.commit();
  }
  EXPECT_EQ(reader.sessions().size(), 2u);
  EXPECT_EQ(reader.keyframes(reader.sessions()[1].id).size(), 1u);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace strata::test
