#include <gtest/gtest.h>

#include <algorithm>

#include "endatsim/slave/encoder.hpp"
#include "endatsim/slave/memory.hpp"
#include "test_support.hpp"

using namespace endatsim;
using namespace endatsim::sim;
using endatsim::test_support::PinSampler;
using endatsim::test_support::ScriptedClock;

namespace {

struct Bench {
  explicit Bench(slave::EncoderParams ep, double cable_m = 0) : line(k, lp(cable_m)), encoder(k, line, ep), sampler(k, line) {}
  static line::LineParams lp(double m) {
    line::LineParams p;
    p.cable_length_m = m;
    return p;
  }
  Kernel k;
  line::Line line;
  slave::Encoder encoder;
  PinSampler sampler;
};

slave::EncoderParams encoder_params(protocol::EndatVersion v, unsigned bits, std::uint64_t position) {
  slave::EncoderParams p;
  p.version = v;
  p.position_bits = bits;
  p.t_cal = Time::zero();
  p.motion.start = position;
  return p;
}

}  // namespace

// Hand-derived from spec 2.3 and docs/model.md §1/§2: slots 9 and 10 LOW (turnaround),
// start bit at RE11, F1, position LSB first, CRC, then DATA HIGH (end of data).
// The defaults the checker's declarations and decoder take for an encoder they are not told
// about (protocol::encoder_default) are those of the encoder model and its line.
TEST(EncoderDefaults, AreWhatTheDeclarationsAndTheDecoderAssume) {
  const slave::EncoderParams e;
  const line::LineParams l;
  namespace d = protocol::encoder_default;
  EXPECT_EQ(l.encoder.receiver_delay + e.output_delay + l.encoder.driver_delay, d::kClockToData);
  EXPECT_EQ(e.position_bits, d::kPositionBits);
  EXPECT_EQ(e.t_cal, d::kCalculationTime);
  EXPECT_EQ(e.t_r, d::kRecoveryTime2);
  EXPECT_EQ(d::kRecoveryTime2, protocol::limit::kRecoveryTime2Min);  // 2.3.2: t_R 500 ns
  EXPECT_EQ(e.t_m, d::kRecoveryTime);
}

TEST(EncoderPositionFrame, EnDat21FrameIsBitExact) {
  Bench b(encoder_params(protocol::EndatVersion::V2_1, 8, 0xA5));
  ScriptedClock clock(b.k, b.line, us(1), 27, 0b000111);
  b.k.run();
  EXPECT_EQ(b.sampler.slots(9, 26), "00" "1" "0" "10100101" "11101" "1");
  ASSERT_EQ(b.encoder.frames().size(), 1U);
  EXPECT_EQ(b.encoder.frames()[0].start_bit_clock, 11U);
  EXPECT_EQ(b.encoder.frames()[0].command, protocol::ModeCommand::EncoderSendPositionValues);
}

TEST(EncoderPositionFrame, EnDat22FrameCarriesLowActiveF2) {
  Bench b(encoder_params(protocol::EndatVersion::V2_2, 8, 0xA5));
  ScriptedClock clock(b.k, b.line, us(1), 28, 0b111000);
  b.k.run();
  EXPECT_EQ(b.sampler.slots(9, 27), "00" "1" "0" "1" "10100101" "01011" "1");
}

TEST(EncoderPositionFrame, SpecCrcExampleAppearsOnTheWire) {
  // A4: 25 bits, F1 = 0, F2 = 1, position 104462 -> CRC 3 = 00011.
  Bench b(encoder_params(protocol::EndatVersion::V2_2, 25, 104462));
  ScriptedClock clock(b.k, b.line, us(1), 44, 0b111000);
  b.k.run();
  std::string pos;
  for (int i = 0; i < 25; ++i) pos += ((104462 >> i) & 1) ? '1' : '0';
  EXPECT_EQ(b.sampler.slots(11, 43), "1" "0" "1" + pos + "00011");
}

TEST(EncoderPositionFrame, StartBitWaitsForTcal) {
  auto p = encoder_params(protocol::EndatVersion::V2_2, 8, 1);
  p.t_cal = us(15);  // at 1 MHz RE_k is at (k - 0.5) us after FE1: first k >= 11 with >= 15 us is 16
  Bench b(p);
  ScriptedClock clock(b.k, b.line, us(1), 40, 0b111000);
  b.k.run();
  EXPECT_EQ(b.encoder.frames()[0].start_bit_clock, 16U);
  EXPECT_EQ(b.sampler.slots(9, 16), "00000001");
}

TEST(EncoderPositionFrame, TcalOfEnDat22CommandsMayDifferFromEnDat21s) {
  // The German brochure (both editions): absolute linear encoders take other calculation times for 2.1 and 2.2
  // mode commands. t_cal 5 us for 000111 (RE11), t_cal_22 15 us for 111000 (RE16).
  auto p = encoder_params(protocol::EndatVersion::V2_2, 8, 1);
  p.t_cal = us(5);
  p.t_cal_22 = us(15);
  for (const auto& [mode, start] : {std::pair{0b000111, 11U}, std::pair{0b111000, 16U}}) {
    Bench b(p);
    ScriptedClock clock(b.k, b.line, us(1), 40, static_cast<std::uint8_t>(mode));
    b.k.run();
    EXPECT_EQ(b.encoder.frames()[0].start_bit_clock, start) << mode;
  }
}

// 3.6.5: word 5 bit 0 switches energy-saving mode on; an encoder that declares a calculation time
// for it answers after that one, unless word 21 (3.9.15) marks the instruction not supported.
TEST(EncoderPositionFrame, EnergySavingModeTakesTheCalculationTimeTheEncoderDeclaresForIt) {
  namespace pm = protocol::parameters;
  using A = protocol::MemoryArea;
  const auto start_bit_clock = [](std::optional<Time> t_cal_energy_saving, std::uint16_t word5, std::uint16_t word21) {
    auto p = encoder_params(protocol::EndatVersion::V2_2, 8, 1);
    p.t_cal = us(5);
    p.t_cal_energy_saving = t_cal_energy_saving;
    p.memory = slave::default_memory_image(p);
    p.memory->areas.at(A::OperatingParameters).at(protocol::word::kInstructions) = word5;
    auto& endat22 = p.memory->areas.at(A::ManufacturerEndat22);
    endat22.at(protocol::word::kInstructionSupport) = word21;
    endat22.at(protocol::word::kEndat22Checksum) = pm::endat22_checksum(endat22);
    Bench b(p);
    ScriptedClock clock(b.k, b.line, us(1), 40, 0b000111);
    b.k.run();
    return b.encoder.frames().at(0).start_bit_clock;
  };
  EXPECT_EQ(start_bit_clock(us(15), pm::kInstructionEnergySaving, 0), 16U) << "at 1 MHz the first RE_k >= 15 us";
  EXPECT_EQ(start_bit_clock(us(15), 0, 0), 11U) << "the mode is off";
  EXPECT_EQ(start_bit_clock(std::nullopt, pm::kInstructionEnergySaving, 0), 11U) << "nothing declared for it";
  EXPECT_EQ(start_bit_clock(us(15), pm::kInstructionEnergySaving, pm::kInstructionEnergySaving), 11U)
      << "word 21 says the encoder does not support it";
}

TEST(EncoderPositionFrame, DataFallsLowExactlyTmAfterTheLastRisingEdge) {
  auto p = encoder_params(protocol::EndatVersion::V2_1, 8, 0xA5);
  p.t_m = us(12);
  Bench b(p, 10);
  struct Fall {
    Kernel* k;
    std::vector<Time> t;
    void on(std::uint64_t v) {
      if (v == 0) t.push_back(k->now());
    }
  } fall{&b.k, {}};
  b.line.pins(line::ObservationPoint::EncoderPins).data.on_change(bind<&Fall::on>(&fall));
  ScriptedClock clock(b.k, b.line, us(1), 26, 0b000111);
  b.k.run();
  ASSERT_FALSE(fall.t.empty());
  // Last RE at the master logic + driver 40 ns + cable 50 ns + encoder receiver 20 ns, then t_m,
  // then the encoder's output delay 20 ns and driver 20 ns.
  const Time last_re_at_encoder_logic = clock.rising().back() + ns(40) + ns(50) + ns(20);
  EXPECT_EQ(fall.t.back(), last_re_at_encoder_logic + us(12) + ns(20) + ns(20));
  EXPECT_TRUE(b.encoder.idle());
}

TEST(EncoderContinuousClock, EnDat21SendsTheNextWordAfterOneHighAndOneLowBit) {
  // 2.3.1 / HEIDENHAIN's encoder catalogue (docs/model.md §6): HIGH for one clock after the CRC,
  // then LOW; the new position is saved with the next falling edge and follows S and F1 (no new
  // mode command).
  auto p = encoder_params(protocol::EndatVersion::V2_1, 8, 0xA5);
  Bench b(p);
  ScriptedClock clock(b.k, b.line, us(1), 44, 0b000111);
  b.k.run();
  EXPECT_EQ(b.sampler.slots(26, 43), "1" "0" "1" "0" "10100101" "11101" "1");
  // FE44, after the second word's HIGH bit, saves the position for a third word.
  EXPECT_EQ(b.encoder.frames()[0].continuous_words, 2U);
}

TEST(EncoderContinuousClock, EnDat22CommandDoesNotContinue) {
  auto p = encoder_params(protocol::EndatVersion::V2_2, 8, 0xA5);
  Bench b(p);
  ScriptedClock clock(b.k, b.line, us(1), 40, 0b111000);
  b.k.run();
  EXPECT_EQ(b.sampler.slots(27, 39), "1111111111111");
  EXPECT_EQ(b.encoder.frames()[0].continuous_words, 0U);
}

TEST(EncoderType1, BrokenRedundancyAbortsWithDataHighByDefault) {
  Bench b(encoder_params(protocol::EndatVersion::V2_2, 8, 0xA5));
  ScriptedClock clock(b.k, b.line, us(1), 21, 0b000101);
  b.k.run();
  EXPECT_TRUE(b.encoder.frames()[0].type1_error);
  EXPECT_EQ(b.sampler.slots(9, 20), "111111111111");
  EXPECT_TRUE(b.encoder.idle());
  EXPECT_FALSE(b.line.pins(line::ObservationPoint::EncoderPins).data.read());  // LOW again after t_m
}

TEST(EncoderType1, HypothesisBKeepsDataLowWithoutStartBit) {
  auto p = encoder_params(protocol::EndatVersion::V2_2, 8, 0xA5);
  p.type1 = slave::Type1Handling::NoStartBit;
  Bench b(p);
  ScriptedClock clock(b.k, b.line, us(1), 21, 0b000101);
  b.k.run();
  EXPECT_EQ(b.sampler.slots(9, 20), "000000000000");
}

TEST(EncoderType1, EnDat21EncoderDoesNotSupport22Commands) {
  Bench b(encoder_params(protocol::EndatVersion::V2_1, 8, 0xA5));
  ScriptedClock clock(b.k, b.line, us(1), 20, 0b111000);
  b.k.run();
  EXPECT_TRUE(b.encoder.frames()[0].type1_error);
  EXPECT_EQ(b.encoder.frames()[0].command, protocol::ModeCommand::EncoderSendPositionValuesWithAdditionalData);
}

TEST(EncoderRecovery, ClockEdgesWithinTrAreIgnored) {
  auto p = encoder_params(protocol::EndatVersion::V2_1, 8, 0xA5);
  p.t_m = us(10);
  p.t_r = us(5);
  Bench b(p);
  ScriptedClock first(b.k, b.line, us(1), 26, 0b000111);
  // The second frame starts 12 us after the first one's last RE: t_m has passed, t_R has not.
  ScriptedClock second(b.k, b.line, us(1), 26, 0b000111, us(25) + us(12) + ns(500));
  b.k.run();
  // The encoder ends the first frame at its RE26 + t_m = 35.56 us and is ready 5 us later, at
  // 40.56 us. The second frame's edges reach its logic 60 ns after the master sends them:
  // FE1 37.56, RE1 38.06, FE2 38.56, RE2 39.06, FE3 39.56, RE3 40.06 are ignored, and FE4 at
  // 40.56 us is taken as the first falling edge of a frame - misaligned by three clocks.
  EXPECT_EQ(b.encoder.ignored_clock_edges(), 6U);
  ASSERT_EQ(b.encoder.frames().size(), 2U);
  EXPECT_EQ(b.encoder.frames()[1].start, us(40) + ns(560));
}

// The round trip the line promises (2.3.2 t_D bound) is what a start bit really takes: from the
// master's RE11 to the start bit's rising edge at the master's receiver output.
TEST(EncoderRoundTrip, StartBitEdgeArrivesOneRoundTripAfterTheRisingEdge) {
  for (double cable : {0.0, 10.0, 100.0}) {
    Bench b(encoder_params(protocol::EndatVersion::V2_2, 8, 0), cable);
    struct Rise {
      Kernel* k;
      std::vector<Time> t;
      void on(std::uint64_t v) {
        if (v != 0) t.push_back(k->now());
      }
    } rise{&b.k, {}};
    b.line.master().data_in.on_change(bind<&Rise::on>(&rise));
    ScriptedClock clock(b.k, b.line, us(5), 12, 0b111000);
    b.k.run();
    ASSERT_FALSE(rise.t.empty());
    // The first rising edge after the turnaround is the start bit at RE11.
    const auto s = std::find_if(rise.t.begin(), rise.t.end(), [&](Time t) { return t > clock.rising()[9]; });
    ASSERT_NE(s, rise.t.end());
    EXPECT_EQ(*s - clock.rising()[10], ns(200) + ns(10) * static_cast<std::int64_t>(cable)) << cable << " m";
  }
}

// An axis moving down crosses its next step half a step after it starts: the count goes down then,
// as an encoder counting down does (toward minus infinity, not toward zero).
TEST(EncoderMotion, ANegativeVelocityCountsDownAtEachStepCrossed) {
  slave::EncoderParams p;
  p.motion.start = 1000;
  p.motion.counts_per_s = -1'000'000;  // a step per microsecond
  EXPECT_EQ(p.position_at(Time::zero()), 1000U);
  EXPECT_EQ(p.position_at(ps(1)), 999U) << "the first step is crossed at once";
  EXPECT_EQ(p.position_at(ns(500)), 999U);
  EXPECT_EQ(p.position_at(us(1)), 999U);
  EXPECT_EQ(p.position_at(us(1) + ps(1)), 998U);
  p.motion.counts_per_s = 1'000'000;  // up: a step is counted once it is complete
  EXPECT_EQ(p.position_at(us(1) - ps(1)), 1000U);
  EXPECT_EQ(p.position_at(us(1)), 1001U);
}

TEST(EncoderMotion, ConstantVelocityWrapsAtTheResolution) {
  slave::EncoderParams p;
  p.position_bits = 12;
  p.motion.start = 4000;
  p.motion.counts_per_s = 1'000'000;
  EXPECT_EQ(p.position_at(us(50)), 4050U);
  EXPECT_EQ(p.position_at(us(100)), 4U);  // 4100 mod 4096
  p.motion.counts_per_s = -1'000'000;
  EXPECT_EQ(p.position_at(ms(4)), 0U);
  EXPECT_EQ(p.position_at(ms(5)), 3096U);  // -1000 mod 4096
}

TEST(EncoderParams, RejectsOutOfRangeTimesNamingTheLimit) {
  slave::EncoderParams p;
  p.t_m = us(5);
  try {
    p.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("10 .. 30 us"), std::string::npos) << e.what();
  }
  p = {};
  p.kind = slave::EncoderKind::Multiturn;
  EXPECT_THROW(p.validate(), std::invalid_argument);  // needs multiturn bits
  p.multiturn_bits = 12;
  p.position_bits = 25;
  EXPECT_NO_THROW(p.validate());
}

// Section 3: compensation values and OEM parameters "must consist of a maximum of 960 words in
// total". OEM areas 1..3 at 0..255, compensation areas 1 and 2 at 0..127 and 0..63 hold 960
// words; compensation area 2 at 0..64 one more, which the image is refused for.
TEST(EncoderMemory, TheOemAndCompensationAreasHoldAtMost960Words) {
  namespace pm = protocol::parameters;
  using A = protocol::MemoryArea;
  const auto image = [](unsigned comp2_end) {
    auto img = slave::default_memory_image(slave::EncoderParams{});
    auto& a1 = img.areas.at(A::Manufacturer1);
    const pm::Partition to255 = pm::AddressRange{0, 255};
    a1[9] = pm::encode_partition_word(to255, to255);
    a1[10] = pm::encode_partition_word(to255, std::nullopt);
    a1[11] = pm::encode_partition_word(pm::AddressRange{0, 127}, pm::AddressRange{0, comp2_end});
    a1[12] = pm::encode_partition_word(std::nullopt, std::nullopt);
    img.areas.erase(A::Oem4);
    for (A a : {A::Compensation3, A::Compensation4}) img.areas.erase(a);
    for (A a : {A::Oem1, A::Oem2, A::Oem3}) img.areas[a].assign(256, 0);
    img.areas[A::Compensation1].assign(128, 0);
    img.areas[A::Compensation2].assign(comp2_end + 1, 0);
    return img;
  };
  EXPECT_NO_THROW(slave::Memory{image(63)});
  try {
    slave::Memory m{image(64)};
    ADD_FAILURE() << "961 words accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("hold 961 words; section 3 allows at most 960"), std::string::npos) << e.what();
  }
}

// 3.5.5: words 9 .. 12 declare the OEM and compensation areas. They lie in the factory-protected
// areas of the encoder manufacturer, so no write changes them; a corrupted one (a flipped NVM bit)
// may declare addresses that were never stored, and those are unavailable (A2 type II), as the
// ones it no longer declares are.
TEST(EncoderMemory, ACorruptedPartitionWordDeclaresNoWordThatIsNotStored) {
  using A = protocol::MemoryArea;
  slave::Memory m(slave::default_memory_image(slave::EncoderParams{}));
  const slave::Selection manufacturer{A::Manufacturer1, 0}, oem1{A::Oem1, 0};
  EXPECT_EQ(m.write(manufacturer, slave::word::kOemPartition, 0x2040), protocol::ErrorCause::WriteProtected);
  ASSERT_EQ(m.word(manufacturer, slave::word::kOemPartition) & 0x00FF, 0x20) << "OEM area 1 at 0 .. 63";
  m.force(manufacturer, slave::word::kOemPartition, 0x2040);  // end code 2 (63) -> 4 (127)
  EXPECT_TRUE(m.read(oem1, 63));
  EXPECT_EQ(m.read(oem1, 64).error, protocol::ErrorCause::ImpermissibleAddress);
  EXPECT_EQ(m.read(oem1, 100).error, protocol::ErrorCause::ImpermissibleAddress);
  EXPECT_EQ(m.write(oem1, 100, 1), protocol::ErrorCause::ImpermissibleAddress);
  m.force(manufacturer, slave::word::kOemPartition, 0x2010);  // end code 1 (31)
  EXPECT_TRUE(m.read(oem1, 31));
  EXPECT_EQ(m.read(oem1, 32).error, protocol::ErrorCause::ImpermissibleAddress);
}

// Section 3's 960 words hold for writes too: words 9 .. 12 cannot be written (factory-protected),
// and with all four of them corrupted to declare every area at 0 .. 255 (2 048 words) no write or
// read reaches a word beyond those the image stored, which the image check held to 960.
TEST(EncoderMemory, NoWriteMakesTheOemAndCompensationAreasHoldMoreThan960Words) {
  namespace pm = protocol::parameters;
  using A = protocol::MemoryArea;
  slave::Memory m(slave::default_memory_image(slave::EncoderParams{}));
  const slave::Selection manufacturer{A::Manufacturer1, 0};
  const pm::Partition to255 = pm::AddressRange{0, 255};
  const std::uint16_t everything = pm::encode_partition_word(to255, to255);
  for (unsigned w = slave::word::kOemPartition; w < slave::word::kOemPartition + 4; ++w) {
    EXPECT_EQ(m.write(manufacturer, static_cast<std::uint8_t>(w), everything), protocol::ErrorCause::WriteProtected);
    m.force(manufacturer, static_cast<std::uint8_t>(w), everything);
  }
  std::size_t readable = 0, writable = 0;
  for (A a : {A::Oem1, A::Oem2, A::Oem3, A::Oem4, A::Compensation1, A::Compensation2, A::Compensation3,
              A::Compensation4}) {
    for (unsigned address = 0; address < 256; ++address) {
      const slave::Selection s{a, 0};
      if (m.read(s, static_cast<std::uint8_t>(address))) ++readable;
      if (!m.write(s, static_cast<std::uint8_t>(address), 0x1234)) ++writable;
    }
  }
  EXPECT_LE(readable, protocol::kPartitionedWordsMax);
  std::size_t stored = 0;
  for (const auto& [area, words] : slave::default_memory_image(slave::EncoderParams{}).areas)
    if (area >= A::Oem1 && area <= A::Compensation4) stored += words.size();
  EXPECT_EQ(readable, stored) << "every stored word, and none that the corrupted words declare beyond them";
  EXPECT_GT(stored, 0U);
  EXPECT_EQ(writable, readable);
}

// 3.6.5 / 3.9.15: an instruction of word 5 takes effect unless word 21 of the EnDat 2.2
// manufacturer parameters marks it as not supported; bits 3 .. 15 of word 5 are no instruction.
TEST(EncoderMemory, InstructionsTakeEffectWhereWord21DoesNotMarkThemUnsupported) {
  namespace pm = protocol::parameters;
  using A = protocol::MemoryArea;
  auto image = slave::default_memory_image(slave::EncoderParams{});
  image.areas.at(A::ManufacturerEndat22).at(protocol::word::kInstructionSupport) = pm::kInstructionEnergySaving;
  slave::Memory m(image);
  const slave::Selection operating{A::OperatingParameters, 0};
  EXPECT_FALSE(m.write(operating, slave::word::kInstructions, 0xFFFF));
  EXPECT_EQ(m.operating_parameter(slave::word::kInstructions), 0xFFFF);
  EXPECT_EQ(m.instructions(), pm::kInstructionHighImpedance | pm::kInstructionNoPositionUpdate);
  slave::Memory all(slave::default_memory_image(slave::EncoderParams{}));
  EXPECT_FALSE(all.write(operating, slave::word::kInstructions, pm::kInstructionEnergySaving));
  EXPECT_EQ(all.instructions(), pm::kInstructionEnergySaving) << "the default image supports every instruction";
}

// 3.4.1 / 3.4.2: "Error bits can be deleted by overwriting the word 0 with 0000h and sending the
// mode command Encoder receive reset" (warnings likewise, word 1): the write alone deletes nothing.
TEST(EncoderMemory, ErrorsAndWarningsClearWithZeroAndTheResetAfterIt) {
  slave::Memory m(slave::default_memory_image(slave::EncoderParams{}));
  const slave::Selection status{protocol::MemoryArea::OperatingStatus, 0};
  m.latch_errors(0x0004, 0x0010);
  m.activate_on_reset();  // a reset without the write deletes nothing
  EXPECT_EQ(m.operating_status(slave::word::kErrors), 0x0004);
  EXPECT_FALSE(m.write(status, slave::word::kErrors, 0x0000).has_value());
  EXPECT_EQ(m.operating_status(slave::word::kErrors), 0x0004) << "still set until the reset";
  EXPECT_EQ(m.operating_status(slave::word::kWarnings), 0x0010) << "word 1 was not written";
  m.activate_on_reset();
  EXPECT_EQ(m.operating_status(slave::word::kErrors), 0x0000);
  EXPECT_EQ(m.operating_status(slave::word::kWarnings), 0x0010);
  EXPECT_FALSE(m.write(status, slave::word::kWarnings, 0x0000).has_value());
  m.activate_on_reset();
  EXPECT_EQ(m.operating_status(slave::word::kWarnings), 0x0000);
  EXPECT_TRUE(m.write(status, slave::word::kErrors, 0x0001).has_value()) << "single bits cannot be written";
}

// 3.6.4: "Error bit 1 is always set if a bit is set in this word [word 4, the bus address]. This
// can only be cleared by resetting the word to 0000h and switching the power off and on."
TEST(EncoderBusAddress, ErrorBitOneHoldsUntilWordFourIsZeroAndThePowerCycles) {
  auto p = encoder_params(protocol::EndatVersion::V2_2, 8, 0xA5);
  p.memory = slave::default_memory_image(p);
  p.memory->areas[protocol::MemoryArea::OperatingParameters][slave::word::kEncoderAddress] = 0x0011;
  Bench b(p);
  const slave::Selection parameters{protocol::MemoryArea::OperatingParameters, 0};
  const auto f1_of_a_frame_at = [&](Time at) {
    ScriptedClock clock(b.k, b.line, us(1), 28, 0b111000, at);
    b.k.run(at + us(100));
    return b.sampler.slots_at(at, 12, 12);  // S on slot 11, F1 on slot 12 (2.3.1)
  };
  EXPECT_EQ(f1_of_a_frame_at(us(10)), "1") << "an address in word 4";
  b.encoder.corrupt_word(parameters, slave::word::kEncoderAddress, 0x0011);  // word 4 back to 0000h
  EXPECT_EQ(f1_of_a_frame_at(us(200)), "1") << "0000h alone does not clear it";
  b.encoder.power_interruption(us(100));
  EXPECT_EQ(f1_of_a_frame_at(us(600)), "0") << "0000h and a power cycle do";
  b.encoder.corrupt_word(parameters, slave::word::kEncoderAddress, 0x0012);
  b.encoder.power_interruption(us(100));
  EXPECT_EQ(f1_of_a_frame_at(us(1000)), "1") << "a power cycle with an address in word 4 keeps it";
}

namespace {

// The times the encoder's DATA driver enable (its logic side) switches off.
struct EnableLog {
  explicit EnableLog(sim::Kernel& k, line::Line& line) : k_(k), enable_(line.encoder().data_enable) {
    enable_.on_change(sim::bind<&EnableLog::on_change>(this));
  }
  void on_change(std::uint64_t level) {
    if (level == 0) off.push_back(k_.now());
  }
  sim::Kernel& k_;
  sim::Signal& enable_;
  std::vector<Time> off;
};

// FE1's release and the release after the answer of "Encoder send position values and selection
// of memory area" (8 bits, 2.2: S F1 F2, 8 bits, CRC on RE11 .. RE26), with its slot levels.
struct Handover {
  std::vector<Time> off;
  std::vector<Time> rising;
  std::string slots;
};

Handover handover(slave::SupplementHandover h) {
  auto p = encoder_params(protocol::EndatVersion::V2_2, 8, 0xA5);
  p.supplement_handover = h;
  Bench b(p);
  EnableLog log(b.k, b.line);
  const auto bits = protocol::info(protocol::ModeCommand::EncoderSendPositionValuesAndSelectionOfMemoryArea).bits;
  ScriptedClock clock(b.k, b.line, us(1), 30, bits);
  b.k.run();
  return {log.off, clock.rising(), b.sampler.slots(26, 28)};
}

}  // namespace

// 2.3 ("following transfer of the data and the CRC, it can then be decided whether and to what
// extent additional data follows by determining the logic level on the data line") with the
// command supplement of 2.4.2: by default the encoder releases DATA on the rising edge after its
// last CRC bit, for the master's supplement; with supplement_handover end_level it drives the
// HIGH that ends its answer for one clock period first and releases on the next rising edge.
TEST(EncoderSupplementHandover, EndLevelDrivesHighForOneClockBeforeReleasing) {
  const auto release = handover(slave::SupplementHandover::Release);
  const auto end_level = handover(slave::SupplementHandover::EndLevel);
  ASSERT_EQ(release.off.size(), 2U);  // FE1, then the handover
  ASSERT_EQ(end_level.off.size(), 2U);
  // RE_k as the master drives it; the encoder sees it after the line's delays (well within half a period).
  const auto re = [&](unsigned k) { return release.rising.at(k - 1); };
  EXPECT_GT(release.off[1], re(27));
  EXPECT_LT(release.off[1], re(27) + ns(500));
  EXPECT_GT(end_level.off[1], re(28));
  EXPECT_LT(end_level.off[1], re(28) + ns(500));
  EXPECT_EQ(end_level.off[1] - release.off[1], us(1));
  // The slot after the last CRC bit reads HIGH either way (fail-safe HIGH when released, docs/model.md §11).
  EXPECT_EQ(end_level.slots.substr(1, 1), "1");
}

// The fast path plays a moving axis only between two measuring steps: steps are counted, so a
// position that wraps around to the same value has still moved.
TEST(EncoderFastPath, HoldsItsPositionOnlyBetweenTwoMeasuringSteps) {
  slave::EncoderParams p = encoder_params(protocol::EndatVersion::V2_2, 8, 10);
  p.motion.counts_per_s = 1'000'000;  // a step every microsecond
  Bench b(p);
  EXPECT_TRUE(b.encoder.holds_position(ns(1'100), ns(1'900)));
  EXPECT_FALSE(b.encoder.holds_position(ns(1'900), ns(2'100)));
  EXPECT_FALSE(b.encoder.holds_position(ns(1'100), ns(257'100)));  // 256 steps: the same 8-bit position
  slave::EncoderParams still = encoder_params(protocol::EndatVersion::V2_2, 8, 10);
  Bench s(still);
  EXPECT_TRUE(s.encoder.holds_position(Time::zero(), sim::ms(100)));
}
