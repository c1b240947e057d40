// The worked examples of spec 3.5, 3.6 and 3.9, reproduced through protocol/parameters.hpp, and
// encode -> decode round trips.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <stdexcept>
#include <vector>

#include "endatsim/protocol/memory_area.hpp"
#include "endatsim/protocol/parameters.hpp"

using namespace endatsim::protocol::parameters;
using namespace std::chrono_literals;

TEST(Parameters, Word8VersionExample) {
  // 3.5.4: "Example Version 4" with bit 15 set for NVM checking.
  EXPECT_EQ(encode_version(4), 0x8004);
  EXPECT_EQ(decode_version(0x8004), 4U);
  EXPECT_THROW(encode_version(0x8000), std::invalid_argument);
}

TEST(Parameters, Words9To12PartitionTheAreasOfTheExampleByte) {
  // 3.5.5 "Example 256 words": words 9..12 = 20FFh, FF20h, FFFFh, 20FFh make OEM areas 2 and 3 and
  // compensation area 4 available at 0..63; word 9's high byte is OEM area 2, word 12's is
  // compensation area 4.
  using A = endatsim::protocol::MemoryArea;
  std::vector<std::uint16_t> m(endatsim::protocol::kManufacturerWords, 0);
  const Partition none, a0_63 = AddressRange{0, 63};
  const std::array<Partition, 4> oem{none, a0_63, a0_63, none}, compensation{none, none, none, a0_63};
  encode_partition_words(m, oem, compensation);
  EXPECT_EQ((std::vector<std::uint16_t>(m.begin() + 9, m.begin() + 13)), (std::vector<std::uint16_t>{0x20FF, 0xFF20, 0xFFFF, 0x20FF}));
  for (std::size_t i = 0; i < kPartitionedAreas.size(); ++i)
    EXPECT_EQ(partition_of(m, kPartitionedAreas[i]), i < 4 ? oem[i] : compensation[i - 4]) << i;
  EXPECT_EQ(partition_byte(A::Oem2)->word, 9U);
  EXPECT_EQ(partition_byte(A::Oem2)->shift, 8U);
  EXPECT_EQ(partition_byte(A::Compensation3)->word, 12U);
  EXPECT_EQ(partition_byte(A::Compensation3)->shift, 0U);
  EXPECT_FALSE(partition_byte(A::OperatingParameters));
  EXPECT_EQ(partition_of(m, A::Manufacturer1), std::nullopt);
}

TEST(Parameters, Words9To12MemoryAllocationExample) {
  // 3.5.5 "Example 256 words": OEM areas 2 and 3 and compensation area 4 at 0..63.
  const Partition none;
  const Partition a0_63 = AddressRange{0, 63};
  EXPECT_EQ(encode_partition_word(none, a0_63), 0x20FF);   // word 9
  EXPECT_EQ(encode_partition_word(a0_63, none), 0xFF20);   // word 10
  EXPECT_EQ(encode_partition_word(none, none), 0xFFFF);    // word 11
  EXPECT_EQ(encode_partition_word(none, a0_63), 0x20FF);   // word 12
  const auto [low, high] = decode_partition_word(0xFF20);
  EXPECT_EQ(low, a0_63);
  EXPECT_EQ(high, std::nullopt);
  // The address codes of the table, both ways.
  const std::array<unsigned, 6> addresses{0, 31, 63, 64, 127, 255};
  for (unsigned code = 0; code < addresses.size(); ++code) {
    EXPECT_EQ(partition_address(code), addresses[code]);
    EXPECT_EQ(partition_code(addresses[code]), code);
  }
  EXPECT_EQ(partition_address(0xF), std::nullopt);
  EXPECT_EQ(partition_address(0x6), std::nullopt);
  EXPECT_EQ(decode_partition(0x50), (AddressRange{0, 255}));
  EXPECT_EQ(decode_partition(0x5F), std::nullopt);  // half "not available"
  EXPECT_THROW(encode_partition(AddressRange{0, 100}), std::invalid_argument);
  EXPECT_THROW(encode_partition(AddressRange{63, 31}), std::invalid_argument);
}

TEST(Parameters, Word13PositionBitsExample) {
  // 3.5.6: "25-bit format = 25 clock pulse periods, 25 bit = 19h", bit 15 = 1.
  EXPECT_EQ(encode_position_bits(25), 0x8019);
  EXPECT_EQ(decode_position_bits(0x8019), 25U);
  for (unsigned bits = 1; bits <= 63; ++bits) {
    const auto w = encode_position_bits(bits);
    EXPECT_EQ(w & kNvmBit15, kNvmBit15);
    EXPECT_EQ(decode_position_bits(w), bits);
  }
  EXPECT_THROW(encode_position_bits(0), std::invalid_argument);
  EXPECT_THROW(encode_position_bits(64), std::invalid_argument);
}

TEST(Parameters, Word14EncoderTypes) {
  // 3.5.7: the type in bits 15..12, bit 0 always 1.
  EXPECT_EQ(encode_encoder_type(EncoderType::Singleturn), 0xC001);
  EXPECT_EQ(encode_encoder_type(EncoderType::MultiturnBattery), 0xD001);
  EXPECT_EQ(encode_encoder_type(EncoderType::MultiturnGears), 0xE001);
  EXPECT_EQ(encode_encoder_type(EncoderType::AbsoluteLinear), 0x4001);
  EXPECT_EQ(encode_encoder_type(EncoderType::IncrementalRotaryDistanceCoded), 0x9001);
  // The spec's future example for absolute encoders with cyclic coding, 7073h, keeps bit 0 and
  // uses bits 11..1; its type nibble is 7.
  EXPECT_EQ(decode_encoder_type(0x7073), EncoderType::NoteD1D11);
  EXPECT_EQ(0x7073 & kNvmBit0, kNvmBit0);
  for (unsigned t = 0; t < 16; ++t) {
    const auto type = static_cast<EncoderType>(t);
    EXPECT_EQ(decode_encoder_type(encode_encoder_type(type)), type);
    EXPECT_NE(encoder_type_name(type), "unknown");
  }
  EXPECT_EQ(encoder_type_name(EncoderType::MultiturnBattery), "multiturn rotary encoder with battery buffer");
  EXPECT_TRUE(is_linear(EncoderType::AbsoluteLinear));
  EXPECT_FALSE(is_linear(EncoderType::Singleturn));
  EXPECT_FALSE(is_linear(EncoderType::ExternalInterfaceBox));
}

TEST(Parameters, Words15To17Examples) {
  // 3.5.8: 20 um = 20000 nm = 4E20h; 2048 periods per revolution = 0800h.
  EXPECT_EQ(encode_signal_period(20000), (std::array<std::uint16_t, 2>{0x4E20, 0x0000}));
  EXPECT_EQ(encode_signal_period(2048), (std::array<std::uint16_t, 2>{0x0800, 0x0000}));
  EXPECT_EQ(decode_signal_period(0x4E20, 0), 20000U);
  // 3.5.9: 2048 distinguishable revolutions = 0800h; more than 65535: 65535 (see 2.2 word 34).
  EXPECT_EQ(encode_revolutions(2048), 0x0800);
  EXPECT_EQ(encode_revolutions(1U << 20), 0xFFFF);
}

TEST(Parameters, Words20And21MeasuringStepExamples) {
  // 3.5.12: 100 nm = 64h; 1 800 000 steps per revolution = 1B7740h.
  EXPECT_EQ(encode_measuring_steps(100), (std::array<std::uint16_t, 2>{0x0064, 0x0000}));
  EXPECT_EQ(encode_measuring_steps(1'800'000), (std::array<std::uint16_t, 2>{0x7740, 0x001B}));
  EXPECT_EQ(decode_measuring_steps(0x7740, 0x001B), 1'800'000U);
  EXPECT_EQ(measuring_step_string(EncoderType::AbsoluteLinear, 100), "100 nm");
  EXPECT_EQ(measuring_step_string(EncoderType::Singleturn, 1'800'000), "1800000 steps/rev");
  EXPECT_EQ(measuring_step_string(EncoderType::Singleturn, 0), "0 (see EnDat 2.2 words 27 .. 29)");
}

TEST(Parameters, Words22And23DatumShiftExamples) {
  // 3.5.13 linear: +20 mm at 0.1 um = 200 000 steps = 30D40h, stored as FFFCF2C0h.
  const std::int64_t linear = 20'000'000 / 100;  // 20 mm in 0.1 um steps
  EXPECT_EQ(linear, 200'000);
  EXPECT_EQ(linear % 160, 0);  // a multiple of 160 steps per 16 um signal period
  EXPECT_EQ(encode_datum_shift32(datum_shift_value(linear)), (std::array<std::uint16_t, 2>{0xF2C0, 0xFFFC}));
  EXPECT_EQ(datum_shift_steps(decode_datum_shift32(0xF2C0, 0xFFFC)), 200'000);
  // 3.5.13 rotary: +45 degrees at 8192 steps/rev (2048 periods: 4 steps per period) = 1024 =
  // 400h, stored as FFFFFC00h.
  const auto rotary = angle_to_steps(45.0, 8192);
  EXPECT_EQ(rotary, 1024);
  EXPECT_EQ(endat_compliant_shift(rotary, 8192 / 2048), 1024);
  EXPECT_EQ(encode_datum_shift32(datum_shift_value(rotary)), (std::array<std::uint16_t, 2>{0xFC00, 0xFFFF}));
}

TEST(Parameters, OperatingParametersDatumShiftExamples) {
  // 3.6.2 linear: read FFFCF2C0h (the manufacturer's 20 mm), add 40 mm (FFF9E580h), write
  // FFF6D840h to words 0 and 1.
  const auto old_value = decode_datum_shift32(0xF2C0, 0xFFFC);
  const auto add = datum_shift_value(40'000'000 / 100);
  EXPECT_EQ(encode_datum_shift32(add), (std::array<std::uint16_t, 2>{0xE580, 0xFFF9}));
  EXPECT_EQ(encode_datum_shift32(old_value + add), (std::array<std::uint16_t, 2>{0xD840, 0xFFF6}));
  // 3.6.2 rotary, 8192 steps/rev: the manufacturer's 5 degrees read as FFFFFF8Eh (114 steps),
  // 20 degrees = 455 steps (FFFFFE39h), together 569 steps (FFFFFDC7h); EnDat-compliant with 4
  // steps per period: 568 = 238h, written as FFFFFDC8h. (The spec's text as we have it prints
  // FFFFFFE39h and FFFFFD7h, one digit too many and one too few; the values here are the ones 569
  // implies.)
  EXPECT_EQ(angle_to_steps(5.0, 8192), 114);
  EXPECT_EQ(decode_datum_shift32(0xFF8E, 0xFFFF), datum_shift_value(114));
  const auto twenty = angle_to_steps(20.0, 8192);
  EXPECT_EQ(twenty, 455);
  EXPECT_EQ(encode_datum_shift32(datum_shift_value(twenty)), (std::array<std::uint16_t, 2>{0xFE39, 0xFFFF}));
  const auto total = datum_shift_steps(decode_datum_shift32(0xFF8E, 0xFFFF)) + twenty;
  EXPECT_EQ(total, 569);
  EXPECT_EQ(encode_datum_shift32(datum_shift_value(total)), (std::array<std::uint16_t, 2>{0xFDC7, 0xFFFF}));
  const auto compliant = endat_compliant_shift(total, 8192 / 2048);
  EXPECT_EQ(compliant, 0x238);
  EXPECT_EQ(encode_datum_shift32(datum_shift_value(compliant)), (std::array<std::uint16_t, 2>{0xFDC8, 0xFFFF}));
}

TEST(Parameters, DatumShiftRoundTrips) {
  for (std::int64_t v : {std::int64_t{0}, std::int64_t{1}, std::int64_t{-1}, std::int64_t{INT32_MAX},
                         std::int64_t{INT32_MIN}, std::int64_t{-600'000}}) {
    const auto w = encode_datum_shift32(v);
    EXPECT_EQ(decode_datum_shift32(w[0], w[1]), v);
  }
  EXPECT_THROW(encode_datum_shift32(std::int64_t{INT32_MAX} + 1), std::invalid_argument);
  // 3.6.2: word 2 extends the shift for positions above 32 bits.
  for (std::int64_t v : {std::int64_t{-600'000}, (std::int64_t{1} << 47) - 1, -(std::int64_t{1} << 47),
                         std::int64_t{0x1234'5678'9ABC}}) {
    const auto w = encode_datum_shift48(v);
    EXPECT_EQ(decode_datum_shift48(w[0], w[1], w[2]), v);
  }
  EXPECT_EQ(encode_datum_shift48(-600'000), (std::array<std::uint16_t, 3>{0xD840, 0xFFF6, 0xFFFF}));
  EXPECT_THROW(encode_datum_shift48(std::int64_t{1} << 47), std::invalid_argument);
  EXPECT_EQ(endat_compliant_shift(-569, 4), -568);
  EXPECT_EQ(endat_compliant_shift(570, 4), 572);  // halves round away from zero
}

TEST(Parameters, Words24To26IdNumberExample) {
  // 3.5.14: "ID number 262 144 A1": 262144 = 40000h; word 24 = 'A' 41h, '1' 31h.
  const IdNumber id = parse_id_number("262 144 A1");
  EXPECT_EQ(id.number, 262144U);
  EXPECT_EQ(encode_id_number(id), (std::array<std::uint16_t, 3>{0x4131, 0x0000, 0x0004}));
  const IdNumber back = decode_id_number(0x4131, 0x0000, 0x0004);
  EXPECT_EQ(back, id);
  EXPECT_EQ(id_number_string(back), "262144 A1");
  EXPECT_EQ(parse_id_number("262144-A1"), id);
  EXPECT_EQ(parse_id_number("262144 A1"), id);
  EXPECT_EQ(id_number_string(parse_id_number("1234 01")), "001234 01");
  EXPECT_EQ(id_number_string(parse_id_number("1065932-02")), "1065932 02");
  EXPECT_THROW(parse_id_number("A1"), std::invalid_argument);
  EXPECT_THROW(parse_id_number("262144 A"), std::invalid_argument);
  EXPECT_THROW(parse_id_number("262144/A1"), std::invalid_argument);
  EXPECT_THROW(id_number_string(decode_id_number(0x0131, 0, 0)), std::invalid_argument);
}

TEST(Parameters, Words27To29SerialNumberExample) {
  // 3.5.15: serial number "(empty)2637991A": 2637991 = 2840A7h.
  const SerialNumber s{' ', 2'637'991, 'A'};
  EXPECT_EQ(encode_serial_number(s), (std::array<std::uint16_t, 3>{0xA741, 0x2840, 0x2000}));
  const SerialNumber back = decode_serial_number(0xA741, 0x2840, 0x2000);
  EXPECT_EQ(back, s);
  EXPECT_EQ(serial_number_string(back), "2637991A");
  const SerialNumber full{'X', 0xFEDC'BA98, 'Z'};
  const auto w = encode_serial_number(full);
  EXPECT_EQ(decode_serial_number(w[0], w[1], w[2]), full);
  EXPECT_EQ(serial_number_string(full), "X4275878552Z");
}

TEST(Parameters, Word30Direction) {
  // 3.5.16: bit 15 = 1 for NVM checking, default 0 (positions in the direction of measurement).
  EXPECT_EQ(encode_direction(false), 0x8000);
  EXPECT_EQ(encode_direction(true), 0x8001);
  EXPECT_FALSE(decode_direction_falling(0x8000));
  EXPECT_TRUE(decode_direction_falling(0x8001));
}

TEST(Parameters, Words33And34AccuracyRangesAsTheExamplesOf3519) {
  // Linear: c_1 = 40, a_1 = +/-16 LSB = 0010 1000 0001 0000. Rotary: c_1 = 10, a_1 = 1; c_2 = 1, a_2 = 50.
  EXPECT_EQ(decode_accuracy_range(0x2810), (AccuracyRange{40, 16}));
  EXPECT_EQ(decode_accuracy_range(0x0A01), (AccuracyRange{10, 1}));
  EXPECT_EQ(decode_accuracy_range(0x0132), (AccuracyRange{1, 50}));
  EXPECT_EQ(kAccuracySeeEndat22, 65535);
  EXPECT_EQ(encode_accuracy_range(40, 16), 0x2810);
  EXPECT_EQ(encode_accuracy_range(1, 50), 0x0132);
}

TEST(Parameters, Endat22Words11To14ScaleTheirValueByBits15To13) {
  // 3.9.11's example: c_1 = 40 and a_1 = 16, each x1.
  EXPECT_EQ(decode_scaled_value(0x0028), 40U);
  EXPECT_EQ(decode_scaled_value(0x0010), 16U);
  EXPECT_EQ(decode_scaled_value(0x2028), 80U);            // 001 x2
  EXPECT_EQ(decode_scaled_value(0xA000 | 0x1FFF), 0x1FFFU * 32);  // 101 x32, the largest value
  EXPECT_EQ(decode_scaled_value(0xE001), std::nullopt);   // 111 not supported
  EXPECT_EQ(decode_scaled_value(0xC001), std::nullopt);   // 110 is not in the table
}

TEST(Parameters, Word37CommandSetBitPairsStoredInversely) {
  // 3.5.22: a function is supported only if its pair of bits is stored inversely.
  EXPECT_EQ(encode_command_set({true, false, true}), 0x0019);
  EXPECT_EQ(encode_command_set({true, false, false}), 0x0029);
  EXPECT_EQ(encode_command_set({false, false, false}), 0x002A);
  EXPECT_EQ(encode_command_set({true, true, true}), 0x0015);
  for (unsigned m = 0; m < 8; ++m) {
    const CommandSet c{(m & 1) != 0, (m & 2) != 0, (m & 4) != 0};
    EXPECT_EQ(decode_command_set(encode_command_set(c)), c);
    EXPECT_TRUE(command_set_consistent(encode_command_set(c)));
  }
  EXPECT_EQ(decode_command_set(0x0003), (CommandSet{}));  // 2.2 bits stored equally: not supported
  EXPECT_FALSE(command_set_consistent(0x0000));
  EXPECT_EQ(command_set_string(0x0019), "2.2, communication command");
  EXPECT_EQ(command_set_string(0x002A), "2.1");
  EXPECT_EQ(command_set_string(0x0000), "2.1 (bit pairs not stored inversely)");
}

TEST(Parameters, Word39CalculationTime) {
  // 3.5.24: unit in bits 15..13 (001 us, 010 ms, 011 ns). The example's figure (1 ms, linear
  // encoder) is lost; 1 ms is stored as ms x 1.
  EXPECT_EQ(encode_calculation_time(calculation_time_from(1ms)), 0x4001);
  EXPECT_EQ(encode_calculation_time(calculation_time_from(5us)), 0x2005);
  EXPECT_EQ(encode_calculation_time(calculation_time_from(750ns)), 0x62EE);
  EXPECT_EQ(encode_calculation_time(calculation_time_from(8191ns)), 0x7FFF);
  EXPECT_THROW(calculation_time_from(10500ns), std::invalid_argument);  // not whole us, too many ns
  EXPECT_THROW(calculation_time_from(std::chrono::nanoseconds(-1)), std::invalid_argument);
  const auto t = decode_calculation_time(0x2005);
  EXPECT_EQ(t.unit, TimeUnit::Microseconds);
  EXPECT_EQ(t.value, 5);
  EXPECT_EQ(calculation_time_duration(t), std::chrono::nanoseconds(5us));
  EXPECT_EQ(calculation_time_string(t), "5 us");
  EXPECT_EQ(calculation_time_string(decode_calculation_time(0x4001)), "1 ms");
  EXPECT_EQ(calculation_time_string(decode_calculation_time(0x62EE)), "750 ns");
  EXPECT_EQ(calculation_time_string(decode_calculation_time(0x0000)), "not supported");
  EXPECT_EQ(calculation_time_duration(decode_calculation_time(0x0000)), std::nullopt);
  for (unsigned unit = 0; unit <= 4; ++unit)
    for (unsigned v : {0U, 1U, 4096U, 8191U}) {
      const CalculationTime c{static_cast<TimeUnit>(unit), static_cast<std::uint16_t>(v)};
      EXPECT_EQ(decode_calculation_time(encode_calculation_time(c)), c);
    }
  EXPECT_THROW(encode_calculation_time({TimeUnit::Microseconds, 8192}), std::invalid_argument);
}

TEST(Parameters, Word40OrderingDesignationExample) {
  // 3.5.25: "EnDat22" = 3232h ('2' = 32h twice); 0000h = not supported.
  EXPECT_EQ(encode_ordering_designation("EnDat22"), 0x3232);
  EXPECT_EQ(decode_ordering_designation(0x3232), "EnDat22");
  for (const char* d : {"EnDat01", "EnDat21", "EnDat02", "EnDat22"})
    EXPECT_EQ(decode_ordering_designation(encode_ordering_designation(d)), d);
  EXPECT_EQ(encode_ordering_designation("EnDat01"), 0x3031);
  EXPECT_EQ(decode_ordering_designation(0), std::nullopt);
  EXPECT_THROW(encode_ordering_designation("EnDat2"), std::invalid_argument);
  EXPECT_THROW(encode_ordering_designation("Endat22"), std::invalid_argument);
  EXPECT_THROW(encode_ordering_designation("EnDat2 "), std::invalid_argument);
}

TEST(Parameters, Word40SecondCharacterTwoNamesTheEndat22CommandSet) {
  EXPECT_TRUE(ordering_designation_needs_endat22(encode_ordering_designation("EnDat22")));
  EXPECT_TRUE(ordering_designation_needs_endat22(encode_ordering_designation("EnDat02")));
  EXPECT_FALSE(ordering_designation_needs_endat22(encode_ordering_designation("EnDat21")));
  EXPECT_FALSE(ordering_designation_needs_endat22(encode_ordering_designation("EnDat01")));
  EXPECT_TRUE(ordering_designation_visible(0x3232));
  EXPECT_FALSE(ordering_designation_visible(0x3220));  // "EnDat2 "
  EXPECT_FALSE(ordering_designation_visible(0x0132));
}

TEST(Parameters, ChecksumsIgnoreOverflow) {
  // 3.5.26: word 47 = word 4 + ... + word 46, overflow not considered; words 0..3 and 47 do not count.
  std::vector<std::uint16_t> m(48, 0);
  m[0] = 0x1111;
  m[4] = 0xFFFF;
  m[5] = 0x0002;
  m[46] = 0x0100;
  m[47] = 0x7777;
  EXPECT_EQ(manufacturer_checksum(m), 0x0101);
  // 3.9.37: EnDat 2.2 word 63 = word 0 + ... + word 62.
  std::vector<std::uint16_t> e(64, 0x0400);  // 63 x 400h = FC00h, + word 63 not counted
  EXPECT_EQ(endat22_checksum(e), 0xFC00);
  e[0] = 0x0800;
  EXPECT_EQ(endat22_checksum(e), 0x0000);  // 10000h: the carry is dropped
  EXPECT_THROW(checksum(m, 4, 48), std::out_of_range);
}

TEST(Parameters, Endat22Words0And1SupportedAdditionalData) {
  // 3.9.2 / 3.9.3: one bit per additional datum.
  const std::array<std::string_view, 2> temps{"temperature_1", "temperature_2"};
  EXPECT_EQ(encode_additional_data_1(temps), 0x000C);
  EXPECT_EQ(encode_additional_data_1(additional_data_1_names()), 0x001F);
  EXPECT_EQ(encode_additional_data_2(additional_data_2_names()), 0x00FF);
  const std::array<std::string_view, 2> d2{"asynchronous_position_value", "timestamp"};
  EXPECT_EQ(encode_additional_data_2(d2), 0x0088);
  EXPECT_EQ(additional_data_string(decode_additional_data_2(0x0088)), "asynchronous_position_value, timestamp");
  EXPECT_EQ(additional_data_string(decode_additional_data_1(0x001F)),
            "position_value_2, test_values, temperature_1, temperature_2, additional_sensors");
  EXPECT_EQ(additional_data_string(decode_additional_data_1(0xFFE0)), "none");
  const std::array<std::string_view, 1> bad{"temperature_3"};
  try {
    encode_additional_data_1(bad);
    ADD_FAILURE() << "accepted temperature_3";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("temperature_3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("additional_sensors"), std::string::npos) << e.what();
  }
}

TEST(Parameters, Endat22Word25MaxClockFrequencyExample) {
  // 3.9.19: 8 MHz = 8000 kHz = 1F40h.
  EXPECT_EQ(encode_max_clock_frequency_khz(8000), 0x1F40);
  EXPECT_EQ(clock_frequency_string(0x1F40), "8 MHz");
  EXPECT_EQ(clock_frequency_string(16000), "16 MHz");
  EXPECT_EQ(clock_frequency_string(2500), "2.5 MHz");
  EXPECT_EQ(clock_frequency_string(500), "500 kHz");
  EXPECT_THROW(encode_max_clock_frequency_khz(70000), std::invalid_argument);
}

TEST(Parameters, Endat22Word45TimestampUnitExample) {
  // 3.9.32: "touch probes with a timestamp with a time unit of 1 us" = 010x xxxx xxxx xxxxb.
  EXPECT_EQ(encode_timestamp_unit(TimestampUnit::Us1), 0x4000);
  EXPECT_EQ(decode_timestamp_unit(0x4000), TimestampUnit::Us1);
  EXPECT_EQ(decode_timestamp_unit(0x5FFF), TimestampUnit::Us1) << "bits 12..0 are not the unit";
  EXPECT_EQ(decode_timestamp_unit(0x2000), TimestampUnit::Us2);
  EXPECT_EQ(decode_timestamp_unit(0x6000), TimestampUnit::Ns500);
  EXPECT_EQ(decode_timestamp_unit(0x8000), TimestampUnit::Ns125);
  EXPECT_EQ(decode_timestamp_unit(0x0000), TimestampUnit::NotSupported);
  EXPECT_EQ(decode_timestamp_unit(0xA000), TimestampUnit::NotSupported) << "code 101b is not assigned";
  EXPECT_EQ(timestamp_unit_duration(TimestampUnit::Ns125), std::chrono::nanoseconds(125));
  EXPECT_FALSE(timestamp_unit_duration(TimestampUnit::NotSupported));
  EXPECT_EQ(timestamp_unit_string(TimestampUnit::Us2), "2 us");
  EXPECT_EQ(timestamp_unit_string(TimestampUnit::Ns500), "500 ns");
}

// 3.4.3 word 2: bit 0 protects the encoder manufacturer's areas (both editions), bits 3, 4 and 5
// compensation areas 4, 3 and 2; those are factory set, the OEM's (bit 2) and the operating
// parameters' (bit 1) are not.
TEST(Parameters, Word2FactoryWriteProtection) {
  EXPECT_EQ(endatsim::protocol::factory_write_protection(), (1U << 0) | (1U << 3) | (1U << 4) | (1U << 5));
  EXPECT_EQ(endatsim::protocol::factory_write_protection() & ((1U << 1) | (1U << 2)), 0U);
}

// 3.4.3 word 2: bits 6, 7 and 8 protect section 2 blocks 0, 1 and 2, bit 9 blocks 3 .. n.
TEST(Parameters, Word2ProtectsSection2BlocksOneBitEachUpToBlock3) {
  using endatsim::protocol::section2_protection_bit;
  EXPECT_EQ(section2_protection_bit(0), 6U);
  EXPECT_EQ(section2_protection_bit(1), 7U);
  EXPECT_EQ(section2_protection_bit(2), 8U);
  EXPECT_EQ(section2_protection_bit(3), 9U);
  EXPECT_EQ(section2_protection_bit(255), 9U);
}

// 3.5.5 words 9 .. 12: OEM areas 1 and 2 at 0 .. 63, the others not available, as a default
// image has them.
TEST(Parameters, Words9To12DefaultAllocation) {
  const Partition oem{AddressRange{0, 63}}, none;
  EXPECT_EQ(encode_partition_word(oem, oem), 0x2020);
  EXPECT_EQ(encode_partition_word(none, none), 0xFFFF);
}
