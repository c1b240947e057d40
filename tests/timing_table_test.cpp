// The timing table (protocol/timing.hpp) against the numbers of D297403 2.3.2 and the sections
// around it, and the places generated from it: the checker's list of check names, the scenario
// schema's enum of check names, docs/checks.md.
#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "endatsim/checker/timing_checker.hpp"
#include "endatsim/protocol/crc.hpp"
#include "endatsim/protocol/mode_command.hpp"
#include "endatsim/protocol/timing.hpp"
#include "endatsim/scenarios/decoder_tables.hpp"
#include "endatsim/scenarios/scenario.hpp"

namespace {

using namespace endatsim;
namespace limit = protocol::limit;
namespace position = protocol::frame_position;

std::string slurp(const std::string& relative) {
  std::ifstream in(std::string(ENDATSIM_SOURCE_DIR) + "/" + relative, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(TimingTable, LimitsAreTheSpecsNumbers) {
  // Table 2.3.2.
  EXPECT_EQ(limit::kFcMin, 100'000);
  EXPECT_EQ(limit::kFcMaxWithoutCompensation, 2'000'000);
  EXPECT_EQ(limit::kFcMaxWithCompensation, 8'000'000);
  EXPECT_EQ(limit::kCalculationTimeMax, sim::parse_duration("1 ms"));
  EXPECT_EQ(limit::kMemoryAccessMax, sim::parse_duration("12 ms"));
  EXPECT_EQ(limit::kRecoveryTimeMin, sim::parse_duration("10 us"));
  EXPECT_EQ(limit::kRecoveryTimeMax, sim::parse_duration("30 us"));
  EXPECT_EQ(limit::kShortRecoveryTimeMin, sim::parse_duration("1.25 us"));
  EXPECT_EQ(limit::kShortRecoveryTimeMax, sim::parse_duration("3.75 us"));
  EXPECT_EQ(limit::kShortRecoveryTimeFcMin, 1'000'000);
  EXPECT_EQ(limit::kRecoveryTime2Min, sim::parse_duration("500 ns"));
  EXPECT_EQ(limit::kStartDelay, sim::parse_duration("2 us"));
  EXPECT_EQ(limit::kPulseWidthMin, sim::parse_duration("0.2 us"));
  EXPECT_EQ(limit::kPulseHighMax, sim::parse_duration("10 us"));
  EXPECT_EQ(limit::kOnOffRatioErrorPercent, 10U);
  EXPECT_EQ(limit::kPeriodAtFcMin, sim::period_of(limit::kFcMin));  // note 6: T = 1/f_c min
  EXPECT_EQ(limit::kTimeBetweenCyclesMin, sim::parse_duration("1 ms"));
  // 2.1.2.
  EXPECT_EQ(limit::kFcMaxSpecial, 16'000'000);
  EXPECT_EQ(limit::kMeasurementFcMin, 100'000);
  EXPECT_EQ(limit::kMeasurementFcMax, 200'000);
  EXPECT_EQ(limit::kMeasurementsMin, 3U);
  EXPECT_EQ(limit::kMeasurementCounterFactor, 8U);
  // 2.3: the set data delay time within +/-10 % x f_c; 2.3.1.1: at most 7 LOW bits.
  EXPECT_EQ(limit::kDataDelayTolerancePercent, 10U);
  EXPECT_EQ(limit::kContinuousClockMaxLowBits, 7U);
  // A2: the maximum t_m after an error handling.
  EXPECT_EQ(limit::kErrorRecoveryWait, limit::kRecoveryTimeMax);
  // 2.3.3 power-on.
  EXPECT_EQ(limit::kPowerOnT1Min, sim::parse_duration("800 ms"));
  EXPECT_EQ(limit::kPowerOnT2Min, sim::parse_duration("80 ms"));
  EXPECT_EQ(limit::kPowerOnT2Max, sim::parse_duration("120 ms"));
  EXPECT_EQ(limit::kPowerOnPulseMin, sim::parse_duration("125 ns"));
  EXPECT_EQ(limit::kPowerOnT3Min, sim::parse_duration("380 ms"));
  EXPECT_EQ(limit::kPowerOnT3Max, sim::parse_duration("420 ms"));
}

// 2.3.2 t_D maximum (0.2 + L x 0.01) us.
TEST(TimingTable, DataDelayMaximumFollowsTheCableLength) {
  EXPECT_EQ(limit::data_delay_max(0), sim::parse_duration("0.2 us"));
  EXPECT_EQ(limit::data_delay_max(100), sim::parse_duration("1.2 us"));
  EXPECT_EQ(limit::data_delay_max(0.5), sim::parse_duration("205 ns"));
  EXPECT_EQ(limit::data_delay_max(300), sim::parse_duration("3.2 us"));
}

// 2.3.2 note 8: 2 us for 2 .. 8 MHz, 1 us at 16 MHz, linear in between.
TEST(TimingTable, StartDelayIsLinearBetweenEightAndSixteenMegahertz) {
  EXPECT_EQ(limit::start_delay(sim::MHz(2)), sim::us(2));
  EXPECT_EQ(limit::start_delay(sim::MHz(8)), sim::us(2));
  EXPECT_EQ(limit::start_delay(sim::MHz(12)), sim::parse_duration("1.5 us"));
  EXPECT_EQ(limit::start_delay(sim::MHz(16)), sim::us(1));
  EXPECT_EQ(limit::start_delay(sim::MHz(8) + 8), sim::us(2) - sim::ps(1));
}

// 2.3: mode bits on RE3..RE8 after the dummy bit of FE2, turnaround at FE9; t_cal min 10.5/f_c
// ends on RE11 with a half-period first LOW phase.
TEST(TimingTable, FramePositionsCountFromTheFirstFallingEdge) {
  EXPECT_EQ(position::kFrameStart, 1U);
  EXPECT_EQ(position::kMasterDrives, 2U);
  EXPECT_EQ(position::kFirstModeBit, 3U);
  EXPECT_EQ(position::kLastModeBit, 8U);
  EXPECT_EQ(position::kModeBits, 6U);
  EXPECT_EQ(position::kTurnaround, 9U);
  const double t_cal_min_periods = 10.5;
  EXPECT_EQ(static_cast<double>(position::kEarliestStartBit) - 0.5, t_cal_min_periods);
}

// The rows' conditions name frame positions in words; they are the positions protocol/ counts with.
TEST(TimingTable, ConditionsNameTheFramePositionsOfTheProtocol) {
  const auto condition = [](std::string_view check) { return std::string(protocol::timing_row(check)->condition); };
  const auto re = [](unsigned k) { return "RE" + std::to_string(k); };
  const auto fe = [](unsigned k) { return "FE" + std::to_string(k); };
  EXPECT_NE(condition(checker::check::kCalculationTime).find("start bit on " + re(position::kEarliestStartBit)),
            std::string::npos);
  EXPECT_NE(condition(checker::check::kDriverOn)
                .find(fe(position::kTurnaround) + " (" + fe(position::kTurnaround + protocol::kPayloadBits) +
                      " after a 2.1 payload)"),
            std::string::npos);
  EXPECT_NE(condition(checker::check::kFloatingData).find(re(position::kFirstModeBit) + ".." + re(position::kLastModeBit)),
            std::string::npos);
  EXPECT_NE(condition(checker::check::kDriverOff).find(fe(position::kFrameStart)), std::string::npos);
}

TEST(TimingTable, OneRowPerCheckNameWithItsSection) {
  std::set<std::string_view> names;
  for (const auto& row : protocol::timing_rows()) {
    EXPECT_TRUE(names.insert(row.check).second) << "two rows for " << row.check;
    EXPECT_FALSE(row.section.empty()) << row.check;
    EXPECT_FALSE(row.designation.empty()) << row.check;
    EXPECT_FALSE(row.observed.empty()) << row.check;
    ASSERT_TRUE(protocol::timing_row(row.check).has_value());
    EXPECT_EQ(protocol::timing_row(row.check)->symbol, row.symbol);
  }
  EXPECT_FALSE(protocol::timing_row("t_nothing").has_value());
  const auto all = checker::check::all();
  EXPECT_EQ(std::set<std::string_view>(all.begin(), all.end()), names);
  EXPECT_EQ(protocol::timing_row(checker::check::kStartDelay)->section, "2.3.2 note 8");
}

TEST(TimingTable, SchemaListsExactlyTheCheckNames) {
  const auto schema = nlohmann::json::parse(slurp("schema/scenario.schema.json"));
  std::set<std::string> in_schema;
  const std::function<void(const nlohmann::json&)> find = [&](const nlohmann::json& j) {
    if (j.is_object()) {
      if (j.contains("violations") && j["violations"].is_object() && j["violations"].contains("propertyNames"))
        for (const auto& n : j["violations"]["propertyNames"]["enum"]) in_schema.insert(n.get<std::string>());
      for (const auto& [key, value] : j.items()) find(value);
    } else if (j.is_array()) {
      for (const auto& value : j) find(value);
    }
  };
  find(schema);
  std::set<std::string> names;
  for (const auto& row : protocol::timing_rows()) names.insert(std::string(row.check));
  names.insert(std::string(scenarios::kAnyOtherCheck));  // expect.violations' "any other check", not a row
  EXPECT_EQ(in_schema, names);
}

TEST(TimingTable, DocsChecksIsTheGeneratedTable) {
  const std::string doc = slurp("docs/checks.md");
  const std::string table = protocol::timing_table_markdown();
  ASSERT_GE(doc.size(), table.size());
  EXPECT_EQ(doc.substr(doc.size() - table.size()), table)
      << "docs/checks.md is out of date: regenerate its table with `endatsim checks`";
}

// The sigrok decoder reads the tables from tools/sigrok/endat/tables.py: the file is what they
// generate, and the document carries the numbers and rows the decoder judges with.
TEST(TimingTable, SigrokDecoderTablesAreTheGeneratedModule) {
  EXPECT_EQ(slurp("tools/sigrok/endat/tables.py"), scenarios::decoder_tables_python())
      << "tools/sigrok/endat/tables.py is out of date: regenerate it with `endatsim checks --python`";
  const auto t = nlohmann::json::parse(scenarios::decoder_tables_json());
  EXPECT_EQ(t["limits"]["recovery_time_min_ps"].get<std::int64_t>(), limit::kRecoveryTimeMin.count());
  EXPECT_EQ(t["limits"]["fc_max_special_hz"].get<std::int64_t>(), limit::kFcMaxSpecial);
  EXPECT_EQ(t["frame_position"]["turnaround"].get<unsigned>(), position::kTurnaround);
  EXPECT_EQ(t["crc"]["polynomial"].get<unsigned>(), protocol::kCrcPolynomial);
  ASSERT_EQ(t["mode_commands"].size(), protocol::mode_commands().size());
  for (std::size_t i = 0; i < protocol::mode_commands().size(); ++i) {
    EXPECT_EQ(t["mode_commands"][i]["bits"].get<unsigned>(), protocol::mode_commands()[i].bits);
    EXPECT_EQ(t["mode_commands"][i]["key"].get<std::string>(), protocol::mode_commands()[i].key);
  }
  ASSERT_EQ(t["checks"].size(), protocol::timing_rows().size());
  for (std::size_t i = 0; i < protocol::timing_rows().size(); ++i)
    EXPECT_EQ(t["checks"][i]["check"].get<std::string>(), protocol::timing_rows()[i].check);
  // Additional data 2.4.2.2: 0x40 .. 0x5F select, 0x4F and 0x5F stop.
  EXPECT_EQ(t["additional_data"]["selecting_mrs"].size(), 32U);
  EXPECT_EQ(t["additional_data"]["selecting_mrs"].front().get<unsigned>(), 0x40U);
  EXPECT_EQ(t["additional_data"]["stop_mrs"]["2"].get<unsigned>(), 0x5FU);
  // The position's width is the decoder's to set: null in the layouts, 25 by default.
  EXPECT_TRUE(t["layouts"]["position_2_2"][3]["width"].is_null());
  EXPECT_EQ(t["decoder"]["position_bits"].get<unsigned>(), 25U);
}

}  // namespace
