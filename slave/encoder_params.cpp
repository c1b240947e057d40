#include "endatsim/slave/encoder_params.hpp"

#include <stdexcept>
#include <string>

#include "endatsim/protocol/parameters.hpp"
#include "endatsim/slave/eib.hpp"
#include "endatsim/slave/reference.hpp"

namespace endatsim::slave {
namespace {

namespace position = protocol::frame_position;

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

std::uint16_t word_of(std::uint64_t value, unsigned index) {  // 16-bit word `index` (0 = LSB word)
  return static_cast<std::uint16_t>(value >> (16 * index));
}

}  // namespace

void EncoderParams::validate() const {
  require(position_bits >= 1 && position_bits <= 48,
          "encoder position_bits (word 13) must be 1 .. 48, got " + std::to_string(position_bits));
  require(multiturn_bits < position_bits, "encoder multiturn_bits must be less than position_bits (" +
                                              std::to_string(position_bits) + "), got " +
                                              std::to_string(multiturn_bits));
  require(kind == EncoderKind::Multiturn || multiturn_bits == 0,
          "multiturn_bits (" + std::to_string(multiturn_bits) + ") needs kind \"multiturn\"");
  require(kind != EncoderKind::Multiturn || multiturn_bits > 0, "kind \"multiturn\" needs multiturn_bits > 0");
  require(kind != EncoderKind::TouchProbe || position_bits == protocol::kTouchProbeBits,
          "kind \"touch_probe\" sends 16 bits (2.3.4.4), got position_bits " + std::to_string(position_bits));
  // 2.3.2 allows at most 1 ms; longer ones are accepted so that an overrun can be shown, and
  // the checker reports them (t_cal).
  require(t_cal >= Time::zero() && t_cal <= sim::ms(100),
          "t_cal must be 0 .. 100 ms (the model's limit), got " + sim::format_time(t_cal));
  require(!t_cal_22 || (*t_cal_22 >= Time::zero() && *t_cal_22 <= sim::ms(100)),
          "t_cal_22 must be 0 .. 100 ms (the model's limit), got " + sim::format_time(t_cal_22.value_or(Time::zero())));
  require(t_m >= sim::us(10) && t_m <= sim::us(30),
          "t_m must be 10 .. 30 us (2.3.2), got " + sim::format_time(t_m));
  if (t_m_short)
    require(*t_m_short >= sim::ns(1250) && *t_m_short <= sim::ns(3750),
            "t_m_short must be 1.25 .. 3.75 us (2.3.2 note 3), got " + sim::format_time(*t_m_short));
  require(!short_t_m_selected || t_m_short.has_value(), "short_t_m_selected needs t_m_short");
  require(t_r >= Time::zero() && t_r <= sim::us(100), "t_R must be 0 .. 100 us, got " + sim::format_time(t_r));
  require(startup_time >= Time::zero() && startup_time <= sim::ms(10'000),
          "encoder startup_time must be 0 .. 10 s, got " + sim::format_time(startup_time));
  require(reset_time >= Time::zero() && reset_time <= sim::ms(1000),
          "encoder reset_time must be 0 .. 1 s, got " + sim::format_time(reset_time));
  for (auto [name, t] : {std::pair{"t_ac_read", t_ac_read}, {"t_ac_write", t_ac_write}})
    require(t >= Time::zero() && t <= sim::ms(12),
            std::string("encoder ") + name + " must be 0 .. 12 ms (2.3.2: t_ac), got " + sim::format_time(t));
  require(supplement_end_marker_delay >= Time::zero() && supplement_end_marker_delay <= sim::us(1),
          "encoder supplement_end_marker_delay must be 0 .. 1 us (below the shortest t_m), got " +
              sim::format_time(supplement_end_marker_delay));
  require(supplement_ignore_clocks <= 16,
          "encoder supplement_ignore_clocks must be 0 .. 16, got " + std::to_string(supplement_ignore_clocks));
  require(output_delay >= Time::zero() && output_delay <= sim::us(1),
          "encoder output_delay must be 0 .. 1 us, got " + sim::format_time(output_delay));
  require(asynchronous_time_delay_step >= Time::zero() && asynchronous_time_delay_step <= sim::ms(1),
          "encoder asynchronous_time_delay_step must be 0 .. 1 ms, got " + sim::format_time(asynchronous_time_delay_step));
  require(multiturn_overflow_error_bit <= 15, "encoder multiturn_overflow_error_bit must be a word 0 bit, 0 .. 15, got " +
                                                  std::to_string(multiturn_overflow_error_bit));
  require(continuous_low_bits >= 1 && continuous_low_bits <= 7,
          "continuous_low_bits must be 1 .. 7 (2.3.1.1: at most 7 low bits), got " +
              std::to_string(continuous_low_bits));
  require(earliest_start_bit_clock > driver_enable_edge && earliest_start_bit_clock <= 32,
          "encoder earliest_start_bit_clock must be after the driver is on (driver_enable_edge " +
              std::to_string(driver_enable_edge) + ") and at most 32, got " + std::to_string(earliest_start_bit_clock));
  require(driver_enable_edge == position::kTurnaround || driver_enable_edge == position::kTurnaround + 1,
          "driver_enable_edge must be 9 or 10 (the turnaround clocks), got " + std::to_string(driver_enable_edge));
  require(motion.start < (std::uint64_t{1} << position_bits),
          "motion.start must be below 2^position_bits = " + std::to_string(std::uint64_t{1} << position_bits) +
              ", got " + std::to_string(motion.start));
  require(unsettled_positions <= 1000,
          "encoder unsettled_positions must be 0 .. 1000, got " + std::to_string(unsettled_positions));
  require(sensors.position2_offset >= -(std::int64_t{1} << 47) && sensors.position2_offset < (std::int64_t{1} << 47),
          "sensors position2_offset must fit 48 bits (3.9.24)");
  require(sensors.additional_sensors.size() <= 16, "at most 16 additional sensors (4-bit address, 2.3.5.1)");
  require(sensors.timestamp_unit > Time::zero(), "sensors.timestamp_unit must be > 0");
  for (const auto& [port, value] : sensors.test_values)
    require(value < (std::uint64_t{1} << protocol::kTestValueBits),
            "test value of port " + std::to_string(port) + " must fit 40 bits (2.9)");
  if (memory) {
    const Memory m(*memory);
    // 3.5.7: an EIB saves word 13 only at initial commissioning; until then position_bits is
    // the width of its "no valid position" answer.
    const bool eib = protocol::parameters::decode_encoder_type(m.manufacturer_word(word::kEncoderType)) ==
                     protocol::parameters::EncoderType::ExternalInterfaceBox;
    const unsigned word13 = m.manufacturer_word(word::kPositionFormat) & 0x3F;
    require(word13 == position_bits || (eib && word13 == 0),
            "memory word 13 says " + std::to_string(word13) + " position bits, but position_bits is " +
                std::to_string(position_bits));
    (void)reference_scheme(m, reference_marks, selected_reference_mark, position_bits);  // throws as it says
  }
}

std::uint64_t EncoderParams::position_at(Time t) const {
  const sim::Int128 range = sim::Int128{1} << position_bits;
  sim::Int128 p = static_cast<sim::Int128>(motion.start) + motion.steps_by(t);
  p %= range;
  if (p < 0) p += range;
  return static_cast<std::uint64_t>(p);
}

MemoryImage default_memory_image(const EncoderParams& p) {
  using A = MemoryArea;
  namespace pm = protocol::parameters;
  const bool v22 = p.version == EndatVersion::V2_2;
  const auto type = p.kind == EncoderKind::Linear       ? pm::EncoderType::AbsoluteLinear
                    : p.kind == EncoderKind::Multiturn  ? pm::EncoderType::MultiturnBattery
                    : p.kind == EncoderKind::TouchProbe ? pm::EncoderType::TouchProbe
                                                        : pm::EncoderType::Singleturn;
  if (p.kind == EncoderKind::Eib) return eib_factory_image();
  MemoryImage img;
  // 3.4.3: the encoder manufacturer's areas and the compensation values are factory protected.
  const std::uint16_t function_init = p.short_t_m_selected ? kShortRecoveryTimeOn : kShortRecoveryTimeOff;
  img.areas[A::OperatingStatus] = {0, 0, 0x0039, function_init};
  std::vector<std::uint16_t> m(48, 0);
  m[word::kVersion] = pm::encode_version(2);                       // 3.5.4
  m[word::kOemPartition] = 0x2020;                                 // OEM areas 1 and 2: addresses 0 .. 63
  m[word::kOemPartition + 1] = 0xFFFF;                             // OEM areas 3 and 4: not available
  m[word::kCompensationPartition] = m[word::kCompensationPartition + 1] = 0xFFFF;
  m[word::kPositionFormat] = static_cast<std::uint16_t>(0x8000 | p.position_bits);  // 3.5.6
  m[word::kEncoderType] = pm::encode_encoder_type(type);           // 3.5.7
  m[word::kCommandSet] = pm::encode_command_set({v22, false, v22 && p.communication_command_permitted});  // 3.5.22
  try {
    m[word::kCalculationTime] = pm::encode_calculation_time(
        pm::calculation_time_from(std::chrono::duration_cast<std::chrono::nanoseconds>(p.t_cal)));  // 3.5.24
  } catch (const std::invalid_argument&) {
    m[word::kCalculationTime] = 0;  // not representable in 13 bits of one unit: "not supported"
  }
  m[40] = pm::encode_ordering_designation(v22 ? "EnDat22" : "EnDat01");  // 3.5.25
  // What the safety comparison of position value 2 needs (3.5.12, 3.5.18, 3.5.19): steps per
  // revolution (rotary) or a 100 nm step (linear, a model default), 12 000 rpm or 120 m/min,
  // and the accuracy ranges of the spec's example (c1 = 40, a1 = 16 LSB) plus c2 = 1, a2 = 64 LSB
  // up to the maximum; a 2.2 encoder keeps them in words 11 .. 14 of its 2.2 area (65535 here).
  const unsigned singleturn = p.position_bits - p.multiturn_bits;
  const auto steps = pm::encode_measuring_steps(
      p.kind == EncoderKind::Linear || singleturn > 31 ? 100 : std::uint32_t{1} << singleturn);
  m[20] = steps[0];
  m[21] = steps[1];
  m[32] = p.kind == EncoderKind::Linear ? 120 : 12000;
  m[33] = v22 ? 0xFFFF : 0x2810;
  m[34] = v22 ? 0xFFFF : 0x0140;
  m[word::kSupportedErrors] = 0x007F;
  m[word::kSupportedWarnings] = 0x01FF;
  m[word::kManufacturerChecksum] = word_sum(m, 4, 46);            // 3.5.26
  img.areas[A::Manufacturer1].assign(m.begin(), m.begin() + 16);
  img.areas[A::Manufacturer2].assign(m.begin() + 16, m.begin() + 32);
  img.areas[A::Manufacturer3].assign(m.begin() + 32, m.end());
  img.areas[A::OperatingParameters].assign(16, 0);
  img.areas[A::Oem1].assign(64, 0);
  img.areas[A::Oem2].assign(64, 0);
  if (v22) {
    std::vector<std::uint16_t> e(64, 0);
    e[word::kAdditionalData1Support] = 0x001F;  // 3.9.2: all additional data 1
    e[word::kAdditionalData2Support] = 0x009F;  // 3.9.3: all but "position value 2" in additional data 2
    e[2] = p.t_m_short ? 0x0002 : 0x0000;      // 3.9.4: settable recovery time I
    e[word::kTemperatureScaling] = 0x8000;      // 3.9.6: 0.1 K (default value)
    // 3.9.7: valuation numbers 1 .. 6, system-specific data where the encoder has any.
    e[word::kDiagnosticStatus] = static_cast<std::uint16_t>(
        protocol::diagnosis::kValuationNumberBits | (p.sensors.system_data.empty() ? 0 : protocol::diagnosis::kSystemSpecificDataBit));
    e[6] = 0x007F;                              // 3.9.8: support of error message 2
    e[word::kMaxEncoderTemperature] = 3881;     // 3.9.16's example: 115 degC
    e[word::kMaxClockFrequency] = 16000;        // 3.9.19: kHz
    e[9] = m[20];                               // 3.9.10: position value 2 in the steps of position value 1
    e[10] = m[21];
    e[11] = 40;                                 // 3.9.11: c1 = 40, a1 = 16 LSB; c2 = 1, a2 = 64 LSB
    e[12] = 16;
    e[13] = 1;
    e[14] = 64;
    e[16] = p.sensors.position2_reversed ? 1 : 0;  // 3.9.13
    const auto offset = static_cast<std::uint64_t>(p.sensors.position2_offset);
    for (unsigned k = 0; k < 3; ++k) e[31 + k] = word_of(offset, k);  // 3.9.24
    if (type == pm::EncoderType::TouchProbe) e[45] = pm::encode_timestamp_unit(pm::TimestampUnit::Us1);  // 3.9.32
    e[word::kEndat22Checksum] = word_sum(e, 0, 62);
    img.areas[A::ManufacturerEndat22] = e;
    // 3.6.6: the default is word 22 minus a safety reserve; 5 K gives the example's 110 degC.
    img.areas[A::OperatingParameters][word::kTemperatureWarningThreshold] = 3831;
    img.areas[A::OperatingParameters2].assign(16, 0);
  }
  return img;
}

}  // namespace endatsim::slave
