// The master's safety functions: each pair in scenarios/safety/ holds a fault that the
// function catches. Switched on, the function reports it; the same scenario with the function
// off reports nothing; an encoder without faults gives no finding with every function on.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "endatsim/master/safety.hpp"
#include "endatsim/protocol/crc.hpp"
#include "endatsim/protocol/parameters.hpp"
#include "endatsim/slave/encoder_params.hpp"
#include "endatsim/scenarios/loader.hpp"
#include "endatsim/scenarios/runner.hpp"

using namespace endatsim;
namespace fs = std::filesystem;

namespace {

const fs::path kSafety = fs::path(ENDATSIM_SOURCE_DIR) / "scenarios" / "safety";

std::vector<fs::path> pairs() {
  std::vector<fs::path> v;
  for (const auto& e : fs::directory_iterator(kSafety))
    if (e.path().extension() == ".json" && !e.path().stem().string().ends_with("_off")) v.push_back(e.path());
  std::sort(v.begin(), v.end());
  return v;
}

// "03_crc_self_test" -> the function of that name.
master::SafetyFunction function_of(const fs::path& p) {
  const std::string name = p.stem().string().substr(3);
  for (auto f : master::kSafetyFunctions)
    if (master::to_string(f) == name) return f;
  ADD_FAILURE() << p << " names no safety function";
  return master::SafetyFunction::ErrorMessages;
}

void set(master::SafetyParams& p, master::SafetyFunction f, bool on) {
  using F = master::SafetyFunction;
  switch (f) {
    case F::ErrorMessages: p.error_messages = on; break;
    case F::PositionValue2: p.position_value_2 = on; break;
    case F::ForcedDynamicSampling: p.forced_dynamic_sampling = on; break;
    case F::CrcSelfTest: p.crc_self_test = on; break;
    case F::StartupPositions: p.startup_positions = on; break;
    case F::Checksums: p.checksums = on; break;
    case F::Acknowledgements: p.acknowledgements = on; break;
    case F::FollowingError: p.following_error = on; break;
    case F::CommandSet: p.command_set = on; break;
  }
}

std::size_t findings(const scenarios::Scenario& s, master::SafetyFunction f) {
  return scenarios::run_scenario(s).safety.count(f);
}

}  // namespace

TEST(SafetyLibrary, HoldsAPairForEverySafetyFunction) {
  std::vector<master::SafetyFunction> covered;
  for (const auto& p : pairs()) {
    covered.push_back(function_of(p));
    EXPECT_TRUE(fs::exists(kSafety / (p.stem().string() + "_off.json"))) << p << ": no variant with the function off";
  }
  for (auto f : master::kSafetyFunctions)
    EXPECT_NE(std::find(covered.begin(), covered.end(), f), covered.end()) << master::to_string(f) << " has no scenario";
}

class SafetyPair : public ::testing::TestWithParam<fs::path> {};

TEST_P(SafetyPair, TheFunctionCatchesTheFaultAndMissesItWhenSwitchedOff) {
  const auto f = function_of(GetParam());
  auto on = scenarios::load_scenario_file(GetParam().string());
  ASSERT_TRUE(on.master.safety.enabled(f));
  EXPECT_GE(findings(on, f), 1U) << "the function did not catch the fault";
  set(on.master.safety, f, false);
  EXPECT_EQ(findings(on, f), 0U) << "switched off, the function still reports";

  auto off = scenarios::load_scenario_file((kSafety / (GetParam().stem().string() + "_off.json")).string());
  EXPECT_FALSE(off.master.safety.enabled(f));
  set(off.master.safety, f, true);
  EXPECT_GE(findings(off, f), 1U) << "the _off variant holds no fault the function would catch";
}

INSTANTIATE_TEST_SUITE_P(Library, SafetyPair, ::testing::ValuesIn(pairs()), [](const auto& param_info) {
  std::string name = param_info.param.stem().string();
  std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
  return name;
});

TEST(SafetyFunctions, AFaultlessEncoderGivesNoFindingWithEveryFunctionOn) {
  auto s = scenarios::load_scenario_file((kSafety / "08_position_value_2.json").string());
  s.events.clear();
  s.encoder.communication_command_permitted = false;  // 2.3: no encoder for safety declares it
  for (auto f : master::kSafetyFunctions) set(s.master.safety, f, true);
  const auto r = scenarios::run_scenario(s);
  for (const auto& x : r.safety.findings) ADD_FAILURE() << master::to_string(x.function) << ": " << x.message;
  EXPECT_TRUE(r.safety.axis_released);
  EXPECT_EQ(r.release_position_correct, true);
  EXPECT_GE(r.safety.position_comparisons, 30U);
  EXPECT_EQ(r.undetected_errors, 0U);
  ASSERT_TRUE(r.safety.checksum63_stored.has_value());
  EXPECT_EQ(*r.safety.checksum63_stored, *r.safety.checksum63_computed);
}

// 2.3: only an encoder that declares the communication command is refused; one whose word 37
// does not (3.5.22 bits 4/5 stored inversely as "not supported") is released.
TEST(SafetyFunctions, CommandSetReleasesAnEncoderWithoutTheCommunicationCommand) {
  auto s = scenarios::load_scenario_file((kSafety / "09_command_set.json").string());
  s.encoder.communication_command_permitted = false;
  s.expect = {};
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(r.safety.count(master::SafetyFunction::CommandSet), 0U);
  EXPECT_TRUE(r.safety.axis_released);
  s.encoder.communication_command_permitted = true;
  const auto refused = scenarios::run_scenario(s);
  ASSERT_EQ(refused.safety.count(master::SafetyFunction::CommandSet), 1U);
  EXPECT_FALSE(refused.safety.axis_released);
  EXPECT_NE(refused.safety.findings.front().message.find("must not be used for safety-oriented applications (2.3)"),
            std::string::npos);
}

TEST(SafetyFunctions, ErrorMessagesReadWordZeroAfterTheErrorAppears) {
  const auto r = scenarios::run_scenario(
      scenarios::load_scenario_file((kSafety / "01_error_messages.json").string()));
  ASSERT_TRUE(r.safety.error_sources.has_value());
  EXPECT_EQ(*r.safety.error_sources, 0x0001) << "3.4.1: bit 0, lighting";
  EXPECT_EQ(protocol::parameters::bits_string(*r.safety.error_sources, protocol::parameters::error_bit_names()), "lighting");
}

TEST(SafetyFunctions, CrcKnownResultsAreTheSpecsAlgorithm) {
  for (const auto& v : master::crc_known_results())
    EXPECT_EQ(protocol::make_crc_pos(v.bits, v.error1, v.error2, v.endat22, v.position), v.crc) << v.bits << " bits";
  EXPECT_EQ(master::crc_known_results()[0].crc, 3) << "A4: 25 bits, position 104462 -> CRC 3";
}

// 3.5.19 example: linear, 120 m/min (word 32), c1 = 40 -> 3 m/min, a1 = +-16 LSB; word 33 = 2810h.
TEST(Position2Parameters, DecodeTheSpecsAccuracyExampleFromEnDat21Words) {
  std::vector<std::uint16_t> m(48, 0), e(64, 0);
  m[14] = 0x4001;  // absolute linear encoder (3.5.7)
  m[20] = 100;     // 100 nm (3.5.12)
  m[32] = 120;
  m[33] = 0x2810;
  m[34] = 0x0140;  // c2 = 1 (120 m/min), a2 = 64 LSB
  const auto p = master::position2_parameters(m, e);
  ASSERT_EQ(p.ranges.size(), 2U);
  EXPECT_EQ(p.ranges[0].conversion_factor, 40U);
  EXPECT_EQ(p.ranges[0].accuracy, 16U);
  // 3 m/min at 100 nm steps = 500 000 steps/s: still range 1; just above: range 2.
  EXPECT_EQ(p.accuracy_at(500'000), 16U);
  EXPECT_EQ(p.accuracy_at(500'001), 64U);
  EXPECT_EQ(p.accuracy_at(20'000'001), std::nullopt) << "above 120 m/min nothing is stated";
}

// 3.9.11 example: word 11 = 0028h (c1 = 40, x1), word 12 = 0010h (a1 = 16); 3.5.19: 65535 in
// words 33 and 34 points there. Bits 15..13 scale: 001 = x2.
TEST(Position2Parameters, DecodeEnDat22WordsWithTheirScalingFactor) {
  std::vector<std::uint16_t> m(48, 0), e(64, 0);
  m[14] = 0xC001;  // singleturn rotary
  m[20] = 0x0000;
  m[21] = 0x0200;  // 2^25 steps per revolution
  m[32] = 12000;
  m[33] = m[34] = 0xFFFF;
  e[11] = 0x0028;
  e[12] = 0x0010;
  e[13] = 0x2001;  // c2 = 1 x 2
  e[14] = 0x2020;  // a2 = 32 x 2
  e[16] = 1;
  e[26] = 9;       // 3.9.20 example: 9 bits
  e[31] = 0xFFFF;  // offset -1 (48-bit two's complement, 3.9.24)
  e[32] = 0xFFFF;
  e[33] = 0xFFFF;
  const auto p = master::position2_parameters(m, e);
  ASSERT_EQ(p.ranges.size(), 2U);
  EXPECT_EQ(p.ranges[0].conversion_factor, 40U);
  EXPECT_EQ(p.ranges[0].accuracy, 16U);
  EXPECT_EQ(p.ranges[1].conversion_factor, 2U);
  EXPECT_EQ(p.ranges[1].accuracy, 64U);
  EXPECT_TRUE(p.reversed);
  EXPECT_EQ(p.comparison_bits, 9U);
  EXPECT_EQ(p.offset, -1);
  // 300 rpm = 12000 / 40 at 2^25 steps per revolution.
  const double steps_300_rpm = 300.0 / 60 * (1 << 25);
  EXPECT_EQ(p.accuracy_at(steps_300_rpm), 16U);
  EXPECT_EQ(p.accuracy_at(steps_300_rpm * 1.01), 64U);
}

TEST(SafetyParams, RejectsValuesOutsideTheirLimitsNamingThem) {
  master::SafetyParams p;
  p.startup_repetitions = 1;
  EXPECT_THROW(
      {
        try {
          p.validate();
        } catch (const std::invalid_argument& e) {
          EXPECT_NE(std::string(e.what()).find("startup_repetitions must be 2 .. 100"), std::string::npos) << e.what();
          throw;
        }
      },
      std::invalid_argument);
  p = {};
  p.forced_error2_port = p.forced_error1_port;
  EXPECT_THROW(p.validate(), std::invalid_argument);
}

// The master's set-point for the following error counts a moving axis as the encoder does
// (EncoderMotion.ANegativeVelocityCountsDownAtEachStepCrossed): a negative velocity crosses its
// first step at once, so the set-point between two steps is the lower one, not the one before.
TEST(SafetyFunctions, FollowingErrorSetpointCountsANegativeVelocityAsTheEncoderDoes) {
  using sim::ns, sim::ps, sim::Time, sim::us;
  const master::MotionSetpoint down{.start = 1000, .counts_per_s = -1'000'000};  // a step per microsecond
  slave::EncoderParams encoder;
  encoder.motion.start = down.start;
  encoder.motion.counts_per_s = down.counts_per_s;
  for (const Time t : {Time::zero(), ps(1), ns(500), us(1), us(1) + ps(1), us(2) + ns(1)}) {
    EXPECT_EQ(down.at(t, 25), encoder.position_at(t)) << t.count() << " ps";
  }
  EXPECT_EQ(down.at(ns(500), 25), 999U);
  const master::MotionSetpoint wrap{.start = 0, .counts_per_s = -1'000'000};
  EXPECT_EQ(wrap.at(ns(500), 25), (1U << 25) - 1) << "below zero the count wraps to the top of the range";
}
