// The master model speaking every kind of mode command to the encoder model, judged by the
// timing checker on the way (no violation may appear on a clean line).
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "endatsim/protocol/parameters.hpp"
#include "endatsim/scenarios/loader.hpp"
#include "endatsim/scenarios/report.hpp"
#include "scenario_support.hpp"

using namespace endatsim;
using namespace endatsim::sim;
using endatsim::test_support::op;
using MC = protocol::ModeCommand;
using Kind = master::Operation::Kind;

namespace {

master::Operation await_not_busy(unsigned max_polls = 100) {
  master::Operation o;
  o.kind = Kind::AwaitNotBusy;
  o.count = max_polls;
  o.cycle = us(50);
  return o;
}

scenarios::Scenario scenario(double cable_m, Hertz f_c, bool compensated, std::vector<master::Operation> script) {
  auto s = test_support::make_scenario(cable_m, f_c, compensated, 1);
  s.script.pop_back();
  s.encoder.t_ac_read = us(200);
  s.encoder.t_ac_write = us(800);
  for (auto& o : script) s.script.push_back(o);
  return s;
}

const master::FrameResult& last_of(const scenarios::ScenarioResult& r, std::size_t operation) {
  const master::FrameResult* f = nullptr;
  for (const auto& x : r.frames)
    if (x.operation == operation) f = &x;
  if (f == nullptr) throw std::runtime_error("no frame for operation " + std::to_string(operation));
  return *f;
}

std::string violations(const scenarios::ScenarioResult& r) {
  std::string s;
  for (const auto& v : r.violations) s += v.check + ": " + v.message + "\n";
  return s;
}

}  // namespace

TEST(MasterParameterAccess, EnDat21SelectWriteAndReadBack) {
  // 2.4, 2.6, 2.5 with the example values of 2.6.1 (OEM2, address 0Bh, A5B4h).
  const auto s = scenario(10, MHz(1), false,
                          {op(MC::SelectionOfMemoryArea, 0xAB), op(MC::EncoderReceiveParameters, 0x0B, 0xA5B4),
                           op(MC::EncoderSendParameters, 0x0B)});
  const auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.finished);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(last_of(r, i).outcome, master::FrameOutcome::Ok) << i;
  EXPECT_EQ(last_of(r, 0).echo_address, 0xAB);
  EXPECT_EQ(last_of(r, 1).echo_parameter, 0xA5B4);
  EXPECT_EQ(last_of(r, 2).echo_parameter, 0xA5B4);
  EXPECT_TRUE(r.violations.empty()) << violations(r);
}

TEST(MasterParameterAccess, EnDat21WriteIntoProtectedAreaIsTypeTwo) {
  const auto s = scenario(10, MHz(1), false,
                          {op(MC::SelectionOfMemoryArea, 0xA1), op(MC::EncoderReceiveParameters, 0x0D, 0x1234)});
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(last_of(r, 1).outcome, master::FrameOutcome::Type2Error);
  EXPECT_EQ(last_of(r, 1).echo_address, 0xF2);  // ~0Dh
  EXPECT_TRUE(r.violations.empty()) << violations(r);
}

// 3.6.5 word 5 bit 2, "no updating of position values": while it is set the encoder keeps
// sending the position of the first frame after it, though the axis moves; cleared, it updates.
TEST(MasterParameterAccess, InstructionNoUpdatingOfPositionValuesFreezesThePosition) {
  auto read = op(MC::EncoderSendPositionValues);
  read.count = 3;
  read.cycle = us(200);
  auto s = scenario(10, MHz(1), false,
                    {op(MC::SelectionOfMemoryArea, 0xA7), op(MC::EncoderReceiveParameters, 0x05, 0x0004), read,
                     op(MC::EncoderReceiveParameters, 0x05, 0x0000), read});
  s.encoder.motion.counts_per_s = 1'000'000;  // one step per microsecond
  const auto r = scenarios::run_scenario(s);
  std::vector<std::uint64_t> frozen, moving;
  for (const auto& f : r.frames) {
    if (f.operation == 2) frozen.push_back(f.position);
    if (f.operation == 4) moving.push_back(f.position);
  }
  ASSERT_EQ(frozen.size(), 3U);
  ASSERT_EQ(moving.size(), 3U);
  EXPECT_EQ(frozen[1], frozen[0]);
  EXPECT_EQ(frozen[2], frozen[0]);
  EXPECT_GT(moving[0], frozen[0]);
  EXPECT_GT(moving[1], moving[0]);
  EXPECT_GT(moving[2], moving[1]);
}

// 3.9.15: word 21 of the EnDat 2.2 manufacturer parameters marks the instructions the encoder does
// not support. One that marks "no updating of position values" stores word 5 bit 2 as written and
// goes on updating the position.
TEST(MasterParameterAccess, AnInstructionWord21MarksUnsupportedTakesNoEffect) {
  auto read = op(MC::EncoderSendPositionValues);
  read.count = 3;
  read.cycle = us(200);
  auto s = scenario(10, MHz(1), false,
                    {op(MC::SelectionOfMemoryArea, 0xA7), op(MC::EncoderReceiveParameters, 0x05, 0x0004),
                     op(MC::EncoderSendParameters, 0x05), read});
  s.encoder.motion.counts_per_s = 1'000'000;
  auto image = slave::default_memory_image(s.encoder);
  image.areas.at(protocol::MemoryArea::ManufacturerEndat22).at(protocol::word::kInstructionSupport) =
      protocol::parameters::kInstructionNoPositionUpdate;
  s.encoder.memory = image;
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(last_of(r, 2).echo_parameter, 0x0004) << "word 5 keeps what was written";
  std::vector<std::uint64_t> positions;
  for (const auto& f : r.frames)
    if (f.operation == 3) positions.push_back(f.position);
  ASSERT_EQ(positions.size(), 3U);
  EXPECT_GT(positions[1], positions[0]);
  EXPECT_GT(positions[2], positions[1]);
}

// 3.6.5 word 5 bit 0, "energy-saving mode": the spec names the instruction and nothing it changes
// (docs/model-reference.md). An encoder that declares no t_cal_energy_saving (this one) stores and
// acknowledges it, reads it back, and goes on answering with moving positions, the same frames on
// the wires as without it.
TEST(MasterParameterAccess, InstructionEnergySavingIsStoredAndChangesNothingOnTheWires) {
  auto read = op(MC::EncoderSendPositionValues);
  read.count = 3;
  read.cycle = us(200);
  const auto with = [&](std::uint16_t instructions) {
    auto s = scenario(10, MHz(1), false,
                      {op(MC::SelectionOfMemoryArea, 0xA7), op(MC::EncoderReceiveParameters, 0x05, instructions),
                       op(MC::EncoderSendParameters, 0x05), read});
    s.encoder.motion.counts_per_s = 1'000'000;
    return scenarios::run_scenario(s);
  };
  const auto saving = with(protocol::parameters::kInstructionEnergySaving);
  const auto plain = with(0x0000);
  EXPECT_EQ(last_of(saving, 1).outcome, master::FrameOutcome::Ok);
  EXPECT_EQ(last_of(saving, 1).echo_parameter, protocol::parameters::kInstructionEnergySaving);
  EXPECT_EQ(last_of(saving, 2).echo_parameter, protocol::parameters::kInstructionEnergySaving);
  ASSERT_EQ(saving.frames.size(), plain.frames.size());
  for (std::size_t i = 0; i < saving.frames.size(); ++i) {
    if (saving.frames[i].operation != 3) continue;
    EXPECT_EQ(saving.frames[i].outcome, master::FrameOutcome::Ok) << i;
    EXPECT_EQ(saving.frames[i].position, plain.frames[i].position) << i;
    EXPECT_EQ(saving.frames[i].start, plain.frames[i].start) << i;
  }
  EXPECT_GT(last_of(saving, 3).position, saving.frames[saving.frames.size() - 3].position);
  EXPECT_TRUE(saving.violations.empty()) << violations(saving);
}

TEST(MasterParameterAccess, EnDat22ReadThroughTheSupplementWithBusyPolling) {
  // 2.5.1: select "memory parameters LSB" as additional data 1, select the area, poll busy,
  // read, poll busy; the last poll carries address 0Dh and the LSB of word 13 (25 bits: 19h).
  const auto s = scenario(
      30, MHz(4), true,
      {op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0x45),
       op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0xA1), await_not_busy(),
       op(MC::EncoderSendPositionValuesAndSendParameter, 0x0D), await_not_busy()});
  const auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.finished);
  const auto& last = last_of(r, 5);
  ASSERT_EQ(last.outcome, master::FrameOutcome::Ok);
  ASSERT_EQ(last.additional_data.size(), 1U);
  EXPECT_EQ(last.additional_data[0].information(), protocol::Information::MemoryParameterLsb);
  EXPECT_FALSE(last.additional_data[0].busy());
  EXPECT_EQ(last.additional_data[0].data, 0x0D19);
  std::size_t polls = 0;
  for (const auto& f : r.frames) polls += f.operation == 5;
  EXPECT_GT(polls, 1U) << "the encoder was busy for t_ac = 200 us";
  EXPECT_EQ(r.frames.back().position, 104462U);
  EXPECT_TRUE(r.violations.empty()) << violations(r);
}

TEST(MasterParameterAccess, EnDat22WriteIntoProtectedAreaIsAcknowledgedInvertedAsInEnDat21) {
  // A2 4.2.2: the address and the parameter come back inverted, as in the 2.1 acknowledgment of
  // the test above: memory parameters LSB shows ~0Dh and the low byte of ~1234h.
  const auto s = scenario(
      30, MHz(4), true,
      {op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0x45),
       op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0xA1), await_not_busy(),
       op(MC::EncoderSendPositionValuesAndReceiveParameter, 0x0D, 0x1234), await_not_busy()});
  const auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.finished);
  const auto& last = last_of(r, 5);
  ASSERT_EQ(last.additional_data.size(), 1U);
  EXPECT_EQ(last.additional_data[0].information(), protocol::Information::MemoryParameterLsb);
  EXPECT_FALSE(last.additional_data[0].busy());
  EXPECT_EQ(last.additional_data[0].data, 0xF2CB);  // ~0Dh, low byte of ~1234h
}

TEST(MasterParameterAccess, TheSupplementsLastBitOutlastsTheEdgeThatTakesIt) {
  // The encoder takes the supplement's last bit on the master's last rising edge. A master whose
  // driver turns off faster than its CLOCK driver switches must still hold that bit past the
  // edge at the encoder, and be off DATA before the encoder drives its end marker, at a slow
  // clock as at the fastest.
  for (const Hertz f_c : {kHz(200), MHz(16)}) {
    auto s = scenario(1, f_c, f_c > MHz(2),
                      {op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0x45),
                       op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0xA9), await_not_busy(),
                       op(MC::EncoderSendPositionValuesAndReceiveParameter, 0x10, 0x1234), await_not_busy()});
    s.line.master = {ns(40), ns(30), ns(30), ns(100)};  // driver off 10 ns before CLOCK switches
    const auto r = scenarios::run_scenario(s);
    ASSERT_TRUE(r.finished) << f_c;
    std::vector<std::uint32_t> sent, taken;
    for (const auto& f : r.frames)
      if (f.supplement) sent.push_back(*f.supplement);
    for (const auto& f : r.encoder_frames)
      if (f.supplement) taken.push_back(*f.supplement);
    EXPECT_EQ(taken, sent) << f_c;
    EXPECT_EQ(r.encoder_memory.areas.at(protocol::MemoryArea::Oem1).at(0x10), 0x1234) << f_c;
    for (const auto& v : r.violations)  // 16 MHz is a warning of its own (2.3.2)
      EXPECT_EQ(v.check, checker::check::kClockFrequency) << f_c << ": " << v.message;
  }
}

TEST(MasterParameterAccess, EnDat22WriteThenReadBack) {
  const auto s = scenario(
      50, MHz(8), true,
      {op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0x45),
       op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0xA9), await_not_busy(),
       op(MC::EncoderSendPositionValuesAndReceiveParameter, 0x10, 0xBEEF), await_not_busy(),
       op(MC::EncoderSendPositionValuesAndSendParameter, 0x10), await_not_busy(),
       op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0x46), await_not_busy()});
  const auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.finished);
  EXPECT_EQ(last_of(r, 7).additional_data.at(0).data, 0x10EF);
  EXPECT_EQ(last_of(r, 9).additional_data.at(0).data, 0x10BE);
  EXPECT_TRUE(r.violations.empty()) << violations(r);
}

TEST(MasterAdditionalData, BothAdditionalDataArriveInWireOrder) {
  auto s = scenario(20, MHz(4), true,
                    {op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0x4D),
                     op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0x51),
                     op(MC::EncoderSendPositionValuesWithAdditionalData)});
  s.encoder.sensors.commutation = 0b101;
  s.encoder.sensors.temperature2 = 3100;
  const auto r = scenarios::run_scenario(s);
  const auto& f = last_of(r, 3);
  ASSERT_EQ(f.outcome, master::FrameOutcome::Ok);
  ASSERT_EQ(f.additional_data.size(), 2U);
  EXPECT_EQ(f.additional_data[0].information(), protocol::Information::Commutation);
  EXPECT_EQ(f.additional_data[0].data, 0xA000);
  EXPECT_EQ(f.additional_data[1].information(), protocol::Information::Temperature2);
  EXPECT_EQ(f.additional_data[1].data, 3100);
  EXPECT_TRUE(r.violations.empty()) << violations(r);
}

TEST(MasterTestValues, EnDat21TestCommandThenTestValues) {
  auto s = scenario(5, MHz(1), false, {op(MC::EncoderReceiveTestCommand, 0x07), op(MC::EncoderSendTestValues)});
  s.encoder.sensors.test_values[0x07] = 0xFF'0000'1234ULL;
  const auto r = scenarios::run_scenario(s);
  ASSERT_EQ(last_of(r, 1).outcome, master::FrameOutcome::Ok);
  EXPECT_EQ(last_of(r, 1).test_value, 0xFF'0000'1234ULL);
  EXPECT_TRUE(r.violations.empty()) << violations(r);
}

TEST(MasterReset, ResetAndErrorReset) {
  auto s = scenario(5, MHz(1), false,
                    {op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0x4C), op(MC::EncoderReceiveReset),
                     op(MC::EncoderSendPositionValuesWithAdditionalData),
                     op(MC::EncoderSendPositionValuesAndReceiveErrorReset)});
  const auto r = scenarios::run_scenario(s);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(last_of(r, i).outcome, master::FrameOutcome::Ok) << i;
  EXPECT_TRUE(last_of(r, 2).additional_data.empty()) << "2.4.2.2: none after a reset";
  EXPECT_TRUE(r.violations.empty()) << violations(r);
}

TEST(MasterBus, TwoActiveEncodersOnOneBusCollide) {
  // 2.10: without the high-impedance instruction both encoders drive DATA (idle LOW, then their
  // answers): the checker reports the collision at the encoder end.
  auto s = scenario(10, MHz(1), false, {op(MC::EncoderSendPositionValuesWithAdditionalData)});
  s.bus.push_back(s.encoder);
  s.bus.back().motion.start = 5;
  const auto r = scenarios::run_scenario(s);
  ASSERT_GE(r.violations.size(), 1U);
  bool between_encoders = false;
  for (const auto& v : r.violations)
    between_encoders = between_encoders || (v.check == checker::check::kContention &&
                                            v.message.find("two encoders") != std::string::npos);
  EXPECT_TRUE(between_encoders) << violations(r);
  EXPECT_NE(last_of(r, 0).outcome, master::FrameOutcome::Ok) << "the answers garble each other";
}

TEST(MasterBus, AHighImpedanceEncoderStaysOffTheBus) {
  auto s = scenario(10, MHz(1), false, {op(MC::EncoderSendPositionValuesWithAdditionalData)});
  s.bus.push_back(s.encoder);
  s.bus.back().memory = slave::default_memory_image(s.bus.back());
  s.bus.back().memory->areas[protocol::MemoryArea::OperatingParameters][slave::word::kInstructions] = 0x0002;
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(last_of(r, 0).outcome, master::FrameOutcome::Ok);
  EXPECT_TRUE(r.violations.empty()) << violations(r);
  ASSERT_EQ(r.bus_frames.size(), 1U);
  EXPECT_EQ(r.bus_frames[0].size(), 1U) << "it sees the frame, but keeps silent";
}

TEST(MasterStartup, RoutineReadsWord13AndMeasuresTheDelayWhenCompensating) {
  // The German brochure's (older edition) start-up routine (docs/model.md §8): reset, 50 ms, alarms and warnings
  // read and cleared, words 13 and 37; then (2.1.2) the delay measurement. The master was
  // configured for 13 bits and takes word 13's 25.
  auto s = test_support::make_scenario(50, MHz(8), true, 2);
  s.script.erase(s.script.begin());  // no measure_delay of its own
  master::Operation routine;
  routine.kind = Kind::StartupRoutine;
  s.script.insert(s.script.begin(), routine);
  s.master.position_bits = 13;
  s.encoder.warning_sources = 0x0004;
  const auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.finished);
  EXPECT_TRUE(r.startup.completed);
  EXPECT_EQ(r.startup.word13, 0x8019);
  EXPECT_EQ(r.startup.warnings, 0x0004);
  ASSERT_EQ(r.measurements.size(), 1U);
  EXPECT_TRUE(r.measurements[0].accepted);
  EXPECT_EQ(last_of(r, 1).position, 104462U);
  EXPECT_TRUE(last_of(r, 1).compensated);
  EXPECT_TRUE(r.violations.empty()) << violations(r);
  // 3.4.1 / 3.4.2: the writes of 0000h delete alarms and warnings only with the reset after them.
  std::vector<MC> commands;
  for (const auto& f : r.frames)
    if (f.operation == 0 && !f.measurement) commands.push_back(f.command);
  const std::vector<MC> routine_commands{MC::EncoderReceiveReset,      MC::SelectionOfMemoryArea,
                                         MC::EncoderSendParameters,    MC::EncoderSendParameters,
                                         MC::EncoderReceiveParameters, MC::EncoderReceiveParameters,
                                         MC::EncoderReceiveReset,      MC::SelectionOfMemoryArea,
                                         MC::EncoderSendParameters,    MC::SelectionOfMemoryArea,
                                         MC::EncoderSendParameters};
  EXPECT_EQ(commands, routine_commands);
}

namespace {

// Without the sequence, `reads` requests 100 us apart from `first`.
scenarios::ScenarioResult switched_on(Time t1_t2, Time pulse, Time t3, bool sequence = true, unsigned reads = 1,
                                      Time first = sim::ms(1500)) {
  auto s = scenario(10, MHz(1), false, {op(MC::EncoderSendPositionValuesWithAdditionalData)});
  s.encoder.startup_time = sim::ms(1000);
  s.master.power_on = {t1_t2, pulse, t3};
  s.max_time = sim::ms(5000);
  if (sequence) {
    master::Operation on;
    on.kind = Kind::PowerOnSequence;
    s.script.insert(s.script.begin(), on);
  } else {
    s.script.front().at = first;
    s.script.front().count = reads;
    s.script.front().cycle = sim::us(100);
  }
  return scenarios::run_scenario(s);
}

std::size_t power_on_findings(const scenarios::ScenarioResult& r) {
  return static_cast<std::size_t>(std::count_if(r.violations.begin(), r.violations.end(), [](const auto& v) {
    return v.check == checker::check::kPowerOn;
  }));
}

}  // namespace

TEST(CheckerPowerOn, TheSequenceOfTheFigureIsClean) {
  const auto r = switched_on(sim::ms(900), sim::us(1), sim::ms(400));
  EXPECT_EQ(last_of(r, 1).outcome, master::FrameOutcome::Ok);
  EXPECT_TRUE(r.violations.empty()) << violations(r);
}

TEST(CheckerPowerOn, EachLimitOfTheSequenceIsJudgedToThePicosecond) {
  // Judged at the encoder's pins (2.3.3: "measurements at the encoder"), where CLOCK arrives
  // after the master's driver and 10 m of cable; the supply came up there at 0.
  const auto line = scenario(10, MHz(1), false, {}).line;
  const Time path = line.master.driver_delay + line.cable_delay();
  EXPECT_EQ(power_on_findings(switched_on(sim::ms(900), sim::ns(125), sim::ms(400))), 1U) << "pulse not > 125 ns";
  EXPECT_EQ(power_on_findings(switched_on(sim::ms(900), sim::ns(125) + sim::ps(1), sim::ms(400))), 0U);
  EXPECT_EQ(power_on_findings(switched_on(sim::ms(880) - path - sim::ps(1), sim::us(1), sim::ms(400))), 1U) << "before t1 + t2";
  EXPECT_EQ(power_on_findings(switched_on(sim::ms(880) - path, sim::us(1), sim::ms(400))), 0U);
  EXPECT_EQ(power_on_findings(switched_on(sim::ms(900), sim::us(1), sim::ms(380) - sim::ps(1))), 1U) << "t3 too short";
  EXPECT_EQ(power_on_findings(switched_on(sim::ms(900), sim::us(1), sim::ms(380))), 0U);
  EXPECT_EQ(power_on_findings(switched_on(sim::ms(900), sim::us(1), sim::ms(420) + sim::ps(1))), 1U) << "t3 too long";
  EXPECT_EQ(power_on_findings(switched_on(sim::ms(900), sim::us(1), sim::ms(420))), 0U);
}

TEST(CheckerPowerOn, JudgedAgainAfterEveryPowerInterruption) {
  // 2.3.3 after the supply comes back at 1.51 s: a master that goes on reading without the
  // sequence has its first read taken for the wake-up cycle and its second long before t3; one
  // that runs the sequence again is clean.
  auto s = scenario(10, MHz(1), false, {op(MC::EncoderSendPositionValuesWithAdditionalData)});
  s.encoder.startup_time = sim::ms(1000);
  s.master.power_on = {sim::ms(900), sim::us(1), sim::ms(400)};
  s.max_time = sim::ms(5000);
  master::Operation on;
  on.kind = Kind::PowerOnSequence;
  master::Operation again = s.script.front();
  again.at = sim::ms(2600);  // the encoder has run up again
  again.count = 2;
  again.cycle = sim::us(100);
  s.script = {on, s.script.front(), again};
  scenarios::Event cut;
  cut.kind = scenarios::Event::Kind::PowerInterruption;
  cut.at = sim::ms(1500);
  cut.duration = sim::ms(10);
  s.events.push_back(cut);
  auto r = scenarios::run_scenario(s);
  ASSERT_EQ(power_on_findings(r), 1U) << violations(r);
  for (const auto& v : r.violations)
    if (v.check == checker::check::kPowerOn) {
      EXPECT_EQ(v.limit, "t3 = 380 .. 420 ms");
      EXPECT_GT(v.time, sim::ms(2600));
    }
  master::Operation on_again = on;
  on_again.at = sim::ms(1510);
  again.at.reset();
  s.script = {on, s.script[1], on_again, again};
  r = scenarios::run_scenario(s);
  EXPECT_EQ(power_on_findings(r), 0U) << violations(r);
  EXPECT_EQ(last_of(r, 1).outcome, master::FrameOutcome::Ok);
}

TEST(CheckerPowerOn, WithoutAPulseTheFirstRequestIsTheWakeUpCycleAndTheNextEndsT3) {
  // 2.3.3: "at least one pulse (> 125 ns) or one request cycle (data not valid)". A master that
  // requests twice, 100 us apart, at 1.5 s: its first request is the wake-up, the second comes
  // 100 us after it instead of t3.
  auto r = switched_on(sim::ms(900), sim::us(1), sim::ms(400), false, 2);
  ASSERT_EQ(power_on_findings(r), 1U) << violations(r);
  for (const auto& v : r.violations)
    if (v.check == checker::check::kPowerOn) {
      EXPECT_EQ(v.limit, "t3 = 380 .. 420 ms");
      EXPECT_EQ(v.frame, 1U);
    }
  // Requested at once after switching on: the wake-up also came before t1 + t2.
  r = switched_on(sim::ms(900), sim::us(1), sim::ms(400), false, 2, sim::ms(1));
  EXPECT_EQ(power_on_findings(r), 2U) << violations(r);
  // One request alone shows no t3: only t1 + t2 are judged, and kept.
  EXPECT_EQ(power_on_findings(switched_on(sim::ms(900), sim::us(1), sim::ms(400), false, 1)), 0U);
  EXPECT_EQ(power_on_findings(switched_on(sim::ms(900), sim::us(1), sim::ms(400), false, 1, sim::ms(1))), 1U);
}

// What the master could not do as the script asked is reported whether or not an expectation
// counts it: a busy bit it could not read, a busy wait it gave up, a read cycle it could not keep.
namespace {

scenarios::ScenarioResult run_text(const std::string& script, const std::string& events = "[]",
                                   const std::string& f_c = "1 MHz") {
  const auto s = scenarios::load_scenario_text(
      R"({"name": "reported", "line": {"cable_length_m": 10}, "master": {"f_c": ")" + f_c + R"("},
          "encoder": {"t_ac_read": "2 ms"}, "events": )" + events + R"(, "script": )" + script + "}",
      "reported.json");
  return scenarios::run_scenario(s);
}

std::string summary_of(const scenarios::ScenarioResult& r) {
  std::ostringstream out;
  scenarios::write_summary(out, r, false);
  return out.str();
}

}  // namespace

// --verbose lists each frame: a position answer with its position and F1, a memory area selection
// or a parameter read with its outcome alone (it showed "position 0, F1 0", fields it has not).
TEST(MasterReports, AFrameListsThePositionAndF1OnlyOfAPositionAnswer) {
  const auto s = scenarios::load_scenario_file(std::string(ENDATSIM_SOURCE_DIR) + "/scenarios/safety/01_error_messages.json");
  const auto r = scenarios::run_scenario(s);
  std::ostringstream out;
  scenarios::write_summary(out, r, true);
  const std::string text = out.str();
  std::size_t selections = 0, positions = 0;
  for (std::size_t at = text.find("\n  #"); at != std::string::npos; at = text.find("\n  #", at + 1)) {
    const std::string line = text.substr(at + 1, text.find('\n', at + 1) - at - 1);
    const bool position_answer = line.find(" encoder_send_position_values") != std::string::npos;
    if (line.find(": ok") == std::string::npos) continue;
    EXPECT_EQ(line.find(", position ") != std::string::npos, position_answer) << line;
    EXPECT_EQ(line.find(", F1 ") != std::string::npos, position_answer) << line;
    (position_answer ? positions : selections) += 1;
  }
  EXPECT_GT(positions, 0U);
  EXPECT_GT(selections, 0U);
}

TEST(MasterReports, AnAwaitNotBusyWithoutAdditionalData1GivesUpAtOnceAndSaysWhy) {
  const auto r = run_text(R"([{"op": "await_not_busy"}])");
  ASSERT_TRUE(r.finished);
  EXPECT_EQ(r.frames.size(), 1U) << "one poll shows the busy bit cannot be read; not 1000";
  EXPECT_EQ(r.busy_unreadable, 1U);
  EXPECT_EQ(r.busy_timeouts, 0U);
  EXPECT_NE(summary_of(r).find("warning: 1 await_not_busy could not read the busy bit: its poll frames carried no "
                               "additional data 1"), std::string::npos) << summary_of(r);
  EXPECT_EQ(scenarios::to_json(r).at("busy_unreadable"), 1);
}

TEST(MasterReports, AnAwaitNotBusyThatRunsOutOfPollsIsReportedWithoutAnExpectation) {
  // Additional data 1 carries the busy bit; a read access of t_ac = 2 ms outlasts 5 polls.
  const auto r = run_text(R"([{"op": "select_additional_data", "additional_data": "memory_parameter_lsb"},
                              {"op": "select_memory_area", "mrs": "manufacturer_1"},
                              {"op": "frame", "command": "encoder_send_position_values_and_send_parameter", "address": 13},
                              {"op": "await_not_busy", "max_polls": 5}])");
  ASSERT_TRUE(r.finished);
  EXPECT_EQ(r.busy_timeouts, 1U);
  EXPECT_EQ(r.busy_unreadable, 0U);
  EXPECT_EQ(r.cycle_overruns, 0U) << "polls that come later than their interval are no read cycle overrun";
  EXPECT_NE(summary_of(r).find("warning: 1 await_not_busy gave up: the busy bit stayed set for max_polls polls"),
            std::string::npos) << summary_of(r);
  EXPECT_EQ(scenarios::to_json(r).at("busy_timeouts"), 1);
}

TEST(MasterReports, AReadCycleThatCannotBeKeptIsReportedAsOverruns) {
  // A frame of some 50 clocks at 1 MHz plus t_m cannot repeat every 20 us.
  const auto late = run_text(R"([{"op": "read_position", "count": 5, "cycle": "20 us"}])");
  EXPECT_EQ(late.cycle_overruns, 4U);
  EXPECT_NE(summary_of(late).find("warning: 4 frame(s) started late: the read cycle could not be kept"), std::string::npos)
      << summary_of(late);
  EXPECT_EQ(scenarios::to_json(late).at("cycle_overruns"), 4);
  const auto kept = run_text(R"([{"op": "read_position", "count": 5, "cycle": "200 us"}])");
  EXPECT_EQ(kept.cycle_overruns, 0U);
  EXPECT_EQ(summary_of(kept).find("started late"), std::string::npos) << summary_of(kept);
}

TEST(MasterReports, TheJsonResultsCarryTheCrcOfEachAdditionalDatum) {
  // A DATA bit flipped inside additional data 1 (frame 1, 25-bit position): the position's CRC
  // agrees, the datum's does not, and the frame is a CRC error.
  const auto r = run_text(R"([{"op": "select_additional_data", "additional_data": "temperature_1"},
                              {"op": "read_position", "command": "encoder_send_position_values_with_additional_data",
                               "count": 2, "cycle": "200 us"}])",
                          R"([{"frame": 2, "clock": 50, "bit_flip": {"wire": "data", "end": "master"}}])");
  ASSERT_TRUE(r.finished);
  const auto j = scenarios::to_json(r);
  const auto& bad = j.at("frames").at(2);
  EXPECT_EQ(bad.at("outcome"), "crc_error");
  EXPECT_EQ(bad.at("crc_received"), bad.at("crc_expected")) << bad.dump();
  ASSERT_EQ(bad.at("additional_data").size(), 1U) << bad.dump();
  const auto& datum = bad.at("additional_data").at(0);
  EXPECT_EQ(datum.at("additional_data"), 1);
  EXPECT_FALSE(datum.at("crc_ok").get<bool>());
  EXPECT_NE(datum.at("crc_received"), datum.at("crc_expected")) << datum.dump();
  const auto& good = j.at("frames").at(1).at("additional_data").at(0);
  EXPECT_EQ(good.at("information"), "temperature_1");
  EXPECT_TRUE(good.at("crc_ok").get<bool>());
  EXPECT_EQ(good.at("crc_received"), good.at("crc_expected"));
}

// The master's supplement goes through with either handover after the encoder's answer (2.3,
// 2.4.2; supplement_handover): what it sends is what the encoder takes, the read comes back, and
// the checker finds nothing.
TEST(MasterParameterAccess, TheSupplementGoesThroughWithEitherHandover) {
  for (const auto h : {slave::SupplementHandover::Release, slave::SupplementHandover::EndLevel}) {
    auto s = scenario(30, MHz(4), true,
                      {op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0x45),
                       op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0xA1), await_not_busy(),
                       op(MC::EncoderSendPositionValuesAndSendParameter, 0x0D), await_not_busy()});
    s.encoder.supplement_handover = h;
    const auto r = scenarios::run_scenario(s);
    ASSERT_TRUE(r.finished);
    std::vector<std::uint32_t> sent, taken;
    for (const auto& f : r.frames)
      if (f.supplement) sent.push_back(*f.supplement);
    for (const auto& f : r.encoder_frames)
      if (f.supplement) taken.push_back(*f.supplement);
    EXPECT_EQ(taken, sent);
    EXPECT_EQ(last_of(r, 5).additional_data.at(0).data, 0x0D19);
    EXPECT_TRUE(r.violations.empty()) << violations(r);
  }
}
