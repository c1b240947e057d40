// The malformed-scenario corpus (tests/malformed/): every file must be rejected by the real
// `endatsim run` binary with exit code 2 and a message naming the file, the JSON path (or the
// line and column of a syntax error) and what was expected - no crash, no hang, no silent default.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace {

namespace fs = std::filesystem;

const fs::path kDir = fs::path(ENDATSIM_SOURCE_DIR) / "tests" / "malformed";

struct Case {
  std::string file;
  std::string path;      // "/..." JSON path, or "line L, column C" for a syntax error
  std::string fragment;  // part of the expectation the message must state
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.file; }

std::vector<Case> manifest() {
  std::vector<Case> cases;
  std::ifstream in(kDir / "MANIFEST.tsv");
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto tab1 = line.find('\t'), tab2 = line.find('\t', tab1 + 1);
    if (tab1 == std::string::npos || tab2 == std::string::npos) {
      cases.push_back({"MANIFEST.tsv: bad line: " + line, "", ""});
      continue;
    }
    cases.push_back({line.substr(0, tab1), line.substr(tab1 + 1, tab2 - tab1 - 1), line.substr(tab2 + 1)});
  }
  return cases;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Outcome {
  int status;  // exit code; 124 from timeout(1) means the run hung, >= 128 a signal
  std::string err;
};

Outcome run_cli(const fs::path& scenario) {
  static int calls = 0;
  const std::string tag = std::to_string(getpid()) + "_" + std::to_string(++calls);
  const fs::path out = fs::temp_directory_path() / ("endatsim_malformed_out_" + tag);
  const fs::path err = fs::temp_directory_path() / ("endatsim_malformed_err_" + tag);
  const std::string cmd = "timeout 60 " + std::string(ENDATSIM_EXE) + " run '" + scenario.string() + "' >'" +
                          out.string() + "' 2>'" + err.string() + "'";
  const int raw = std::system(cmd.c_str());
  Outcome o{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(err)};
  fs::remove(out);
  fs::remove(err);
  return o;
}

class Malformed : public testing::TestWithParam<Case> {};

TEST_P(Malformed, RejectedWithExitCodeTwoNamingFilePathAndExpectation) {
  const Case& c = GetParam();
  ASSERT_FALSE(c.path.empty()) << c.file;
  const fs::path file = kDir / c.file;
  ASSERT_TRUE(fs::exists(file)) << file;
  const Outcome o = run_cli(file);
  EXPECT_EQ(o.status, 2) << "stderr: " << o.err;
  EXPECT_NE(o.err.find(file.string() + ": "), std::string::npos) << "the message must name the file: " << o.err;
  const std::string where = c.path[0] == '/' ? "at " + c.path : c.path;
  EXPECT_NE(o.err.find(where), std::string::npos) << "the message must name " << where << ": " << o.err;
  EXPECT_NE(o.err.find(c.fragment), std::string::npos) << "the message must say \"" << c.fragment << "\": " << o.err;
  EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << "one line of error, not a dump: " << o.err;
}

std::string case_name(const testing::TestParamInfo<Case>& info) {
  std::string n;
  for (char ch : info.param.file) n += std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
  return n;
}

INSTANTIATE_TEST_SUITE_P(Corpus, Malformed, testing::ValuesIn(manifest()), case_name);

TEST(MalformedCorpus, EveryFileIsListedOnceAndTheCorpusIsLarge) {
  const auto cases = manifest();
  std::set<std::string> listed;
  for (const auto& c : cases) EXPECT_TRUE(listed.insert(c.file).second) << "listed twice: " << c.file;
  std::set<std::string> present;
  for (const auto& e : fs::directory_iterator(kDir))
    if (e.path().filename() != "MANIFEST.tsv") present.insert(e.path().filename().string());
  EXPECT_EQ(listed, present) << "every file in tests/malformed/ needs a MANIFEST.tsv line, and every line a file";
  EXPECT_GE(cases.size(), 50U);
}

}  // namespace
