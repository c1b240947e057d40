// The small parts the encoder and the master are built from, each on its own: the bits of a frame
// (slave/frame_bits.hpp), the bounded frame log (sim/record_log.hpp), the master's operation queue
// (master/operation.hpp), the frames that read the EnDat 2.2 area (master/startup.hpp), a busy
// wait's polls (master/busy_polling.hpp), when the master's clock edges are due
// (master/clock_timing.hpp), its search for the start bit (master/start_bit_hunt.hpp) and the encoder's decisions on commands with 8 + 16 bits
// (slave/parameter_commands.hpp). The delay measurement's part test is with the master's.
#include <gtest/gtest.h>

#include <vector>

#include "endatsim/master/busy_polling.hpp"
#include "endatsim/master/clock_timing.hpp"
#include "endatsim/master/operation.hpp"
#include "endatsim/master/start_bit_hunt.hpp"
#include "endatsim/master/startup.hpp"
#include "endatsim/protocol/error_handling.hpp"
#include "endatsim/protocol/parameters.hpp"
#include "endatsim/sim/record_log.hpp"
#include "endatsim/slave/encoder_params.hpp"
#include "endatsim/slave/frame_bits.hpp"
#include "endatsim/slave/parameter_commands.hpp"
#include "endatsim/slave/position_source.hpp"

namespace endatsim {
namespace {

using sim::Time;

TEST(AnswerBits, StartsNoEarlierThanItsClockAndTime) {
  slave::AnswerBits a;
  a.load({1, 0, 1});
  a.not_before(11, sim::us(5));
  EXPECT_FALSE(a.start_due(10, sim::us(6)));  // RE10: before RE11
  EXPECT_FALSE(a.start_due(11, sim::us(5) - Time{1}));  // t_cal not over by 1 ps
  EXPECT_TRUE(a.start_due(11, sim::us(5)));
  EXPECT_FALSE(a.started());
}

TEST(AnswerBits, SendsEachBitOnceInOrderAndAppendedBitsFollow) {
  slave::AnswerBits a;
  a.load({1, 0});
  a.bits().push_back(1);  // additional data appended after the CRC (2.3.5)
  std::vector<bool> sent;
  while (!a.sent()) sent.push_back(a.next());
  EXPECT_EQ(sent, (std::vector<bool>{true, false, true}));
  EXPECT_TRUE(a.started());
  a.clear();
  EXPECT_FALSE(a.started());
  EXPECT_TRUE(a.sent());  // nothing left to send
}

TEST(ReceivedBits, TakesTwentyFourBitsMsbFirst) {
  protocol::ReceivedBits r;
  const std::uint32_t payload = 0xB9'1234;  // MRS B9h, parameter 1234h
  for (int i = static_cast<int>(protocol::kPayloadBits) - 1; i >= 0; --i) {
    const bool last = r.take(((payload >> i) & 1U) != 0);
    EXPECT_EQ(last, i == 0) << "bit " << i;
  }
  EXPECT_EQ(r.value(), payload);
  r.clear();
  EXPECT_FALSE(r.take(true));
  EXPECT_EQ(r.value(), 1U);
}

TEST(SupplementStart, IgnoresTheFirstEdgesThenTakesTheHighAfterALow) {
  protocol::SupplementStart s;
  s.handed_over(40);
  EXPECT_FALSE(s.found(41, false, 3));  // ignored: the encoder's own last bit fades
  EXPECT_FALSE(s.found(43, true, 3));
  EXPECT_FALSE(s.found(44, true, 3));   // the floating line reads HIGH: no LOW seen yet
  EXPECT_FALSE(s.found(45, false, 3));  // the master's lead bits
  EXPECT_TRUE(s.found(46, true, 3));    // the start bit
  s.handed_over(50);
  EXPECT_FALSE(s.found(54, true, 3));   // a new hand-over waits for a LOW again
}

TEST(RecordLog, KeepFirstKeepsTheFirstNAndCountsEveryRecord) {
  sim::RecordLog<int> log(sim::RecordLog<int>::Keep::First);
  log.keep(3);
  for (int i = 0; i < 10; ++i) log.add(i);
  EXPECT_EQ(log.records(), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(log.count(), 10U);
}

TEST(RecordLog, KeepFirstZeroKeepsNothing) {
  sim::RecordLog<int> log(sim::RecordLog<int>::Keep::First);
  log.keep(0);
  log.add(1);
  EXPECT_TRUE(log.records().empty());
  EXPECT_EQ(log.count(), 1U);
}

TEST(RecordLog, KeepRecentKeepsTheLastNToTwoNAndTheLastRecordAlways) {
  sim::RecordLog<int> log(sim::RecordLog<int>::Keep::Recent);
  log.keep(3);
  for (int i = 0; i < 6; ++i) log.add(i);
  EXPECT_EQ(log.records(), (std::vector<int>{0, 1, 2, 3, 4, 5}));  // 2n: not trimmed yet
  log.add(6);
  EXPECT_EQ(log.records(), (std::vector<int>{4, 5, 6}));
  log.last() = 60;
  EXPECT_EQ(log.records().back(), 60);
  EXPECT_EQ(log.count(), 7U);
  log.keep(0);  // at least the record being written: one to two kept
  log.add(7);
  EXPECT_EQ(log.records(), (std::vector<int>{7}));
  log.add(8);
  EXPECT_EQ(log.records(), (std::vector<int>{7, 8}));
  log.add(9);
  EXPECT_EQ(log.records(), (std::vector<int>{9}));
}

TEST(OperationQueue, NumbersTheScriptsOperationsAndRunsWhatIsPutInFrontFirst) {
  master::OperationQueue q;
  master::Operation a, b, front;
  a.kind = master::Operation::Kind::ReadPosition;
  b.kind = master::Operation::Kind::Wait;
  front.kind = master::Operation::Kind::MeasureDelay;
  q.enqueue(a);
  q.enqueue(b);
  std::vector<master::Operation> sequence(2);
  sequence[0].kind = master::Operation::Kind::StartupRoutine;
  sequence[1].kind = master::Operation::Kind::VerifyChecksum;
  q.insert_front(sequence);
  q.push_front(front);
  EXPECT_EQ(q.take().kind, master::Operation::Kind::MeasureDelay);
  EXPECT_EQ(q.take().kind, master::Operation::Kind::StartupRoutine);
  EXPECT_EQ(q.take().kind, master::Operation::Kind::VerifyChecksum);
  const master::Operation first = q.take();
  EXPECT_EQ(first.kind, master::Operation::Kind::ReadPosition);
  EXPECT_EQ(first.script_index, 0U);
  EXPECT_EQ(q.take().script_index, 1U);
  EXPECT_TRUE(q.empty());
}

TEST(Endat22AreaRead, NothingIsPlannedWithoutTheEndat22CommandSetInWord37) {
  master::Sequence plan;
  EXPECT_FALSE(master::plan_endat22_read(plan, ~std::uint64_t{0}, std::nullopt));  // word 37 unread
  const protocol::parameters::CommandSet only21;  // 2.1 only: 002Ah
  EXPECT_FALSE(master::plan_endat22_read(plan, ~std::uint64_t{0}, protocol::parameters::encode_command_set(only21)));
  EXPECT_TRUE(plan.ops.empty());
}

TEST(Endat22AreaRead, EachWordIsSelectedAwaitedAndReadAsLsbAndMsb) {
  protocol::parameters::CommandSet both;
  both.endat22 = true;
  master::Sequence plan;
  ASSERT_TRUE(master::plan_endat22_read(plan, (std::uint64_t{1} << 3) | (std::uint64_t{1} << 40), protocol::parameters::encode_command_set(both)));
  // Select memory parameter LSB and area BD, await; then per word: read, await, MSB, read, LSB.
  ASSERT_EQ(plan.ops.size(), 3U + 2U * 5U);
  EXPECT_EQ(plan.ops[1].address, protocol::mrs_of(protocol::MemoryArea::ManufacturerEndat22));
  const master::Operation& await = plan.ops[2];
  EXPECT_EQ(await.kind, master::Operation::Kind::AwaitNotBusy);
  EXPECT_GE(await.cycle * await.count, protocol::limit::kMemoryAccessMax);  // polls past t_ac max (2.3.2)
  EXPECT_EQ(plan.ops[3].address, 3U);
  EXPECT_EQ(plan.ops[6].purpose, master::Operation::Purpose::Endat22Msb);
  EXPECT_EQ(plan.ops[6].manufacturer_word, 3U);
  EXPECT_EQ(plan.ops[8].address, 40U);
}

TEST(TypeTwoAcknowledgment, ReturnsTheAddressAndParameterInvertedOnlyWithAnError) {
  // A2 type II: "the address or parameter is returned inverted".
  EXPECT_EQ(protocol::acknowledged_address(0xA1, true), 0x5E);
  EXPECT_EQ(protocol::acknowledged_parameter(0x1234, true), 0xEDCB);
  EXPECT_EQ(protocol::acknowledged_address(0xA1, false), 0xA1);
  EXPECT_EQ(protocol::acknowledged_parameter(0x1234, false), 0x1234);
}

// 2.5.1 / 2.6.1: additional data 1 carries the busy bit an await_not_busy polls for.
master::FrameResult poll(std::optional<protocol::Information> information, bool busy, master::FrameOutcome outcome) {
  master::FrameResult f;
  f.outcome = outcome;
  if (information) {
    master::AdditionalDatum d;
    d.status = static_cast<std::uint8_t>(static_cast<std::uint8_t>(*information) | (busy ? protocol::AdditionalDataStatus::kBusy : 0));
    f.additional_data.push_back(d);
  }
  return f;
}

TEST(BusyPolling, AWaitEndsWhenBusyIsResetOrCannotBeSeenAndTimesOutOnTheLastPoll) {
  using I = protocol::Information;
  using O = master::FrameOutcome;
  master::BusyPolling polling;
  EXPECT_FALSE(polling.poll_ends_wait(poll(I::MemoryParameterLsb, true, O::Ok), false));
  EXPECT_FALSE(polling.poll_ends_wait(poll(I::MemoryParameterLsb, false, O::CrcError), false));  // not read
  EXPECT_TRUE(polling.poll_ends_wait(poll(I::MemoryParameterLsb, false, O::Ok), false));
  EXPECT_EQ(polling.timeouts(), 0U);
  EXPECT_EQ(polling.unreadable(), 0U);
  EXPECT_TRUE(polling.poll_ends_wait(poll(std::nullopt, false, O::Ok), false));  // no additional data 1
  EXPECT_TRUE(polling.poll_ends_wait(poll(I::Commutation, false, O::Ok), false));  // additional data 2 only
  EXPECT_EQ(polling.unreadable(), 2U);
  EXPECT_FALSE(polling.poll_ends_wait(poll(I::MemoryParameterLsb, true, O::Ok), true));
  EXPECT_EQ(polling.timeouts(), 1U);
}

TEST(StartBitHunt, AHighCountsOnlyAfterALowAndHighsBeforeAnyLowAreATypeOneError) {
  using R = master::StartBitHunt::Result;
  master::StartBitHunt h;
  h.begin(true);
  EXPECT_EQ(h.sample(true, 3), R::Waiting);  // the fail-safe HIGH of the undriven line
  EXPECT_EQ(h.sample(false, 3), R::Waiting);  // the LOW
  EXPECT_EQ(h.sample(false, 3), R::Waiting);
  EXPECT_EQ(h.sample(true, 3), R::StartBit);
  h.begin(true);
  EXPECT_EQ(h.sample(true, 3), R::Waiting);
  EXPECT_EQ(h.sample(true, 3), R::Waiting);
  EXPECT_EQ(h.sample(true, 3), R::Type1Error);  // A2 type I: DATA held HIGH
  h.begin(false);  // the first HIGH is the start bit
  EXPECT_EQ(h.sample(false, 3), R::Waiting);
  EXPECT_EQ(h.sample(true, 3), R::StartBit);
}

TEST(ClockTiming, PhasesFollowTheDutyCycleAndTheFirstLowPhaseIsStretchedToTst) {
  master::MasterParams p;
  p.high_permille = 400;
  p.t_st = sim::us(2);
  master::ClockTiming t(p);
  t.begin(sim::MHz(1), sim::us(10));  // FE1 at 10 us
  EXPECT_EQ(t.high(), sim::ns(400));
  EXPECT_EQ(t.low(), sim::ns(600));
  EXPECT_EQ(t.after_falling(1, sim::us(10)), sim::us(12));  // 2.3.2 note 8: t_ST after FE1
  EXPECT_EQ(t.after_rising(sim::us(12)), sim::ns(12400));
  EXPECT_EQ(t.after_falling(2, sim::ns(12400)), sim::us(13));
}

TEST(ClockTiming, JitterMovesEachEdgeAroundItsNominalTimeWithoutAccumulating) {
  master::MasterParams p;
  p.jitter = sim::ns(5);
  master::ClockTiming t(p);
  t.begin(sim::MHz(1), Time::zero());
  Time nominal = Time::zero(), now = Time::zero();
  bool moved = false;
  for (unsigned clock = 1; clock < 200; ++clock) {
    nominal += clock == 1 ? std::max(t.low(), p.t_st) : t.low();
    now = t.after_falling(clock, now);
    EXPECT_LE(now > nominal ? now - nominal : nominal - now, p.jitter);
    moved = moved || now != nominal;
    nominal += t.high();
    now = t.after_rising(now);
    EXPECT_LE(now > nominal ? now - nominal : nominal - now, p.jitter);
  }
  EXPECT_TRUE(moved);
}

// The encoder's decisions on 2.1 commands with 8 + 16 bits, without its frame engine.
struct ParameterCommandsFixture : ::testing::Test {
  struct NoClient : slave::MemoryAccess::Client {
    void written(const slave::Selection&, std::uint8_t) override {}
  };
  sim::Kernel kernel;
  slave::EncoderParams params;
  slave::Memory memory{slave::default_memory_image(params)};
  slave::PositionSource positions{params, memory};
  slave::AdditionalData additional_data{params, memory, positions};
  NoClient client;
  slave::MemoryAccess access{kernel, memory, additional_data, client};
  slave::EibCommissioning eib{params, memory};
  slave::BusAddressing bus;
  slave::ParameterCommands commands{params, memory, access, additional_data, eib, bus};
  using Kind = slave::ParameterCommands::Pending::Kind;
  static std::uint32_t payload(std::uint8_t address, std::uint16_t parameter) { return protocol::make_payload(address, parameter); }
};

TEST_F(ParameterCommandsFixture, ASelectionIsAcknowledgedAndCarriedOutOnceWhenTheFrameCompletes) {
  const auto mrs = protocol::mrs_of(protocol::MemoryArea::OperatingParameters);
  const auto d = commands.decide(protocol::ModeCommand::SelectionOfMemoryArea, payload(mrs, 0x1234), kernel.now());
  EXPECT_FALSE(d.error);
  EXPECT_FALSE(d.silent);
  EXPECT_EQ(d.address, mrs);  // 2.4.1: the MRS code and parameter echoed
  EXPECT_EQ(d.parameter, 0x1234);
  EXPECT_EQ(d.start_delay, params.t_ac_read);  // in frame: the start bit waits for t_ac
  const auto p = commands.take_pending();
  EXPECT_EQ(p.kind, Kind::Select);
  EXPECT_EQ(p.selection.area, protocol::MemoryArea::OperatingParameters);
  EXPECT_EQ(commands.take_pending().kind, Kind::None);
}

TEST_F(ParameterCommandsFixture, AFrameCutShortMakesTheNextAcknowledgmentATypeTwoErrorOnce) {
  commands.transmission_cut_short();
  const auto mrs = protocol::mrs_of(protocol::MemoryArea::OperatingParameters);
  const auto d = commands.decide(protocol::ModeCommand::SelectionOfMemoryArea, payload(mrs, 0x1234), kernel.now());
  EXPECT_EQ(d.error, protocol::ErrorCause::TransmissionNotCompleted);  // A2 cause 3
  EXPECT_EQ(d.address, protocol::acknowledged_address(mrs, true));
  EXPECT_EQ(d.parameter, protocol::acknowledged_parameter(0x1234, true));
  EXPECT_EQ(d.start_delay, sim::Time::zero());
  EXPECT_EQ(commands.take_pending().kind, Kind::None);  // the access is discarded
  EXPECT_FALSE(commands.decide(protocol::ModeCommand::SelectionOfMemoryArea, payload(mrs, 0), kernel.now()).error);
}

TEST_F(ParameterCommandsFixture, ASupplementSelectsAdditionalDataAndAMemoryAccessMeetingBusyIsIgnored) {
  using MC = protocol::ModeCommand;
  const auto mrs = protocol::selection_mrs(protocol::Information::Temperature1);
  const auto d = commands.decide_supplement(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, payload(mrs, 0));
  EXPECT_FALSE(d.memory_access);
  EXPECT_FALSE(d.ignored);
  EXPECT_EQ(additional_data.selected(protocol::AdditionalDataNumber::One), protocol::Information::Temperature1);
  access.busy_until(kernel.now() + sim::us(1));  // 2.3.1 note 1: a 2.2 access meeting Busy is ignored
  const auto area = protocol::mrs_of(protocol::MemoryArea::OperatingParameters);
  const auto busy = commands.decide_supplement(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, payload(area, 0));
  EXPECT_TRUE(busy.ignored);
  EXPECT_FALSE(busy.error);
}

TEST_F(ParameterCommandsFixture, TheTestCommandSetsThePortUntilARestart) {
  EXPECT_EQ(commands.test_port(), 0);
  EXPECT_FALSE(commands.decide(protocol::ModeCommand::EncoderReceiveTestCommand, payload(0x5A, 0), kernel.now()).error);
  EXPECT_EQ(commands.test_port(), 0x5A);
  commands.restart();
  EXPECT_EQ(commands.test_port(), 0);
}

}  // namespace
}  // namespace endatsim
