// Diagnosis (appendix A3, 2.3.5.1, 3.4.2, 3.6.3, 3.6.6, 3.9.6, 3.9.7, 3.9.16): the
// spec's scaling examples, the encoder's temperature warning and the master's collection.
#include <gtest/gtest.h>

#include <algorithm>

#include "endatsim/master/diagnostics.hpp"
#include "endatsim/protocol/diagnosis.hpp"
#include "scenario_support.hpp"
#include "endatsim/scenarios/loader.hpp"
#include "endatsim/slave/encoder.hpp"

using namespace endatsim;
namespace dg = protocol::diagnosis;
using master::DiagnosisNoteKind;
using protocol::MemoryArea;
using protocol::ModeCommand;

namespace {

// An EnDat 2.2 encoder read cyclically with additional data; the master's diagnosis on.
scenarios::Scenario diagnosis_scenario(unsigned reads = 120) {
  auto s = test_support::make_scenario(10, sim::MHz(1), false, reads);
  s.master.diagnostics.enabled = true;
  master::Operation setup;
  setup.kind = master::Operation::Kind::DiagnosisSetup;
  s.script.insert(s.script.begin(), setup);
  return s;
}

// The default image with a word of the 2.2 area changed and word 63 made valid again (3.9.37).
slave::MemoryImage with_endat22_word(const slave::EncoderParams& p, unsigned w, std::uint16_t value) {
  auto image = slave::default_memory_image(p);
  auto& e = image.areas.at(MemoryArea::ManufacturerEndat22);
  e.at(w) = value;
  e[slave::word::kEndat22Checksum] = protocol::parameters::endat22_checksum(e);
  return image;
}

std::size_t frames_with(const scenarios::ScenarioResult& r, ModeCommand c) {
  return static_cast<std::size_t>(std::count_if(r.frames.begin(), r.frames.end(), [c](const auto& f) { return f.command == c; }));
}

std::uint16_t warnings_at_end(const scenarios::ScenarioResult& r) {
  return r.encoder_memory.areas.at(MemoryArea::OperatingStatus)[slave::word::kWarnings];
}

}  // namespace

// ---- the spec's values ------------------------------------------------------------------------

TEST(TemperatureScaling, ReproducesTheExamplesOfWords6And22) {
  // 3.6.6: 110 degC = 383.1 K = 3831 = EF7h; 3.9.16: 115 degC = 388.1 K = 3881 = F29h.
  EXPECT_EQ(dg::tenth_kelvin_of_celsius(110.0), 0xEF7);
  EXPECT_EQ(dg::tenth_kelvin_of_celsius(115.0), 0xF29);
  EXPECT_DOUBLE_EQ(dg::celsius(0xEF7), 110.0);
  EXPECT_DOUBLE_EQ(dg::kelvin(0xEF7), 383.1);
  EXPECT_DOUBLE_EQ(dg::celsius(0xF29), 115.0);
  EXPECT_EQ(dg::temperature_string(3831), "110.0 degC (383.1 K)");
  EXPECT_EQ(dg::temperature_scaling(0x8000), 0.1) << "3.9.6 default 8000h: scaling 000b = 0.1";
  EXPECT_FALSE(dg::temperature_scaling(0x8003).has_value());
}

TEST(TemperatureScaling, AdditionalSensorsFollowTheTableOf396) {
  // 3.9.6: output 0 = 115.0 K, 1 = 115.1 K, 1580 = 273.0 K, 1581 = 273.1 K, 4094 = 524.4 K, 4095 = 524.5 K.
  for (const auto& [output, tenth_kelvin] : {std::pair{0U, 1150U}, {1U, 1151U}, {1580U, 2730U}, {1581U, 2731U},
                                            {4094U, 5244U}, {4095U, 5245U}}) {
    const auto v = dg::decode_additional_sensor(static_cast<std::uint16_t>(0x3000 | output));
    EXPECT_EQ(v.address, 3U);
    EXPECT_EQ(v.tenth_kelvin, tenth_kelvin) << "output " << output;
    EXPECT_EQ(dg::encode_additional_sensor(3, tenth_kelvin), 0x3000 | output);
  }
  EXPECT_EQ(dg::encode_additional_sensor(0, 1000), 0x0000) << "below 115 K: clamped";
  EXPECT_EQ(dg::encode_additional_sensor(0, 6000), 0x0FFF) << "above 524.5 K: clamped";
}

TEST(DiagnosisAddress, FollowsTheTableOfA3) {
  // A3: bit 0 <-> addresses 1, 17, 33, 49; bit 7 <-> 8, 24, 40, 56; bit 8 <-> 9, 25, 41, 57.
  for (unsigned k = 0; k < 4; ++k) {
    EXPECT_EQ(dg::decode_diagnosis_address(1 + 16 * k)->bit, 0U);
    EXPECT_EQ(dg::decode_diagnosis_address(1 + 16 * k)->area, k);
    EXPECT_EQ(dg::decode_diagnosis_address(8 + 16 * k)->bit, 7U);
    EXPECT_EQ(dg::decode_diagnosis_address(9 + 16 * k)->bit, 8U);
  }
  EXPECT_FALSE(dg::decode_diagnosis_address(0).has_value());
  EXPECT_FALSE(dg::decode_diagnosis_address(65).has_value());
}

TEST(TemperatureInScenarios, DegreesCelsiusUseThe2731OfSection396) {
  const auto s = scenarios::load_scenario_text(R"({"name": "t", "line": {"cable_length_m": 1},
      "encoder": {"sensors": {"temperature_1": "110 degC", "temperature_2": "383.1 K", "additional_sensors": [2982, "-0.5 degC"]}},
      "master": {"f_c": "1 MHz"}, "script": [{"op": "read_position"}]})", "t.json");
  EXPECT_EQ(s.encoder.sensors.temperature1, 3831);
  EXPECT_EQ(s.encoder.sensors.temperature2, 3831);
  EXPECT_EQ(s.encoder.sensors.additional_sensors, (std::vector<std::uint16_t>{2982, 2726}));
}

TEST(TemperatureInScenarios, OtherUnitsAreRejectedWithThePath) {
  try {
    scenarios::load_scenario_text(R"({"name": "t", "line": {"cable_length_m": 1},
        "encoder": {"sensors": {"temperature_2": "110 F"}}, "master": {"f_c": "1 MHz"}, "script": [{"op": "read_position"}]})",
                                  "t.json");
    FAIL() << "accepted";
  } catch (const scenarios::ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("t.json: at /encoder/sensors/temperature_2: expected a temperature"), std::string::npos)
        << e.what();
  }
}

TEST(DiagnosticsParams, RejectsConfigurationBitsThatAreNotValuationNumbers) {
  master::DiagnosticsParams p;
  p.configuration = 0x0040;
  try {
    p.validate();
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("bits 0 .. 5"), std::string::npos) << e.what();
  }
}

// ---- the encoder ------------------------------------------------------------------------------

TEST(DefaultImage, CarriesTheDiagnosisWords) {
  const slave::EncoderParams p;
  const auto image = slave::default_memory_image(p);
  const auto& e = image.areas.at(MemoryArea::ManufacturerEndat22);
  EXPECT_EQ(e[slave::word::kTemperatureScaling], 0x8000) << "3.9.6 default";
  EXPECT_EQ(e[slave::word::kDiagnosticStatus], 0x003F) << "3.9.7: valuation numbers 1 .. 6";
  EXPECT_EQ(e[slave::word::kMaxEncoderTemperature], 3881) << "3.9.16 example";
  EXPECT_EQ(image.areas.at(MemoryArea::OperatingParameters)[slave::word::kTemperatureWarningThreshold], 3831)
      << "3.6.6: word 22 minus a reserve";
  EXPECT_EQ(e[slave::word::kEndat22Checksum], protocol::parameters::endat22_checksum(e));
}

TEST(EncoderTemperatureWarning, Temperature2AboveWord6SetsWarningBit1AndWrn) {
  auto s = test_support::make_scenario(10, sim::MHz(1), false, 3);
  s.encoder.sensors.temperature2 = 3832;  // 110.1 degC
  s.script.insert(s.script.begin(), test_support::op(ModeCommand::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0x4D));
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(warnings_at_end(r) & 0x0002, 0x0002);
  ASSERT_FALSE(r.frames.back().additional_data.empty());
  EXPECT_NE(r.frames.back().additional_data.back().status & protocol::AdditionalDataStatus::kWarning, 0);
}

TEST(EncoderTemperatureWarning, AtTheThresholdNoWarning) {
  auto s = test_support::make_scenario(10, sim::MHz(1), false, 3);
  s.encoder.sensors.temperature2 = 3831;  // exactly 110.0 degC: not exceeded
  EXPECT_EQ(warnings_at_end(scenarios::run_scenario(s)) & 0x0002, 0);
}

TEST(EncoderTemperatureWarning, OnlyTheInternalSensorTriggersIt) {
  // 3.4.2: "only triggered by the internal temperature sensor (integrated in the encoder)".
  auto s = test_support::make_scenario(10, sim::MHz(1), false, 3);
  s.encoder.sensors.temperature1 = 4500;
  s.encoder.sensors.additional_sensors = {4500, 4500};
  EXPECT_EQ(warnings_at_end(scenarios::run_scenario(s)) & 0x0002, 0);
}

TEST(EncoderTemperatureWarning, Word6ZeroMeansNoThreshold) {
  auto s = test_support::make_scenario(10, sim::MHz(1), false, 3);
  s.encoder.sensors.temperature2 = 4500;
  s.encoder.memory = slave::default_memory_image(s.encoder);
  s.encoder.memory->areas[MemoryArea::OperatingParameters][slave::word::kTemperatureWarningThreshold] = 0;
  EXPECT_EQ(warnings_at_end(scenarios::run_scenario(s)) & 0x0002, 0);
}

// ---- the master -------------------------------------------------------------------------------

TEST(MasterDiagnosis, SetupActivatesWhatWord5SupportsThenResets) {
  auto s = diagnosis_scenario();
  s.encoder.memory = with_endat22_word(s.encoder, slave::word::kDiagnosticStatus, 0x0005);  // numbers 1 and 3
  s.encoder.sensors.valuation_numbers = {91, 92, 93, 94, 95, 96};
  const auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.diagnosis.has_value());
  EXPECT_EQ(r.diagnosis->configuration_written, 0x0005);
  EXPECT_EQ(r.encoder_memory.areas.at(MemoryArea::OperatingParameters)[slave::word::kDiagnosticsConfiguration], 0x0005);
  EXPECT_EQ(frames_with(r, ModeCommand::EncoderReceiveReset), 1U) << "3.6: valid after Encoder receive reset";
  ASSERT_EQ(r.diagnosis->valuation_numbers.size(), 2U);
  EXPECT_EQ(r.diagnosis->valuation_numbers.at(1).last, 91U);
  EXPECT_EQ(r.diagnosis->valuation_numbers.at(3).last, 93U);
  EXPECT_TRUE(r.diagnosis->notes.empty()) << r.diagnosis->notes.front().message;
}

TEST(MasterDiagnosis, ConfigurationAlreadyInForceNeedsNoReset) {
  auto s = diagnosis_scenario();
  s.master.diagnostics.configuration = 0x0007;
  s.encoder.memory = slave::default_memory_image(s.encoder);
  s.encoder.memory->areas[MemoryArea::OperatingParameters][slave::word::kDiagnosticsConfiguration] = 0x0007;
  const auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.diagnosis.has_value());
  EXPECT_FALSE(r.diagnosis->configuration_written.has_value());
  EXPECT_EQ(frames_with(r, ModeCommand::EncoderReceiveReset), 0U);
  EXPECT_EQ(r.diagnosis->valuation_numbers.size(), 3U);
}

TEST(MasterDiagnosis, CollectsTemperaturesAndAdditionalSensorsWithTheirScaling) {
  auto s = diagnosis_scenario();
  s.encoder.sensors.temperature1 = 3181;  // 45.0 degC
  s.encoder.sensors.temperature2 = 3331;  // 60.0 degC
  s.encoder.sensors.additional_sensors = {3431, 3456};
  s.master.diagnostics.additional_sensors = 2;
  const auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.diagnosis && r.diagnosis->temperature1 && r.diagnosis->temperature2);
  EXPECT_EQ(r.diagnosis->temperature1->last, 3181U);
  EXPECT_EQ(r.diagnosis->temperature2->last, 3331U);
  ASSERT_EQ(r.diagnosis->additional_sensors.size(), 2U);
  EXPECT_EQ(r.diagnosis->additional_sensors.at(0).last, 3431U);
  EXPECT_EQ(r.diagnosis->additional_sensors.at(1).last, 3456U);
  EXPECT_EQ(r.diagnosis->max_temperature, 3881);
  EXPECT_EQ(r.diagnosis->warning_threshold, 3831);
  EXPECT_TRUE(test_support::count_ok(r) >= 120U) << "the diagnosis rides on the position reads";
}

TEST(MasterDiagnosis, IgnoresSystemSpecificAddresses) {
  // A3: "the subsequent electronics must ignore undefined addresses".
  auto s = diagnosis_scenario();
  s.encoder.sensors.system_data = {{10, 7}, {20, 9}};
  s.master.diagnostics.configuration = 0x8001;
  const auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.diagnosis.has_value());
  EXPECT_GT(r.diagnosis->ignored_addresses, 0U);
  ASSERT_EQ(r.diagnosis->valuation_numbers.size(), 1U);
  EXPECT_TRUE(r.diagnosis->valuation_numbers.contains(1));
}

TEST(MasterDiagnosis, OnlyTemperature2IsHeldAgainstTheEncoderLimits) {
  // 3.6.6 / 3.9.16: words 6 and 22 concern the encoder; temperature 1 and the additional sensors
  // measure the motor (2.3.5.1).
  auto s = diagnosis_scenario();
  s.encoder.sensors.temperature1 = 3931;  // 120 degC
  s.encoder.sensors.additional_sensors = {3931};
  s.master.diagnostics.additional_sensors = 1;
  auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.diagnosis.has_value());
  EXPECT_TRUE(r.diagnosis->notes.empty()) << r.diagnosis->notes.front().message;
  s.encoder.sensors.temperature2 = 3931;
  r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.diagnosis.has_value());
  EXPECT_EQ(r.diagnosis->count(DiagnosisNoteKind::TemperatureAboveMaximum), 1U);
  EXPECT_EQ(r.diagnosis->count(DiagnosisNoteKind::TemperatureAboveThreshold), 1U);
}

TEST(MasterDiagnosis, WrnHasWord1ReadUnlessSwitchedOff) {
  for (const bool read : {true, false}) {
    auto s = diagnosis_scenario();
    s.encoder.sensors.temperature2 = 3900;
    s.master.diagnostics.read_warnings = read;
    const auto r = scenarios::run_scenario(s);
    ASSERT_TRUE(r.diagnosis.has_value());
    EXPECT_TRUE(r.diagnosis->warning_bit_at.has_value());
    EXPECT_EQ(r.diagnosis->count(DiagnosisNoteKind::TemperatureAboveThreshold), 1U);
    EXPECT_EQ(r.diagnosis->warnings, read ? std::optional<std::uint16_t>{0x0002} : std::nullopt) << read;
    EXPECT_EQ(r.diagnosis->count(DiagnosisNoteKind::Warning), read ? 1U : 0U);
  }
}

TEST(MasterDiagnosis, LowReserveIsNotedOnceUntilItRecovers) {
  auto s = diagnosis_scenario(200);
  s.encoder.sensors.valuation_numbers = {10, 100, 100, 100, 100, 100};
  s.master.diagnostics.configuration = 0x0001;
  s.encoder.memory = slave::default_memory_image(s.encoder);
  s.encoder.memory->areas[MemoryArea::OperatingParameters][slave::word::kDiagnosticsConfiguration] = 0x0001;
  const auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.diagnosis.has_value());
  EXPECT_GT(r.diagnosis->valuation_numbers.at(1).count, 10U);
  EXPECT_EQ(r.diagnosis->count(DiagnosisNoteKind::FunctionReserveLow), 1U);
}

TEST(MasterDiagnosis, SharesAdditionalData1WithPositionValue2) {
  auto s = diagnosis_scenario(200);
  s.master.safety.position_value_2 = true;
  master::Operation startup;
  startup.kind = master::Operation::Kind::SafetyStartup;
  startup.command = ModeCommand::EncoderSendPositionValuesWithAdditionalData;
  s.script.insert(s.script.begin() + 1, startup);
  const auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.diagnosis.has_value());
  EXPECT_GT(r.safety.position_comparisons, 10U);
  EXPECT_TRUE(r.safety.findings.empty()) << r.safety.findings.front().message;
  EXPECT_FALSE(r.diagnosis->valuation_numbers.empty());
  EXPECT_TRUE(r.diagnosis->temperature2.has_value());
}

TEST(MasterDiagnosis, AnEndat21EncoderHasNoDiagnosisThroughAdditionalData) {
  auto s = diagnosis_scenario(5);
  s.encoder.version = protocol::EndatVersion::V2_1;
  s.script.back().command = ModeCommand::EncoderSendPositionValues;
  const auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.diagnosis.has_value());
  ASSERT_EQ(r.diagnosis->count(DiagnosisNoteKind::Setup), 1U);
  EXPECT_NE(r.diagnosis->notes[0].message.find("word 37"), std::string::npos);
}

namespace {

slave::SensorValues valuation_numbers(std::uint8_t first) {
  slave::SensorValues v;
  v.valuation_numbers = std::array<std::uint8_t, 6>{first, 100, 100, 100, 100, 100};
  return v;
}

slave::SensorValues temperature2(std::uint16_t tenth_kelvin) {
  slave::SensorValues v;
  v.temperature2 = tenth_kelvin;
  return v;
}

scenarios::Event sensors_at(sim::Time at, slave::SensorValues values) {
  scenarios::Event e;
  e.kind = scenarios::Event::Kind::SensorValues;
  e.at = at;
  e.sensors = std::move(values);
  return e;
}

}  // namespace

TEST(MasterDiagnosis, LowReserveIsNotedAgainAfterItRecovered) {
  auto s = diagnosis_scenario(400);
  s.master.diagnostics.configuration = 0x0001;
  s.encoder.sensors.valuation_numbers = {10, 100, 100, 100, 100, 100};
  s.events.push_back(sensors_at(sim::ms(75), valuation_numbers(90)));
  s.events.push_back(sensors_at(sim::ms(85), valuation_numbers(12)));
  const auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.diagnosis.has_value());
  const auto& vn1 = r.diagnosis->valuation_numbers.at(1);
  EXPECT_EQ(vn1.max, 90U) << "the recovery was read";
  EXPECT_EQ(vn1.last, 12U);
  EXPECT_EQ(r.diagnosis->count(DiagnosisNoteKind::FunctionReserveLow), 2U);
}

TEST(MasterDiagnosis, RollingSelectionKeepsItsRoundUnderBitErrors) {
  // A selection frame that fails must not send the round back to its start: every item of the
  // schedule is still read, position value 2 still compared.
  auto s = diagnosis_scenario(1500);
  s.master.safety.position_value_2 = true;
  s.master.diagnostics.additional_sensors = 3;
  master::Operation startup;
  startup.kind = master::Operation::Kind::SafetyStartup;
  startup.command = ModeCommand::EncoderSendPositionValuesWithAdditionalData;
  s.script.insert(s.script.begin() + 1, startup);
  scenarios::Event noise;
  noise.kind = scenarios::Event::Kind::RandomBitErrors;
  noise.at = sim::ms(250);  // after the safety start-up
  noise.end = line::ObservationPoint::MasterPins;
  noise.rate = 0.002;
  s.events.push_back(noise);
  const auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.diagnosis.has_value());
  std::size_t failed_selections = 0;
  for (const auto& f : r.frames)
    failed_selections += f.command == ModeCommand::EncoderSendPositionValuesAndSelectionOfMemoryArea &&
                         f.outcome != master::FrameOutcome::Ok && f.start > sim::ms(250);
  EXPECT_GT(failed_selections, 3U) << "the noise must hit selections for this test to mean something";
  ASSERT_TRUE(r.diagnosis->temperature2.has_value());
  EXPECT_GT(r.diagnosis->temperature2->count, 10U);
  EXPECT_GT(r.diagnosis->temperature2->last_at, sim::ms(330)) << "still read late under the noise";
  EXPECT_EQ(r.diagnosis->additional_sensors.size(), 3U);
  for (const auto& [address, reading] : r.diagnosis->additional_sensors) EXPECT_GT(reading.count, 10U) << address;
  EXPECT_GT(r.safety.position_comparisons, 100U);
}

TEST(MasterDiagnosis, AWriteProtectedConfigurationIsReportedNotAssumed) {
  auto s = diagnosis_scenario();
  s.encoder.memory = slave::default_memory_image(s.encoder);
  s.encoder.memory->areas[MemoryArea::OperatingStatus][slave::word::kWriteProtection] |= 0x0002;  // 3.4.3: operating parameters
  const auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.diagnosis.has_value());
  EXPECT_EQ(r.diagnosis->configuration_written, 0x003F);
  EXPECT_EQ(r.diagnosis->configuration, 0x0000) << "still what was read";
  ASSERT_EQ(r.diagnosis->count(DiagnosisNoteKind::Setup), 1U);
  EXPECT_NE(r.diagnosis->notes[0].message.find("could not be written"), std::string::npos) << r.diagnosis->notes[0].message;
  EXPECT_TRUE(r.diagnosis->valuation_numbers.empty()) << "nothing activated, nothing to read";
}

TEST(MasterDiagnosis, AFurtherWarningUnderWrnIsReadAtTheNextInterval) {
  auto s = diagnosis_scenario(600);
  s.master.diagnostics.warnings_interval = sim::ms(10);
  s.events.push_back(sensors_at(sim::ms(70), temperature2(3900)));
  scenarios::Event reserve;
  reserve.kind = scenarios::Event::Kind::ErrorSources;
  reserve.at = sim::ms(90);
  reserve.warnings = 0x0004;  // 3.4.2: light-source control reserve
  s.events.push_back(reserve);
  const auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.diagnosis.has_value());
  EXPECT_EQ(r.diagnosis->warnings, 0x0006);
  EXPECT_EQ(r.diagnosis->count(DiagnosisNoteKind::Warning), 2U);
}

TEST(MasterDiagnosis, AWarningSeenDuringTheSetupIsReadWhenItEnds) {
  auto s = diagnosis_scenario();
  s.script.pop_back();  // the setup only: its last frames see WRN
  s.encoder.sensors.temperature2 = 3900;
  const auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.diagnosis.has_value());
  EXPECT_EQ(r.diagnosis->warnings, 0x0002);
}
