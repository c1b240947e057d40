#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>

#include "endatsim/tools/exit_status.hpp"
#include "scenario_support.hpp"

namespace {

struct Run {
  int status;
  std::string err;
  std::string out;
};

// This process's own directory for the files its tests write (ctest runs them in parallel
// processes), removed when it exits.
const std::filesystem::path& scratch() {
  struct Dir {
    std::filesystem::path path;
    Dir() {
      std::string pattern = (std::filesystem::temp_directory_path() / "endatsim_cli_XXXXXX").string();
      if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
      path = pattern;
    }
    ~Dir() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  };
  static const Dir dir;
  return dir.path;
}

Run run(const std::string& args) {
  const auto& dir = scratch();
  static int calls = 0;
  const std::string tag = std::to_string(++calls);
  const std::string out = (dir / ("endatsim_cli_out_" + tag)).string(), err = (dir / ("endatsim_cli_err_" + tag)).string();
  const std::string cmd = std::string(ENDATSIM_EXE) + " " + args + " >" + out + " 2>" + err;
  const int raw = std::system(cmd.c_str());
  const auto slurp = [](const std::string& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  Run r{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(err), slurp(out)};
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = (scratch() / name).string();
  std::ofstream(path) << text;
  return path;
}

const std::string kBundled = std::string(ENDATSIM_SOURCE_DIR) + "/scenarios/bundled/";

}  // namespace

TEST(Cli, PassingScenarioExitsZero) {
  const auto r = run("run " + kBundled + "endat21_1mhz_10m.json");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("PASS endat21_1mhz_10m"), std::string::npos);
}

TEST(Cli, UnmetExpectationExitsOne) {
  const auto path = write_temp("endatsim_cli_fail.json", R"({"name": "wrong", "line": {"cable_length_m": 1},
    "master": {"f_c": "1 MHz"}, "script": [{"op": "read_position"}], "expect": {"outcomes": {"ok": 2}}})");
  const auto r = run("run " + path);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.out.find("FAIL outcomes.ok: 1 (expected 2)"), std::string::npos) << r.out;
}

TEST(Cli, MalformedScenarioExitsTwoNamingFileAndPath) {
  const auto path = write_temp("endatsim_cli_bad.json", R"({"name": "bad", "line": {"cable_length_m": -5},
    "master": {"f_c": "1 MHz"}, "script": [{"op": "read_position"}]})");
  const auto r = run("run " + path);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find(path + ": at /line/cable_length_m"), std::string::npos) << r.err;
}

TEST(Cli, UsageErrorsExitTwo) {
  EXPECT_EQ(run("").status, 2);
  EXPECT_EQ(run("frobnicate x.json").status, 2);
  EXPECT_EQ(run("run").status, 2);
  EXPECT_EQ(run("run --no-such-option x.json").status, 2);
}

TEST(Cli, HelpAndVersionExitZero) {
  const auto help = run("--help");
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.out.find("--vcd"), std::string::npos);
  EXPECT_NE(help.out.find("Exit status"), std::string::npos);
  const auto version = run("--version");
  EXPECT_EQ(version.status, 0);
  EXPECT_EQ(version.out.rfind("endatsim ", 0), 0U);
}

TEST(Cli, WritesJsonResultsAndVcd) {
  const std::string json = (scratch() / "endatsim_cli.json").string(), vcd = (scratch() / "endatsim_cli.vcd").string();
  const auto r = run("run " + kBundled + "endat21_1mhz_10m.json --json " + json + " --vcd " + vcd + " --quiet");
  EXPECT_EQ(r.status, 0);
  std::ifstream j(json);
  std::stringstream ss;
  ss << j.rdbuf();
  EXPECT_NE(ss.str().find("\"passed\": true"), std::string::npos);
  EXPECT_GT(std::filesystem::file_size(vcd), 1000U);
  std::ifstream v(vcd);
  std::stringstream vs;
  vs << v.rdbuf();
  endatsim::test_support::expect_clean_vcd(vs.str(), vcd);
}

TEST(Cli, SeedMustBeANonNegativeInteger) {
  EXPECT_EQ(run("run " + kBundled + "endat21_1mhz_10m.json --seed=-1").status, 2);
  EXPECT_EQ(run("run " + kBundled + "endat21_1mhz_10m.json --seed=12x").status, 2);
  EXPECT_EQ(run("run " + kBundled + "endat21_1mhz_10m.json --seed=12 --quiet").status, 0);
}

// The complete scenario example of docs/scenario-format.md must load and hold its own expectations.
TEST(Cli, ReadmeScenarioExamplePasses) {
  std::ifstream in(std::string(ENDATSIM_SOURCE_DIR) + "/docs/scenario-format.md");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string doc = ss.str();
  const auto section = doc.find("# Scenario format");
  ASSERT_NE(section, std::string::npos);
  const auto begin = doc.find("```json\n", section);
  ASSERT_NE(begin, std::string::npos);
  const auto end = doc.find("```\n", begin + 8);
  ASSERT_NE(end, std::string::npos);
  const auto path = write_temp("endatsim_readme_example.json", doc.substr(begin + 8, end - begin - 8));
  const auto r = run("run " + path);
  EXPECT_EQ(r.status, 0) << r.out << r.err;
}

// Errors the input can cause exit 2; anything else is a bug: its own status and a request for a report.
TEST(CliExitStatus, BadInputIsTwoAndAnInternalErrorIsSeventyWithARequestForABugReport) {
  const auto status_of = [](auto exception, std::string& said) {
    std::ostringstream err;
    const int status = endatsim::tools::report_failure(std::make_exception_ptr(exception), err);
    said = err.str();
    return status;
  };
  std::string said;
  EXPECT_EQ(status_of(std::runtime_error("x.json: at /line: bad"), said), 2);
  EXPECT_EQ(said, "endatsim: x.json: at /line: bad\n");
  EXPECT_EQ(status_of(std::invalid_argument("--max-time: not a duration"), said), 2);
  EXPECT_EQ(status_of(std::logic_error("Kernel::schedule_at: time in the past"), said), 70);
  EXPECT_NE(said.find("endatsim: internal error: Kernel::schedule_at: time in the past\n"), std::string::npos) << said;
  EXPECT_NE(said.find("this is a bug in endatsim " ENDATSIM_VERSION "; please report it"), std::string::npos) << said;
  EXPECT_EQ(status_of(std::bad_alloc(), said), 70);
  EXPECT_EQ(status_of(42, said), 70);
  EXPECT_NE(said.find("an exception of an unknown type"), std::string::npos) << said;
}
