// Operating status word 3, function initialization (3.4.4): the bit pairs, activation by
// "Encoder receive reset" or power-on, and what each modelled function does on the wire. The
// master reads and writes the encoder through its own frames; nothing looks inside the encoder.
#include <gtest/gtest.h>

#include "endatsim/protocol/parameters.hpp"
#include "scenario_support.hpp"
#include "endatsim/slave/encoder.hpp"

using namespace endatsim;
using namespace endatsim::sim;
using endatsim::test_support::op;
using MC = protocol::ModeCommand;
using F = protocol::parameters::EncoderFunction;
namespace pm = protocol::parameters;

namespace {

master::Operation read_position() { return op(MC::EncoderSendPositionValues); }

master::Operation await_not_busy() {
  master::Operation o;
  o.kind = master::Operation::Kind::AwaitNotBusy;
  o.count = 100;
  o.cycle = us(50);
  return o;
}

master::Operation wait(Time t) {
  master::Operation o;
  o.kind = master::Operation::Kind::Wait;
  o.duration = t;
  return o;
}

// 2.1 frames (3.4.4: "only activated after the mode command Encoder receive reset").
std::vector<master::Operation> write_word3_and_reset(std::uint16_t value) {
  return {op(MC::SelectionOfMemoryArea, 0xB9), op(MC::EncoderReceiveParameters, 3, value),
          op(MC::EncoderReceiveReset)};
}

std::vector<master::Operation> read_operating_status(std::uint8_t word) {
  return {op(MC::SelectionOfMemoryArea, 0xB9), op(MC::EncoderSendParameters, word)};
}

scenarios::Scenario scenario(std::vector<std::vector<master::Operation>> parts) {
  auto s = test_support::make_scenario(10, MHz(1), false, 1);
  s.script.clear();
  for (const auto& part : parts) s.script.insert(s.script.end(), part.begin(), part.end());
  s.encoder.t_ac_read = us(100);
  s.encoder.t_ac_write = us(300);
  s.encoder.reset_time = Time::zero();
  return s;
}

// 13 bits per revolution, 12 bits of revolutions (2.3.4.1), word 3 as stored at power-on.
void make_multiturn(scenarios::Scenario& s, std::uint64_t start, std::uint16_t word3) {
  s.encoder.kind = slave::EncoderKind::Multiturn;
  s.encoder.position_bits = 25;
  s.encoder.multiturn_bits = 12;
  s.encoder.motion.start = start;
  s.encoder.memory = slave::default_memory_image(s.encoder);
  s.encoder.memory->areas[protocol::MemoryArea::OperatingStatus][slave::word::kFunctionInitialization] = word3;
}

const master::FrameResult& frame_of(const scenarios::ScenarioResult& r, std::size_t operation) {
  const master::FrameResult* f = nullptr;
  for (const auto& x : r.frames)
    if (x.operation == operation) f = &x;
  if (f == nullptr) throw std::runtime_error("no frame for operation " + std::to_string(operation));
  return *f;
}

}  // namespace

// ---- the word itself -----------------------------------------------------------------------------

TEST(FunctionInitializationWord, EveryFunctionDeactivatedIsTheInversePatternOfEachPair) {
  // 3.4.4: bits 0/1, 2/3, 4/5, 6/7 and 11/12 are pairs; 8, 9, 10 and 13 single bits.
  EXPECT_EQ(pm::encode_function_initialization({}), 0x10AA);
  const F all[] = {F::ShortRecoveryTime,          F::ReferencePulseInitialization, F::Oversampling,
                   F::CyclicOperation,            F::MultiturnOverflowErrorMessage, F::MultiturnOverflowLatch,
                   F::MultiturnErrorMessages,     F::MultiturnCounterReset,        F::DiagnosticsReset};
  EXPECT_EQ(pm::encode_function_initialization(all), 0x2F55);
  for (F f : all) {
    const F one[] = {f};
    const auto w = pm::encode_function_initialization(one);
    for (F g : all) EXPECT_EQ(pm::function_activated(w, g), g == f) << pm::function_initialization_string(w);
  }
}

TEST(FunctionInitializationWord, APairStoredEquallyLeavesTheFunctionDeactivated) {
  EXPECT_FALSE(pm::function_activated(0x0003, F::ShortRecoveryTime));
  EXPECT_FALSE(pm::function_activated(0x0000, F::ShortRecoveryTime));
  EXPECT_FALSE(pm::function_activated(0x1800, F::MultiturnCounterReset));
  EXPECT_TRUE(pm::function_activated(0x0001, F::ShortRecoveryTime)) << "the factory setting is 0002h (3.4.4)";
  EXPECT_EQ(pm::function_initialization_string(0x0002), "none activated");
  EXPECT_EQ(pm::function_initialization_string(0x0811), "short recovery time I, oversampling, multiturn counter reset");
}

// ---- multiturn counter reset (bits 11/12) --------------------------------------------------------

TEST(MultiturnCounterReset, ZeroesTheRevolutionsAtTheResetAndKeepsTheStepsWithinTheRevolution) {
  const F reset_on[] = {F::MultiturnCounterReset};
  auto s = scenario({{read_position()},
                     write_word3_and_reset(pm::encode_function_initialization(reset_on)),
                     {read_position()},
                     write_word3_and_reset(pm::encode_function_initialization({})),
                     {read_position()}});
  make_multiturn(s, (std::uint64_t{5} << 13) + 1234, pm::encode_function_initialization({}));
  const auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.finished);
  EXPECT_EQ(frame_of(r, 0).position, (5U << 13) + 1234U);
  EXPECT_EQ(frame_of(r, 4).position, 1234U) << "revolution 5 became revolution 0";
  EXPECT_EQ(frame_of(r, 8).position, 1234U) << "deactivating does not bring the old count back";
}

TEST(MultiturnCounterReset, LeftActivatedItZeroesTheCountAgainAtEveryReset) {
  // 3.4.4: "the deactivation ... must be performed actively (e.g. resetting the multiturn
  // counter reset)". One revolution per 10 ms.
  const F reset_on[] = {F::MultiturnCounterReset};
  auto s = scenario({{wait(ms(25)), read_position(), op(MC::EncoderReceiveReset), read_position()}});
  make_multiturn(s, 100, pm::encode_function_initialization(reset_on));
  s.encoder.motion.counts_per_s = 8192 * 100;
  const auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.finished);
  const auto before = frame_of(r, 1).position, after = frame_of(r, 3).position;
  EXPECT_EQ(before >> 13, 2U) << "counted from power-on, where the count was zeroed";
  const auto steps = static_cast<std::uint64_t>((frame_of(r, 3).start - frame_of(r, 1).start).count()) * 8192 * 100 /
                     1'000'000'000'000;
  EXPECT_EQ(after >> 13, ((before + steps) >> 13) - 2) << "the reset zeroed revolution 2 again";
  EXPECT_NEAR(static_cast<double>(after & 0x1FFF), static_cast<double>((before + steps) & 0x1FFF), 2.0)
      << "the steps within the revolution run on";
}

// ---- multiturn overflow error message and latch (bits 8, 9) --------------------------------------

namespace {

// The count leaves 2^25 after 100 us (one step per microsecond).
scenarios::Scenario overflow_scenario(std::span<const F> functions) {
  std::vector<master::Operation> reads{read_position(), wait(us(200)), read_position()};
  auto s = scenario({reads, read_operating_status(0)});
  make_multiturn(s, (std::uint64_t{1} << 25) - 100, pm::encode_function_initialization(functions));
  s.encoder.motion.counts_per_s = 1'000'000;
  return s;
}

}  // namespace

TEST(MultiturnOverflow, DeactivatedTheCounterWrapsWithoutAnError) {
  const auto r = scenarios::run_scenario(overflow_scenario({}));
  ASSERT_TRUE(r.finished);
  EXPECT_FALSE(frame_of(r, 0).error1);
  EXPECT_FALSE(frame_of(r, 2).error1);
  EXPECT_LT(frame_of(r, 2).position, 1000U) << "wrapped past 2^25";
  EXPECT_EQ(frame_of(r, 4).echo_parameter, 0x0000);
}

TEST(MultiturnOverflow, TheMessageSetsF1InTheFramesAfterTheOverflow) {
  const F on[] = {F::MultiturnOverflowErrorMessage};
  const auto r = scenarios::run_scenario(overflow_scenario(on));
  ASSERT_TRUE(r.finished);
  EXPECT_FALSE(frame_of(r, 0).error1);
  EXPECT_TRUE(frame_of(r, 2).error1);
  EXPECT_EQ(frame_of(r, 4).echo_parameter, 0x0000) << "unlatched: not stored in word 0";
}

TEST(MultiturnOverflow, LatchedTheErrorIsStoredInWord0) {
  const F on[] = {F::MultiturnOverflowErrorMessage, F::MultiturnOverflowLatch};
  const auto r = scenarios::run_scenario(overflow_scenario(on));
  ASSERT_TRUE(r.finished);
  EXPECT_TRUE(frame_of(r, 2).error1);
  EXPECT_EQ(frame_of(r, 4).echo_parameter, 0x0004) << "word 0 bit 2^2 (position), the model's default";
}

// ---- EnDat 2.2 cyclic operation (bits 6/7) -------------------------------------------------------

TEST(CyclicOperation, ActivatedItShowsAsWarningBit5) {
  // 3.4.2: word 1 bit 2^5 "cyclic mode".
  const F on[] = {F::CyclicOperation};
  auto s = scenario({read_operating_status(1), write_word3_and_reset(pm::encode_function_initialization(on)),
                     {read_position()}, read_operating_status(1)});
  const auto r = scenarios::run_scenario(s);
  ASSERT_TRUE(r.finished);
  EXPECT_EQ(frame_of(r, 1).echo_parameter, 0x0000);
  EXPECT_EQ(frame_of(r, 7).echo_parameter, 0x0020);
}

// ---- oversampling (bits 4/5) and the asynchronous position's time delay (2.4.2.3) ----------------

namespace {

// One step per microsecond: the asynchronous position k time-delay steps back is k smaller.
scenarios::Scenario asynchronous_position(std::uint16_t word3, std::uint8_t time_delay) {
  auto s = scenario({{op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, 0x60, time_delay), await_not_busy(),
                      op(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea,
                         protocol::selection_mrs(protocol::Information::AsynchronousPositionWord1)),
                      op(MC::EncoderSendPositionValuesWithAdditionalData)}});
  s.encoder.motion.start = 50'000;
  s.encoder.motion.counts_per_s = 1'000'000;
  s.encoder.memory = slave::default_memory_image(s.encoder);
  s.encoder.memory->areas[protocol::MemoryArea::OperatingStatus][slave::word::kFunctionInitialization] = word3;
  return s;
}

std::uint16_t asynchronous_word1(const scenarios::Scenario& s) {
  const auto r = scenarios::run_scenario(s);
  EXPECT_TRUE(r.finished);
  const auto& f = frame_of(r, 3);
  EXPECT_EQ(f.outcome, master::FrameOutcome::Ok);
  if (f.additional_data.size() != 1) {
    ADD_FAILURE() << "expected one additional datum, got " << f.additional_data.size();
    return 0;
  }
  EXPECT_EQ(f.additional_data[0].information(), protocol::Information::AsynchronousPositionWord1);
  return static_cast<std::uint16_t>(f.additional_data[0].data - f.position);
}

}  // namespace

TEST(AsynchronousPosition, WithOversamplingTimeDelayKIsKStepsBeforeTheLatch) {
  const F on[] = {F::Oversampling};
  EXPECT_EQ(asynchronous_word1(asynchronous_position(pm::encode_function_initialization(on), 50)),
            static_cast<std::uint16_t>(-50));
  EXPECT_EQ(asynchronous_word1(asynchronous_position(pm::encode_function_initialization(on), 0)), 0);
}

TEST(AsynchronousPosition, WithoutOversamplingOnlyTimeDelay0) {
  EXPECT_EQ(asynchronous_word1(asynchronous_position(pm::encode_function_initialization({}), 50)), 0);
}
