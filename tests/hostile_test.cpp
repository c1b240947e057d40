// Hostile input: scenario files that pass the loader but ask for unbounded work, output paths that
// would destroy inputs or cannot be written, and text that used to slip through. Each ends in
// seconds with bounded memory, and with a message that names the file, the place and the limit.
// (The bounds on time and memory leave room for sanitized builds; a release build needs under 2 s
// and 150 MiB for each; without the limits these ran for minutes and grew to gigabytes.)
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "endatsim/scenarios/loader.hpp"
#include "endatsim/scenarios/runner.hpp"
#include "endatsim/scenarios/vcd_reader.hpp"
#include "endatsim/sim/kernel.hpp"

namespace {

namespace fs = std::filesystem;

struct Run {
  int status;
  std::string err;
  std::string out;
  double seconds;
};

std::string slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A directory of this test's own, removed at the end.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "endatsim_hostile_XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    fs::permissions(path_, fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(path_, ec);
  }
  std::string operator/(const std::string& name) const { return path_ + "/" + name; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

Run run(const std::string& args, const TempDir& dir, const std::string& env = "") {
  const std::string out = dir / "stdout", err = dir / "stderr";
  const std::string cmd = env + " " + std::string(ENDATSIM_EXE) + " " + args + " >" + out + " 2>" + err;
  const auto begin = std::chrono::steady_clock::now();
  const int raw = std::system(cmd.c_str());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  return Run{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(err), slurp(out), seconds};
}

// The largest resident set of any child this process waited for, in MiB.
long peak_child_mib() {
  rusage usage{};
  getrusage(RUSAGE_CHILDREN, &usage);
  return usage.ru_maxrss / 1024;
}

std::string write(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

nlohmann::json base(const std::string& name, const std::string& f_c = "2 MHz") {
  return {{"name", name}, {"line", {{"cable_length_m", 10}}}, {"master", {{"f_c", f_c}}}, {"max_time", "60 s"},
          {"script", nlohmann::json::array({{{"op", "read_position"}, {"count", 10}}})}};
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

const std::string kBundled = std::string(ENDATSIM_SOURCE_DIR) + "/scenarios/bundled/";

}  // namespace

// --- What the file shows: refused before the run --------------------------------------------

TEST(Hostile, FortyThousandGlitchEventsAreRefusedBeforeTheRun) {
  TempDir dir;
  auto s = base("glitches");
  for (int i = 0; i < 40'000; ++i)
    s["events"].push_back({{"at", std::to_string(i) + " us"}, {"glitch", {{"wire", "data"}, {"end", "master"}, {"width", "10 ns"}}}});
  const auto file = write(dir / "glitches.json", s.dump());
  const auto r = run("run " + file + " --quiet", dir);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(contains(r.err, file + ": at /events: expected at most 1000 events")) << r.err;
  EXPECT_TRUE(contains(r.err, "got 40000")) << r.err;
  EXPECT_TRUE(contains(r.err, "--max-events")) << r.err;
  EXPECT_LT(r.seconds, 300.0);  // 0.6 s in a release build; parsing 3 MB is slow under the sanitizers
  EXPECT_LT(peak_child_mib(), 1024);
}

TEST(Hostile, TenThousandPowerCutsAreRefusedBeforeTheRun) {
  TempDir dir;
  auto s = base("power_cuts");
  for (int i = 0; i < 10'000; ++i)
    s["events"].push_back({{"at", std::to_string(i * 100) + " us"}, {"power_interruption", {{"duration", "10 us"}}}});
  const auto file = write(dir / "cuts.json", s.dump());
  const auto r = run("run " + file, dir);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(contains(r.err, file + ": at /events: expected at most 1000 events")) << r.err;
  // Granted more, the same file loads (validate checks it as run would).
  EXPECT_EQ(run("validate " + file + " --max-events 10000", dir).status, 0);
}

TEST(Hostile, AwaitNotBusyAMillionTimesIsRefusedBeforeTheRun) {
  TempDir dir;
  auto s = base("await");
  s["script"] = {{{"op", "read_position"}}, {{"op", "await_not_busy"}, {"max_polls", 1'000'000}}};
  const auto file = write(dir / "await.json", s.dump());
  const auto r = run("run " + file, dir);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(contains(r.err, file + ": at /script: expected at most 100000 frames and polls")) << r.err;
  EXPECT_TRUE(contains(r.err, "got 1000001, 1000000 of them at /script/1")) << r.err;
  // Many entries of the default 1000 polls add up the same way.
  s["script"] = nlohmann::json::array();
  for (int i = 0; i < 101; ++i) s["script"].push_back({{"op", "await_not_busy"}});
  const auto many = write(dir / "many.json", s.dump());
  const auto m = run("validate " + many, dir);
  EXPECT_EQ(m.status, 2);
  EXPECT_TRUE(contains(m.err, "got 101000, 1000 of them at /script/0")) << m.err;
}

TEST(Hostile, ContinuousClockWordsAtTheLoadersMaximumAreRefusedBeforeTheRun) {
  TempDir dir;
  auto s = base("continuous");
  s["encoder"] = {{"version", "2.1"}};
  s["script"] = {{{"op", "read_position"}, {"command", "encoder_send_position_values"}, {"count", 1'000'000},
                  {"continuous_words", 100'000}}};
  const auto file = write(dir / "continuous.json", s.dump());
  const auto r = run("run " + file, dir);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(contains(r.err, "got 100001000000")) << r.err;
  EXPECT_LT(r.seconds, 30.0);
}

TEST(Hostile, AMillionFramesAt16MHzAreRefusedBeforeTheRun) {
  TempDir dir;
  auto s = base("million", "16 MHz");
  s["script"] = {{{"op", "read_position"}, {"count", 1'000'000}}};
  const auto file = write(dir / "million.json", s.dump());
  EXPECT_LT(s.dump().size(), 200U);  // a small file asks for it
  const auto r = run("run " + file, dir);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(contains(r.err, file + ": at /script: ")) << r.err;
  EXPECT_TRUE(contains(r.err, "--max-script-frames")) << r.err;
}

TEST(Hostile, ASweepOfTwoThousandPointsOfALargeScenarioStopsAtItsFirstPoint) {
  TempDir dir;
  // A megabyte of description (quick to parse, heavy to hold 2000 times) and a script beyond the
  // limits.
  auto s = base("large");
  s["description"] = std::string(1'000'000, 'd');
  s["script"] = nlohmann::json::array();
  for (int i = 0; i < 101; ++i) s["script"].push_back({{"op", "await_not_busy"}});
  const auto file = write(dir / "large.json", s.dump());
  ASSERT_GT(fs::file_size(file), 1'000'000U);
  const auto r = run("sweep " + file + " --grid /seed=1:2000:1 --jobs 2 --json " + (dir / "sweep.json"), dir);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(contains(r.err, "grid point 1 of 2000 (/seed=1): " + file + ": at /script: expected at most 100000")) << r.err;
  EXPECT_FALSE(fs::exists(dir / "sweep.json"));
  EXPECT_LT(peak_child_mib(), 1024);
}

TEST(Hostile, AScenarioMayNotGrantItselfMoreThanTheCommandLine) {
  TempDir dir;
  auto s = base("greedy");
  s["limits"] = {{"events", 5000}};
  const auto file = write(dir / "greedy.json", s.dump());
  const auto r = run("validate " + file, dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(contains(r.err, file + ": at /limits/events: expected at most 1000")) << r.err;
  EXPECT_TRUE(contains(r.err, "--max-events raises it), got 5000")) << r.err;
  EXPECT_EQ(run("validate " + file + " --max-events 5000", dir).status, 0);
  s["limits"] = {{"events", 0}};
  const auto zero = run("validate " + write(dir / "zero.json", s.dump()), dir);
  EXPECT_EQ(zero.status, 2);
  EXPECT_TRUE(contains(zero.err, "at /limits/events: expected an integer 1 .. 18446744073709551615, got number 0")) << zero.err;
  EXPECT_EQ(run("run " + file + " --max-records 0", dir).status, 2);
  EXPECT_EQ(run("run " + file + " --max-time 1e9", dir).status, 2);
}

// --- What shows only while running: the run ends early, incomplete, exit 3 ------------------

TEST(Hostile, AHundredThousandReadsEndAtTheRecordsLimitWithBoundedMemory) {
  TempDir dir;
  auto s = base("reads");
  s["script"] = {{{"op", "read_position"}, {"count", 100'000}}};
  const auto file = write(dir / "reads.json", s.dump());
  const auto json = dir / "out.json", junit = dir / "out.xml";
  // --examples keeps every frame and finding in memory: the records limit is what stops it.
  const auto r = run("run " + file + " --quiet --examples 1000000 --json " + json + " --junit " + junit, dir);
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "limit records reached")) << r.err;
  EXPECT_TRUE(contains(r.err, "--max-records or limits.records changes it")) << r.err;
  EXPECT_TRUE(contains(r.out, "INCOMPLETE: limit records reached")) << r.out;
  const auto j = nlohmann::json::parse(slurp(json));
  EXPECT_EQ(j["complete"], false);
  EXPECT_EQ(j["passed"], false);
  EXPECT_EQ(j["scenarios"][0]["complete"], false);
  EXPECT_TRUE(contains(j["scenarios"][0]["incomplete"].get<std::string>(), "the run ended at "));
  const auto xml = slurp(junit);
  EXPECT_TRUE(contains(xml, "errors=\"1\"")) << xml;
  EXPECT_TRUE(contains(xml, "<error type=\"incomplete\" message=\"limit records reached")) << xml;
  EXPECT_LT(r.seconds, 120.0);
  EXPECT_LT(peak_child_mib(), 1024);
  // A scenario's own, lower limit.
  s["limits"] = {{"records", 100}};
  const auto low = run("run " + write(dir / "low.json", s.dump()) + " --quiet", dir);
  EXPECT_EQ(low.status, 3);
  EXPECT_TRUE(contains(low.err, "at most 100 (")) << low.err;
}

// What a run keeps is bounded by --examples, not by its length: far more frames than the records
// limit allows to keep all run to their end, and every one is written out.
TEST(Hostile, ARunLongerThanTheRecordsLimitRunsToItsEndWithEveryFrameWrittenAndFewKept) {
  TempDir dir;
  auto s = base("reads");
  s["script"] = {{{"op", "read_position"}, {"count", 10'000}}};
  const auto file = write(dir / "reads.json", s.dump());
  const auto json = dir / "out.json", log = dir / "out.log";
  const auto r = run("run " + file + " --quiet --max-records 500 --examples 10 --json " + json + " --log " + log, dir);
  EXPECT_EQ(r.status, 1) << r.err;  // its f_c and sampling_window findings are not expected
  EXPECT_FALSE(contains(r.out, "INCOMPLETE")) << r.out;
  EXPECT_TRUE(contains(r.out, "frames: 10000 (ok 10000)")) << r.out;
  EXPECT_TRUE(contains(r.out, "violation f_c x10000")) << r.out;
  const auto j = nlohmann::json::parse(slurp(json));
  const auto& scenario = j["scenarios"][0];
  EXPECT_EQ(scenario["frames"].size(), 10'000U);
  EXPECT_EQ(scenario["violations"].size(), 20U);  // ten of each check
  EXPECT_EQ(scenario["violations_not_kept"], 2 * 10'000 - 20);
  EXPECT_TRUE(contains(slurp(log), "\n# 10000 frames\n"));
  EXPECT_LT(peak_child_mib(), 1024);
  EXPECT_EQ(run("run " + file + " --examples 0", dir).status, 2);
  EXPECT_EQ(run("run " + file + " --examples ten", dir).status, 2);
}

TEST(Hostile, SweepPointsThatReachALimitAreNotCleanAndMarkedIncomplete) {
  TempDir dir;
  const auto json = dir / "sweep.json";
  const auto r = run("sweep " + std::string(ENDATSIM_SOURCE_DIR) +
                         "/scenarios/sweeps/figure2.json --grid /line/cable_length_m=0,10 --max-records 10 --json " + json,
                     dir);
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "2 points ended early, the first at grid point 1: limit records reached")) << r.err;
  const auto j = nlohmann::json::parse(slurp(json));
  for (const auto& p : j["points"]) {
    EXPECT_EQ(p["clean"], false);
    EXPECT_TRUE(contains(p["incomplete"].get<std::string>(), "at most 10 (--max-records")) << p;
  }
}

TEST(Hostile, AWaveformAt16MHzEndsAtTheKernelEventLimitAndStaysValid) {
  TempDir dir;
  auto s = base("vcd", "16 MHz");
  s["script"] = {{{"op", "read_position"}, {"count", 90'000}}};
  const auto file = write(dir / "vcd.json", s.dump());
  const auto vcd = dir / "out.vcd";
  const auto r = run("run " + file + " --quiet --max-kernel-events 2000000 --vcd " + vcd, dir);
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "limit kernel_events reached")) << r.err;
  EXPECT_TRUE(contains(r.err, "at most 2000000 (--max-kernel-events or limits.kernel_events changes it)")) << r.err;
  ASSERT_TRUE(fs::exists(vcd));
  EXPECT_LT(fs::file_size(vcd), 40'000'000U);
  for (const auto& e : fs::directory_iterator(dir.path())) EXPECT_FALSE(contains(e.path().string(), ".part-")) << e.path();
  const auto f = endatsim::scenarios::read_vcd_file(vcd, {.sigrok = true});
  EXPECT_TRUE(f.issues.empty()) << f.issues.front().message;
  EXPECT_GT(f.end_time, 0);
}

TEST(Hostile, MaxTimeOnTheCommandLineEndsTheRunIncomplete) {
  TempDir dir;
  const auto r = run("run " + kBundled + "endat21_1mhz_10m.json --max-time \"10 us\"", dir);
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "limit max_time reached: 10 us simulated, less than the scenario's")) << r.err;
  // A real scenario within every default limit runs as it always has.
  EXPECT_EQ(run("run " + kBundled + "endat21_1mhz_10m.json --quiet", dir).status, 0);
}

TEST(Hostile, TheKernelCallsItsWatchAtEventBoundariesAndStopsThere) {
  using namespace endatsim::sim;
  Kernel k;
  struct Counter {
    Kernel* k;
    int fired = 0;
    std::uint64_t watched_at = 0;
    void tick() {
      ++fired;
      k->schedule(ns(1), bind<&Counter::tick>(this));
    }
    void watch() {
      watched_at = k->events_processed();
      k->stop();
    }
  } c{&k};
  k.schedule(ns(1), bind<&Counter::tick>(&c));
  k.watch(1000, bind<&Counter::watch>(&c));
  k.run(ms(1));
  EXPECT_EQ(c.watched_at, 1000U);
  EXPECT_EQ(c.fired, 1000);
  EXPECT_EQ(k.now(), ns(1000));
}

TEST(Hostile, RunScenarioRefusesAScenarioBeyondItsLimits) {
  auto s = base("api");
  s["events"] = nlohmann::json::array();
  for (int i = 0; i < 3; ++i)
    s["events"].push_back({{"at", std::to_string(i) + " us"}, {"glitch", {{"wire", "data"}, {"end", "master"}, {"width", "10 ns"}}}});
  const auto scenario = endatsim::scenarios::load_scenario_text(s.dump(), "api.json");
  endatsim::scenarios::RunOptions o;
  o.limits.events = 2;
  EXPECT_THROW(endatsim::scenarios::run_scenario(scenario, o), endatsim::scenarios::ScenarioError);
  o.limits.events = 3;
  EXPECT_TRUE(endatsim::scenarios::run_scenario(scenario, o).incomplete.empty());
}

// --- Output paths ----------------------------------------------------------------------------

TEST(HostileOutputs, AnInputGivenAsAnOutputIsRefusedAndKept) {
  TempDir dir;
  const auto file = write(dir / "in.json", base("in").dump());
  const std::string before = slurp(file);
  for (const std::string option : {"--json", "--junit", "--vcd", "--log", "--log-json"}) {
    const auto r = run("run " + file + " " + option + " " + file, dir);
    EXPECT_EQ(r.status, 2) << option;
    EXPECT_TRUE(contains(r.err, option + " " + file + ": that is a scenario file")) << r.err;
    EXPECT_EQ(slurp(file), before) << option;
  }
  // Through another name of the same file, too.
  fs::create_symlink(file, dir / "alias.json");
  EXPECT_EQ(run("run " + file + " --json " + (dir / "alias.json"), dir).status, 2);
  EXPECT_EQ(slurp(file), before);
  const auto sweep = run("sweep " + file + " --grid /seed=1,2 --csv " + file, dir);
  EXPECT_EQ(sweep.status, 2);
  EXPECT_TRUE(contains(sweep.err, "that is the scenario file")) << sweep.err;
  EXPECT_EQ(slurp(file), before);
}

TEST(HostileOutputs, TwoOutputsToOneFileAreRefused) {
  TempDir dir;
  const auto file = write(dir / "in.json", base("in").dump());
  const auto r = run("run " + file + " --vcd " + (dir / "x") + " --log " + (dir / "x"), dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(contains(r.err, "--vcd " + (dir / "x") + " and --log " + (dir / "x") + ": the same file")) << r.err;
  EXPECT_FALSE(fs::exists(dir / "x"));
  EXPECT_TRUE(r.out.empty()) << "nothing ran: " << r.out;
  // One file yet to be made, spelled two ways (run in the directory itself): refused the same.
  fs::create_directory(dir / "sub");
  for (const auto& [a, b] : {std::pair<std::string, std::string>{"x", "./x"}, {"./x", dir / "x"}, {"x", "sub/../x"}}) {
    const auto twice = run("run " + file + " --vcd " + a + " --log-json " + b, dir, "cd " + dir.path() + " &&");
    EXPECT_EQ(twice.status, 2) << a << " " << b;
    EXPECT_TRUE(contains(twice.err, "--vcd " + a + " and --log-json " + b + ": the same file")) << twice.err;
    EXPECT_FALSE(fs::exists(dir / "x"));
  }
}

// A reader that goes away (`| head`): the write fails with EPIPE instead of SIGPIPE killing the
// process, which left every output's part file behind; now it says so, exits 2 and leaves no part file.
TEST(HostileOutputs, AClosedPipeEndsTheRunWithAnErrorAndNoPartFiles) {
  TempDir dir;
  auto s = base("piped");
  s["script"][0]["count"] = 2000;
  const auto file = write(dir / "p.json", s.dump());
  const std::string cmd = "cd " + dir.path() + " && bash -c '" + std::string(ENDATSIM_EXE) + " run " + file +
                          " --quiet --log - --json p.out.json --vcd p.out.vcd 2>err | head -c 100 >/dev/null; "
                          "echo ${PIPESTATUS[0]} >status'";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_EQ(slurp(dir / "status"), "2\n");
  EXPECT_TRUE(contains(slurp(dir / "err"), "cannot write to standard output: Broken pipe")) << slurp(dir / "err");
  for (const auto& e : fs::directory_iterator(dir.path()))
    EXPECT_EQ(e.path().filename().string().find(".part-"), std::string::npos) << e.path();
}

TEST(HostileOutputs, DirectoriesFifosAndReadOnlyFilesAreRefusedBeforeAnythingRuns) {
  TempDir dir;
  const auto file = write(dir / "in.json", base("in").dump());
  fs::create_directory(dir / "d");
  auto r = run("run " + file + " --json " + (dir / "d"), dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(contains(r.err, "cannot open the file for writing: it is a directory")) << r.err;
  ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0600), 0);
  r = run("run " + file + " --junit " + (dir / "fifo"), dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(contains(r.err, "it is a FIFO, socket or block device")) << r.err;
  write(dir / "ro.json", "old");
  fs::permissions(dir / "ro.json", fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  r = run("run " + file + " --json " + (dir / "ro.json"), dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(contains(r.err, "cannot open the file for writing: it is read-only")) << r.err;
  EXPECT_EQ(slurp(dir / "ro.json"), "old");
  r = run("run " + file + " --log " + (dir / "missing/x.log"), dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(contains(r.err, "does not exist")) << r.err;
  for (const auto& check : {"check " + file + " --clock c --data d --json " + (dir / "d"),
                            "diagram " + file + " --svg " + file})
    EXPECT_EQ(run(check, dir).status, 2) << check;
  EXPECT_TRUE(r.out.empty()) << "nothing ran: " << r.out;
}

TEST(HostileOutputs, AFullDeviceIsACleanErrorNamingThePath) {
  if (!fs::exists("/dev/full")) GTEST_FAIL() << "/dev/full is needed";
  TempDir dir;
  const auto file = write(dir / "in.json", base("in").dump());
  for (const std::string option : {"--vcd", "--json", "--junit", "--log", "--log-json"}) {
    const auto r = run("run " + file + " --quiet " + option + " /dev/full", dir);
    EXPECT_EQ(r.status, 2) << option << ": " << r.err;
    EXPECT_TRUE(contains(r.err, "/dev/full")) << r.err;
    EXPECT_TRUE(contains(r.err, "No space left on device")) << option << ": " << r.err;
    EXPECT_FALSE(contains(r.err, "terminate")) << r.err;
  }
  const auto d = run("diagram " + kBundled + "endat21_1mhz_10m.json --svg /dev/full", dir);
  EXPECT_EQ(d.status, 2) << d.err;
  EXPECT_TRUE(contains(d.err, "No space left on device")) << d.err;
}

// Standard output is an output too: a summary, a table or "--json -" that cannot be written is
// an error with the reason, not exit 0.
TEST(HostileOutputs, StandardOutputThatCannotBeWrittenIsAnErrorWithTheReason) {
  if (!fs::exists("/dev/full")) GTEST_FAIL() << "/dev/full is needed";
  TempDir dir;
  const auto file = write(dir / "in.json", base("in").dump());
  for (const std::string& args : {"run " + file, "run " + file + " --quiet --json -", std::string("checks"),
                                 std::string("--help"), "validate " + file}) {
    const std::string err = dir / "stderr";
    const int raw = std::system((std::string(ENDATSIM_EXE) + " " + args + " >/dev/full 2>" + err).c_str());
    ASSERT_TRUE(WIFEXITED(raw)) << args;
    EXPECT_EQ(WEXITSTATUS(raw), 2) << args;
    EXPECT_TRUE(contains(slurp(err), "endatsim: cannot write to standard output: No space left on device\n"))
        << args << ": " << slurp(err);
  }
  // The same command with somewhere to write gives its verdict.
  const auto r = run("run " + file, dir);
  EXPECT_TRUE(r.status == 0 || r.status == 1) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST(HostileOutputs, DiagramKeepsItsWaveformInAPrivateDirectoryAndRemovesIt) {
  TempDir dir, tmp;
  // What an attacker plants where the old code wrote its temporary file.
  // What an attacker plants where a predictable name would be written: a symlink for each process
  // id the command may get.
  write(tmp / "victim", "precious");
  constexpr int kPlanted = 2000;
  for (int pid = ::getpid(); pid < ::getpid() + kPlanted; ++pid)
    fs::create_symlink(tmp / "victim", tmp / ("endatsim_diagram_" + std::to_string(pid) + "_0.vcd"));
  const auto svg = dir / "d.svg";
  const auto r = run("diagram " + kBundled + "endat21_1mhz_10m.json --quiet --svg " + svg, dir, "TMPDIR=" + tmp.path());
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(contains(slurp(svg), "<svg"));
  EXPECT_EQ(slurp(tmp / "victim"), "precious");
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(tmp.path())) ++entries;
  EXPECT_EQ(entries, std::size_t{kPlanted} + 1) << "the private directory is gone";
}

// A window over 3 000 frames, each with findings (16 MHz warns of f_c): the axis found each
// edge's x by walking every segment before it and the labels were staggered against every earlier
// one, hours in all; now a few seconds. The bound catches a return to quadratic time, not a speed.
TEST(HostileOutputs, ADiagramOfAWindowOverThousandsOfFramesIsDrawnInSeconds) {
  TempDir dir;
  auto s = base("long_window", "16 MHz");
  s["line"]["cable_length_m"] = 0;
  s["script"][0]["count"] = 3000;
  const auto file = write(dir / "long.json", s.dump());
  const auto svg = dir / "d.svg";
  const auto r = run("diagram " + file + " --svg " + svg + " --from '0 ps' --to '60 s'", dir);
  EXPECT_EQ(r.status, 0) << r.err;
  const auto count = r.out.rfind("; "), end = r.out.find(" violations");
  ASSERT_TRUE(count != std::string::npos && end != std::string::npos && end > count) << r.out;
  EXPECT_GE(std::stol(r.out.substr(count + 2, end - count - 2)), 3000) << r.out;
  EXPECT_LT(r.seconds, 120.0);
  EXPECT_TRUE(contains(slurp(svg), "</svg>"));
}

// --- Text that used to slip through ----------------------------------------------------------

TEST(HostileText, ANulByteIsRefusedWhereItStands) {
  const std::string good = base("nul").dump();
  const std::string text = good + std::string(1, '\0') + "garbage }}}}";
  try {
    (void)endatsim::scenarios::load_scenario_text(text, "nul.json");
    FAIL() << "a NUL byte and garbage after the object were accepted";
  } catch (const endatsim::scenarios::ScenarioError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("nul.json: not valid JSON: a NUL byte at line 1, column " +
                                              std::to_string(good.size() + 1),
                                          0),
              0U)
        << e.what();
  }
  EXPECT_NO_THROW((void)endatsim::scenarios::load_scenario_text(good, "nul.json"));
}

// A description is free text, printed in the summary on a terminal: an escape sequence or a
// carriage return that forges a line is shown escaped, never sent.
TEST(HostileText, ControlCharactersInADescriptionAreShownEscaped) {
  TempDir dir;
  auto s = base("described");
  s["description"] = "evil\x1b]0;pwned\x07\x1b[31mRED\r\nPASS fake (x.json)";
  const auto r = run("run " + write(dir / "d.json", s.dump()), dir);
  EXPECT_LE(r.status, 1) << r.err;  // ran (its verdict is not the point)
  EXPECT_TRUE(contains(r.out, "  evil\\x1B]0;pwned\\x07\\x1B[31mRED\\x0D\\x0APASS fake (x.json)\n")) << r.out;
  EXPECT_EQ(r.out.find('\x1b'), std::string::npos);
  EXPECT_EQ(r.out.find('\r'), std::string::npos);
}

TEST(HostileText, NullIsNamedOnce) {
  try {
    (void)endatsim::scenarios::load_scenario_text(R"({"name": null})", "null.json");
    FAIL();
  } catch (const endatsim::scenarios::ScenarioError& e) {
    EXPECT_EQ(std::string(e.what()), "null.json: at /name: expected a string, got null");
  }
}

// A duration or frequency beyond what 64 bits hold is out of the key's range like any other: the
// message names that range.
TEST(HostileText, ADurationBeyondSixtyFourBitsIsRefusedWithTheKeysRange) {
  // The loader's message for `s`, or "accepted".
  const auto refusal = [](const nlohmann::json& s) -> std::string {
    try {
      (void)endatsim::scenarios::load_scenario_text(s.dump(), "huge.json");
      return "accepted";
    } catch (const endatsim::scenarios::ScenarioError& e) {
      return e.what();
    }
  };
  auto s = base("huge");
  s["encoder"]["t_cal"] = "4611687 s";
  const std::string duration = refusal(s);
  EXPECT_TRUE(contains(duration, "/encoder/t_cal: expected a duration string 0 ps .. 100 ms")) << duration;
  EXPECT_TRUE(contains(duration, "\"4611687 s\"")) << duration;
  s = base("huge");
  s["master"]["f_c"] = "10000000000000000000 GHz";
  const std::string frequency = refusal(s);
  EXPECT_TRUE(contains(frequency, "/master/f_c: expected a frequency string 100 kHz .. 16 MHz")) << frequency;
}

// Readers look at a file before they open it: a FIFO would wait for a writer that never comes,
// a device would never end.
TEST(HostileInputs, FifosAndDevicesAreRefusedByEveryReader) {
  TempDir dir;
  const std::string fifo = dir / "pipe", vcd = dir / "s.vcd";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const auto made = run("run " + write(dir / "s.json", base("fifo").dump()) + " --quiet --vcd " + vcd, dir);
  ASSERT_TRUE(made.status == 0 || made.status == 1) << made.err;
  for (const std::string& input : {fifo, std::string("/dev/zero")}) {
    const std::string signals = " --clock endat.encoder_clock --data endat.encoder_data --quiet";
    const auto check = run("check " + input + signals, dir);
    EXPECT_EQ(check.status, 2) << input << ": " << check.err;
    EXPECT_TRUE(contains(check.err, "not a regular file")) << check.err;
    const auto encoder = run("check " + vcd + signals + " --encoder " + input, dir);
    EXPECT_EQ(encoder.status, 2) << input << ": " << encoder.err;
    EXPECT_TRUE(contains(encoder.err, "not a regular file")) << encoder.err;
    const auto merge = run("merge " + input + " --json " + (dir / "m.json"), dir);
    EXPECT_EQ(merge.status, 2) << input << ": " << merge.err;
    EXPECT_TRUE(contains(merge.err, "not a regular file")) << merge.err;
    try {
      (void)endatsim::scenarios::read_vcd_file(input, {});
      ADD_FAILURE() << input << " was read as a VCD";
    } catch (const std::runtime_error& e) {
      EXPECT_TRUE(contains(e.what(), "not a regular file")) << e.what();
    }
  }
}

// A folder stands for every scenario in it: one that cannot be read (a link to a file moved away,
// a FIFO) is refused by name, not skipped, so that it cannot drop out of a CI run unseen.
TEST(HostileInputs, AScenarioInAFolderThatCannotBeReadIsRefusedNotSkipped) {
  TempDir dir;
  fs::create_directory(dir / "suite");
  write(dir / "suite/a.json", base("a").dump());
  fs::create_symlink(dir / "gone.json", dir / "suite/moved.json");
  for (const std::string command : {"run", "validate"}) {
    const auto r = run(command + " " + (dir / "suite") + " --quiet", dir);
    EXPECT_EQ(r.status, 2) << command;
    EXPECT_TRUE(contains(r.err, dir / "suite/moved.json")) << command << ": " << r.err;
  }
  fs::remove(dir / "suite/moved.json");
  ASSERT_EQ(::mkfifo((dir / "suite/pipe.json").c_str(), 0600), 0);
  const auto r = run("run " + (dir / "suite") + " --quiet", dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(contains(r.err, dir / "suite/pipe.json")) << r.err;
}

TEST(HostileText, HugeNamesAndKeysAreCutInMessages) {
  TempDir dir;
  const std::string name(3'000'000, 'n');
  const auto a = write(dir / "a.json", base(name).dump()), b = write(dir / "b.json", base(name).dump());
  const auto r = run("run " + a + " " + b + " --vcd " + (dir / "v"), dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(contains(r.err, "another scenario is also named")) << r.err.substr(0, 300);
  EXPECT_LT(r.err.size(), 2000U);
  auto s = base("key");
  s[std::string(3'000'000, 'k')] = 1;
  const auto k = run("validate " + write(dir / "k.json", s.dump()), dir);
  EXPECT_EQ(k.status, 2);
  EXPECT_TRUE(contains(k.err, "unknown key")) << k.err.substr(0, 300);
  EXPECT_LT(k.err.size(), 5000U);
}
