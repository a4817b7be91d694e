// Every input a fuzz target ever crashed on, replayed through the same entry point (parser_entries.h):
// test/data/fuzz_regressions/<target>/<input> must now be refused with an InputError whose message
// contains the text of <input>.expected (the problem the fixed parser names). The seeds of
// fuzz/corpus/ go through the same entries and must be accepted.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "strata/core/error.h"
#include "parser_entries.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

std::string readAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// The first line of `<input>.expected`.
std::string expectedMessage(const fs::path& input) {
  std::string text = readAll(input.string() + ".expected");
  text = text.substr(0, text.find('\n'));
  return text;
}

void expectRefused(fuzz::Entry entry, const fs::path& input) {
  SCOPED_TRACE(input.string());
  const std::string expected = expectedMessage(input);
  ASSERT_FALSE(expected.empty()) << "no " << input.string() << ".expected";
  const std::string data = readAll(input);
  try {
    entry(reinterpret_cast<const std::uint8_t*>(data.data()), data.size());
    ADD_FAILURE() << "accepted; expected an InputError containing '" << expected << "'";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos)
        << "message '" << e.what() << "' lacks '" << expected << "'";
  }
}

TEST(FuzzRegressions, EveryCommittedCrasherIsRefusedWithItsError) {
  const fs::path root(STRATA_FUZZ_REGRESSIONS_DIR);
  ASSERT_TRUE(fs::is_directory(root)) << root;
  int replayed = 0;
  for (const fs::directory_entry& folder : fs::directory_iterator(root)) {
    if (!folder.is_directory()) continue;
    const fuzz::Entry entry = fuzz::findEntry(folder.path().filename().string());
    ASSERT_NE(entry, nullptr) << "no fuzz target named " << folder.path().filename();
    for (const fs::directory_entry& file : fs::directory_iterator(folder.path())) {
      if (file.path().extension() == ".expected") continue;
      expectRefused(entry, file.path());
      ++replayed;
    }
  }
  EXPECT_GT(replayed, 0);
}

// The seeds are valid inputs: a seed the parser refuses starts the fuzzer off the parser's main path.
TEST(FuzzRegressions, EverySeedIsAccepted) {
  for (const std::string& name : fuzz::entryNames()) {
    const fs::path folder = fs::path(STRATA_FUZZ_CORPUS_DIR) / name;
    ASSERT_TRUE(fs::is_directory(folder)) << "no seed corpus " << folder;
    for (const fs::directory_entry& file : fs::directory_iterator(folder)) {
      const std::string data = readAll(file.path());
      EXPECT_NO_THROW(fuzz::findEntry(name)(reinterpret_cast<const std::uint8_t*>(data.data()),
                                      data.size()))
          << file.path();
    }
  }
}

TEST(FuzzRegressions, EveryTargetHasAnEntry) {
  for (const std::string& name : fuzz::entryNames()) EXPECT_NE(fuzz::findEntry(name), nullptr);
  EXPECT_EQ(fuzz::findEntry("fuzz_no_such_target"), nullptr);
}

}  // namespace
}  // namespace strata
