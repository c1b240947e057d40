// `endatsim check` against `endatsim run`: every bundled and safety scenario's waveform, read
// back from its VCD at the encoder's connector and judged from the wires alone, breaks the same
// rows as often as the simulated run found (the rows a capture can judge), and decodes as many
// frames with good answers as the master read. Bad captures and names exit 2 through the CLI.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <tuple>
#include <sys/wait.h>
#include <unistd.h>
#include <zip.h>

#include "endatsim/capture/capture.hpp"
#include "endatsim/scenarios/scenarios.hpp"
#include "capture_support.hpp"
#include "scenario_support.hpp"
#include "sigrok_cli.hpp"

namespace {

using namespace endatsim;
using sim::ns;
using sim::Time;
namespace fs = std::filesystem;

std::vector<fs::path> scenarios_in(std::initializer_list<const char*> folders) {
  std::vector<fs::path> out;
  for (const char* folder : folders)
    for (const auto& e : fs::directory_iterator(fs::path(ENDATSIM_SOURCE_DIR) / "scenarios" / folder))
      if (e.path().extension() == ".json") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

fs::path temp(const std::string& name) {
  return fs::temp_directory_path() / ("endatsim_capture_check_" + std::to_string(getpid()) + "_" + name);
}

// A scenario's VCD opened on the encoder's pins: CLOCK, DATA and the driver's enable, selected
// in that order.
std::pair<std::unique_ptr<capture::Reader>, std::vector<std::uint32_t>> open_encoder_pins(const fs::path& vcd) {
  auto reader = capture::open_vcd(vcd.string());
  std::vector<std::uint32_t> wanted;
  for (const char* n : {"encoder_clock", "encoder_data", "encoder_data_driver_enable"})
    wanted.push_back(capture::find_signal(*reader, n));
  reader->select(wanted);
  return {std::move(reader), wanted};
}

// A scenario run to a VCD, and the options that check it at the encoder's connector as the
// scenario declares its encoder (its transceivers in the delay at the connector).
scenarios::ScenarioResult run_to_vcd(const scenarios::Scenario& scenario, const fs::path& vcd) {
  scenarios::RunOptions options;
  options.vcd_path = vcd.string();
  return scenarios::run_scenario(scenario, options);
}

scenarios::CaptureCheckOptions encoder_pins_of(const scenarios::Scenario& scenario, const fs::path& vcd) {
  scenarios::CaptureCheckOptions o;
  o.file = vcd.string();
  o.clock = "encoder_clock";
  o.data = "encoder_data";
  o.data_enable = "encoder_data_driver_enable";
  o.encoder = scenarios::declared_encoder(scenario.encoder);
  o.encoder.output_delay = scenario.line.encoder.receiver_delay + scenario.encoder.output_delay +
                           scenario.line.encoder.driver_delay;
  o.checker = scenario.checker;
  o.cable_m = scenario.line.cable_length_m;
  return o;
}

class CaptureRoundTrip : public ::testing::TestWithParam<fs::path> {};

TEST_P(CaptureRoundTrip, CheckFindsWhatRunFoundOnTheWires) {
  const auto scenario = scenarios::load_scenario_file(GetParam().string());
  const fs::path vcd = temp(GetParam().stem().string() + ".vcd");
  const auto run = run_to_vcd(scenario, vcd);
  const auto check = scenarios::check_capture(encoder_pins_of(scenario, vcd));
  fs::remove(vcd);

  EXPECT_EQ(test_support::wire_rows(check.violations, check.conformance),
            test_support::wire_rows(run.violations, check.conformance));
  // Every frame the master read cleanly is on the wires, in the same order, with the same mode
  // command and position (the wires may show more: frames a master retried). The supplement is
  // not compared: a fault at the encoder's end changes what its pins show from what was sent.
  using Seen = std::tuple<protocol::ModeCommand, std::uint64_t>;
  std::vector<Seen> read, decoded;
  for (const auto& f : run.frames)
    if (f.word == 0 && f.outcome == master::FrameOutcome::Ok && f.crc_received == f.crc_expected &&
        protocol::info(f.command).answer == protocol::AnswerFormat::Position)
      read.emplace_back(f.command, f.position);
  for (const auto& f : check.frames)
    if (f.command && f.answer_complete && f.crc_ok && protocol::info(*f.command).answer == protocol::AnswerFormat::Position)
      decoded.emplace_back(*f.command, f.fields[static_cast<std::size_t>(protocol::Field::Position)]);
  ASSERT_LT(check.frames_decoded, scenarios::kMaxFramesKept);  // every frame kept, so every one compared
  // Every refusal (A2 type II) the master received is seen on the wires as one.
  const auto type2 = std::count_if(run.frames.begin(), run.frames.end(),
                                   [](const auto& f) { return f.outcome == master::FrameOutcome::Type2Error; });
  const auto refused = std::count_if(check.frames.begin(), check.frames.end(), [](const auto& f) { return f.refused(); });
  EXPECT_EQ(refused, type2);
  auto next = decoded.begin();
  for (std::size_t i = 0; i < read.size(); ++i) {
    next = std::find(next, decoded.end(), read[i]);
    ASSERT_NE(next, decoded.end()) << "frame " << i << " of the master's clean reads (position " << std::get<1>(read[i])
                                   << ") is not on the wires in order";
    ++next;
  }
}

// With both drivers' enables as endatsim's VCD holds them, each at its own connector, and the
// master's moved by the cable's one-way delay (--master-data-enable-at master), the drivers on DATA
// at the encoder's connector are the run's: the same bus contentions and undriven mode bits there,
// and every other row of the wires as with the encoder's enable alone.
class BothEnablesRoundTrip : public ::testing::TestWithParam<fs::path> {};

TEST_P(BothEnablesRoundTrip, TheMastersEnableMovedByTheCableGivesTheRunsDriversAtTheEncoder) {
  const auto scenario = scenarios::load_scenario_file(GetParam().string());
  const fs::path vcd = temp(GetParam().stem().string() + "_both.vcd");
  const auto run = run_to_vcd(scenario, vcd);
  auto o = encoder_pins_of(scenario, vcd);
  o.master_data_enable = "master_data_driver_enable";
  o.master_enable_at_master = true;
  o.cable_delay_per_m = scenario.line.cable_delay_per_m;
  const auto check = scenarios::check_capture(o);
  fs::remove(vcd);
  const auto at_encoder = [](const std::vector<checker::Violation>& vs, std::string_view row) {
    return std::count_if(vs.begin(), vs.end(), [&](const checker::Violation& v) {
      return v.check == row && v.where == line::ObservationPoint::EncoderPins;
    });
  };
  for (const std::string_view row : {checker::check::kContention, checker::check::kFloatingData})
    EXPECT_EQ(at_encoder(check.violations, row), at_encoder(run.violations, row)) << row;
  auto rows = test_support::wire_rows(check.violations, check.conformance);
  rows.erase(std::string(checker::check::kContention));
  auto run_rows = test_support::wire_rows(run.violations, check.conformance);
  run_rows.erase(std::string(checker::check::kContention));
  EXPECT_EQ(rows, run_rows);
  EXPECT_EQ(scenarios::capture_json(check).at("master_enable_delay_ps"), check.master_enable_delay->count());
  ASSERT_TRUE(check.master_enable_delay.has_value());
  EXPECT_EQ(*check.master_enable_delay, scenario.line.cable_delay());
}

// Every bundled, safety and field scenario but the four whose wires legitimately tell another
// story than the master's declarations (docs/analyzer.md, "Where check and run differ").
std::vector<fs::path> round_trip_scenarios() {
  const std::vector<std::string> differ{"02_delay_measured_at_the_wrong_clock", "03_false_start_bit_after_a_frame",
                                        "12_unshielded_cable_near_a_drive_inverter",
                                        "14_additional_data_lost_after_a_power_dip"};
  auto all = scenarios_in({"bundled", "safety", "field"});
  std::erase_if(all, [&](const fs::path& p) {
    return std::find(differ.begin(), differ.end(), p.stem().string()) != differ.end();
  });
  return all;
}

INSTANTIATE_TEST_SUITE_P(Scenarios, CaptureRoundTrip, ::testing::ValuesIn(round_trip_scenarios()),
                         [](const auto& param_info) { return endatsim::test_support::scenario_test_name(param_info.param); });

// The round trip's scenarios but those the capture's two enables cannot tell: a cable that changes
// while running (one --cable moves the master's enable) and a second encoder on the bus (whose
// enable the capture does not hold, so its contentions with the first do not show).
std::vector<fs::path> both_enables_scenarios() {
  auto all = round_trip_scenarios();
  std::erase_if(all, [](const fs::path& p) {
    const auto s = scenarios::load_scenario_file(p.string());
    return !s.bus.empty() || std::any_of(s.events.begin(), s.events.end(), [](const scenarios::Event& e) {
      return e.kind == scenarios::Event::Kind::SetCable;
    });
  });
  return all;
}

INSTANTIATE_TEST_SUITE_P(Scenarios, BothEnablesRoundTrip, ::testing::ValuesIn(both_enables_scenarios()),
                         [](const auto& param_info) { return endatsim::test_support::scenario_test_name(param_info.param); });


// The capture a logic analyzer sampling every `period` would make of a scenario's encoder pins:
// each change shows at the first sample at or after it; a pulse shorter than a sample may vanish.
// Written as a VCD at 10 ns (a period that is a multiple of it). The analyzer was armed 100 us
// before the run began, so the capture shows CLOCK at rest for longer than any t_m before the
// first frame (a logic analyzer's capture may begin inside a frame: docs/analyzer.md).
constexpr std::int64_t kArmedBeforeNs = 100'000;

void resample(const fs::path& from, const fs::path& to, Time period) {
  auto pins = open_encoder_pins(from);
  auto& reader = pins.first;
  const auto& wanted = pins.second;
  std::ofstream out(to);
  constexpr Time unit = ns(10);
  out << "$timescale 10 ns $end\n$scope module endat $end\n"
      << "$var wire 1 c encoder_clock $end\n$var wire 1 d encoder_data $end\n$var wire 1 e encoder_data_driver_enable $end\n"
      << "$upscope $end\n$enddefinitions $end\n";
  const char ids[] = {'c', 'd', 'e'};
  std::vector<char> shown(3, '?'), pending(3, '?');
  std::int64_t sample = -1;
  const auto flush = [&] {
    bool stamped = false;
    for (std::size_t i = 0; i < 3; ++i) {
      if (pending[i] == shown[i] || pending[i] == '?') continue;
      if (!stamped) out << "#" << (sample == 0 ? 0 : (ns(kArmedBeforeNs) + sample * period) / unit) << "\n";
      stamped = true;
      out << pending[i] << ids[i] << "\n";
      shown[i] = pending[i];
    }
  };
  capture::Change c;
  while (reader->next(c)) {
    const std::int64_t at = (c.time.count() + period.count() - 1) / period.count();
    if (at != sample) {
      flush();
      sample = at;
    }
    const auto i = static_cast<std::size_t>(std::find(wanted.begin(), wanted.end(), c.signal) - wanted.begin());
    pending[i] = c.value;
  }
  flush();
  // The capture ends where the recording did, at the first sample at or after its end.
  const std::int64_t end = (reader->end().count() + period.count() - 1) / period.count();
  if (end > sample) out << "#" << (ns(kArmedBeforeNs) + end * period) / unit << "\n";
}

// The frames a check decoded: command, and of each complete answer its CRC and position.
std::vector<std::tuple<std::optional<protocol::ModeCommand>, bool, bool, std::uint64_t>> decoded(
    const scenarios::CaptureCheckResult& r) {
  std::vector<std::tuple<std::optional<protocol::ModeCommand>, bool, bool, std::uint64_t>> out;
  for (const auto& f : r.frames)
    out.emplace_back(f.command, f.answer_complete, f.answer_complete && f.crc_ok,
                     f.answer_complete ? f.fields[static_cast<std::size_t>(protocol::Field::Position)] : 0);
  return out;
}

// A sampled capture against the exact one: the same frames; no row fails that the exact capture
// passes; every row the exact capture fails is failed or undecided.
void expect_like_exact(const scenarios::CaptureCheckResult& exact, const scenarios::CaptureCheckResult& r,
                       const std::string& what) {
  const auto findings = [](const scenarios::CaptureCheckResult& c, checker::Severity severity) {
    std::map<std::string, std::size_t> counts;
    for (const auto& v : c.violations)
      if (v.severity == severity) ++counts[v.check];
    return counts;
  };
  const auto count = [](const std::map<std::string, std::size_t>& m, const std::string& check) {
    return m.count(check) != 0 ? m.at(check) : 0U;
  };
  const auto a = decoded(r), b = decoded(exact);
  EXPECT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
    if (a[i] != b[i]) {
      ADD_FAILURE() << "frame " << i << " decodes otherwise " << what << ": " << scenarios::frame_log_line(r.frames[i])
                    << " against " << scenarios::frame_log_line(exact.frames[i]);
      break;
    }
  const auto exact_errors = findings(exact, checker::Severity::Error);
  const auto sampled_errors = findings(r, checker::Severity::Error);
  const auto sampled_undecided = findings(r, checker::Severity::Undecided);
  for (const auto& [check, n] : sampled_errors) EXPECT_LE(n, count(exact_errors, check)) << check << " fails only " << what;
  for (const auto& [check, n] : exact_errors)
    EXPECT_GE(count(sampled_errors, check) + count(sampled_undecided, check), n) << check << " lost " << what;
}

class CaptureResampled : public ::testing::TestWithParam<fs::path> {};

// A Saleae Logic 2 digital export of a capture: a row at the start and at every change, times
// in seconds, no sample rate stated.
void to_saleae(const fs::path& vcd, const fs::path& csv) {
  auto pins = open_encoder_pins(vcd);
  auto& reader = pins.first;
  const auto& wanted = pins.second;
  std::ofstream out(csv);
  out << "Time [s],clock,data,data_driver_enable\n";
  std::vector<char> level(3, '0');
  std::optional<Time> at;
  const auto row = [&] {
    char seconds[64];
    std::snprintf(seconds, sizeof seconds, "%lld.%012lld", static_cast<long long>(at->count() / 1'000'000'000'000),
                  static_cast<long long>(at->count() % 1'000'000'000'000));
    out << seconds << "," << level[0] << "," << level[1] << "," << level[2] << "\n";
  };
  capture::Change c;
  while (reader->next(c)) {
    if (at && c.time != *at) row();
    at = c.time;
    const auto i = static_cast<std::size_t>(std::find(wanted.begin(), wanted.end(), c.signal) - wanted.begin());
    level[i] = c.value == '1' ? '1' : '0';
  }
  if (at) row();
  // The recording's end as a last row with the levels unchanged, so that the capture ends where
  // the recording did (else its last frame is one the end cuts).
  if (at && reader->end() > *at) {
    at = reader->end();
    row();
  }
}

// A logic analyzer needs some four samples per clock period to show each phase: the scenarios
// whose clock allows that at 100 MHz (10 ns) and 25 MHz (40 ns) are checked at those rates, as a
// VCD and as a Saleae export. The frames decode the same; no row fails that the exact capture
// passes; every row the exact capture fails is failed or undecided.
TEST_P(CaptureResampled, LogicAnalyzerRatesGiveTheSameFramesAndUndecidedNearLimits) {
  const auto scenario = scenarios::load_scenario_file(GetParam().string());
  const fs::path vcd = temp(GetParam().stem().string() + "_exact.vcd");
  run_to_vcd(scenario, vcd);
  auto o = encoder_pins_of(scenario, vcd);
  const auto exact = scenarios::check_capture(o);
  for (const Time period : {ns(10), ns(40)}) {
    if (sim::period_of(scenario.master.f_c) < period * 4) continue;
    const fs::path sampled = temp(GetParam().stem().string() + "_" + std::to_string(period.count()) + ".vcd");
    resample(vcd, sampled, period);
    o.file = sampled.string();
    o.resolution = period;
    const auto r = scenarios::check_capture(o);
    expect_like_exact(exact, r, "at " + sim::format_time(period));
    // The same samples as a Saleae export: its sample period is read from its time steps.
    const fs::path saleae = temp(GetParam().stem().string() + "_" + std::to_string(period.count()) + ".csv");
    to_saleae(sampled, saleae);
    auto from_csv = o;
    from_csv.file = saleae.string();
    from_csv.resolution.reset();
    from_csv.clock = "clock";
    from_csv.data = "data";
    from_csv.data_enable = "data_driver_enable";
    const auto s = scenarios::check_capture(from_csv);
    EXPECT_EQ(s.resolution, period);
    expect_like_exact(exact, s, "as a Saleae export at " + sim::format_time(period));
    fs::remove(sampled);
    fs::remove(saleae);
  }
  fs::remove(vcd);
}

// The name of a scenario's test: its folder and file name.
std::string scenario_test_name(const fs::path& p) {
  std::string name = p.parent_path().filename().string() + "_" + p.stem().string();
  std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
  return name;
}

INSTANTIATE_TEST_SUITE_P(Scenarios, CaptureResampled, ::testing::ValuesIn(scenarios_in({"bundled", "safety", "field"})),
                         [](const auto& param_info) { return scenario_test_name(param_info.param); });

// The same waveforms as a logic analyzer's files: sigrok-cli (Debian's) turns the 10 ns and 40 ns
// captures into sigrok session files, and those into CSV; `check` reads each with its sample
// period as the resolution and finds what the exact capture showed, as above.
class CaptureThroughSigrok : public ::testing::TestWithParam<fs::path> {};

Time reader_end(const fs::path& vcd) {
  auto reader = capture::open_vcd(vcd.string());
  reader->select({});
  capture::Change c;
  while (reader->next(c)) {
  }
  return reader->end();
}

TEST_P(CaptureThroughSigrok, SessionsAndCsvGiveTheSameFramesAndVerdicts) {
  const std::string cli = test_support::sigrok_cli();
  ASSERT_FALSE(cli.empty()) << test_support::kNoSigrokCli;
  const auto scenario = scenarios::load_scenario_file(GetParam().string());
  const fs::path vcd = temp(GetParam().stem().string() + "_sigrok_exact.vcd");
  run_to_vcd(scenario, vcd);
  auto o = encoder_pins_of(scenario, vcd);
  const auto exact = scenarios::check_capture(o);
  ASSERT_FALSE(exact.frames.empty());
  unsigned rates = 0;
  for (const Time period : {ns(10), ns(40)}) {
    if (sim::period_of(scenario.master.f_c) < period * 4) continue;
    ++rates;
    const std::string stem = GetParam().stem().string() + "_" + std::to_string(period.count());
    const fs::path sampled = temp(stem + ".vcd"), sr = temp(stem + ".sr"), csv = temp(stem + ".csv"),
                   log = temp(stem + ".log");
    resample(vcd, sampled, period);
    const auto sigrok = [&](const std::string& args) {
      return std::system((cli + " " + args + " >" + log.string() + " 2>&1").c_str());
    };
    // The resampled VCD is at 10 ns: sigrok reads it at 100 MHz, downsampled to the period.
    const std::string downsample = std::to_string(period / ns(10));
    ASSERT_EQ(sigrok("-I vcd:downsample=" + downsample + " -i " + sampled.string() + " -o " + sr.string()), 0);
    // One row per sample, as sigrok-cli writes by default, while that stays below some 100 MB;
    // a longer capture as a row per change with its time, as one would export it.
    const bool per_sample = reader_end(sampled) / period < 2'000'000;
    ASSERT_EQ(sigrok("-i " + sr.string() + " -O " + (per_sample ? "csv" : "csv:dedup=true:time=true") + " -o " +
                     csv.string()),
              0);
    for (const fs::path& file : {sr, csv}) {
      auto from = o;
      from.file = file.string();
      from.clock = "encoder_clock";
      from.data = "encoder_data";
      from.data_enable = "encoder_data_driver_enable";
      const auto r = scenarios::check_capture(from);
      EXPECT_EQ(r.resolution, period) << file;
      expect_like_exact(exact, r, file.extension().string() + " at " + sim::format_time(period));
    }
    for (const auto& f : {sampled, sr, csv, log}) fs::remove(f);
  }
  fs::remove(vcd);
  EXPECT_GT(rates, 0U);
}

INSTANTIATE_TEST_SUITE_P(Scenarios, CaptureThroughSigrok, ::testing::ValuesIn(scenarios_in({"bundled", "safety", "field"})),
                         [](const auto& param_info) { return scenario_test_name(param_info.param); });

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
  EXPECT_EQ(r.status, 2) << r.out;  // CLOCK never framed anything: nothing was judged, so no PASS
  EXPECT_NE(r.err.find("no EnDat frame began on CLOCK 'encoder.clock'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("are these the right signals?"), std::string::npos) << r.err;

  r = cli("check '" + temp("missing.vcd").string() + "' --clock a --data b");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("cannot open"), std::string::npos) << r.err;

  // A second $timescale would change every time stamp after it; which one was meant is not known.
  const fs::path twice = temp("twice.vcd");
  std::ofstream(twice) << "$timescale 1ps $end\n$timescale 1ns $end\n$var wire 1 ! clock $end\n$enddefinitions $end\n";
  r = cli("check '" + twice.string() + "' --clock clock --data clock");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find(twice.string() + ": line 2: a second $timescale (the first: 1 ps)"), std::string::npos) << r.err;
  // A resolution of zero would call the capture sampled and exact at once.
  r = cli("check '" + two.string() + "' --clock encoder.clock --data encoder.data --resolution '0 ps'");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--resolution must be 1 ps .. 1 ms, got 0"), std::string::npos) << r.err;
  for (const auto& p : {truncated, timescale, two, twice}) fs::remove(p);
}

TEST(CheckCommand, ADefectInACaptureExitsOneWithItsRow) {
  // The bundled 16 MHz scenario with t_ST shortened below note 8's 1 us: the capture shows it.
  auto s = scenarios::load_scenario_file(std::string(ENDATSIM_SOURCE_DIR) + "/scenarios/bundled/endat22_16mhz_20m_tst1us.json");
  s.master.t_st = sim::ns(900);
  const fs::path vcd = temp("short_tst.vcd");
  scenarios::RunOptions options;
  options.vcd_path = vcd.string();
  scenarios::run_scenario(s, options);
  const auto r = cli("check '" + vcd.string() + "' --clock encoder_clock --data encoder_data --data-enable encoder_data_driver_enable");
  fs::remove(vcd);
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("violation t_st"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("measured 900 ns, limit >= 1 us"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("    t_st: 16 / 16 / 0  BROKEN"), std::string::npos) << r.out;  // the 16 MHz frames

  // Without the encoder's enable the release of DATA cannot be seen, and the table says so.
  scenarios::run_scenario(s, options);
  const auto bare = cli("check '" + vcd.string() + "' --clock encoder_clock --data encoder_data");
  fs::remove(vcd);
  EXPECT_EQ(bare.status, 1) << bare.out << bare.err;
  EXPECT_NE(bare.out.find("t_z: not observable (needs the DATA drivers' enables)"), std::string::npos) << bare.out;
}

}  // namespace

TEST(CheckCommand, ALimitWithinOneSampleIsUndecidedNeverPassedOrFailed) {
  // The project's master waits exactly t_m 30 us + t_R 500 ns, the envelope's bound: from a
  // simulator's exact VCD that passes; sampled every 10 ns it can be neither passed nor failed.
  auto scenario = scenarios::load_scenario_file(std::string(ENDATSIM_SOURCE_DIR) + "/scenarios/bundled/endat21_1mhz_10m.json");
  for (auto& op : scenario.script) op.cycle = Time::zero();  // frame after frame, as fast as the master's waits allow
  const fs::path vcd = temp("undecided_exact.vcd"), sampled = temp("undecided_10ns.vcd");
  scenarios::RunOptions options;
  options.vcd_path = vcd.string();
  scenarios::run_scenario(scenario, options);
  resample(vcd, sampled, ns(10));
  const std::string signals = " --clock encoder_clock --data encoder_data --data-enable encoder_data_driver_enable";
  auto r = cli("check '" + vcd.string() + "'" + signals);
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("event times exact"), std::string::npos) << r.out;
  r = cli("check '" + sampled.string() + "'" + signals + " --resolution 10ns");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_EQ(r.out.rfind("UNDECIDED ", 0), 0U) << r.out;
  EXPECT_NE(r.out.find("resolution 10 ns"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("undecided at the capture's resolution of 10 ns"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("t_m_t_r:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  UNDECIDED; worst 30.5 us against >= 30.5 us (spec), margin 0 ps"), std::string::npos)
      << r.out;  // the row's conformance, with the worst case the resolution cannot decide
  EXPECT_EQ(r.out.find("BROKEN"), std::string::npos) << r.out;
  r = cli("check '" + sampled.string() + "'" + signals + " --resolution 2ms");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--resolution must be 0 .. 1 ms"), std::string::npos) << r.err;
  fs::remove(vcd);
  fs::remove(sampled);
}

TEST(Decision, ALimitWithinTheResolutionIsUndecided) {
  using checker::Decision;
  const Time r = ns(10);
  EXPECT_EQ(checker::at_least(ns(100), ns(100), Time::zero()), Decision::Pass);
  EXPECT_EQ(checker::at_least(ns(100) - sim::ps(1), ns(100), Time::zero()), Decision::Fail);
  EXPECT_EQ(checker::more_than(ns(100), ns(100), Time::zero()), Decision::Fail);
  EXPECT_EQ(checker::at_most(ns(100), ns(100), Time::zero()), Decision::Pass);
  EXPECT_EQ(checker::at_most(ns(100) + sim::ps(1), ns(100), Time::zero()), Decision::Fail);
  // Measured 110 ns at 10 ns: the true value lies in (100, 120) ns.
  EXPECT_EQ(checker::at_least(ns(110), ns(100), r), Decision::Pass);
  EXPECT_EQ(checker::at_least(ns(110) - sim::ps(1), ns(100), r), Decision::Undecided);
  EXPECT_EQ(checker::at_least(ns(90), ns(100), r), Decision::Fail);
  EXPECT_EQ(checker::at_least(ns(90) + sim::ps(1), ns(100), r), Decision::Undecided);
  EXPECT_EQ(checker::at_most(ns(90), ns(100), r), Decision::Pass);
  EXPECT_EQ(checker::at_most(ns(90) + sim::ps(1), ns(100), r), Decision::Undecided);
  EXPECT_EQ(checker::at_most(ns(110), ns(100), r), Decision::Fail);
  EXPECT_EQ(checker::at_most(ns(110) - sim::ps(1), ns(100), r), Decision::Undecided);
}

TEST(CheckCommand, SeveralCapturesGiveOneJunitSuiteEachAndTheWorstExitStatus) {
  auto fast = scenarios::load_scenario_file(std::string(ENDATSIM_SOURCE_DIR) + "/scenarios/bundled/endat21_1mhz_10m.json");
  const fs::path clean = temp("junit_clean.vcd"), broken = temp("junit_broken.vcd"), missing = temp("junit_missing.vcd");
  const fs::path junit = temp("check.xml"), json = temp("check.json");
  scenarios::RunOptions options;
  options.vcd_path = clean.string();
  scenarios::run_scenario(fast, options);
  for (auto& op : fast.script) op.cycle = Time::zero();
  fast.master.t_m_wait = sim::us(5);  // into the encoder's t_m
  options.vcd_path = broken.string();
  scenarios::run_scenario(fast, options);
  const std::string signals = " --clock encoder_clock --data encoder_data --data-enable encoder_data_driver_enable";
  auto r = cli("check '" + clean.string() + "' '" + broken.string() + "'" + signals + " --junit '" + junit.string() +
               "' --json '" + json.string() + "'");
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  std::ifstream in(junit);
  std::stringstream xml;
  xml << in.rdbuf();
  EXPECT_NE(xml.str().find("<testsuite name=\"" + clean.string() + "\""), std::string::npos) << xml.str();
  EXPECT_NE(xml.str().find("<testsuite name=\"" + broken.string() + "\""), std::string::npos) << xml.str();
  EXPECT_NE(xml.str().find("<testcase classname=\"endatsim.check\" name=\"t_m_t_r\""), std::string::npos);
  EXPECT_NE(xml.str().find("<failure type=\"violation\""), std::string::npos);
  EXPECT_NE(xml.str().find("<skipped message=\"not observable: needs the master&apos;s declaration"), std::string::npos)
      << xml.str();
  std::ifstream json_in(json);
  const auto j = nlohmann::json::parse(json_in);
  ASSERT_EQ(j.at("captures").size(), 2U);
  EXPECT_TRUE(j["captures"][0]["conforms"].get<bool>());
  EXPECT_FALSE(j["captures"][1]["conforms"].get<bool>());
  EXPECT_FALSE(j["captures"][1]["verdict"]["this_encoder"].get<bool>());
  const auto& counted = j["captures"][0];
  EXPECT_GT(counted.at("frames_decoded").get<std::uint64_t>(), 0U);
  EXPECT_EQ(counted.at("frames_clean"), counted.at("frames_decoded"));  // every frame answered with a good CRC
  EXPECT_EQ(counted.at("frames_not_kept").get<std::uint64_t>(), 0U);
  EXPECT_EQ(counted.at("frames").size(), counted.at("frames_decoded").get<std::size_t>());
  // A capture that cannot be read is bad input; the others are still checked, and the reports
  // list it with its error rather than leave it out.
  r = cli("check '" + clean.string() + "' '" + missing.string() + "'" + signals + " --junit '" + junit.string() +
          "' --json '" + json.string() + "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("PASS " + clean.string()), std::string::npos) << r.out;
  EXPECT_NE(r.err.find(missing.string()), std::string::npos) << r.err;
  std::ifstream json_again(json);
  const auto k = nlohmann::json::parse(json_again);
  ASSERT_EQ(k.at("captures").size(), 2U);
  EXPECT_TRUE(k["captures"][0]["conforms"].get<bool>());
  EXPECT_EQ(k["captures"][1].at("file"), missing.string());
  EXPECT_NE(k["captures"][1].at("error").get<std::string>().find("cannot open"), std::string::npos) << k.dump();
  std::ifstream junit_again(junit);
  std::stringstream xml_again;
  xml_again << junit_again.rdbuf();
  const auto suite = xml_again.str().find("<testsuite name=\"" + missing.string() + "\"");
  ASSERT_NE(suite, std::string::npos) << xml_again.str();
  EXPECT_NE(xml_again.str().find("errors=\"1\"", suite), std::string::npos) << xml_again.str();
  EXPECT_NE(xml_again.str().find("<error", suite), std::string::npos) << xml_again.str();
  for (const auto& p : {clean, broken, junit, json}) fs::remove(p);
}

// --log is written frame by frame and renamed into place when complete; a scenario given as
// --encoder brings its cable, which the summary names.
TEST(CheckCommand, TheLogHoldsEveryFrameAndAScenarioBringsItsCable) {
  const std::string scenario = std::string(ENDATSIM_SOURCE_DIR) + "/scenarios/bundled/endat21_1mhz_10m.json";
  const fs::path vcd = temp("log_cable.vcd"), log = temp("log_cable.txt");
  scenarios::RunOptions options;
  options.vcd_path = vcd.string();
  scenarios::run_scenario(scenarios::load_scenario_file(scenario), options);
  const std::string signals = " --clock encoder_clock --data encoder_data --data-enable encoder_data_driver_enable";
  auto r = cli("check '" + vcd.string() + "'" + signals + " --encoder '" + scenario + "' --log '" + log.string() + "'");
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("  cable 10 m: "), std::string::npos) << r.out;
  std::ifstream in(log);
  std::string line;
  std::size_t lines = 0;
  while (std::getline(in, line)) {
    EXPECT_EQ(line.rfind("#" + std::to_string(lines) + " ", 0), 0U) << line;  // in order, none missing
    ++lines;
  }
  const auto counted = r.out.find("frames decoded: " + std::to_string(lines) + " (" + std::to_string(lines) + " with");
  EXPECT_NE(counted, std::string::npos) << r.out;
  for (const auto& entry : fs::directory_iterator(log.parent_path()))  // no part file left beside it
    EXPECT_EQ(entry.path().string().find(log.filename().string() + "."), std::string::npos) << entry.path();
  // --cable wins over the scenario's; without either the summary says what was assumed.
  r = cli("check '" + vcd.string() + "'" + signals + " --encoder '" + scenario + "' --cable 25");
  EXPECT_NE(r.out.find("  cable 25 m: "), std::string::npos) << r.out;
  r = cli("check '" + vcd.string() + "'" + signals);
  EXPECT_NE(r.out.find("cable not given (--cable): taken as 0 m"), std::string::npos) << r.out;
  for (const auto& p : {vcd, log}) fs::remove(p);
}

// A bench file (an encoder section without a master) declares what a profile cannot: here the
// datasheet's t_LO maximum, held against this encoder only; its checker section is honoured too.
TEST(CheckCommand, ABenchFileDeclaresTheEncodersDatasheetTimes) {
  const std::string scenario = std::string(ENDATSIM_SOURCE_DIR) + "/scenarios/bundled/endat21_1mhz_10m.json";
  const fs::path vcd = temp("bench_declares.vcd"), bench = temp("bench_declares.json");
  scenarios::RunOptions options;
  options.vcd_path = vcd.string();
  scenarios::run_scenario(scenarios::load_scenario_file(scenario), options);
  const std::string signals = " --clock encoder_clock --data encoder_data --data-enable encoder_data_driver_enable";
  std::ofstream(bench) << R"({"name": "datasheet", "line": {"cable_length_m": 10},
    "encoder": {"version": "2.2", "t_lo_max": "0.4 us"}, "checker": {"t_st_reduced_for_cable": true}})";
  auto r = cli("check '" + vcd.string() + "'" + signals + " --encoder '" + bench.string() + "'");
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("violation t_lo"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("does not conform to this encoder (its declared limits); within the spec envelope"),
            std::string::npos) << r.out;
  EXPECT_NE(r.out.find("t_st_reduced_for_cable"), std::string::npos) << r.out;       // the relaxation named
  std::ofstream(bench) << R"({"name": "datasheet", "line": {"cable_length_m": 10}, "encoder": {"t_lo_max": "1 us"}})";
  r = cli("check '" + vcd.string() + "'" + signals + " --encoder '" + bench.string() + "'");
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  std::ofstream(bench) << R"({"name": "datasheet", "line": {"cable_length_m": 10}, "encoder": {"t_lo_max": "1 s"}})";
  r = cli("check '" + vcd.string() + "'" + signals + " --encoder '" + bench.string() + "'");
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("at /encoder/t_lo_max"), std::string::npos) << r.err;
  for (const auto& p : {vcd, bench}) fs::remove(p);
}

TEST(CheckCapture, ReportsProgressThroughTheFile) {
  const fs::path vcd = temp("progress.vcd");
  {
    std::ofstream out(vcd);
    out << "$timescale 1 ns $end\n$scope module encoder $end\n$var wire 1 c clock $end\n$var wire 1 d data $end\n"
           "$upscope $end\n$enddefinitions $end\n#0\n1c\n1d\n";
    for (int i = 1; i <= 200'000; ++i) out << "#" << i * 500 << "\n" << (i % 2 != 0 ? '0' : '1') << "c\n";
  }
  scenarios::CaptureCheckOptions o;
  o.file = vcd.string();
  o.clock = "clock";
  o.data = "data";
  std::vector<std::pair<std::uint64_t, std::uint64_t>> calls;
  o.progress = [&](std::uint64_t read, std::uint64_t total) { calls.emplace_back(read, total); };
  const auto r = scenarios::check_capture(o);
  EXPECT_EQ(r.changes, 200'002U);
  ASSERT_EQ(calls.size(), 3U);  // every 65536 changes
  for (std::size_t i = 0; i < calls.size(); ++i) {
    EXPECT_EQ(calls[i].second, fs::file_size(vcd));
    EXPECT_LE(calls[i].first, calls[i].second);
    if (i > 0) {
      EXPECT_GE(calls[i].first, calls[i - 1].first);
    }
  }
  fs::remove(vcd);
}

// t_D is the round trip as the master sees it: only a capture at the master's connector shows
// it. An encoder that takes 300 ns from CLOCK to DATA on 10 m of cable makes t_D about 470 ns,
// over the bound of 0.2 + 0.01 x 10 = 0.3 us.
TEST(CheckCommand, AtTheMastersConnectorTheRoundTripIsJudged) {
  auto scenario = scenarios::load_scenario_file(std::string(ENDATSIM_SOURCE_DIR) + "/scenarios/bundled/endat21_1mhz_10m.json");
  scenario.encoder.output_delay = ns(300);
  const fs::path vcd = temp("at_master.vcd");
  scenarios::RunOptions options;
  options.vcd_path = vcd.string();
  const auto run = scenarios::run_scenario(scenario, options);
  std::size_t t_d_in_run = 0;
  for (const auto& v : run.violations) t_d_in_run += v.check == checker::check::kDataDelay;
  ASSERT_GE(t_d_in_run, 1U);
  const std::string encoder_side = " --clock encoder_clock --data encoder_data --clock-to-data 370ns";
  auto r = cli("check '" + vcd.string() + "'" + encoder_side + " --verbose");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("t_d: not observable (the round trip shows only at the master's connector)"), std::string::npos)
      << r.out;
  const std::string master_side = " --clock master_clock --data master_data --at master --cable 10 --clock-to-data 370ns";
  r = cli("check '" + vcd.string() + "'" + master_side + " --verbose");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("violation t_d x" + std::to_string(t_d_in_run)), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("at the master's connector"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("5 with a complete answer and a good CRC"), std::string::npos) << r.out;
  // Every finding is placed at the connector recorded (before, each said "encoder pins").
  EXPECT_NE(r.out.find("(master pins, frame #"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("encoder pins"), std::string::npos) << r.out;
  // Usage: --at master needs the cable; --t-d belongs to it; a bad length.
  EXPECT_EQ(cli("check '" + vcd.string() + "' --clock master_clock --data master_data --at master").status, 2);
  r = cli("check '" + vcd.string() + "'" + encoder_side + " --t-d 400ns");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--t-d is the round trip at the master's connector"), std::string::npos) << r.err;
  r = cli("check '" + vcd.string() + "'" + master_side.substr(0, master_side.find(" --cable")) + " --cable ten");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--cable must be a length"), std::string::npos) << r.err;
  fs::remove(vcd);
}

// At the master's connector a fast clock leaves no doubt only if the round trip is known: the
// bundled 8 MHz master on 100 m has t_D near 1.06 us, almost nine periods. Assumed from a wrong
// cable (10 m: 160 ns), the encoder's bits were looked for at the wrong edges and 20 of its 23
// frames decoded incomplete, their clocks "too few". The three delay measurements at 200 kHz in
// the capture show the round trip beyond doubt, and every frame after them is read with it: all
// 23 decode with a good CRC, and t_D is measured from the edge that carried each start bit (and
// is judged against the cable given, so here it breaks 10 m's 300 ns).
TEST(CheckCapture, AtTheMastersConnectorTheMeasuredRoundTripFindsTheStartBitsEdge) {
  const auto s = scenarios::load_scenario_file(std::string(ENDATSIM_SOURCE_DIR) +
                                               "/scenarios/bundled/endat22_8mhz_100m_compensated.json");
  const fs::path vcd = temp("round_trip.vcd");
  run_to_vcd(s, vcd);
  std::vector<unsigned> first_starts;
  for (const double cable : {100.0, 10.0}) {
    scenarios::CaptureCheckOptions o;
    o.file = vcd.string();
    o.clock = "master_clock";
    o.data = "master_data";
    o.at = scenarios::CaptureCheckOptions::At::Master;
    o.cable_m = cable;
    o.encoder = scenarios::declared_encoder(s.encoder);
    const auto r = scenarios::check_capture(o);
    EXPECT_EQ(r.frames_decoded, 23U) << cable;
    EXPECT_EQ(r.frames_clean, 23U) << cable;
    const auto row = [&](std::string_view name) {
      return *std::find_if(r.conformance.begin(), r.conformance.end(), [&](const auto& c) { return c.check == name; });
    };
    EXPECT_EQ(row(checker::check::kClockCount).violations, 0U) << cable;
    EXPECT_EQ(row(checker::check::kDataDelay).judged, 23U) << cable;
    EXPECT_EQ(row(checker::check::kDataDelay).violations, cable == 10.0 ? 23U : 0U) << cable;
    // The same edges, whichever cable was given.
    std::vector<unsigned> starts;
    for (const auto& f : r.frames) starts.push_back(f.start_bit_clock);
    if (first_starts.empty()) first_starts = starts;
    EXPECT_EQ(starts, first_starts) << cable;
  }
  fs::remove(vcd);
}

// f_c is shown before the oscillator's allowance (f_c_tolerance_ppm, 1000 ppm by default): a
// master at 2.001 MHz without compensation is outside 2 MHz by 1.001 kHz and passes by that
// allowance, which the conformance line now names; at 2 MHz it is inside, and nothing is named.
TEST(CheckCapture, AClockThatPassesOnlyByTheOscillatorAllowanceSaysSo) {
  for (const auto& [f_c, allowed] : {std::pair{sim::Hertz{2'001'000}, true}, std::pair{sim::Hertz{2'000'000}, false}}) {
    auto s = test_support::make_scenario(1, f_c, false);
    s.expect = {};
    const fs::path vcd = temp("allowance.vcd");
    run_to_vcd(s, vcd);
    const auto r = scenarios::check_capture(encoder_pins_of(s, vcd));
    std::ostringstream summary;
    scenarios::write_capture_summary(summary, r, false);
    const std::string text = summary.str();
    const auto line = text.substr(text.find("    f_c: "), text.find('\n', text.find("    f_c: ")) - text.find("    f_c: "));
    EXPECT_NE(line.find("3 / 0 / 0  ok; worst"), std::string::npos) << line;
    EXPECT_EQ(line.find("(within the oscillator allowance, f_c_tolerance_ppm)") != std::string::npos, allowed) << line;
    fs::remove(vcd);
  }
}

// An RTL master's own signals: data_out with data_oe, data_in (here unknown while the master
// drives, to show it is not used then; data_out is 0 while released, to show it is ignored).
TEST(CheckCommand, AnRtlMastersSplitDataIsJudgedAtItsConnector) {
  const auto scenario = scenarios::load_scenario_file(std::string(ENDATSIM_SOURCE_DIR) + "/scenarios/bundled/endat21_1mhz_10m.json");
  const fs::path vcd = temp("split_sim.vcd"), split = temp("split_rtl.vcd");
  run_to_vcd(scenario, vcd);
  {
    auto reader = capture::open_vcd(vcd.string());
    const std::vector<std::uint32_t> wanted{capture::find_signal(*reader, "master_clock"),
                                            capture::find_signal(*reader, "master_data"),
                                            capture::find_signal(*reader, "master_data_driver_enable")};
    reader->select(wanted);
    std::ofstream out(split);
    out << "$timescale 1 ps $end\n$scope module tb $end\n$scope module dut $end\n$var wire 1 ! clk $end\n"
           "$var wire 1 \" data_out $end\n$var wire 1 # data_in $end\n$var wire 1 $ data_oe $end\n$upscope $end\n"
           "$upscope $end\n$enddefinitions $end\n";
    char clock = '1', data = '1', oe = '0';
    capture::Change c;
    std::int64_t stamp = -1;
    while (reader->next(c)) {
      if (c.time.count() != stamp) out << "#" << (stamp = c.time.count()) << "\n";
      if (c.signal == wanted[0]) clock = c.value;
      else if (c.signal == wanted[1]) data = c.value;
      else oe = c.value;
      out << clock << "!\n" << (oe == '1' ? data : '0') << "\"\n" << (oe == '1' ? 'x' : data) << "#\n" << oe << "$\n";
    }
  }
  const std::string signals = " --clock dut.clk --data-out data_out --data-in data_in --data-enable data_oe --cable 10";
  auto r = cli("check '" + split.string() + "'" + signals + " --verbose");
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("5 with a complete answer and a good CRC"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("at the master's connector"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("t_d: 5 / 0 / 0  ok"), std::string::npos) << r.out;
  r = cli("check '" + split.string() + "' --clock dut.clk --data data_in --data-out data_out --cable 10");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("give one or the other"), std::string::npos) << r.err;
  r = cli("check '" + split.string() + "' --clock dut.clk --data-out data_out --cable 10");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--data-out and --data-in go together"), std::string::npos) << r.err;
  r = cli("check '" + split.string() + "'" + signals + " --at encoder");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("they are at the master"), std::string::npos) << r.err;
  fs::remove(vcd);
  fs::remove(split);
}

namespace {

// A capture at the encoder's connector, in ns, with the encoder's supply: `events` are
// (time, signal, level) with signal c (CLOCK), d (DATA) or p (supply). DATA stays LOW (idle).
struct PowerCapture {
  std::vector<std::tuple<std::int64_t, char, char>> events;
  void request(std::int64_t at) {  // a frame of 12 pulses at 1 MHz: it carries mode bits
    for (int k = 0; k < 12; ++k) {
      events.emplace_back(at + 1000 * k, 'c', '0');
      events.emplace_back(at + 1000 * k + 500, 'c', '1');
    }
  }
  void pulse(std::int64_t at, std::int64_t width) {
    events.emplace_back(at, 'c', '0');
    events.emplace_back(at + width, 'c', '1');
  }
  fs::path write(const std::string& name) {
    std::sort(events.begin(), events.end());
    const fs::path vcd = temp(name);
    std::ofstream out(vcd);
    out << "$timescale 1 ns $end\n$scope module bench $end\n$var wire 1 c clock $end\n$var wire 1 d data $end\n"
           "$var wire 1 p up $end\n$upscope $end\n$enddefinitions $end\n#0\n1c\n0d\n0p\n";
    for (const auto& [t, s, v] : events) out << "#" << t << "\n" << v << s << "\n";
    return vcd;
  }
};

constexpr std::int64_t kMs = 1'000'000;  // in ns

std::size_t power_on_findings(const scenarios::CaptureCheckResult& r) {
  return static_cast<std::size_t>(
      std::count_if(r.violations.begin(), r.violations.end(), [](const auto& v) { return v.check == checker::check::kPowerOn; }));
}

scenarios::CaptureCheckResult check_with_power(const fs::path& vcd, bool power = true) {
  scenarios::CaptureCheckOptions o;
  o.file = vcd.string();
  o.clock = "clock";
  o.data = "data";
  if (power) o.power = "up";
  return scenarios::check_capture(o);
}

}  // namespace

// 2.3.3 after each switch-on a recorded supply shows: up at 10 ms, the pulse 900 ms later, the
// first request t3 after it. A dip at 2 s: the master reads on 1.2 s after it without a pulse,
// twice 100 us apart (the first read is the wake-up cycle, the second comes before t3).
// t_z and t_OE bounded by one period of the frame's clock (2.3.2 note 6), from the wires alone:
// the release after FE1 comes before the frame's second rising edge shows its f_c, so it is
// judged once the edges do. The encoder turns DATA around in receiver 20 + logic + driver 20 ns.
TEST(CheckCapture, TzAndToeFromTheWiresAreBoundedByTheFramesOwnPeriodToThePicosecond) {
  for (const auto& [logic, expected] : {std::pair{ns(85), 0U}, std::pair{ns(85) + sim::ps(1), 1U}}) {
    auto s = test_support::make_scenario(1, sim::MHz(8), true, 1);  // T = 125 ns
    s.encoder.output_delay = logic;
    const fs::path vcd = temp("tz.vcd");
    run_to_vcd(s, vcd);
    const auto c = scenarios::check_capture(encoder_pins_of(s, vcd));
    fs::remove(vcd);
    const auto count = [&](std::string_view row) {
      return std::count_if(c.violations.begin(), c.violations.end(), [&](const auto& v) { return v.check == row; });
    };
    EXPECT_EQ(count(checker::check::kDriverOff), expected) << logic.count();  // 200 kHz frames: T = 5 us
    EXPECT_EQ(count(checker::check::kDriverOn), expected) << logic.count();
    for (const auto& v : c.violations) {
      if (v.check == checker::check::kDriverOff) {
        EXPECT_EQ(v.limit, "<= T = 125 ns");
      }
    }
  }
}

TEST(CheckCapture, TheSupplyShowsEachSwitchOnAndPowerOnIsJudgedAfterEach) {
  const auto capture = [](std::int64_t t3_ns, bool dip) {
    PowerCapture c;
    c.events.emplace_back(10 * kMs, 'p', '1');
    c.pulse(910 * kMs, 1000);
    c.request(910 * kMs + 1000 + t3_ns);
    c.request(910 * kMs + 1000 + t3_ns + 100'000);
    if (dip) {
      c.events.emplace_back(2000 * kMs, 'p', '0');
      c.events.emplace_back(2010 * kMs, 'p', '1');
      c.request(3210 * kMs);
      c.request(3210 * kMs + 100'000);
    }
    return c;
  };
  auto vcd = capture(400 * kMs, false).write("power_clean.vcd");
  EXPECT_EQ(power_on_findings(check_with_power(vcd)), 0U);
  const auto judged = [](const scenarios::CaptureCheckResult& r) {
    for (const auto& row : r.conformance)
      if (row.check == checker::check::kPowerOn) return row.judged;
    return std::uint64_t{0};
  };
  EXPECT_EQ(judged(check_with_power(vcd)), 1U);
  EXPECT_EQ(judged(check_with_power(vcd, false)), 0U) << "without the supply no switch-on is seen";
  vcd = capture(380 * kMs - 1, false).write("power_t3.vcd");
  EXPECT_EQ(power_on_findings(check_with_power(vcd)), 1U);
  EXPECT_EQ(power_on_findings(check_with_power(vcd, false)), 0U);
  vcd = capture(400 * kMs, true).write("power_dip.vcd");
  const auto r = check_with_power(vcd);
  ASSERT_EQ(power_on_findings(r), 1U);
  for (const auto& v : r.violations)
    if (v.check == checker::check::kPowerOn) {
      EXPECT_EQ(v.limit, "t3 = 380 .. 420 ms");
      EXPECT_GT(v.time, sim::ms(3210));
    }
  EXPECT_EQ(judged(r), 2U);
  for (const char* name : {"power_clean.vcd", "power_t3.vcd", "power_dip.vcd"}) fs::remove(temp(name));
}

// 2.3.3 with CLOCK LOW already before the supply comes up: its rise ends t1 and begins t2, which
// must last 80 .. 120 ms before the pulse. (Before, a LOW that began before switching on left t2
// unjudged.)
TEST(CheckCapture, TwoIsJudgedFromClocksRiseAfterALowThatBeganBeforeSwitchingOn) {
  const auto t2_findings = [](std::int64_t t2_ns) {
    PowerCapture c;
    c.events.emplace_back(1, 'c', '0');
    c.events.emplace_back(10 * kMs, 'p', '1');
    c.events.emplace_back(810 * kMs, 'c', '1');
    c.pulse(810 * kMs + t2_ns, 1000);
    c.request(810 * kMs + t2_ns + 1000 + 400 * kMs);
    const auto vcd = c.write("power_t2.vcd");
    const auto r = check_with_power(vcd);
    fs::remove(vcd);
    return std::count_if(r.violations.begin(), r.violations.end(),
                         [](const auto& v) { return v.check == checker::check::kPowerOn && v.limit == "t2 = 80 .. 120 ms"; });
  };
  EXPECT_EQ(t2_findings(100 * kMs), 0);
  EXPECT_EQ(t2_findings(120 * kMs), 0);
  EXPECT_EQ(t2_findings(120 * kMs + 1), 1);
  EXPECT_EQ(t2_findings(200 * kMs), 1);
  EXPECT_EQ(t2_findings(80 * kMs - 1), 1);
}

// The wake-up pulse of 2.3.3 needs only to be longer than 125 ns: a pulse of 150 ns passes the
// power-on row and is no clock pulse of a transmission, so t_LO (200 ns) does not judge it. A lone
// 150 ns pulse when no power-on sequence is due, and a 10 ns runt while it is, are judged by t_LO.
// (Before, the wake-up pulse broke t_LO.)
TEST(CheckCapture, TheWakeUpPulseIsJudgedByPowerOnNotByTlo) {
  const auto lo_violations = [](const scenarios::CaptureCheckResult& r) {
    return std::count_if(r.violations.begin(), r.violations.end(), [](const auto& v) { return v.check == checker::check::kPulseLow; });
  };
  PowerCapture c;
  c.events.emplace_back(10 * kMs, 'p', '1');
  c.pulse(910 * kMs, 150);
  c.request(910 * kMs + 150 + 400 * kMs);
  c.pulse(800 * kMs, 10);    // a runt while the sequence waits: no wake-up pulse, t_LO judges it
  c.pulse(1400 * kMs, 150);  // long after the sequence: a runt pulse
  c.request(1400 * kMs + 100'000);
  const auto vcd = c.write("power_150.vcd");
  const auto r = check_with_power(vcd);
  EXPECT_EQ(power_on_findings(r), 0U);
  ASSERT_EQ(lo_violations(r), 2);
  std::vector<std::string> measured;
  for (const auto& v : r.violations)
    if (v.check == checker::check::kPulseLow) measured.push_back(v.measured);
  EXPECT_EQ(measured, (std::vector<std::string>{"10 ns", "150 ns"}));
  fs::remove(vcd);
}

// A capture that ends inside the wake-up pulse, while the power-on sequence waits for it: that LOW
// is the power-on row's, however long, and not judged by a declared t_LO maximum; the same LOW at
// the end after the sequence is.
TEST(CheckCapture, ACaptureEndingInsideTheWakeUpPulseLeavesItToPowerOn) {
  const auto lo_violations = [](const scenarios::CaptureCheckResult& r) {
    return std::count_if(r.violations.begin(), r.violations.end(), [](const auto& v) { return v.check == checker::check::kPulseLow; });
  };
  const auto check = [](const fs::path& vcd) {
    scenarios::CaptureCheckOptions o;
    o.file = vcd.string();
    o.clock = "clock";
    o.data = "data";
    o.power = "up";
    o.encoder.t_lo_max = sim::us(30);
    return scenarios::check_capture(o);
  };
  PowerCapture waiting;
  waiting.events.emplace_back(10 * kMs, 'p', '1');
  waiting.events.emplace_back(910 * kMs, 'c', '0');
  waiting.events.emplace_back(911 * kMs, 'd', '0');  // the capture's last instant: 1 ms LOW
  auto vcd = waiting.write("wake_up_cut.vcd");
  auto r = check(vcd);
  ASSERT_TRUE(r.frame_cut_by_end.has_value());
  EXPECT_EQ(lo_violations(r), 0);
  PowerCapture after;
  after.events.emplace_back(10 * kMs, 'p', '1');
  after.pulse(910 * kMs, 150);
  after.request(910 * kMs + 150 + 400 * kMs);
  after.events.emplace_back(1400 * kMs, 'c', '0');
  after.events.emplace_back(1401 * kMs, 'd', '0');
  vcd = after.write("after_sequence_cut.vcd");
  r = check(vcd);
  ASSERT_TRUE(r.frame_cut_by_end.has_value());
  EXPECT_EQ(lo_violations(r), 1);
  fs::remove(vcd);
  fs::remove(temp("wake_up_cut.vcd"));
}

// 3.5.6: the start-up routine reads word 13 (8019h: 25 bits) before its first position. A
// capture checked with a wrong declared width (13 bits) is read with the width word 13 shows
// from the frame after that read on, and says where it learnt it.
TEST(CheckCapture, AReadOfWordThirteenSetsThePositionWidthForTheFramesAfterIt) {
  const auto scenario =
      scenarios::load_scenario_file(std::string(ENDATSIM_SOURCE_DIR) + "/scenarios/bundled/power_on_startup_routine.json");
  const fs::path vcd = temp("word13.vcd");
  run_to_vcd(scenario, vcd);
  auto o = encoder_pins_of(scenario, vcd);
  o.encoder.position_bits = 13;
  const auto r = scenarios::check_capture(o);
  EXPECT_EQ(r.position_bits, 25U);
  ASSERT_TRUE(r.position_bits_learnt_at.has_value());
  EXPECT_EQ(r.frames_clean + 1, r.frames_decoded);  // every answer read at its true width; #0 is the power-on pulse
  std::size_t positions = 0;
  for (const auto& f : r.frames) {
    if (f.index <= *r.position_bits_learnt_at || !f.command ||
        protocol::info(*f.command).answer != protocol::AnswerFormat::Position)
      continue;
    EXPECT_EQ(f.fields[static_cast<std::size_t>(protocol::Field::Position)], 123456U) << scenarios::frame_log_line(f);
    ++positions;
  }
  EXPECT_GE(positions, 3U);  // the delay measurements and the three reads of the script
  const auto& reading = r.frames.at(*r.position_bits_learnt_at);
  EXPECT_EQ(reading.learnt_position_bits, 25U);
  EXPECT_NE(scenarios::frame_log_line(reading).find("word 13: the position has 25 bits"), std::string::npos);
  std::ostringstream summary;
  scenarios::write_capture_summary(summary, r, false);
  EXPECT_NE(summary.str().find("position 25 bits, from word 13 in frame #" +
                               std::to_string(*r.position_bits_learnt_at)),
            std::string::npos)
      << summary.str();
  fs::remove(vcd);
  // Without such a read the declared width stands, and the summary says so.
  const auto plain = scenarios::load_scenario_file(std::string(ENDATSIM_SOURCE_DIR) + "/scenarios/bundled/endat21_1mhz_10m.json");
  run_to_vcd(plain, vcd);
  const auto declared = scenarios::check_capture(encoder_pins_of(plain, vcd));
  EXPECT_FALSE(declared.position_bits_learnt_at.has_value());
  summary.str("");
  scenarios::write_capture_summary(summary, declared, false);
  EXPECT_NE(summary.str().find("position " + std::to_string(plain.encoder.position_bits) + " bits as declared"),
            std::string::npos)
      << summary.str();
  fs::remove(vcd);
}

// 2.3: one driver on DATA at a time. With both drivers' enables recorded, a capture shows the
// contentions the run found at the same connector, each once; with the encoder's alone it cannot.
TEST(CheckCapture, BothDriversEnablesShowABusContentionOnceAtTheRecordedConnector) {
  const auto scenario = scenarios::load_scenario_file(std::string(ENDATSIM_SOURCE_DIR) +
                                                      "/scenarios/field/05_short_recovery_time_not_activated.json");
  const fs::path vcd = temp("contention.vcd");
  const auto run = run_to_vcd(scenario, vcd);
  const auto at_encoder = [](const std::vector<checker::Violation>& vs) {
    return std::count_if(vs.begin(), vs.end(), [](const checker::Violation& v) {
      return v.check == checker::check::kContention && v.where == line::ObservationPoint::EncoderPins;
    });
  };
  const auto contentions = [](const std::vector<checker::Violation>& vs) {
    return std::count_if(vs.begin(), vs.end(), [](const checker::Violation& v) { return v.check == checker::check::kContention; });
  };
  ASSERT_GT(at_encoder(run.violations), 0);
  auto o = encoder_pins_of(scenario, vcd);
  o.master_data_enable = "master_data_driver_enable";
  const auto both = scenarios::check_capture(o);
  EXPECT_EQ(contentions(both.violations), at_encoder(run.violations));
  EXPECT_EQ(at_encoder(both.violations), at_encoder(run.violations));
  o.master_data_enable.reset();
  const auto one = scenarios::check_capture(o);
  EXPECT_EQ(contentions(one.violations), 0);
  const auto row = std::find_if(one.conformance.begin(), one.conformance.end(),
                                [](const auto& c) { return c.check == checker::check::kContention; });
  ASSERT_NE(row, one.conformance.end());
  EXPECT_EQ(row->status, checker::RowConformance::Status::NotObservable);
  // Through the command line, the master's enable needs the encoder's beside it.
  auto r = cli("check '" + vcd.string() + "' --clock encoder_clock --data encoder_data --master-data-enable master_data_driver_enable");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--master-data-enable goes with one DATA wire (--data) and the encoder's --data-enable"),
            std::string::npos)
      << r.err;
  r = cli("check '" + vcd.string() + "' --clock encoder_clock --data encoder_data --data-enable encoder_data_driver_enable "
          "--master-data-enable master_data_driver_enable");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.out.find("violation bus_contention"), std::string::npos) << r.out;
  // Without a cable the two connectors are one; with one, the summary warns of the skew.
  EXPECT_EQ(r.out.find("an enable recorded at the other end is off by the cable's delay"), std::string::npos) << r.out;
  r = cli("check '" + vcd.string() + "' --clock encoder_clock --data encoder_data --data-enable encoder_data_driver_enable "
          "--master-data-enable master_data_driver_enable --cable 20");
  EXPECT_NE(r.out.find("an enable recorded at the other end is off by the cable's delay"), std::string::npos) << r.out;
  // Recorded at the master's connector: moved by the cable's one-way delay, which needs the cable.
  const std::string both_cli = "check '" + vcd.string() + "' --clock encoder_clock --data encoder_data --data-enable "
                           "encoder_data_driver_enable --master-data-enable master_data_driver_enable";
  r = cli(both_cli + " --master-data-enable-at master --cable 20");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.out.find("the master's DATA enable, recorded at its connector, judged 100 ns later at the encoder's"),
            std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("off by the cable's delay"), std::string::npos) << r.out;
  r = cli(both_cli + " --master-data-enable-at master");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--master-data-enable-at master needs --cable LENGTH"), std::string::npos) << r.err;
  r = cli(both_cli + " --master-data-enable-at there --cable 20");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--master-data-enable-at must be 'encoder' or 'master', got 'there'"), std::string::npos) << r.err;
  r = cli("check '" + vcd.string() + "' --clock encoder_clock --data encoder_data --data-enable encoder_data_driver_enable "
          "--master-data-enable-at master --cable 20");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--master-data-enable-at says where --master-data-enable was recorded"), std::string::npos) << r.err;
  fs::remove(vcd);
}

// Every finding cites a section its row of the timing table names, so that a reader with the spec
// open finds the rule where the report says (over every bundled, field and safety scenario).
TEST(CheckerReports, EachFindingCitesASectionOfItsRow) {
  std::set<std::string> seen;
  for (const auto& file : scenarios_in({"bundled", "field", "safety"})) {
    const auto r = scenarios::run_scenario(scenarios::load_scenario_file(file.string()));
    for (const auto& v : r.violations) {
      const auto& row = protocol::timing_rows()[protocol::check::row_of(v.check)];
      const std::string section = v.spec.substr(0, v.spec.find_first_of(" ("));
      const auto sections = std::string(row.section);
      // "2.3.2" in "2.3.2 note 7, 2.3.1.1"; "A2" in "A2"; a whole section, not a prefix of one.
      bool cited = false;
      for (std::size_t at = sections.find(section); at != std::string::npos; at = sections.find(section, at + 1)) {
        const std::size_t end = at + section.size();
        const bool starts = at == 0 || sections[at - 1] == ' ';
        const bool ends = end == sections.size() || sections[end] == ' ' || sections[end] == ',';
        cited = cited || (starts && ends);
      }
      EXPECT_TRUE(cited) << file.filename() << ": " << v.check << " cites \"" << v.spec << "\", its row \"" << sections
                         << "\"";
      seen.insert(v.check);
    }
  }
  EXPECT_GE(seen.size(), 12U);  // most rows were reported somewhere
}

// 3.5.7: an EIB's commissioning writes word 13 (8020h: 32 bits) in area A1h, and the reset after
// it activates the width; a capture checked with a declared 25 bits reads the positions after
// that reset at 32.
TEST(CheckCapture, AWordThirteenWrittenAndActivatedByAResetSetsThePositionWidth) {
  const auto scenario = scenarios::load_scenario_file(std::string(ENDATSIM_SOURCE_DIR) +
                                                      "/scenarios/bundled/eib_initial_commissioning.json");
  const fs::path vcd = temp("eib.vcd");
  run_to_vcd(scenario, vcd);
  auto o = encoder_pins_of(scenario, vcd);
  ASSERT_EQ(o.encoder.position_bits, 32U);
  o.encoder.position_bits = 25;
  const auto r = scenarios::check_capture(o);
  fs::remove(vcd);
  // The first frame that set the width is the reset after the write (later reads of word 13
  // confirm it).
  const auto activated = std::find_if(r.frames.begin(), r.frames.end(), [](const auto& f) { return f.learnt_position_bits != 0; });
  ASSERT_NE(activated, r.frames.end());
  ASSERT_TRUE(activated->command.has_value());
  EXPECT_EQ(*activated->command, protocol::ModeCommand::EncoderReceiveReset);
  EXPECT_EQ(activated->learnt_position_bits, 32U);
  EXPECT_NE(scenarios::frame_log_line(*activated).find("word 13 as written, now active: the position has 32 bits"),
            std::string::npos);
  for (auto f = activated + 1; f != r.frames.end(); ++f) EXPECT_TRUE(f->crc_ok) << scenarios::frame_log_line(*f);
  const auto& first = *(activated + 1);  // the first position after the reset
  EXPECT_EQ(first.fields[static_cast<std::size_t>(protocol::Field::Position)], 49980U);
}

namespace {

// The encoder pins of a scenario's VCD seen through a window from `start` to `end`, as a logic
// analyzer armed mid-traffic records them: the levels at `start` as the initial values, then
// every change up to `end`. Times kept, or re-based so that the window opens at 0. Returns CLOCK's
// level at `start`.
char cut_vcd(const fs::path& from, const fs::path& to, Time start, Time end, bool rebase) {
  auto pins = open_encoder_pins(from);
  auto& reader = pins.first;
  const auto& wanted = pins.second;
  std::ofstream out(to);
  out << "$timescale 1 ps $end\n$scope module endat $end\n"
      << "$var wire 1 c encoder_clock $end\n$var wire 1 d encoder_data $end\n$var wire 1 e encoder_data_driver_enable $end\n"
      << "$upscope $end\n$enddefinitions $end\n";
  const char ids[] = {'c', 'd', 'e'};
  std::vector<char> level(3, 'x');
  const auto stamp = [&](Time t) { out << "#" << (rebase ? t - start : t).count() << "\n"; };
  bool opened = false;
  char clock_at_start = 'x';
  capture::Change c;
  while (reader->next(c) && c.time <= end) {
    const auto i = static_cast<std::size_t>(std::find(wanted.begin(), wanted.end(), c.signal) - wanted.begin());
    if (c.time > start && !opened) {
      stamp(start);
      for (std::size_t k = 0; k < 3; ++k) out << level[k] << ids[k] << "\n";
      opened = true;
      clock_at_start = level[0];
    }
    if (opened) {
      stamp(c.time);
      out << c.value << ids[i] << "\n";
    }
    level[i] = c.value;
  }
  return clock_at_start;
}

// The findings of a check as (check, time, measured), the time re-based by `shift`.
std::multiset<std::tuple<std::string, Time, std::string>> findings_of(const scenarios::CaptureCheckResult& r,
                                                                      Time from, Time to, Time shift) {
  std::multiset<std::tuple<std::string, Time, std::string>> out;
  for (const auto& v : r.violations)
    if (v.time + shift >= from && v.time + shift < to) out.emplace(v.check, v.time + shift, v.measured);
  return out;
}

}  // namespace

// A logic analyzer's capture begins and ends inside frames. The bundled 8 MHz scenario with t_ST
// 100 ns short of note 8's 2 us breaks t_st in every compensated frame; cut inside frame #15 and
// inside the answer of frame #19, the capture judges the frames wholly inside it as the uncut one
// does, skips what comes before the first (CLOCK LOW or HIGH at the cut), and judges neither
// clock_count nor the start-bit polling of the frame its end cut.
TEST(CheckCapture, ACaptureCutInsideFramesAtBothEndsJudgesItsWholeFramesAsTheUncutOne) {
  auto s = scenarios::load_scenario_file(std::string(ENDATSIM_SOURCE_DIR) +
                                         "/scenarios/bundled/endat22_8mhz_100m_compensated.json");
  s.master.t_st = ns(1900);
  const fs::path vcd = temp("uncut.vcd"), cut = temp("cut.vcd");
  run_to_vcd(s, vcd);
  auto o = encoder_pins_of(s, vcd);
  const auto whole = scenarios::check_capture(o);
  ASSERT_EQ(whole.edges_before_first_frame, 0U);
  ASSERT_FALSE(whole.frame_cut_by_end.has_value());
  const Time end = sim::us(1505);  // inside the answer of the frame that begins at 1.49904 ms
  // Inside the frame that begins at 1.29914 ms: CLOCK LOW at the cut, or HIGH.
  for (const auto& [start, rebase, clock] : {std::tuple{sim::ns(1303050), false, '0'}, std::tuple{sim::ns(1303100), false, '1'},
                                             std::tuple{sim::ns(1303050), true, '0'}}) {
    ASSERT_EQ(cut_vcd(vcd, cut, start, end, rebase), clock) << sim::format_time(start);
    o.file = cut.string();
    const auto r = scenarios::check_capture(o);
    const std::string what = sim::format_time(start) + (rebase ? " re-based" : "");
    const Time shift = rebase ? start : Time::zero();
    EXPECT_GT(r.edges_before_first_frame, 0U) << what;
    ASSERT_FALSE(r.frames.empty()) << what;
    ASSERT_TRUE(r.frame_cut_by_end.has_value()) << what;
    EXPECT_EQ(*r.frame_cut_by_end, r.frames.back().index) << what;
    const Time first = r.frames.front().fe1 + shift, last = r.frames.back().fe1 + shift;
    EXPECT_GT(first, start) << what;
    // The complete frames: the same findings at the same times.
    const auto complete = findings_of(r, first, last, shift);
    EXPECT_EQ(complete, findings_of(whole, first, last, Time::zero())) << what;
    EXPECT_EQ(complete.size(), 3U) << what;  // t_st in each of the three
    // The cut frame: what its start shows, nothing that needs its end.
    for (const auto& v : r.violations) {
      EXPECT_NE(v.check, checker::check::kClockCount) << what << ": " << v.message;
      EXPECT_NE(v.check, checker::check::kCalculationTime) << what << ": " << v.message;
    }
    std::ostringstream summary;
    scenarios::write_capture_summary(summary, r, false);
    EXPECT_NE(summary.str().find("capture begins inside a frame: " + std::to_string(r.edges_before_first_frame) +
                                 " edges before the first frame not judged"),
              std::string::npos)
        << summary.str();
    EXPECT_NE(summary.str().find("capture ends inside frame #" + std::to_string(*r.frame_cut_by_end)), std::string::npos)
        << summary.str();
    const auto j = scenarios::capture_json(r);
    EXPECT_EQ(j.at("edges_before_first_frame").get<std::uint64_t>(), r.edges_before_first_frame);
    EXPECT_EQ(j.at("frame_cut_by_end").get<std::uint64_t>(), *r.frame_cut_by_end);
  }
  fs::remove(vcd);
  fs::remove(cut);
}

// A master that hangs mid-frame with CLOCK LOW until the capture ends: the LOW phase still going on
// fails the encoder's declared t_LO maximum once it has lasted longer, and is not judged while it is
// shorter or where no maximum is declared (the spec envelope has none: "see encoder
// specifications").
TEST(CheckCapture, AClockLowThatOutlastsTheEncodersMaximumUntilTheEndFailsTlo) {
  const fs::path vcd = temp("hung_low.vcd");
  const auto write = [&](int end_us) {
    std::ofstream out(vcd);
    out << "$timescale 1 ns $end\n$scope module encoder $end\n$var wire 1 c clock $end\n$var wire 1 d data $end\n"
           "$upscope $end\n$enddefinitions $end\n#0\n1c\n1d\n";
    for (int i = 0; i < 5; ++i) out << "#" << 50000 + 1000 * i << "\n0c\n#" << 50500 + 1000 * i << "\n1c\n";
    out << "#55000\n0c\n#" << end_us * 1000 << "\n";  // CLOCK LOW from 55 us to the end
  };
  scenarios::CaptureCheckOptions o;
  o.file = vcd.string();
  o.clock = "clock";
  o.data = "data";
  const auto t_lo = [](const scenarios::CaptureCheckResult& r) {
    return std::count_if(r.violations.begin(), r.violations.end(),
                         [](const checker::Violation& v) { return v.check == checker::check::kPulseLow; });
  };
  write(555);
  auto r = scenarios::check_capture(o);
  ASSERT_TRUE(r.frame_cut_by_end.has_value());
  EXPECT_EQ(t_lo(r), 0) << "no maximum declared";
  o.encoder.t_lo_max = sim::us(30);
  r = scenarios::check_capture(o);
  ASSERT_EQ(t_lo(r), 1);
  const auto& v = *std::find_if(r.violations.begin(), r.violations.end(),
                                [](const checker::Violation& x) { return x.check == checker::check::kPulseLow; });
  EXPECT_EQ(v.measured, ">= 500 us");
  EXPECT_EQ(v.time, sim::us(55));
  EXPECT_EQ(v.verdict, checker::Verdict::ThisEncoder);
  EXPECT_NE(v.message.find("still LOW where the run or capture ended inside the frame"), std::string::npos) << v.message;
  o.encoder.t_lo_max = sim::us(500);  // just as long as the end shows: not known to be longer
  EXPECT_EQ(t_lo(scenarios::check_capture(o)), 0);
  o.encoder.t_lo_max = sim::us(500) - sim::ns(1);
  EXPECT_EQ(t_lo(scenarios::check_capture(o)), 1);
  write(80);  // 25 us LOW at the end, under the 30 us
  o.encoder.t_lo_max = sim::us(30);
  r = scenarios::check_capture(o);
  ASSERT_TRUE(r.frame_cut_by_end.has_value());
  EXPECT_EQ(t_lo(r), 0);
  fs::remove(vcd);
}

namespace {

checker::Violation finding(checker::Severity severity, checker::Verdict verdict) {
  checker::Violation v;
  v.check = std::string(checker::check::kRecovery);
  v.measured = "30.5 us";
  v.limit = ">= 30.5 us (spec envelope)";
  v.severity = severity;
  v.verdict = verdict;
  return v;
}

std::string verdict_line(const std::vector<checker::Violation>& vs) {
  std::ostringstream out;
  scenarios::write_verdict(out, checker::conclude(vs), vs);
  return out.str();
}

}  // namespace

// A finding undecided at the capture's resolution never reads as conforming: the verdict it
// counts against is "undecided at this resolution", in the summary and in JSON.
TEST(Verdict, UndecidedNeverReadsAsConforming) {
  using checker::Severity;
  using checker::Verdict;
  EXPECT_EQ(verdict_line({}), "  verdict: conforms to the spec envelope and to this encoder\n");
  EXPECT_EQ(scenarios::verdict_json(checker::conclude({})), (nlohmann::json{{"spec_envelope", true}, {"this_encoder", true}}));
  const std::vector both{finding(Severity::Undecided, Verdict::Both)};
  EXPECT_FALSE(checker::conclude(both).conforms_to_spec_envelope());
  EXPECT_FALSE(checker::conclude(both).conforms_to_this_encoder());
  EXPECT_EQ(verdict_line(both), "  verdict: undecided at this resolution for the spec envelope and for this encoder\n");
  EXPECT_EQ(scenarios::verdict_json(checker::conclude(both)),
            (nlohmann::json{{"spec_envelope", "undecided"}, {"this_encoder", "undecided"}}));
  const std::vector envelope{finding(Severity::Undecided, Verdict::SpecEnvelope)};
  EXPECT_TRUE(checker::conclude(envelope).conforms_to_this_encoder());
  EXPECT_EQ(verdict_line(envelope), "  verdict: conforms to this encoder; undecided at this resolution for the spec "
                                    "envelope: t_m_t_r 30.5 us (>= 30.5 us (spec envelope))\n");
  EXPECT_EQ(scenarios::verdict_json(checker::conclude(envelope)),
            (nlohmann::json{{"spec_envelope", "undecided"}, {"this_encoder", true}}));
  // An error decides its verdict whatever is undecided beside it.
  const std::vector mixed{finding(Severity::Undecided, Verdict::SpecEnvelope), finding(Severity::Error, Verdict::ThisEncoder)};
  EXPECT_EQ(verdict_line(mixed), "  verdict: does not conform to this encoder; undecided at this resolution for the spec envelope\n");
  EXPECT_EQ(scenarios::verdict_json(checker::conclude(mixed)),
            (nlohmann::json{{"spec_envelope", "undecided"}, {"this_encoder", false}}));
  const std::vector error{finding(Severity::Undecided, Verdict::ThisEncoder), finding(Severity::Error, Verdict::Both)};
  EXPECT_EQ(scenarios::verdict_json(checker::conclude(error)),
            (nlohmann::json{{"spec_envelope", false}, {"this_encoder", false}}));
}

// Through the command line: the bundled 8 MHz capture meets t_ST and the envelope's t_m + t_R
// with no margin; read at a logic analyzer's 10 ns they are undecided, and so is the verdict.
TEST(CheckCommand, AnUndecidedCapturesVerdictIsUndecided) {
  const auto s = scenarios::load_scenario_file(std::string(ENDATSIM_SOURCE_DIR) +
                                               "/scenarios/bundled/endat22_8mhz_100m_compensated.json");
  const fs::path vcd = temp("undecided_verdict.vcd"), json = temp("undecided_verdict.json");
  run_to_vcd(s, vcd);
  const auto r = cli("check '" + vcd.string() + "' --clock encoder_clock --data encoder_data --data-enable "
                     "encoder_data_driver_enable --cable 100 --resolution 10ns --json '" + json.string() + "'");
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  EXPECT_EQ(r.out.find("conforms to the spec envelope"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  verdict: undecided at this resolution for the spec envelope and for this encoder\n"),
            std::string::npos)
      << r.out;
  std::ifstream in(json);
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j.at("verdict"), (nlohmann::json{{"spec_envelope", "undecided"}, {"this_encoder", "undecided"}}));
  fs::remove(vcd);
  fs::remove(json);
}

namespace {

// The encoder pins of a scenario's VCD written again at `timescale` femtoseconds per unit, with
// RE1 of the `nth` frame whose first LOW phase lasts 1.5 .. 2.2 us (a compensated frame's t_ST;
// the 200 kHz measurement frames' LOW phases last 2.5 us) moved by `shift_fs` femtoseconds.
// The encoder pins' changes of a scenario's VCD: time (ps), pin (0 clock, 1 data, 2 the driver's
// enable), level.
using PinChanges = std::vector<std::tuple<std::int64_t, std::size_t, char>>;
PinChanges encoder_pin_changes(const fs::path& vcd) {
  auto pins = open_encoder_pins(vcd);
  auto& reader = pins.first;
  const auto& wanted = pins.second;
  PinChanges changes;
  capture::Change c;
  while (reader->next(c)) {
    const auto i = static_cast<std::size_t>(std::find(wanted.begin(), wanted.end(), c.signal) - wanted.begin());
    changes.emplace_back(c.time.count(), i, c.value);
  }
  return changes;
}

// The changes, sorted by time, as a VCD of the encoder's pins in `timescale` units.
void write_encoder_pins(const fs::path& to, const std::string& timescale, PinChanges changes) {
  std::stable_sort(changes.begin(), changes.end(), [](const auto& a, const auto& b) { return std::get<0>(a) < std::get<0>(b); });
  std::ofstream out(to);
  out << "$timescale " << timescale << " $end\n$scope module endat $end\n"
      << "$var wire 1 c encoder_clock $end\n$var wire 1 d encoder_data $end\n$var wire 1 e encoder_data_driver_enable $end\n"
      << "$upscope $end\n$enddefinitions $end\n";
  const char ids[] = {'c', 'd', 'e'};
  for (const auto& [t, i, v] : changes) out << "#" << t << "\n" << v << ids[i] << "\n";
}

// The rising CLOCK edges of each frame (a falling edge after more than 5 us HIGH begins one).
std::vector<std::vector<std::int64_t>> rises_per_frame(const PinChanges& changes) {
  std::vector<std::vector<std::int64_t>> rises;
  std::int64_t last_rise = -1'000'000'000;
  char clock = '1';
  for (const auto& [t, i, v] : changes) {
    if (i != 0 || v == clock) continue;
    clock = v;
    if (v == '0' && t - last_rise > 5'000'000) rises.emplace_back();
    if (v == '1' && !rises.empty()) rises.back().push_back(t);
    if (v == '1') last_rise = t;
  }
  return rises;
}

// Three position reads at 2 MHz without compensation run to `vcd`: the options that check its
// encoder pins, and their changes to mark up.
std::pair<scenarios::CaptureCheckOptions, PinChanges> three_reads_at_2mhz(const fs::path& vcd) {
  const auto s = test_support::make_scenario(3, sim::MHz(2), false);
  run_to_vcd(s, vcd);
  return {encoder_pins_of(s, vcd), encoder_pin_changes(vcd)};
}

// DATA unknown (x) from `from` to `to` in a capture's changes, then the level it had at `to`.
void hide_data(PinChanges& changes, std::int64_t from, std::int64_t to) {
  char after = '1';
  for (const auto& [t, i, v] : changes)
    if (i == 1 && t <= to) after = v;
  std::erase_if(changes, [&](const auto& c) { return std::get<1>(c) == 1 && std::get<0>(c) >= from && std::get<0>(c) <= to; });
  changes.emplace_back(from, 1, 'x');
  changes.emplace_back(to, 1, after);
  std::sort(changes.begin(), changes.end());
}

void to_femtoseconds(const fs::path& from, const fs::path& to, int nth, std::int64_t shift_fs) {
  auto changes = encoder_pin_changes(from);
  for (auto& [t, i, v] : changes) t *= 1000;  // fs
  std::int64_t fell = -1;
  int found = 0;
  for (auto& [t, i, v] : changes) {
    if (i != 0) continue;
    if (v == '0') fell = t;
    else if (fell >= 0 && t - fell > 1'500'000'000 && t - fell < 2'200'000'000 && ++found == nth) t += shift_fs;
  }
  write_encoder_pins(to, "1 fs", changes);
}

}  // namespace

// The encoder's driver turned off at FE1 itself and on at FE9 itself (t_z = t_OE = 0, as a
// zero-delay RTL encoder does): at one instant the clock's edge counts first, so both turnarounds
// are within their limits and every frame decodes as before, whichever order the time step lists
// the two lines in. (Before, the enable reached the checker before the edge, and every frame
// broke t_z, t_cal and its turnaround.)
TEST(CheckCapture, AnEnableThatChangesAtTheClockEdgeItselfCountsAfterTheEdge) {
  const auto s = test_support::make_scenario(3, sim::MHz(2), false);
  const fs::path vcd = temp("edge.vcd"), moved = temp("edge_moved.vcd");
  run_to_vcd(s, vcd);
  const auto original = scenarios::check_capture(encoder_pins_of(s, vcd));
  ASSERT_TRUE(original.conforms());
  ASSERT_GE(original.frames_clean, 3U);
  for (const bool enable_line_first : {false, true}) {
    PinChanges changes = encoder_pin_changes(vcd);
    // Each frame's FE1 (CLOCK HIGH for more than 5 us before it) and FE9.
    std::vector<std::int64_t> fe1, fe9;
    std::int64_t rose = 0;
    int falls = 0;
    for (const auto& [t, i, v] : changes) {
      if (i != 0) continue;
      if (v == '1') rose = t;
      else if (fe1.empty() || t - rose > 5'000'000) falls = 1, fe1.push_back(t);
      else if (++falls == 9) fe9.push_back(t);
    }
    ASSERT_EQ(fe1.size(), fe9.size());
    PinChanges out;
    std::size_t released = 0, driven = 0;
    for (const auto& [t, i, v] : changes) {
      if (i != 2) {
        out.emplace_back(t, i, v);
        continue;
      }
      // The release after each FE1 and the drive after each FE9, each moved onto its edge.
      const auto after = [&](const std::vector<std::int64_t>& edges) {
        const auto e = std::upper_bound(edges.begin(), edges.end(), t);
        return e == edges.begin() ? std::int64_t{-1} : *(e - 1);
      };
      const std::int64_t edge = v == '0' ? after(fe1) : after(fe9);
      const bool move = edge >= 0 && t - edge < 200'000;
      if (move) (v == '0' ? released : driven) += 1;
      const std::int64_t at = move ? edge : t;
      if (enable_line_first) {
        const auto clock_line = std::find(out.begin(), out.end(), std::make_tuple(at, std::size_t{0}, '0'));
        out.insert(clock_line, std::make_tuple(at, std::size_t{2}, v));
      } else {
        out.emplace_back(at, i, v);
      }
    }
    EXPECT_EQ(released, fe1.size());
    EXPECT_EQ(driven, fe9.size());
    write_encoder_pins(moved, "1 ps", out);
    auto o = encoder_pins_of(s, moved);
    const auto r = scenarios::check_capture(o);
    EXPECT_TRUE(r.conforms()) << enable_line_first << "\n" << verdict_line(r.violations);
    EXPECT_EQ(r.frames_decoded, original.frames_decoded);
    EXPECT_EQ(r.frames_clean, original.frames_clean);
    EXPECT_EQ(decoded(r), decoded(original));
  }
  fs::remove(vcd);
  fs::remove(moved);
}

// The start bit belongs to the rising edge whose bit the decoder takes it for: the slot of RE_k
// runs from half a period before RE_k plus the declared CLOCK-to-DATA delay to half a period after.
// An encoder faster or slower than declared by less than half a period (T = 500 ns) keeps its
// start bit on RE11, as the decoded frame shows; by more, it moves to the next edge, and t_cal's
// minimum (RE11, 10.5 periods after FE1) or the clock count says so. (Before, the encoder had to
// be no faster than declared: 1 ps faster put the start bit on RE10.)
TEST(CheckCapture, TheStartBitBelongsToTheEdgeWithinHalfAPeriodOfTheDeclaredDelay) {
  const auto s = test_support::make_scenario(3, sim::MHz(2), false);
  const fs::path vcd = temp("slot.vcd");
  run_to_vcd(s, vcd);
  const auto start_bits = [](const scenarios::CaptureCheckResult& r) {
    std::vector<unsigned> clocks;
    for (const auto& f : r.frames) clocks.push_back(f.start_bit_clock);
    return clocks;
  };
  const auto rows = [](const scenarios::CaptureCheckResult& r, std::string_view row) {
    return std::count_if(r.violations.begin(), r.violations.end(), [&](const auto& v) { return v.check == row; });
  };
  const auto exact = scenarios::check_capture(encoder_pins_of(s, vcd));
  ASSERT_TRUE(exact.conforms());
  ASSERT_EQ(start_bits(exact), (std::vector<unsigned>{11, 11, 11}));
  // Declared slower than the encoder is: the encoder looks faster by `by`.
  for (const Time by : {sim::ps(1), ns(249), ns(250) - sim::ps(1), -sim::ps(1), -ns(249)}) {
    auto o = encoder_pins_of(s, vcd);
    o.encoder.output_delay += by;
    const auto r = scenarios::check_capture(o);
    EXPECT_TRUE(r.conforms()) << by.count() << "\n" << verdict_line(r.violations);
    EXPECT_EQ(rows(r, checker::check::kCalculationTime), 0) << by.count();
    EXPECT_EQ(rows(r, checker::check::kClockCount), 0) << by.count();
  }
  // More than half a period faster than declared: the start bit is the one of the edge before.
  auto o = encoder_pins_of(s, vcd);
  o.encoder.output_delay += ns(251);
  const auto early = scenarios::check_capture(o);
  EXPECT_EQ(rows(early, checker::check::kCalculationTime), 3);
  fs::remove(vcd);
}

// A master that gives no pulse after the last bit (docs/model.md section 5) samples it half a
// period after the last rising edge, with CLOCK already HIGH: the clock count accepts its 43
// pulses, and the decoder reads that bit there, so every answer is complete with its CRC, as the
// run's master read it. (Before, the last bit had no rising edge after it and every frame was
// "incomplete after 43 clocks".) One pulse fewer still leaves the answer incomplete.
TEST(CheckCapture, TheLastBitIsReadWithoutAPulseAfterIt) {
  auto s = test_support::make_scenario(3, sim::MHz(2), false);
  const fs::path vcd = temp("no_extra_pulse.vcd");
  for (const bool extra : {true, false}) {
    s.master.extra_clock_after_last_bit = extra;
    s.master.position_bits = s.encoder.position_bits;
    const auto run = run_to_vcd(s, vcd);
    const auto r = scenarios::check_capture(encoder_pins_of(s, vcd));
    EXPECT_TRUE(r.conforms()) << extra << "\n" << verdict_line(r.violations);
    ASSERT_EQ(r.frames.size(), 3U) << extra;
    EXPECT_EQ(r.frames_clean, 3U) << extra;
    std::vector<std::uint64_t> read;
    for (const auto& f : run.frames) read.push_back(f.position);
    ASSERT_EQ(read.size(), 3U);
    for (std::size_t i = 0; i < r.frames.size(); ++i) {
      EXPECT_EQ(r.frames[i].clocks, extra ? 44U : 43U);
      EXPECT_TRUE(r.frames[i].answer_complete) << extra << " " << i;
      EXPECT_TRUE(r.frames[i].crc_ok) << extra << " " << i;
      EXPECT_EQ(r.frames[i].fields[static_cast<std::size_t>(protocol::Field::Position)], read[i]) << extra << " " << i;
    }
  }
  s.master.position_bits = s.encoder.position_bits - 1;  // 42 pulses: the last bit is never clocked out
  run_to_vcd(s, vcd);
  const auto short_frames = scenarios::check_capture(encoder_pins_of(s, vcd));
  EXPECT_EQ(short_frames.frames_clean, 0U);
  for (const auto& f : short_frames.frames) EXPECT_FALSE(f.answer_complete);
  fs::remove(vcd);
}

// DATA unknown (x) in a capture where an answer bit is read: the bit is read as the level before,
// but the frame is not counted clean and the log, the JSON and the summary say so. (Before, it was
// read silently.) An x on the floating line before the mode command, where no bit is read, counts
// for nothing.
TEST(CheckCapture, AnAnswerBitReadWhileDataIsUnknownIsNamedAndTheFrameNotClean) {
  const fs::path vcd = temp("xbit.vcd"), marked = temp("xbit_marked.vcd");
  auto [o, changes] = three_reads_at_2mhz(vcd);
  ASSERT_EQ(scenarios::check_capture(o).frames_clean, 3U);
  const auto rises = rises_per_frame(changes);
  ASSERT_EQ(rises.size(), 3U);
  const auto level_at = [&](std::int64_t t) {
    char level = '1';
    for (const auto& [when, i, v] : changes)
      if (i == 1 && when <= t) level = v;
    return level;
  };
  // Frame #1, slot 20 (a position bit): read 250 ns after RE20 plus the encoder's delay.
  const std::int64_t read = rises[1][19] + o.encoder.output_delay.count() + 250'000;
  // Frame #0: around RE1, on the line the encoder has released and the master not yet driven.
  const std::int64_t floating = rises[0][0];
  const char read_level = level_at(read), floating_level = level_at(floating);
  for (const auto& [at, level] : {std::pair{read, read_level}, std::pair{floating, floating_level}}) {
    changes.emplace_back(at - 100'000, 1, 'x');
    changes.emplace_back(at + 100'000, 1, level);
  }
  // Frame #2: x over the slots of RE10 .. RE12, where the start bit (RE11) rises after the
  // encoder's LOW: read as that LOW, it hides the start bit, and counts.
  const std::int64_t delay = o.encoder.output_delay.count();
  hide_data(changes, rises[2][9] + delay + 100'000, rises[2][11] + delay + 400'000);
  write_encoder_pins(marked, "1 ps", changes);
  auto m = o;
  m.file = marked.string();
  const auto r = scenarios::check_capture(m);
  EXPECT_EQ(r.frames_decoded, 3U);
  EXPECT_EQ(r.frames_clean, 1U);
  EXPECT_EQ(r.data_unknown_first_frame, 1U);
  ASSERT_EQ(r.frames.size(), 3U);
  EXPECT_EQ(r.frames[0].unknown_bits, 0U);
  EXPECT_EQ(r.frames[1].unknown_bits, 1U);
  EXPECT_GE(r.frames[2].unknown_bits, 1U);
  EXPECT_EQ(r.frames[2].first_unknown_clock, 10U);
  EXPECT_EQ(r.data_unknown_bits, 1U + r.frames[2].unknown_bits);
  EXPECT_EQ(r.frames[1].first_unknown_clock, 20U);
  EXPECT_TRUE(r.frames[1].crc_ok);  // the level before was the bit's own
  EXPECT_FALSE(r.frames[1].clean());
  EXPECT_NE(scenarios::frame_log_line(r.frames[1]).find("1 bit(s) read while DATA was unknown (x), the first on clock 20"),
            std::string::npos)
      << scenarios::frame_log_line(r.frames[1]);
  std::ostringstream summary;
  scenarios::write_capture_summary(summary, r, false);
  EXPECT_NE(summary.str().find("DATA unknown (x) where " + std::to_string(r.data_unknown_bits) +
                               " bit(s) of the frames were read, first in frame #1"),
            std::string::npos)
      << summary.str();
  const auto j = scenarios::capture_json(r);
  EXPECT_EQ(j["data_unknown_bits"], r.data_unknown_bits);
  EXPECT_EQ(j["frames"][1]["unknown_bits"], 1);
  EXPECT_FALSE(j["frames"][0].contains("unknown_bits"));
  fs::remove(vcd);
  fs::remove(marked);
}

// DATA unknown (x) from the moment the encoder's recorded enable turns its driver on until after
// the start bit: the x hides the encoder's LOW as well as the start bit. With the enable recorded,
// the slots read in it count (the driver is on: the level is the encoder's, unknown); without
// it, an x before any LOW is taken for the released line, as before, and decides nothing.
TEST(CheckCapture, AnXWhileTheEncodersDriverIsOnCountsWhereTheStartBitMayBe) {
  const fs::path vcd = temp("xdriven.vcd"), marked = temp("xdriven_marked.vcd");
  auto [o, changes] = three_reads_at_2mhz(vcd);
  const auto rises = rises_per_frame(changes);
  ASSERT_EQ(rises.size(), 3U);
  std::int64_t driver_on = -1;
  for (const auto& [t, i, v] : changes)
    if (i == 2 && v == '1' && t > rises[2][0]) {
      driver_on = t;
      break;
    }
  ASSERT_GT(driver_on, 0);
  hide_data(changes, driver_on, rises[2][11] + o.encoder.output_delay.count() + 400'000);
  write_encoder_pins(marked, "1 ps", changes);
  auto m = o;
  m.file = marked.string();
  const auto with_enable = scenarios::check_capture(m);
  ASSERT_EQ(with_enable.frames.size(), 3U);
  EXPECT_EQ(with_enable.frames[0].unknown_bits + with_enable.frames[1].unknown_bits, 0U);
  EXPECT_GE(with_enable.frames[2].unknown_bits, 1U);
  EXPECT_FALSE(with_enable.frames[2].clean());
  EXPECT_EQ(with_enable.data_unknown_first_frame, 2U);
  m.data_enable.reset();
  const auto without = scenarios::check_capture(m);
  ASSERT_EQ(without.frames.size(), 3U);
  EXPECT_EQ(without.frames[2].unknown_bits, 0U);
  fs::remove(vcd);
  fs::remove(marked);
}

// One glitch on CLOCK in a 2 MHz frame without compensation: 10 ns LOW, 100 ns after RE20. The
// pulse-width rows break on it; the frame's clock is still fitted at 2 MHz and judged as a clock
// without compensation. (Before, its extra rising edge fitted the frame at 2.07 MHz, which moved
// it to the compensated column: t_ST was then required of its first LOW phase and broken.)
TEST(CheckCapture, AClockGlitchBreaksThePulseWidthsNotTheFramesFrequency) {
  const fs::path vcd = temp("glitch.vcd"), glitched = temp("glitch_marked.vcd");
  auto [o, changes] = three_reads_at_2mhz(vcd);
  const auto rises = rises_per_frame(changes);
  ASSERT_EQ(rises.size(), 3U);
  const std::vector<std::int64_t>& frame1 = rises[1];
  ASSERT_GT(frame1.size(), 20U);
  changes.emplace_back(frame1[19] + 100'000, 0, '0');
  changes.emplace_back(frame1[19] + 110'000, 0, '1');
  write_encoder_pins(glitched, "1 ps", changes);
  auto g = o;
  g.file = glitched.string();
  const auto r = scenarios::check_capture(g);
  const auto row = [&](std::string_view name) {
    return *std::find_if(r.conformance.begin(), r.conformance.end(), [&](const auto& c) { return c.check == name; });
  };
  EXPECT_EQ(row(checker::check::kPulseLow).violations, 1U);
  EXPECT_EQ(row(checker::check::kClockFrequency).violations, 0U);
  EXPECT_EQ(row(checker::check::kClockFrequency).judged, 3U);
  for (const auto& w : row(checker::check::kClockFrequency).worst) EXPECT_EQ(w.measured, "2 MHz");
  EXPECT_EQ(row(checker::check::kStartDelay).judged, 0U);
  EXPECT_EQ(row(checker::check::kOnOffRatio).judged, 0U);  // judged for compensated clocks only
  fs::remove(vcd);
  fs::remove(glitched);
}

// At the master's connector, with no delay measurement in the capture and no --t-d, the round trip
// is only estimated from the cable, and the spec bounds the real one only by t_D's maximum: more
// than half a period of a compensated clock. Which edge carried the start bit is then not known,
// and t_D and the clock count are undecided in each compensated frame, never passed or failed on
// the guess; what holds for every edge within t_D's bound (t_cal's limits here) is judged. (Before, a round trip 1 ps over t_D's bound at 8 MHz on 100 m was read one
// edge off and passed t_D.) With --t-d given, each is judged; a clock without compensation is
// judged as before.
TEST(CheckCapture, AtTheMastersConnectorAnUnmeasuredRoundTripLeavesTheStartBitsEdgeUndecided) {
  const auto check_at_master = [](bool compensated, std::optional<Time> t_d) {
    auto s = test_support::make_scenario(10, sim::MHz(compensated ? 8 : 1), compensated);
    if (compensated) {
      s.script.erase(s.script.begin());  // no measurement: the commissioning sheet's value
      s.master.fixed_t_d = ns(40 + 20 + 20 + 20 + 20 + 100) + 2 * s.line.cable_delay();
    }
    const fs::path vcd = temp("unmeasured.vcd");
    run_to_vcd(s, vcd);
    scenarios::CaptureCheckOptions o;
    o.file = vcd.string();
    o.clock = "master_clock";
    o.data = "master_data";
    o.at = scenarios::CaptureCheckOptions::At::Master;
    o.cable_m = 10;
    o.t_d = t_d;
    o.encoder = scenarios::declared_encoder(s.encoder);
    o.encoder.output_delay = s.line.encoder.receiver_delay + s.encoder.output_delay + s.line.encoder.driver_delay;
    auto r = scenarios::check_capture(o);
    fs::remove(vcd);
    return r;
  };
  const auto row = [](const scenarios::CaptureCheckResult& r, std::string_view name) {
    return *std::find_if(r.conformance.begin(), r.conformance.end(), [&](const auto& c) { return c.check == name; });
  };
  const auto guessed = check_at_master(true, std::nullopt);
  ASSERT_EQ(guessed.frames_clean, 3U);
  for (const auto name : {checker::check::kDataDelay, checker::check::kClockCount}) {
    EXPECT_EQ(row(guessed, name).judged, 3U) << name;
    EXPECT_EQ(row(guessed, name).undecided, 3U) << name;
    EXPECT_EQ(row(guessed, name).violations, 0U) << name;
  }
  // t_cal's 1 ms maximum and its minimum (RE11) hold for every edge within t_D's bound of the
  // guessed one (at 8 MHz the start bit comes near RE30): still judged.
  EXPECT_EQ(row(guessed, checker::check::kCalculationTime).judged, 3U);
  EXPECT_EQ(row(guessed, checker::check::kCalculationTime).undecided, 0U);
  EXPECT_TRUE(guessed.undecided() != 0);
  for (const auto& v : guessed.violations) {
    EXPECT_EQ(v.severity, checker::Severity::Undecided) << v.check;
    EXPECT_NE(v.message.find("neither measured in the capture nor given (--t-d)"), std::string::npos) << v.message;
  }
  // 60 ns in the encoder, 2 x 50 ns of cable: the round trip between the master's pins.
  for (const auto& [compensated, t_d] : {std::pair{true, std::optional<Time>(ns(160))}, std::pair{false, std::optional<Time>()}}) {
    const auto judged = check_at_master(compensated, t_d);
    EXPECT_EQ(judged.frames_clean, 3U) << compensated;
    EXPECT_TRUE(judged.conforms()) << compensated << "\n" << verdict_line(judged.violations);
    for (const auto name : {checker::check::kDataDelay, checker::check::kCalculationTime, checker::check::kClockCount}) {
      EXPECT_EQ(row(judged, name).judged, 3U) << compensated << name;
      EXPECT_EQ(row(judged, name).undecided, 0U) << compensated << name;
    }
  }
}

// A continuous clock (2.3.1): every further word is decoded from the wires as the first, its
// position and CRC in the log and the JSON, as the run's master read them; a word whose CRC fails
// is counted and said, where before only the number of words was.
TEST(CheckCapture, EachContinuousClockWordIsDecodedWithItsCrc) {
  const auto s = scenarios::load_scenario_file(std::string(ENDATSIM_SOURCE_DIR) + "/scenarios/bundled/endat21_continuous_clock.json");
  const fs::path vcd = temp("continuous.vcd");
  const auto run = run_to_vcd(s, vcd);
  const auto c = scenarios::check_capture(encoder_pins_of(s, vcd));
  ASSERT_FALSE(c.frames.empty());
  std::size_t words = 0;
  for (const auto& f : c.frames) {
    // The run's frames: word 0 with the mode command, then each further word of the same burst.
    std::vector<std::uint64_t> read;
    for (const auto& r : run.frames)
      if (r.start >= f.fe1 - sim::us(1) && r.start < f.fe1 + sim::us(500) && !r.measurement) read.push_back(r.position);
    ASSERT_EQ(read.size(), 1 + f.continuous_words) << f.index;
    ASSERT_EQ(f.words.size(), f.continuous_words);
    EXPECT_EQ(f.bad_words, 0U);
    for (std::size_t k = 0; k < f.words.size(); ++k) {
      EXPECT_TRUE(f.words[k].crc_ok);
      EXPECT_EQ(f.words[k].fields[static_cast<std::size_t>(protocol::Field::Position)], read[k + 1]) << f.index << " " << k;
    }
    words += f.words.size();
  }
  EXPECT_GT(words, 0U);
  EXPECT_EQ(c.words_bad_crc, 0U);
  // One bit of the first burst's second word (slot 54: that word's start bit on RE45) inverted
  // on the capture across the middle of its data-valid window: that word's CRC fails, alone.
  const auto o = encoder_pins_of(s, vcd);
  PinChanges changes = encoder_pin_changes(vcd);
  std::vector<std::int64_t> rises;
  bool level = false, data = false;
  for (const auto& [t, i, v] : changes) {
    if (i == 0 && v == '1' && !level && c.frames.front().fe1.count() <= t) rises.push_back(t);
    if (i == 0) level = v == '1';
  }
  ASSERT_GT(rises.size(), 54U);
  const std::int64_t slot = rises[53] + o.encoder.output_delay.count();
  for (const auto& [t, i, v] : changes)
    if (i == 1 && t <= slot + 500'000) data = v == '1';
  changes.emplace_back(slot + 250'000, 1, data ? '0' : '1');
  changes.emplace_back(slot + 750'000, 1, data ? '1' : '0');
  const fs::path flipped = temp("continuous_flipped.vcd");
  write_encoder_pins(flipped, "1 ps", changes);
  auto of = o;
  of.file = flipped.string();
  const auto bad = scenarios::check_capture(of);
  EXPECT_EQ(bad.words_bad_crc, 1U);
  ASSERT_FALSE(bad.frames.empty());
  ASSERT_EQ(bad.frames.front().words.size(), 4U);
  EXPECT_FALSE(bad.frames.front().words[0].crc_ok);
  EXPECT_TRUE(bad.frames.front().words[1].crc_ok);
  EXPECT_TRUE(bad.frames.front().crc_ok);
  EXPECT_NE(scenarios::capture_log(bad).find("4 further continuous-clock word(s) (1 with a BAD CRC): position "),
            std::string::npos) << scenarios::capture_log(bad);
  fs::remove(vcd);
  fs::remove(flipped);
}

// A VCD finer than the picosecond is read to the nearest picosecond: once a time rounds, the
// resolution is a picosecond, and t_ST 400 fs short of note 8's 2 us is undecided, never passed;
// while every time falls on a whole picosecond the file is exact. The bundled 8 MHz scenario meets t_ST with no margin in each of its 20
// compensated frames; RE1 of the fifth is moved.
TEST(CheckCapture, ATimescaleFinerThanAPicosecondHasAPicosecondsResolution) {
  const auto s = scenarios::load_scenario_file(std::string(ENDATSIM_SOURCE_DIR) +
                                               "/scenarios/bundled/endat22_8mhz_100m_compensated.json");
  const fs::path vcd = temp("ps.vcd"), femto = temp("fs.vcd");
  run_to_vcd(s, vcd);
  auto o = encoder_pins_of(s, vcd);
  o.file = femto.string();
  const auto t_st = [&](std::int64_t shift_fs, Time uncertainty) {
    to_femtoseconds(vcd, femto, 5, shift_fs);
    const auto r = scenarios::check_capture(o);
    EXPECT_EQ(r.uncertainty, uncertainty) << shift_fs << " fs";
    std::pair<std::size_t, std::size_t> errors_undecided{0, 0};
    for (const auto& v : r.violations)
      if (v.check == checker::check::kStartDelay)
        ++(v.severity == checker::Severity::Error ? errors_undecided.first : errors_undecided.second);
    return errors_undecided;
  };
  // Every t_ST of the 20 frames is 2 us, the limit. The fifth frame's RE1 moved by less than a
  // picosecond rounds: from there on each limit met within 1 ps is undecided (16 frames); the
  // four before were read exactly.
  EXPECT_EQ(t_st(-400, sim::ps(1)), std::pair(std::size_t{0}, std::size_t{16}));
  // 1.4 ps short reads as 1 ps short, a whole resolution outside the limit: that one fails.
  EXPECT_EQ(t_st(-1400, sim::ps(1)), std::pair(std::size_t{1}, std::size_t{15}));
  std::ostringstream summary;
  scenarios::write_capture_summary(summary, scenarios::check_capture(o), false);
  EXPECT_NE(summary.str().find("resolution 1 ps (timescale 1 fs, times rounded to the picosecond)"), std::string::npos)
      << summary.str();
  EXPECT_EQ(summary.str().find("event times exact"), std::string::npos) << summary.str();
  // Moved by whole picoseconds, every time of the 1 fs file is exact (as GHDL's VCDs are): one
  // picosecond short fails, one picosecond long passes.
  EXPECT_EQ(t_st(-1000, Time::zero()), std::pair(std::size_t{1}, std::size_t{0}));
  EXPECT_EQ(t_st(+1000, Time::zero()), std::pair(std::size_t{0}, std::size_t{0}));
  std::ostringstream exact;
  scenarios::write_capture_summary(exact, scenarios::check_capture(o), false);
  EXPECT_NE(exact.str().find("event times exact (timescale 1 fs)"), std::string::npos) << exact.str();
  fs::remove(vcd);
  fs::remove(femto);
}

// Bad input through the command line exits 2 naming the file and the problem: a VCD cut inside
// its last timestamp ("#11" of "#1100": truncated, not time going backwards), a zip that is no
// sigrok session, a CSV without its header line.
TEST(CheckCommand, ATruncatedVcdAZipThatIsNoSessionAndAHeaderlessCsvExitTwo) {
  const fs::path vcd = temp("cut_body.vcd"), zip = temp("no_session.sr"), csv = temp("no_header.csv");
  std::ofstream(vcd) << "$timescale 1 ns $end\n$scope module encoder $end\n$var wire 1 ! clock $end\n"
                        "$var wire 1 \" data $end\n$upscope $end\n$enddefinitions $end\n#0\n1!\n0\"\n#1000\n0!\n#11";
  auto r = cli("check '" + vcd.string() + "' --clock clock --data data");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.err.find(vcd.string() + ": line 12: truncated"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("backwards"), std::string::npos) << r.err;
  {
    // A zip archive of one text entry: "PK\3\4" opens it as a sigrok session.
    int error = 0;
    zip_t* z = zip_open(zip.string().c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
    ASSERT_NE(z, nullptr);
    static const char kText[] = "not a session";
    zip_source_t* src = zip_source_buffer(z, kText, sizeof kText - 1, 0);
    ASSERT_GE(zip_file_add(z, "readme.txt", src, ZIP_FL_OVERWRITE), 0);
    ASSERT_EQ(zip_close(z), 0);
  }
  r = cli("check '" + zip.string() + "' --clock clock --data data");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.err.find(zip.string() + ": "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("not a sigrok session file"), std::string::npos) << r.err;
  std::ofstream(csv) << "0,1\n1,1\n";
  r = cli("check '" + csv.string() + "' --clock clock --data data");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.err.find(csv.string() + ": line 1: no header"), std::string::npos) << r.err;
  for (const auto& p : {vcd, zip, csv}) fs::remove(p);
}

namespace {

std::string slurp_file(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

// The option that relaxes t_ST for a short cable (2.3.2 note 8) is named in every report: the
// summary, the JSON, the JUnit suite and its t_st test case, and the head of --log; for `check`
// and for `run` (scenario key checker.t_st_reduced_for_cable).
TEST(CheckCommand, TheOptionThatRelaxesARowIsNamedInEveryReport) {
  const std::string bundled = std::string(ENDATSIM_SOURCE_DIR) + "/scenarios/bundled/endat22_16mhz_20m_tst1us.json";
  const fs::path vcd = temp("relaxed.vcd"), junit = temp("relaxed.xml"), log = temp("relaxed.log"),
                 json = temp("relaxed.json"), scenario = temp("relaxed_scenario.json");
  run_to_vcd(scenarios::load_scenario_file(bundled), vcd);
  const std::string named = "t_st_reduced_for_cable: a t_ST shorter than note 8";
  auto r = cli("check '" + vcd.string() + "' --clock encoder_clock --data encoder_data --cable 20 "
               "--t-st-reduced-for-cable --junit '" + junit.string() + "' --log '" + log.string() + "' --json '" +
               json.string() + "'");
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("relaxed by option: t_st (" + named), std::string::npos) << r.out;
  const std::string xml = slurp_file(junit);
  const auto t_st_case = xml.find("<testcase classname=\"endatsim.check\" name=\"t_st\"");
  ASSERT_NE(t_st_case, std::string::npos) << xml;
  const auto suite_property = xml.find("<property name=\"relaxed_by\" value=\"t_st: " + named);
  EXPECT_LT(suite_property, xml.find("<testcase")) << xml;  // the suite's properties, before its cases
  const auto case_property = xml.find("<property name=\"relaxed_by\" value=\"" + named, t_st_case);
  EXPECT_LT(case_property, xml.find("</testcase>", t_st_case)) << xml;
  EXPECT_EQ(xml.find("relaxed_by", xml.find("</testcase>", t_st_case)), std::string::npos) << xml;  // that row only
  EXPECT_EQ(slurp_file(log).rfind("# relaxed by option: t_st (" + named, 0), 0U) << slurp_file(log);
  EXPECT_NE(slurp_file(json).find("\"relaxed_by\": \"" + named), std::string::npos);
  // Without the option no report names it.
  r = cli("check '" + vcd.string() + "' --clock encoder_clock --data encoder_data --cable 20 --junit '" + junit.string() +
          "' --log '" + log.string() + "'");
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_EQ(slurp_file(junit).find("relaxed_by"), std::string::npos);
  EXPECT_EQ(slurp_file(log).find("relaxed"), std::string::npos);
  // run: the scenario's testcase and the transaction log's head.
  auto j = nlohmann::json::parse(slurp_file(bundled));
  j["checker"]["t_st_reduced_for_cable"] = true;
  std::ofstream(scenario) << j.dump(2);
  r = cli("run '" + scenario.string() + "' --quiet --junit '" + junit.string() + "' --log '" + log.string() + "'");
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(slurp_file(junit).find("<property name=\"relaxed_by\" value=\"t_st: " + named), std::string::npos)
      << slurp_file(junit);
  const std::string run_log = slurp_file(log);
  EXPECT_NE(run_log.find("\n# relaxed by option: t_st (" + named), std::string::npos) << run_log.substr(0, 400);
  EXPECT_LT(run_log.find("# relaxed by option"), run_log.find("\n ")) << run_log.substr(0, 400);  // in the header
  for (const auto& p : {vcd, junit, log, json, scenario}) fs::remove(p);
}

// 2.1.2: delay compensation is given for up to 100 m of cable; above 2 MHz over a longer one a
// warning says to consult the encoder's maker. The bundled 8 MHz capture over exactly 100 m draws
// none; over the next length a double can hold, and over 100.5 m, each compensated frame draws
// one that prints the length as given.
TEST(CheckCapture, ACompensatedClockOverMoreThanOneHundredMetresWarnsFromTheNextLengthOn) {
  const auto s = scenarios::load_scenario_file(std::string(ENDATSIM_SOURCE_DIR) +
                                               "/scenarios/bundled/endat22_8mhz_100m_compensated.json");
  const fs::path vcd = temp("cable_100m.vcd");
  run_to_vcd(s, vcd);
  auto o = encoder_pins_of(s, vcd);
  const auto warnings = [&](double cable) {
    o.cable_m = cable;
    std::vector<std::string> measured;
    for (const auto& v : scenarios::check_capture(o).violations)
      if (v.check == checker::check::kClockFrequency && v.severity == checker::Severity::Warning &&
          v.spec.rfind("2.1.2 (with delay compensation up to 100 m", 0) == 0)
        measured.push_back(v.measured);
    return measured;
  };
  EXPECT_TRUE(warnings(100).empty());
  const auto just_over = warnings(std::nextafter(100.0, 101.0));
  ASSERT_EQ(just_over.size(), 20U);  // the 20 compensated frames
  EXPECT_EQ(just_over.front(), "8 MHz over 100.00000000000001 m");
  const auto half = warnings(100.5);
  ASSERT_EQ(half.size(), 20U);
  EXPECT_EQ(half.front(), "8 MHz over 100.5 m");
  fs::remove(vcd);
}

// 2.1.2 at a capture's master connector: compensated frames and no measurement in the recording
// (field 02 measures at 1 MHz, which is no measurement frame) cannot be told apart from a master
// whose measurements came before the recording began, unless the recording shows the switch-on.
TEST(CheckCapture, CompensationWithoutAMeasurementInTheRecordingIsNotObservableWithoutTheSwitchOn) {
  const auto scenario = scenarios::load_scenario_file(std::string(ENDATSIM_SOURCE_DIR) +
                                                      "/scenarios/field/02_delay_measured_at_the_wrong_clock.json");
  const fs::path vcd = temp("measurements_may_precede.vcd");
  scenarios::RunOptions options;
  options.vcd_path = vcd.string();
  scenarios::run_scenario(scenario, options);
  scenarios::CaptureCheckOptions o;
  o.file = vcd.string();
  o.clock = "master_clock";
  o.data = "master_data";
  o.at = scenarios::CaptureCheckOptions::At::Master;
  o.cable_m = scenario.line.cable_length_m;
  o.encoder = scenarios::declared_encoder(scenario.encoder);
  const auto r = scenarios::check_capture(o);
  const auto row = std::find_if(r.conformance.begin(), r.conformance.end(),
                                [](const auto& c) { return c.check == checker::check::kMeasurementSpread; });
  ASSERT_NE(row, r.conformance.end());
  EXPECT_EQ(row->status, checker::RowConformance::Status::NotObservable);
  EXPECT_NE(row->reason.find("the measurements may precede it"), std::string::npos) << row->reason;
  fs::remove(vcd);
}

// A disturbance at the encoder's connector that inverts DATA from one rising edge to the next
// (one period, as a bit_flip event lays it) covers the middle of that bit's data-valid window:
// the bit is decoded inverted, and the CRC (appendix A4) fails, although the line is back at its
// true level as the next edge comes.
TEST(CheckCapture, ADisturbanceEndingAsTheNextClockRisesIsDecodedInTheBitItCovers) {
  const auto scenario = scenarios::load_scenario_text(R"({
    "name": "flip", "seed": 1, "line": { "cable_length_m": 20 },
    "encoder": { "version": "2.2", "position_bits": 25, "motion": { "start": 104462 } },
    "master": { "f_c": "4 MHz", "t_st": "2 us", "position_bits": 25, "delay_compensation": true,
                "delay_measurement": { "f_c": "200 kHz", "count": 3 } },
    "script": [ { "op": "measure_delay" },
                { "op": "read_position", "command": "encoder_send_position_values", "count": 3, "cycle": "50 us" } ],
    "events": [ { "frame": 4, "clock": 33, "bit_flip": { "wire": "data", "end": "encoder" } } ] })",
                                                      "flip.json");
  const fs::path vcd = temp("flip.vcd");
  run_to_vcd(scenario, vcd);
  const auto r = scenarios::check_capture(encoder_pins_of(scenario, vcd));
  fs::remove(vcd);
  ASSERT_EQ(r.frames.size(), 6U);
  for (std::size_t i = 0; i < r.frames.size(); ++i) {
    const auto& f = r.frames[i];
    ASSERT_TRUE(f.answer_complete) << scenarios::frame_log_line(f);
    EXPECT_EQ(f.crc_ok, i != 4) << scenarios::frame_log_line(f);
  }
  // The flip at the master's 33rd rising edge reaches the encoder's connector at its RE34, which
  // carries position bit 18 (start bit RE13, F1, F2, then the position LSB first).
  EXPECT_EQ(r.frames[4].fields[static_cast<std::size_t>(protocol::Field::Position)], 104462U ^ (1U << 18));
}

// A file's bytes quoted in a message are shown as \xNN where they are not UTF-8: the message stays
// readable, and the JSON and JUnit results of every capture are still written (a capture from
// another tool may hold any bytes, in its names too).
TEST(CheckCommand, BytesThatAreNotUtf8AreShownEscapedAndEveryReportIsStillWritten) {
  const fs::path garbage = temp("garbage.vcd"), latin1 = temp("latin1.csv"), json = temp("bytes.json"),
                 junit = temp("bytes.xml"), good = temp("good.vcd");
  std::ofstream(garbage) << "\xff\xfe$garbage\x01";
  std::ofstream(latin1) << "Time [s],D\xe9,CLK\n0,1,1\n1e-6,0,1\n";
  const auto scenario = scenarios::load_scenario_file(std::string(ENDATSIM_SOURCE_DIR) +
                                                      "/scenarios/bundled/endat21_1mhz_10m.json");
  run_to_vcd(scenario, good);
  auto r = cli("check '" + garbage.string() + "' '" + good.string() +
               "' --clock encoder_clock --data encoder_data --json '" + json.string() + "' --junit '" + junit.string() +
               "'");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("(got '\\xFF\\xFE$garbage\\x01')"), std::string::npos) << r.err;
  const auto j = nlohmann::json::parse(slurp_file(json));  // throws if not UTF-8
  ASSERT_EQ(j.at("captures").size(), 2U);
  EXPECT_NE(j.at("captures")[0].at("error").get<std::string>().find("\\xFF\\xFE"), std::string::npos);
  EXPECT_FALSE(j.at("captures")[1].contains("error"));
  const std::string xml = slurp_file(junit);
  EXPECT_NE(xml.find("\\xFF\\xFE"), std::string::npos);
  EXPECT_EQ(xml.find('\xff'), std::string::npos) << "raw bytes in the XML";
  r = cli("check '" + latin1.string() + "' --clock CLK --data D");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("the capture has: D\\xE9, CLK"), std::string::npos) << r.err;
  for (const auto& p : {garbage, latin1, json, junit, good}) fs::remove(p);
}

namespace {

// The encoder pins of a VCD rewritten with CLOCK unknown from time 0 until `known_at` (an RTL
// master in reset), and unknown once more for 1 ns at `x_at`, if given.
void with_unknown_clock(const fs::path& from, const fs::path& to, Time known_at, std::optional<Time> x_at) {
  auto changes = encoder_pin_changes(from);
  std::erase_if(changes, [&](const auto& c) { return std::get<1>(c) == 0 && std::get<0>(c) < known_at.count(); });
  changes.emplace_back(0, 0, 'x');
  changes.emplace_back(known_at.count(), 0, '1');
  if (x_at) {
    changes.emplace_back(x_at->count(), 0, 'x');
    changes.emplace_back((*x_at + sim::ns(1)).count(), 0, '1');
  }
  write_encoder_pins(to, "1 ps", changes);
}

}  // namespace

// A simulation whose master holds CLOCK at X until its reset ends starts at rest when CLOCK first
// goes HIGH: its first frame is judged, however soon it follows. An X on CLOCK later is named.
TEST(CheckCapture, AClockUnknownFromTimeZeroStartsAtRestAndALaterUnknownIsNamed) {
  const auto s = scenarios::load_scenario_file(std::string(ENDATSIM_SOURCE_DIR) + "/scenarios/bundled/endat21_1mhz_10m.json");
  const fs::path vcd = temp("x_exact.vcd"), xvcd = temp("x_start.vcd");
  run_to_vcd(s, vcd);
  auto o = encoder_pins_of(s, vcd);
  const auto exact = scenarios::check_capture(o);
  ASSERT_FALSE(exact.frames.empty());
  const Time fe1 = exact.frames.front().fe1;
  ASSERT_GT(fe1, sim::ns(50));
  // CLOCK known only 50 ns before the first FE1, far less than t_m.
  with_unknown_clock(vcd, xvcd, fe1 - sim::ns(50), std::nullopt);
  o.file = xvcd.string();
  auto r = scenarios::check_capture(o);
  EXPECT_EQ(r.edges_before_first_frame, 0U);
  EXPECT_EQ(r.frames_decoded, exact.frames_decoded);
  EXPECT_EQ(r.clock_unknown, 0U) << "the X before the first level is the reset's";
  // X for 1 ns inside the first frame's answer: read as the level before, and named.
  const Time inside = exact.frames.front().last_rise - sim::ns(200);
  with_unknown_clock(vcd, xvcd, fe1 - sim::ns(50), inside);
  r = scenarios::check_capture(o);
  EXPECT_EQ(r.clock_unknown, 1U);
  EXPECT_EQ(r.clock_unknown_first, inside);
  std::ostringstream summary;
  scenarios::write_capture_summary(summary, r, false);
  EXPECT_NE(summary.str().find("CLOCK unknown (x) 1 time(s) after it had a level, first at " + sim::format_time(inside)),
            std::string::npos)
      << summary.str();
  fs::remove(vcd);
  fs::remove(xvcd);
}
