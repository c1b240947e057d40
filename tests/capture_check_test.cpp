// `endatsim check` against `endatsim run`: every bundled and safety scenario's waveform, read
// back from its VCD at the encoder's connector and judged from the wires alone, breaks the same
// rows as often as the simulated run found (the rows a capture can judge), and decodes as many
// frames with good answers as the master read. Bad captures and names exit 2 through the CLI.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

#include "scenarios/scenarios.hpp"

namespace {

using namespace endatsim;
namespace fs = std::filesystem;

std::vector<fs::path> scenarios_in(std::initializer_list<const char*> folders) {
  std::vector<fs::path> out;
  for (const char* folder : folders)
    for (const auto& e : fs::directory_iterator(fs::path(ENDATSIM_SOURCE_DIR) / "scenarios" / folder))
      if (e.path().extension() == ".json") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

// Rows a capture at the encoder's connector can judge: wire rows the capture's conformance does
// not call unobservable (bus_contention needs the master's enable too). floating_data is left
// out: its master half needs the master's declared sampling instants.
std::map<std::string, std::size_t> wire_rows(const std::vector<checker::Violation>& violations,
                                             const std::vector<checker::RowConformance>& observable) {
  std::map<std::string, std::size_t> counts;
  for (const auto& v : violations) {
    const auto row = protocol::timing_row(v.check);
    const bool seen = std::any_of(observable.begin(), observable.end(), [&](const auto& c) {
      return c.check == v.check && c.status != checker::RowConformance::Status::NotObservable;
    });
    if (row && row->evidence == protocol::Evidence::Wires && seen && v.check != checker::check::kFloatingData)
      ++counts[v.check];
  }
  return counts;
}

fs::path temp(const std::string& name) {
  return fs::temp_directory_path() / ("endatsim_capture_check_" + std::to_string(getpid()) + "_" + name);
}

class CaptureRoundTrip : public ::testing::TestWithParam<fs::path> {};

TEST_P(CaptureRoundTrip, CheckFindsWhatRunFoundOnTheWires) {
  const auto scenario = scenarios::load_scenario_file(GetParam().string());
  const fs::path vcd = temp(GetParam().stem().string() + ".vcd");
  scenarios::RunOptions options;
  options.vcd_path = vcd.string();
  const auto run = scenarios::run_scenario(scenario, options);

  scenarios::CaptureCheckOptions o;
  o.file = vcd.string();
  o.clock = "encoder.clock";
  o.data = "encoder.data";
  o.data_enable = "encoder.data_driver_enable";
  o.encoder = scenarios::declared_encoder(scenario.encoder);
  o.encoder.output_delay = scenario.line.encoder.receiver_delay + scenario.encoder.output_delay +
                           scenario.line.encoder.driver_delay;
  o.checker = scenario.checker;
  const auto check = scenarios::check_capture(o);
  fs::remove(vcd);

  EXPECT_EQ(wire_rows(check.violations, check.conformance), wire_rows(run.violations, check.conformance));
  const auto good = static_cast<std::size_t>(std::count_if(run.frames.begin(), run.frames.end(), [](const auto& f) {
    return f.word == 0 && f.outcome == master::FrameOutcome::Ok && f.crc_received == f.crc_expected;
  }));
  const auto decoded = static_cast<std::size_t>(std::count_if(check.frames.begin(), check.frames.end(), [](const auto& f) {
    return f.answer_complete && f.crc_ok;
  }));
  EXPECT_GE(decoded, good) << "every frame the master read cleanly is on the wires";
}

INSTANTIATE_TEST_SUITE_P(Scenarios, CaptureRoundTrip, ::testing::ValuesIn(scenarios_in({"bundled", "safety"})),
                         [](const auto& param_info) {
                           std::string name = param_info.param.parent_path().filename().string() + "_" +
                                              param_info.param.stem().string();
                           std::replace_if(name.begin(), name.end(),
                                           [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
                           return name;
                         });

struct Cli {
  int status = -1;
  std::string out, err;
};

Cli cli(const std::string& args) {
  const fs::path out = temp("stdout"), err = temp("stderr");
  const std::string cmd = "timeout 120 " + std::string(ENDATSIM_EXE) + " " + args + " >'" + out.string() + "' 2>'" +
                          err.string() + "'";
  const int raw = std::system(cmd.c_str());
  const auto slurp = [](const fs::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  Cli r{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(out), slurp(err)};
  fs::remove(out);
  fs::remove(err);
  return r;
}

TEST(CheckCommand, BadCapturesAndNamesExitTwoNamingTheFileAndTheProblem) {
  const fs::path truncated = temp("truncated.vcd");
  std::ofstream(truncated) << "$timescale 1ps $end\n$scope module encoder $end\n$var wire 1 ! clock $end\n";
  auto r = cli("check '" + truncated.string() + "' --clock clock --data data");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find(truncated.string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("truncated"), std::string::npos) << r.err;

  const fs::path timescale = temp("timescale.vcd");
  std::ofstream(timescale) << "$timescale 3 ns $end\n$enddefinitions $end\n";
  r = cli("check '" + timescale.string() + "' --clock clock --data data");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("unknown $timescale"), std::string::npos) << r.err;

  const fs::path two = temp("two.vcd");
  std::ofstream(two) << "$timescale 1ns $end\n$scope module master $end\n$var wire 1 ! clock $end\n$var wire 1 \" data $end\n"
                        "$upscope $end\n$scope module encoder $end\n$var wire 1 # clock $end\n$var wire 1 $ data $end\n"
                        "$upscope $end\n$enddefinitions $end\n#0\n1!\n1\"\n1#\n1$\n";
  r = cli("check '" + two.string() + "' --clock clock --data encoder.data");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("ambiguous"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("master.clock, encoder.clock"), std::string::npos) << r.err;  // in declaration order
  r = cli("check '" + two.string() + "' --clock encoder.clk --data encoder.data");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("no signal named 'encoder.clk'"), std::string::npos) << r.err;
  r = cli("check '" + two.string() + "' --clock encoder.clock --data encoder.data");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("frames decoded: 0"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("t_z: not observable (needs the DATA drivers' enables)"), std::string::npos) << r.out;

  r = cli("check '" + temp("missing.vcd").string() + "' --clock a --data b");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("cannot open"), std::string::npos) << r.err;
  for (const auto& p : {truncated, timescale, two}) fs::remove(p);
}

TEST(CheckCommand, ADefectInACaptureExitsOneWithItsRow) {
  // The bundled 16 MHz scenario with t_ST shortened below note 8's 1 us: the capture shows it.
  auto s = scenarios::load_scenario_file(std::string(ENDATSIM_SOURCE_DIR) + "/scenarios/bundled/endat22_16mhz_20m_tst1us.json");
  s.master.t_st = sim::ns(900);
  const fs::path vcd = temp("short_tst.vcd");
  scenarios::RunOptions options;
  options.vcd_path = vcd.string();
  scenarios::run_scenario(s, options);
  const auto r = cli("check '" + vcd.string() + "' --clock encoder.clock --data encoder.data --data-enable encoder.data_driver_enable");
  fs::remove(vcd);
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("violation t_st"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("measured 900 ns, limit >= 1 us"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("    t_st: 16 / 16 / 0  BROKEN"), std::string::npos) << r.out;  // the 16 MHz frames
}

}  // namespace
