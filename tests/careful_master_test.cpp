// Master faults and the careful master's reactions: each fault shows on the wire or in
// the master's results the way a broken master in the field shows it, and each reaction of a
// careful master works and can be switched off.
#include <gtest/gtest.h>

#include "endatsim/master/additional_data_selection.hpp"
#include "endatsim/master/careful_policy.hpp"
#include "scenario_support.hpp"

using namespace endatsim;
using namespace endatsim::sim;
using endatsim::test_support::op;
using K = scenarios::Event::Kind;
using MC = protocol::ModeCommand;
using O = master::FrameOutcome;
using test_support::count_violations;

namespace {

// Ten reads, 100 us apart, at 1 MHz over 10 m; no compensation unless asked for.
scenarios::Scenario reads(MC command = MC::EncoderSendPositionValuesWithAdditionalData, unsigned n = 10) {
  auto s = test_support::make_scenario(10, MHz(1), false, n);
  s.script.back().command = command;
  return s;
}

std::size_t count(const scenarios::ScenarioResult& r, O outcome) {
  std::size_t n = 0;
  for (const auto& f : r.frames) n += !f.measurement && f.outcome == outcome;
  return n;
}

}  // namespace

// ---- CRC faults (docs/model.md §12) -----------------------------------------------------------

TEST(MasterCrcFault, PresetZeroWithoutInversionFailsEveryFrameOfARealEncoder) {
  auto s = reads();
  s.master.crc.generator = {0x00, false};
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(count(r, O::CrcError), 10U);
}

TEST(MasterCrcFault, AnEmulatorBuiltWithTheSameWrongSettingsPassesTheLoopback) {
  auto s = reads();
  s.master.crc.generator = {0x00, false};
  s.encoder.crc = {0x00, false};
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(count(r, O::Ok), 10U) << "both ends agree, so the bench test passes";
}

TEST(MasterCrcFault, TheEndat22RuleOn21FramesFailsOnly21Frames) {
  auto s21 = reads(MC::EncoderSendPositionValues);
  s21.master.crc.endat22_rule_for_21 = true;
  EXPECT_EQ(count(scenarios::run_scenario(s21), O::CrcError), 10U);
  auto s22 = reads(MC::EncoderSendPositionValuesWithAdditionalData);
  s22.master.crc.endat22_rule_for_21 = true;
  EXPECT_EQ(count(scenarios::run_scenario(s22), O::Ok), 10U);
}

TEST(MasterCrcFault, ATableCrcFaultShowsOnlyAtItsWidth) {
  const auto run = [](unsigned bits) {
    auto s = reads();
    s.encoder.position_bits = bits;
    s.encoder.motion.start = 0x1234;
    s.master.position_bits = bits;
    s.master.crc.table_fault_width = 31;
    return scenarios::run_scenario(s);
  };
  EXPECT_EQ(count(run(31), O::CrcError), 10U);
  EXPECT_EQ(count(run(25), O::Ok), 10U);
  EXPECT_EQ(count(run(32), O::Ok), 10U);
}

// ---- wrong clock counts ---------------------------------------------------------------------------

TEST(MasterClockCount, TooFewPulsesLeaveTheAnswerIncompleteAndTheEncoderHanging) {
  auto s = reads(MC::EncoderSendPositionValues, 3);
  s.script.back().clock_adjust = -6;
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(count(r, O::TooFewClocks), 3U) << "an answer cut short is not a CRC error: no CRC was received";
  EXPECT_EQ(count(r, O::CrcError), 0U);
  EXPECT_EQ(count_violations(r, checker::check::kClockCount), 3U) << "the clock stopped before the encoder's last bit";
  ASSERT_EQ(r.encoder_frames.size(), 3U);
  EXPECT_FALSE(r.encoder_frames[0].too_many_clocks);
}

TEST(MasterClockCount, TooManyPulsesWithPositionValuesAreAContinuousClockToTheEncoder) {
  // 2.3.1: the encoder sends the next position word; the master, expecting one, reads it fine.
  auto s = reads(MC::EncoderSendPositionValues, 3);
  s.script.back().clock_adjust = 12;
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(count(r, O::Ok), 3U);
  ASSERT_EQ(r.encoder_frames.size(), 3U);
  EXPECT_EQ(r.encoder_frames[0].continuous_words, 1U);
  EXPECT_EQ(r.frames[0].clocks, 43U + 12U);
  EXPECT_EQ(count_violations(r, checker::check::kClockCount), 0U) << "a continuous clock is allowed here (2.3.1)";
}

TEST(MasterClockCount, TooManyPulsesDiscardAParameterWrite) {
  // 2.4.1: "more clock pulses than required" -> the access is not carried out.
  auto s = test_support::make_scenario(10, MHz(1), false, 1);
  s.encoder.t_ac_write = us(300);
  auto write = op(MC::EncoderReceiveParameters, 0x01, 0xBEEF);
  write.clock_adjust = 4;
  s.script = {op(MC::SelectionOfMemoryArea, 0xA9), write};
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(r.encoder_memory.areas.at(protocol::MemoryArea::Oem1).at(1), 0x0000);
  ASSERT_GE(r.encoder_frames.size(), 2U);
  EXPECT_TRUE(r.encoder_frames[1].too_many_clocks);
}

// ---- retries and echo verification ----------------------------------------------------------------

TEST(CarefulMaster, RetriesRepeatFailedFramesUntilTheyAnswer) {
  auto s = reads(MC::EncoderSendPositionValuesWithAdditionalData, 100);
  scenarios::Event noise;
  noise.kind = K::RandomBitErrors;
  noise.at = Time::zero();
  noise.end = line::ObservationPoint::MasterPins;
  noise.rate = 0.01;
  s.events.push_back(noise);
  const auto careless = scenarios::run_scenario(s);
  EXPECT_LT(count(careless, O::Ok), 100U);
  EXPECT_EQ(careless.retries, 0U);
  s.master.careful.retries = 5;
  const auto careful = scenarios::run_scenario(s);
  EXPECT_GT(careful.retries, 0U);
  std::size_t operations_ok = 0;
  for (std::size_t i = 0; i < careful.frames.size(); ++i)
    operations_ok += careful.frames[i].outcome == O::Ok;
  EXPECT_EQ(operations_ok, 100U) << "every read answered in the end";
  EXPECT_EQ(count(careful, O::CrcError), careful.retries);
}

namespace {

// A 2.1 write of A5B4h to OEM 2 address 0Bh (2.6.1) with one parameter bit flipped on its way
// to the encoder: at the encoder's pins, around the 20th rising edge of frame 1.
scenarios::Scenario disturbed_write() {
  auto s = test_support::make_scenario(10, MHz(1), false, 1);
  s.encoder.t_ac_write = us(300);
  s.script = {op(MC::SelectionOfMemoryArea, 0xAB), op(MC::EncoderReceiveParameters, 0x0B, 0xA5B4)};
  scenarios::Event flip;
  flip.kind = K::BitFlip;
  flip.frame = 1;
  flip.clock = 20;
  flip.offset = ns(500);
  flip.end = line::ObservationPoint::EncoderPins;
  s.events.push_back(flip);
  return s;
}

std::uint16_t oem2_word_0b(const scenarios::ScenarioResult& r) {
  return r.encoder_memory.areas.at(protocol::MemoryArea::Oem2).at(0x0B);
}

}  // namespace

TEST(CarefulMaster, AWriteDisturbedOnItsWayIsCaughtByTheEchoAndWrittenAgain) {
  auto s = disturbed_write();
  s.master.careful.retries = 1;
  const auto r = scenarios::run_scenario(s);
  ASSERT_EQ(r.frames.size(), 3U);
  EXPECT_EQ(r.frames[1].outcome, O::EchoMismatch);
  EXPECT_EQ(r.frames[2].outcome, O::Ok);
  EXPECT_EQ(oem2_word_0b(r), 0xA5B4);
}

TEST(CarefulMaster, WithoutEchoVerificationTheWrongWordStays) {
  auto s = disturbed_write();
  s.master.careful.retries = 1;
  s.master.careful.verify_echo = false;
  const auto r = scenarios::run_scenario(s);
  ASSERT_EQ(r.frames.size(), 2U);
  EXPECT_EQ(r.frames[1].outcome, O::Ok) << "the echo differs, but nobody looks";
  EXPECT_NE(oem2_word_0b(r), 0xA5B4);
  EXPECT_EQ(r.frames[1].echo_parameter, oem2_word_0b(r)) << "the encoder acknowledged what it wrote";
}

// ---- re-measuring t_D (2.1.2) -------------------------------------------------------------------

namespace {

scenarios::Scenario compensated_with_cable_change() {
  auto s = test_support::make_scenario(10, MHz(8), true, 30);
  s.master.start_bit_detection = master::StartBitDetection::FirstHigh;
  s.events.push_back(scenarios::cable_change(ms(2), 100, ns(5)));
  return s;
}

}  // namespace

TEST(CarefulMaster, ALineChangeItIsToldOfIsMeasuredAgainBeforeTheNextFrame) {
  const auto r = scenarios::run_scenario(compensated_with_cable_change());
  EXPECT_EQ(r.remeasurements, 1U);
  EXPECT_LE(count(r, O::CrcError), 1U) << "at most the frame on the wire during the swap";
  ASSERT_EQ(r.measurements.size(), 2U);
  EXPECT_GT(r.measurements[1].t_d, r.measurements[0].t_d + ns(800));
}

TEST(CarefulMaster, WithoutNoticeThreeFailedFramesInARowTriggerTheMeasurement) {
  auto s = compensated_with_cable_change();
  s.master.careful.remeasure_after_line_change = false;
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(r.remeasurements, 1U);
  EXPECT_GE(count(r, O::CrcError), 3U);
  EXPECT_LE(count(r, O::CrcError), 4U);
}

TEST(CarefulMaster, ACarelessMasterKeepsTheOldDelay) {
  auto s = compensated_with_cable_change();
  s.master.careful.remeasure_after_line_change = false;
  s.master.careful.remeasure_after_crc_errors = 0;
  const auto r = scenarios::run_scenario(s);
  EXPECT_EQ(r.remeasurements, 0U);
  EXPECT_GE(count(r, O::CrcError), 10U);
  EXPECT_EQ(count_violations(r, checker::check::kMeasurementProcedure), 1U);
}

TEST(CarefulMaster, APowerInterruptionIsFollowedByAMeasurementAndTheSelectionsAgain) {
  auto s = test_support::make_scenario(10, MHz(4), true, 0);
  s.master.t_st = us(2);
  master::Operation select = op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0x4C);  // temperature 1
  master::Operation reads_before = s.script.back();
  reads_before.count = 5;
  reads_before.cycle = us(100);
  master::Operation pause;
  pause.kind = master::Operation::Kind::Wait;
  pause.duration = ms(3);
  master::Operation reads_after = reads_before;
  s.script = {s.script.front(), select, reads_before, pause, reads_after};
  scenarios::Event cut;
  cut.kind = K::PowerInterruption;
  cut.at = ms(2);
  cut.duration = ms(1);
  s.events.push_back(cut);
  const auto careful = scenarios::run_scenario(s);
  EXPECT_EQ(careful.remeasurements, 1U);
  EXPECT_EQ(count(careful, O::Ok), 12U) << "selection, 5 reads, the selection again, 5 reads";
  EXPECT_EQ(careful.frames.back().additional_data.size(), 1U);
  s.master.careful.reselect_after_power_interruption = false;
  const auto careless = scenarios::run_scenario(s);
  EXPECT_EQ(count(careless, O::CrcError), 5U) << "expects additional data the encoder forgot";
}

// ---- parameter checksum (3.5.26) ------------------------------------------------------------------

TEST(MasterChecksum, VerifyChecksumReadsWords4To47AndComparesWord47) {
  auto s = test_support::make_scenario(10, MHz(2), false, 1);
  s.line.cable_length_m = 2;
  master::Operation check;
  check.kind = master::Operation::Kind::VerifyChecksum;
  s.script = {check};
  const auto good = scenarios::run_scenario(s);
  ASSERT_TRUE(good.checksum.has_value());
  EXPECT_TRUE(good.checksum->complete);
  EXPECT_TRUE(good.checksum->ok());
  EXPECT_EQ(good.frames.size(), 47U) << "3 selections, 44 words";
  scenarios::Event corrupt;
  corrupt.kind = K::CorruptWord;
  corrupt.at = Time::zero();
  corrupt.selection.area = protocol::MemoryArea::Manufacturer2;
  corrupt.address = 4;  // word 20
  corrupt.xor_mask = 0x0001;
  s.events.push_back(corrupt);
  const auto bad = scenarios::run_scenario(s);
  ASSERT_TRUE(bad.checksum.has_value());
  EXPECT_TRUE(bad.checksum->complete);
  EXPECT_FALSE(bad.checksum->ok());
  EXPECT_EQ(static_cast<std::uint16_t>(bad.checksum->computed - good.checksum->computed), 0x0001);
}

namespace {

master::FrameResult frame(master::FrameOutcome outcome) {
  master::FrameResult f;
  f.outcome = outcome;
  return f;
}

}  // namespace

// 2.1.2: with delay compensation, remeasure_after_crc_errors failed frames in a row call for a new
// measurement; a good frame between them starts the count again; measurement frames do not count.
TEST(CarefulPolicy, FailedFramesInARowCallForANewMeasurement) {
  master::CarefulMaster params;
  params.remeasure_after_crc_errors = 3;
  master::CarefulPolicy careful(params, true);
  careful.frame_done(frame(master::FrameOutcome::CrcError));
  careful.frame_done(frame(master::FrameOutcome::CrcError));
  careful.frame_done(frame(master::FrameOutcome::Ok));
  careful.frame_done(frame(master::FrameOutcome::NoStartBit));
  auto measurement = frame(master::FrameOutcome::CrcError);
  measurement.measurement = true;
  careful.frame_done(measurement);
  careful.frame_done(frame(master::FrameOutcome::TooFewClocks));
  EXPECT_FALSE(careful.interruption_due());
  careful.frame_done(frame(master::FrameOutcome::EchoMismatch));
  ASSERT_TRUE(careful.interruption_due());
  const auto due = careful.take_interruption();
  EXPECT_TRUE(due.remeasure);
  EXPECT_FALSE(due.reselect);
  EXPECT_FALSE(careful.interruption_due());
  EXPECT_EQ(careful.remeasurements(), 1U);
  master::CarefulPolicy uncompensated(params, false);
  for (int i = 0; i < 5; ++i) uncompensated.frame_done(frame(master::FrameOutcome::CrcError));
  EXPECT_FALSE(uncompensated.interruption_due()) << "without delay compensation there is no t_D to measure";
}

// A position read repeats each failed frame up to `retries` times in a row; a frame that did not
// fail (type II is an answer) gives the retries back.
TEST(CarefulPolicy, RetriesAreUsedByFailedFramesInARowAndGivenBackByAnyOther) {
  master::CarefulMaster params;
  params.retries = 2;
  master::CarefulPolicy careful(params, false);
  careful.position_read_started();
  const auto crc = frame(master::FrameOutcome::CrcError);
  EXPECT_TRUE(careful.retry(crc, true));
  EXPECT_TRUE(careful.retry(crc, true));
  EXPECT_FALSE(careful.retry(crc, true)) << "two retries used";
  EXPECT_TRUE(careful.retry(crc, true)) << "the refusal gave them back";
  EXPECT_FALSE(careful.retry(frame(master::FrameOutcome::Type2Error), true));
  EXPECT_TRUE(careful.retry(crc, true));
  EXPECT_FALSE(careful.retry(crc, false)) << "only position reads are repeated";
  EXPECT_EQ(careful.retries(), 4U);
}

// 2.4.2.2: what the encoder accepted as additional data 1 and 2; a stop code ends one, a reset
// (2.7) both; after a power interruption they are selected again, additional data 2 first.
TEST(AdditionalDataSelection, FollowsTheSelectionsTheEncoderAccepted) {
  const auto select = [](std::uint8_t mrs) {
    master::FrameResult f;
    f.command = protocol::ModeCommand::EncoderSendPositionValuesAndSelectionOfMemoryArea;
    f.supplement = protocol::make_payload(mrs, 0);
    return f;
  };
  master::AdditionalDataSelection s;
  EXPECT_EQ(s.count(), 0U);
  s.accepted(select(protocol::selection_mrs(protocol::Information::Temperature1)));
  s.accepted(select(protocol::selection_mrs(protocol::Information::Commutation)));
  s.accepted(select(0xA1));  // a memory area, not additional data
  EXPECT_EQ(s.count(), 2U);
  EXPECT_EQ(s.additional_data_1(), protocol::Information::Temperature1);
  s.accepted(select(protocol::kStopAdditionalData1));
  EXPECT_EQ(s.count(), 1U);
  EXPECT_FALSE(s.additional_data_1());
  s.accepted(select(protocol::selection_mrs(protocol::Information::Temperature2)));
  EXPECT_EQ(s.take(), (std::vector<std::uint8_t>{protocol::selection_mrs(protocol::Information::Commutation),
                                                 protocol::selection_mrs(protocol::Information::Temperature2)}));
  EXPECT_EQ(s.count(), 0U);
  s.accepted(select(protocol::selection_mrs(protocol::Information::Temperature1)));
  master::FrameResult reset;
  reset.command = protocol::ModeCommand::EncoderReceiveReset;
  s.accepted(reset);
  EXPECT_EQ(s.count(), 0U);
}
