// JUnit XML, the decoded transaction log and frame diagrams, from real runs of bundled scenarios.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <vector>

#include "endatsim/scenarios/diagram.hpp"
#include "endatsim/scenarios/gtkw.hpp"
#include "endatsim/scenarios/junit.hpp"
#include "endatsim/scenarios/scenarios.hpp"
#include "endatsim/scenarios/transaction_log.hpp"

using namespace endatsim;

namespace {

const std::string kBundled = std::string(ENDATSIM_SOURCE_DIR) + "/scenarios/bundled/";

scenarios::ScenarioResult run_bundled(const std::string& name) {
  return scenarios::run_scenario(scenarios::load_scenario_file(kBundled + name + ".json"));
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto p = text.find(what); p != std::string::npos; p = text.find(what, p + what.size())) ++n;
  return n;
}

// A scenario whose expectation cannot hold: one clean read, expected two.
scenarios::ScenarioResult failing() {
  const auto s = scenarios::load_scenario_text(R"({"name": "wrong<&>", "line": {"cable_length_m": 1},
    "master": {"f_c": "1 MHz"}, "script": [{"op": "read_position"}], "expect": {"outcomes": {"ok": 2}}})",
                                               "inline.json");
  return scenarios::run_scenario(s);
}

}  // namespace

TEST(Junit, OneTestCasePerScenarioAndFailuresCarryTheExpectation) {
  const std::vector<scenarios::ScenarioResult> results{run_bundled("endat21_1mhz_10m"), failing()};
  const std::string xml = scenarios::junit_xml(results);
  EXPECT_EQ(xml.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"endatsim\" tests=\"2\" failures=\"1\"", 0), 0U)
      << xml;
  EXPECT_EQ(count(xml, "<testcase "), 2U);
  EXPECT_NE(xml.find("name=\"endat21_1mhz_10m\""), std::string::npos);
  EXPECT_EQ(count(xml, "<failure "), 1U);
  // The violated expectation, escaped, in the message; the name escaped too.
  EXPECT_NE(xml.find("<failure type=\"expectation\" message=\"outcomes.ok: 1 (expected 2)\">"), std::string::npos) << xml;
  EXPECT_NE(xml.find("name=\"wrong&lt;&amp;&gt;\""), std::string::npos) << xml;
  EXPECT_EQ(xml, scenarios::junit_xml(results));  // no clocks, no host names: same bytes
}

TEST(Junit, EscapesMarkupAndDropsControlCharacters) {
  EXPECT_EQ(scenarios::xml_escape("a<b>&\"c'\x01\n"), "a&lt;b&gt;&amp;&quot;c&apos;\n");
}

TEST(TransactionLog, OneRecordPerFrameWithCrcAndViolations) {
  const auto r = run_bundled("endat22_2mhz_100m_uncompensated");
  const std::string text = scenarios::transaction_log_text(r);
  EXPECT_EQ(count(text, "\n"), r.frames.size() + 2);  // a header line, one line per frame, the count
  EXPECT_TRUE(text.ends_with("\n# " + std::to_string(r.frames.size()) + " frames\n")) << text;
  const auto first = text.substr(text.find('\n') + 1, text.find('\n', text.find('\n') + 1) - text.find('\n') - 1);
  EXPECT_NE(first.find("encoder_send_position_values_with_additional_data"), std::string::npos) << first;
  EXPECT_NE(first.find("sent: mode_bits=111000 f_c=2 MHz"), std::string::npos) << first;
  EXPECT_NE(first.find("position=" + std::to_string(r.frames[0].position)), std::string::npos) << first;
  EXPECT_NE(first.find("CRC FAIL (expected " + std::to_string(r.frames[0].crc_expected) + ")"), std::string::npos) << first;
  EXPECT_NE(first.find("-> crc_error  violations:"), std::string::npos) << first;
  EXPECT_NE(first.find("sampling_window"), std::string::npos) << first;

  const std::string jsonl = scenarios::transaction_log_jsonl(r);
  std::istringstream in(jsonl);
  std::string line;
  std::size_t n = 0;
  while (std::getline(in, line)) {
    const auto j = nlohmann::json::parse(line);
    const auto& f = r.frames[n];
    EXPECT_EQ(j.at("frame").get<std::uint64_t>(), f.index);
    EXPECT_EQ(j.at("time_ps").get<std::int64_t>(), f.start.count());
    EXPECT_EQ(j.at("crc_ok"), false);
    EXPECT_EQ(j.at("received").at("position").get<std::uint64_t>(), f.position);
    EXPECT_TRUE(j.at("additional").is_object());
    EXPECT_FALSE(j.at("violations").empty());
    EXPECT_EQ(j.at("scenario"), "endat22_2mhz_100m_uncompensated");
    ++n;
  }
  EXPECT_EQ(n, r.frames.size());
}

TEST(TransactionLog, CleanReadsAndMeasurementFrames) {
  const auto r = run_bundled("endat22_2mhz_100m_compensated");
  const auto records = scenarios::transactions(r.frames, r.violations);
  ASSERT_EQ(records.size(), r.frames.size());
  std::size_t measurements = 0, ok = 0;
  for (std::size_t i = 0; i < records.size(); ++i) {
    const auto& t = records[i];
    if (r.frames[i].measurement) {
      ++measurements;
      EXPECT_TRUE(t["sent"]["delay_measurement"].get<bool>());
      EXPECT_TRUE(t["received"].contains("delay_count")) << t.dump();
    } else {
      ++ok;
      EXPECT_EQ(t["crc_ok"], true) << t.dump();
      EXPECT_EQ(t["sent"]["t_d"], sim::format_time(r.frames[i].t_d_used));
      EXPECT_NE(scenarios::transaction_line(scenarios::transaction_tokens(r.frames[i], r.violations)).find("CRC ok"),
                std::string::npos);
    }
    EXPECT_TRUE(t["violations"].empty()) << t.dump();
  }
  EXPECT_GE(measurements, 3U);
  EXPECT_EQ(ok, 10U);
}

TEST(TransactionLog, RecorderCollectsWhatTheMasterReports) {
  scenarios::TransactionRecorder recorder;
  master::FrameResult f;
  f.index = 7;
  f.outcome = master::FrameOutcome::NoStartBit;
  recorder.on_frame_start(f);
  recorder.on_frame_end(f);
  ASSERT_EQ(recorder.frames().size(), 1U);
  const auto t = scenarios::transaction_of(recorder.frames().front(), {});
  EXPECT_EQ(t["frame"], 7);
  EXPECT_TRUE(t["crc_ok"].is_null());
  EXPECT_EQ(t["outcome"], "no_start_bit");
}

TEST(Diagram, DrawsTheFrameWithMeasuredTimingAndViolations) {
  const auto s = scenarios::load_scenario_file(kBundled + "endat22_2mhz_100m_uncompensated.json");
  const auto d = scenarios::frame_diagram(s, {});
  EXPECT_EQ(d.svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0), 0U);
  // At the master's pins the round trip lacks the master's own driver and receiver (40 + 100 ns).
  EXPECT_NE(d.svg.find(">t_D on the wires = 1.06 us</text>"), std::string::npos);
  EXPECT_NE(d.svg.find(">t_ST = 2 us</text>"), std::string::npos);
  EXPECT_NE(d.svg.find(">t_m = 20.06 us</text>"), std::string::npos);
  EXPECT_NE(d.svg.find(">t_cal = "), std::string::npos);
  EXPECT_NE(d.svg.find(">mode bits 111000</text>"), std::string::npos);
  for (const char* field : {">S</text>", ">F1</text>", ">F2</text>", ">position (25 bits, LSB first)</text>"})
    EXPECT_NE(d.svg.find(field), std::string::npos) << field;
  // The checker's findings for frame 0, in red: f_c too fast for 100 m without compensation,
  // sampling_window, floating_data, clock_count.
  EXPECT_NE(d.svg.find("fill=\"#c00000\" font-size=\"11\">error sampling_window at 6.25 us"), std::string::npos);
  EXPECT_NE(d.svg.find("fill=\"#c00000\" font-size=\"11\">error f_c at "), std::string::npos);
  EXPECT_EQ(count(d.svg, "stroke=\"#c00000\" stroke-width=\"1.5\""), 4U);
  EXPECT_NE(d.caption.find("4 violations"), std::string::npos) << d.caption;
  EXPECT_EQ(d.svg, scenarios::frame_diagram(s, {}).svg);  // same input, same bytes
}

TEST(Diagram, CleanCompensatedFrameHasTheCrcAndNoRed) {
  const auto s = scenarios::load_scenario_file(kBundled + "endat22_8mhz_100m_compensated.json");
  const auto d = scenarios::frame_diagram(s, {});
  EXPECT_NE(d.svg.find(">t_D on the wires = 1.06 us</text>"), std::string::npos);  // 8 MHz: t_D is 8.5 periods
  EXPECT_NE(d.svg.find(">CRC"), std::string::npos);  // "CRC (5 bits)" or, when narrow, "CRC"
  EXPECT_EQ(d.svg.find("#c00000\" font-size"), std::string::npos);
}

TEST(Diagram, WindowsAndBadRequests) {
  const auto s = scenarios::load_scenario_file(kBundled + "endat21_1mhz_10m.json");
  scenarios::DiagramOptions o;
  o.window = std::make_pair(sim::us(0), sim::us(60));
  const auto d = scenarios::frame_diagram(s, o);
  EXPECT_NE(d.caption.find("0 ps .. 60 us"), std::string::npos) << d.caption;
  o.window.reset();
  o.frame = 999;
  try {
    scenarios::frame_diagram(s, o);
    FAIL() << "frame 999 was drawn";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("frame 999: the run has 5 frames (0 .. 4)"), std::string::npos) << e.what();
  }
}

TEST(TransactionLog, DecodesDiagnosisValues) {
  master::FrameResult f;
  f.command = protocol::ModeCommand::EncoderSendPositionValuesWithAdditionalData;
  f.outcome = master::FrameOutcome::Ok;
  f.additional_data = {{static_cast<std::uint8_t>(protocol::Information::Temperature2), 3831, true},
                       {static_cast<std::uint8_t>(protocol::Information::Diagnosis), 0x0314, true},
                       {static_cast<std::uint8_t>(protocol::Information::AdditionalSensors), 0x1902, true}};
  const auto t = scenarios::transactions({f}, {});
  ASSERT_EQ(t.size(), 1U);
  EXPECT_EQ(t[0]["additional"]["temperature_2.decoded"], "110.0degC");
  EXPECT_EQ(t[0]["additional"]["diagnosis.decoded"], "3:20");
  EXPECT_EQ(t[0]["additional"]["additional_sensors.decoded"], "1:72.5degC");
}

TEST(TransactionLog, ParameterFramesAndAdditionalDataAreFields) {
  const auto params = run_bundled("parameters_endat21_write_read");
  bool parameter_frame = false;
  for (auto t : scenarios::transactions(params.frames, params.violations)) {
    if (t["command"] != "encoder_receive_parameters" || t["crc_ok"] != true) continue;
    parameter_frame = true;
    EXPECT_TRUE(t["sent"].contains("address")) << t.dump();
    EXPECT_EQ(t["received"]["address"], t["sent"]["address"]) << t.dump();  // the encoder echoes the address
    EXPECT_FALSE(t["received"].contains("position")) << t.dump();
  }
  EXPECT_TRUE(parameter_frame);

  const auto additional = run_bundled("additional_data_rolling_selection");
  std::size_t with_data = 0;
  for (const auto& f : additional.frames) {
    const auto t = scenarios::transaction_of(f, additional.violations);
    EXPECT_EQ(t["additional"].size() > 0, !f.additional_data.empty() && t["crc_ok"].is_boolean()) << t.dump();
    if (f.additional_data.empty()) continue;
    ++with_data;
    const std::string key(protocol::info(f.additional_data.front().information()).key);
    ASSERT_TRUE(t["additional"].contains(key)) << t.dump();
    EXPECT_NE(scenarios::transaction_line(scenarios::transaction_tokens(f, additional.violations)).find("additional: " + key + "="),
              std::string::npos);
  }
  EXPECT_GT(with_data, 0U);
}

TEST(Diagram, ParameterFrameShowsThePayloadAndBreaksTheMemoryAccessWait) {
  const auto s = scenarios::load_scenario_file(kBundled + "parameters_endat21_write_read.json");
  scenarios::DiagramOptions o;
  o.frame = 1;  // encoder_receive_parameters: address 0x0B, 0xA5B4, then about 2 ms of polling
  const auto d = scenarios::frame_diagram(s, o);
  EXPECT_NE(d.svg.find(">address 0x0B</text>"), std::string::npos);
  EXPECT_NE(d.svg.find(">parameter 0xA5B4</text>"), std::string::npos);
  EXPECT_NE(d.svg.find(">S</text>"), std::string::npos);
  EXPECT_EQ(d.svg.find(">position"), std::string::npos);  // the answer is an echo, not a position
  // The polling while the encoder writes its memory is one axis break of about 2 ms.
  EXPECT_NE(d.svg.find(">// 1.99"), std::string::npos) << d.caption;
}

// What a frame carries besides the position: each additional datum with its Busy bit, the
// command supplement, and the clock numbers that violations cite.
TEST(Diagram, LabelsAdditionalDataTheBusyBitTheSupplementAndNumbersTheClocks) {
  const auto s = scenarios::load_scenario_file(kBundled + "additional_data_rolling_selection.json");
  scenarios::DiagramOptions o;
  o.frame = 5;
  const auto d = scenarios::frame_diagram(s, o);
  EXPECT_NE(d.svg.find(">additional data 1: temperature_1</text>"), std::string::npos);
  EXPECT_EQ(count(d.svg, "additional data 2: operating_status_error_sources") + count(d.svg, ">AD2</text>"), 1U);
  EXPECT_EQ(count(d.svg, ">Busy 0</text>") + count(d.svg, ">B0</text>"), 2U);  // one per datum
  EXPECT_NE(d.svg.find("supplement"), std::string::npos);
  for (const char* n : {">1</text>", ">10</text>", ">20</text>"})  // crowded: every fifth
    EXPECT_NE(d.svg.find(std::string("fill=\"#666\" font-size=\"8\"") + n), std::string::npos) << n;
}

// The subtitle says whether the master compensates, also for a time window, and never calls
// the compensation value and the wires' delay by one name.
TEST(Diagram, TheSubtitleNamesTheCompensationInWindowsToo) {
  const auto s = scenarios::load_scenario_file(kBundled + "endat22_8mhz_100m_compensated.json");
  EXPECT_NE(scenarios::frame_diagram(s, {}).svg.find("compensating with the measured t_D "), std::string::npos);
  scenarios::DiagramOptions o;
  o.window = std::make_pair(sim::us(700), sim::us(760));
  const auto window = scenarios::frame_diagram(s, o).svg;
  EXPECT_NE(window.find("delay compensation on"), std::string::npos);
  EXPECT_EQ(window.find("no delay compensation"), std::string::npos);
}

// The GTKWave save file: opens on the first frame that is not a delay measurement, named markers
// at the violations in time order, and a scenario name from a file cannot break its lines.
TEST(Gtkw, OpensOnTheFirstFrameWithMarkersAtTheViolations) {
  auto r = run_bundled("endat22_2mhz_100m_uncompensated");
  const auto& first = r.frames.front();  // no delay measurement in this scenario
  const auto length = first.end - first.start;
  auto text = scenarios::gtkw_save_file(r, "/tmp/w.vcd");
  EXPECT_NE(text.find("[timestart] " + std::to_string(std::max<std::int64_t>(0, (first.start - length / 10).count())) + "\n"),
            std::string::npos) << text;
  std::vector<std::int64_t> times;
  for (const auto& v : r.violations) times.push_back(v.time.count());
  std::sort(times.begin(), times.end());
  EXPECT_NE(text.find("\n*-"), std::string::npos);
  EXPECT_NE(text.find(" " + std::to_string(first.start.count()) + " " + std::to_string(times.front()) + " "),
            std::string::npos) << text;
  EXPECT_NE(text.find("endat.decoded\n"), std::string::npos);
  r.name = "two\nlines";
  text = scenarios::gtkw_save_file(r, "/tmp/w.vcd");
  EXPECT_EQ(text.rfind("[*] endatsim two lines\n", 0), 0U) << text;
}
