#include "endatsim/slave/encoder_params.hpp"
#include "endatsim/sim/parameter.hpp"

#include <array>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <string>

#include "endatsim/protocol/additional_data.hpp"
#include "endatsim/protocol/diagnosis.hpp"
#include "endatsim/protocol/parameters.hpp"
#include "endatsim/protocol/timing.hpp"
#include "endatsim/slave/eib.hpp"
#include "endatsim/slave/reference.hpp"

namespace endatsim::slave {
namespace {

namespace position = protocol::frame_position;
// 3.9.16's example of the maximum encoder temperature.
constexpr double kDefaultMaxTemperatureCelsius = 115;

using sim::require;

using image_default::kOemArea;

using protocol::parameters::word_of;

}  // namespace

void EncoderParams::validate() const {
  if (const auto why = sim::first_out_of_range(encoder_parameters(), *this, "encoder")) throw std::invalid_argument(*why);
  require(multiturn_bits < position_bits, "encoder multiturn_bits must be less than position_bits (" +
                                              std::to_string(position_bits) + "), got " +
                                              std::to_string(multiturn_bits));
  require(kind == EncoderKind::Multiturn || multiturn_bits == 0,
          "multiturn_bits (" + std::to_string(multiturn_bits) + ") needs kind \"multiturn\"");
  require(kind != EncoderKind::Multiturn || multiturn_bits > 0, "kind \"multiturn\" needs multiturn_bits > 0");
  require(kind != EncoderKind::TouchProbe || position_bits == protocol::kTouchProbeBits,
          "kind \"touch_probe\" sends 16 bits (2.3.4.4), got position_bits " + std::to_string(position_bits));
  require(!short_t_m_selected || t_m_short.has_value(), "short_t_m_selected needs t_m_short");
  require(earliest_start_bit_clock > driver_enable_edge,
          "encoder earliest_start_bit_clock must be after the driver is on (driver_enable_edge " +
              std::to_string(driver_enable_edge) + "), got " + std::to_string(earliest_start_bit_clock));
  require(motion.start < (std::uint64_t{1} << position_bits),
          "motion.start must be below 2^position_bits = " + std::to_string(std::uint64_t{1} << position_bits) +
              ", got " + std::to_string(motion.start));
  if (const auto why = sim::first_out_of_range(sensor_parameters(), sensors, "encoder sensors")) throw std::invalid_argument(*why);
  if (const auto why = sim::first_out_of_range(motion_parameters(), motion, "encoder motion")) throw std::invalid_argument(*why);
  require(sensors.additional_sensors.size() <= protocol::diagnosis::kAdditionalSensorAddresses,
          "at most 16 additional sensors (4-bit address, 2.3.5.1)");
  for (const auto& [port, value] : sensors.test_values)
    require(value <= protocol::kTestValueMax,
            "test value of port " + std::to_string(port) + " must fit " + std::to_string(protocol::kTestValueBits) + " bits (2.9)");
  if (memory) {
    const Memory m(*memory);
    // 3.5.7: an EIB saves word 13 only at initial commissioning; until then position_bits is
    // the width of its "no valid position" answer.
    const bool eib = protocol::parameters::decode_encoder_type(m.manufacturer_word(word::kEncoderType)) ==
                     protocol::parameters::EncoderType::ExternalInterfaceBox;
    const unsigned word13 = protocol::parameters::decode_position_bits(m.manufacturer_word(word::kPositionFormat));
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
  img.areas[A::OperatingStatus] = {0, 0, protocol::factory_write_protection(), function_init};
  std::vector<std::uint16_t> m(protocol::kManufacturerWords, 0);
  m[word::kVersion] = pm::encode_version(image_default::kInterfaceVersion);       // 3.5.4
  // 3.5.5: OEM areas 1 and 2 at addresses 0 .. 63; OEM areas 3 and 4 and the compensation values
  // not available.
  const pm::Partition oem{kOemArea}, none;
  m[word::kOemPartition] = pm::encode_partition_word(oem, oem);
  m[word::kOemPartition + 1] = pm::encode_partition_word(none, none);
  m[word::kCompensationPartition] = m[word::kCompensationPartition + 1] = pm::encode_partition_word(none, none);
  m[word::kPositionFormat] = pm::encode_position_bits(p.position_bits);  // 3.5.6
  m[word::kEncoderType] = pm::encode_encoder_type(type);           // 3.5.7
  m[word::kCommandSet] = pm::encode_command_set({v22, false, v22 && p.communication_command_permitted});  // 3.5.22
  try {
    m[word::kCalculationTime] = pm::encode_calculation_time(
        pm::calculation_time_from(std::chrono::duration_cast<std::chrono::nanoseconds>(p.t_cal)));  // 3.5.24
  } catch (const std::invalid_argument&) {
    m[word::kCalculationTime] = 0;  // not representable in 13 bits of one unit: "not supported"
  }
  m[word::kOrderingDesignation] = pm::encode_ordering_designation(v22 ? "EnDat22" : "EnDat01");  // 3.5.25
  // What the safety comparison of position value 2 needs (3.5.12, 3.5.18, 3.5.19): steps per
  // revolution (rotary) or a measuring step (linear, a model default), the maximum velocity,
  // and the accuracy ranges of the spec's example (c1 = 40, a1 = 16 LSB) plus c2 = 1, a2 = 64 LSB
  // up to the maximum; a 2.2 encoder keeps them in words 11 .. 14 of its 2.2 area (65535 here).
  using namespace image_default;
  const bool linear = p.kind == EncoderKind::Linear;
  const unsigned singleturn = p.position_bits - p.multiturn_bits;
  const auto steps = pm::encode_measuring_steps(linear || singleturn > kStepsPerRevolutionBitsMax ? kLinearMeasuringStepNm
                                                                                                  : std::uint32_t{1} << singleturn);
  m[word::kMeasuringSteps] = steps[0];
  m[word::kMeasuringSteps + 1] = steps[1];
  m[word::kMaxVelocity] = linear ? kMaxVelocityMetresPerMinute : kMaxVelocityRpm;
  m[word::kAccuracy] = v22 ? pm::kAccuracySeeEndat22 : pm::encode_accuracy_range(kAccuracyC1, kAccuracyA1);
  m[word::kAccuracy + 1] = v22 ? pm::kAccuracySeeEndat22 : pm::encode_accuracy_range(kAccuracyC2, kAccuracyA2);
  m[word::kSupportedErrors] = pm::kEveryErrorBit;
  m[word::kSupportedWarnings] = pm::kEveryWarningBit;
  m[word::kManufacturerChecksum] = pm::manufacturer_checksum(m);  // 3.5.26
  set_manufacturer_words(img, m);
  img.areas[A::OperatingParameters].assign(protocol::kOperatingParametersWords, 0);
  img.areas[A::Oem1].assign(kOemArea.end + 1, 0);
  img.areas[A::Oem2].assign(kOemArea.end + 1, 0);
  if (v22) {
    std::vector<std::uint16_t> e(protocol::kEndat22Words, 0);
    e[word::kAdditionalData1Support] = pm::kSupportsEveryAdditionalData1;  // 3.9.2
    e[word::kAdditionalData2Support] = pm::kSupportsEveryAdditionalData2ButPositionValue2;  // 3.9.3
    e[word::kAdditionalFunctionsSupport] = p.t_m_short ? pm::kSupportsSettableRecoveryTime : 0;  // 3.9.4
    e[word::kTemperatureScaling] = pm::kTemperatureScalingTenthKelvin;  // 3.9.6 (default value)
    // 3.9.7: valuation numbers 1 .. 6, system-specific data where the encoder has any.
    e[word::kDiagnosticStatus] = static_cast<std::uint16_t>(
        protocol::diagnosis::kValuationNumberBits | (p.sensors.system_data.empty() ? 0 : protocol::diagnosis::kSystemSpecificDataBit));
    e[word::kErrorMessage2Support] = pm::kEveryErrorBit;                  // 3.9.8: support of error message 2
    e[word::kMaxEncoderTemperature] =  // 3.9.16's example: 115 degC
        static_cast<std::uint16_t>(protocol::diagnosis::tenth_kelvin_of_celsius(kDefaultMaxTemperatureCelsius));
    e[word::kMaxClockFrequency] = static_cast<std::uint16_t>(protocol::limit::kFcMaxSpecial / sim::kHz(1));  // 3.9.19: kHz
    // 3.9.10: position value 2 in the steps of position value 1
    e[word::kPosition2MeasuringSteps] = m[word::kMeasuringSteps];
    e[word::kPosition2MeasuringSteps + 1] = m[word::kMeasuringSteps + 1];
    // 3.9.11: the same accuracy ranges, c_1, a_1, c_2, a_2 in words 11 .. 14
    for (unsigned k = 0; const unsigned v : {kAccuracyC1, kAccuracyA1, kAccuracyC2, kAccuracyA2})
      e[word::kPosition2Accuracy + k++] = static_cast<std::uint16_t>(v);
    e[word::kPosition2Direction] = p.sensors.position2_reversed ? 1 : 0;  // 3.9.13
    const auto offset = static_cast<std::uint64_t>(p.sensors.position2_offset);
    for (unsigned k = 0; k < protocol::kPositionValue2WordsMax; ++k) e[word::kPosition2Offset + k] = word_of(offset, k);  // 3.9.24
    if (type == pm::EncoderType::TouchProbe) e[word::kTimestampUnit] = pm::encode_timestamp_unit(pm::TimestampUnit::Us1);  // 3.9.32
    e[word::kEndat22Checksum] = pm::endat22_checksum(e);  // 3.9.37
    img.areas[A::ManufacturerEndat22] = e;
    // 3.6.6: the default is word 22 minus a safety reserve; 5 K gives the example's 110 degC.
    constexpr std::uint16_t kSafetyReserveTenthKelvin = 50;
    img.areas[A::OperatingParameters][word::kTemperatureWarningThreshold] =
        static_cast<std::uint16_t>(e[word::kMaxEncoderTemperature] - kSafetyReserveTenthKelvin);
    img.areas[A::OperatingParameters2].assign(protocol::kOperatingParameters2DefaultWords, 0);
  }
  return img;
}

// ---- the parameter table -----------------------------------------------------------------------

namespace {

using Row = sim::Parameter<EncoderParams>;
namespace limit = protocol::limit;

template <auto Field, const auto& Names>
constexpr sim::ChoiceField<EncoderParams> choice() {
  return sim::enum_choice<EncoderParams, Field, Names>();
}

constexpr std::array<std::string_view, 2> kType1{"abort_high", "no_start_bit"};
static_assert(static_cast<std::size_t>(Type1Handling::NoStartBit) == 1);
constexpr std::array<std::string_view, 2> kPlacements{"in_frame", "after_frame"};
static_assert(static_cast<std::size_t>(MemoryAccessPlacement::AfterFrame) == 1);
constexpr std::array<std::string_view, 2> kNvm{"keep_old", "torn"};
static_assert(static_cast<std::size_t>(InterruptedNvmWrite::Torn) == 1);
constexpr std::array<std::string_view, 2> kActivations{"reset", "word14_write"};
static_assert(static_cast<std::size_t>(EibActivation::Word14Write) == 1);
constexpr std::array<std::string_view, 2> kEibPositions{"error_bit", "not_supported"};
constexpr std::array<std::string_view, 2> kHandovers{"release", "end_level"};
static_assert(static_cast<std::size_t>(SupplementHandover::EndLevel) == 1);
static_assert(static_cast<std::size_t>(EibPositionBeforeCommissioning::NotSupported) == 1);

using sim::row_bound;
constexpr std::int64_t kModelTimeMax = row_bound(EncoderParams::kMaxModelTime);

const std::array kRows{
    Row{"kind", choice<&EncoderParams::kind, kEncoderKindNames>(), 0, 0, "3.5.7",
        "What the encoder is (word 14). touch_probe sends 16 bits, the LSB its trigger status (2.3.4.4); eib is an "
        "External Interface Box in factory delivery state, the connected encoder after initial commissioning."},
    Row{"version", choice<&EncoderParams::version, kEndatVersionNames>(), 0, 0, "1",
        "The interface's command set: EnDat 2.1 is a subset of EnDat 2.2's (1). A 2.1 encoder answers EnDat 2.2 mode "
        "commands as not supported (type I)."},
    Row{"position_bits", &EncoderParams::position_bits, 1, EncoderParams::kMaxPositionBits, "3.5.6", "Clock pulses for the position value (word 13)."},
    Row{"multiturn_bits", &EncoderParams::multiturn_bits, 0, EncoderParams::kMaxPositionBits - 1, "3.5.6",
        "Upper bits of the position that count revolutions; needs kind \"multiturn\" and fewer than position_bits."},
    Row{"t_cal", &EncoderParams::t_cal, 0, kModelTimeMax, "2.3.2",
        "Position calculation time t_cal, FE1 to the start bit. The spec allows at most 1 ms; longer ones run and "
        "the checker reports them."},
    Row{"t_cal_22", &EncoderParams::t_cal_22, 0, kModelTimeMax, "2.3.2",
        "t_cal for EnDat 2.2 mode commands where it differs (absolute linear encoders may); none: t_cal."},
    Row{"t_cal_energy_saving", &EncoderParams::t_cal_energy_saving, 0, kModelTimeMax, "3.6.5",
        "t_cal of every mode command while the instruction energy-saving mode (operating parameters word 5 bit 0) is "
        "in effect; none: unchanged (the spec does not say what the mode saves)."},
    Row{"t_m", &EncoderParams::t_m, row_bound(limit::kRecoveryTimeMin), row_bound(limit::kRecoveryTimeMax), "2.3.2",
        "Recovery time I t_m: DATA HIGH after the last bit until the encoder is idle again."},
    Row{"t_m_short", &EncoderParams::t_m_short, row_bound(limit::kShortRecoveryTimeMin), row_bound(limit::kShortRecoveryTimeMax),
        "2.3.2 note 3", "The short recovery time I for 2.2 mode commands, if the encoder has one (word 3, 3.4.4)."},
    Row{"short_t_m_selected", &EncoderParams::short_t_m_selected, 0, 0, "3.4.4",
        "Word 3 selects the short recovery time at power-on; needs t_m_short."},
    Row{"t_r", &EncoderParams::t_r, 0, row_bound(sim::us(100)), "2.3.2", "t_R: time before the next query can be received."},
    Row{"t_st_max", &EncoderParams::t_st_max, row_bound(limit::kStartDelayAt16MHz), row_bound(sim::ms(10)), "2.3.2",
        "t_ST maximum from the encoder's datasheet (\"see encoder specifications\"); judged against this encoder."},
    Row{"t_lo_max", &EncoderParams::t_lo_max, row_bound(limit::kPulseWidthMin), row_bound(sim::ms(10)), "2.3.2",
        "t_LO maximum from the encoder's datasheet (\"see encoder specifications\"); judged against this encoder."},
    Row{"startup_time", &EncoderParams::startup_time, 0, row_bound(EncoderParams::kMaxFaultTime), "2.3.3",
        "Run-up after switching on (about 1 s), DATA high-impedance and clocks ignored meanwhile; 0: the run starts "
        "with the encoder up."},
    Row{"reset_time", &EncoderParams::reset_time, 0, row_bound(sim::ms(1000)), "2.7",
        "Restart after \"Encoder receive reset\" (a guess: the spec gives the same reaction as switching on)."},
    Row{"t_ac_read", &EncoderParams::t_ac_read, 0, row_bound(limit::kMemoryAccessMax), "2.3.2",
        "Memory access time t_ac for reads and selections."},
    Row{"t_ac_write", &EncoderParams::t_ac_write, 0, row_bound(limit::kMemoryAccessMax), "2.3.2",
        "Memory access time t_ac for writes."},
    Row{"t_ac_placement", choice<&EncoderParams::t_ac_placement, kPlacements>(), 0, 0, "2.3.1 note 1",
        "Where t_ac of a 2.1 parameter frame lies: in_frame (the acknowledgment waits for it) or after_frame (busy "
        "after the frame); the figure is lost."},
    Row{"interrupted_nvm_write", choice<&EncoderParams::interrupted_nvm_write, kNvm>(), 0, 0, "3.4.3",
        "What a word holds when a power interruption cuts its write short: keep_old, or torn (high byte new, low "
        "byte old); stored write protection bits survive either way."},
    Row{"supplement_end_marker_delay", &EncoderParams::supplement_end_marker_delay, 0, row_bound(sim::us(1)), "2.3",
        "After the master's command supplement, the encoder drives the HIGH end marker this long after its last "
        "bit (a guess, below the shortest t_m)."},
    Row{"supplement_ignore_clocks", &EncoderParams::supplement_ignore_clocks, 0, 16, "2.3",
        "Rising edges the encoder ignores DATA for after handing the line to the master's supplement (a guess)."},
    Row{"supplement_handover", choice<&EncoderParams::supplement_handover, kHandovers>(), 0, 0, "2.3",
        "After the answer of a 2.2 command with a command supplement: release DATA at once for the master's "
        "supplement, or end_level: first drive the level that says nothing follows (HIGH) for one clock, then "
        "release; the figures are lost."},
    Row{"output_delay", &EncoderParams::output_delay, 0, row_bound(sim::us(1)), "", "Clock input to data output inside the encoder."},
    Row{"asynchronous_time_delay_step", &EncoderParams::asynchronous_time_delay_step, 0, row_bound(sim::ms(1)), "2.4.2.3",
        "With oversampling activated (word 3, 3.4.4), time delay k selects the position sampled k steps of this "
        "length before the latch (a guess: the spec leaves it to the encoder's specifications)."},
    Row{"multiturn_overflow_error_bit", &EncoderParams::multiturn_overflow_error_bit, 0, 15, "3.4.4",
        "The word 0 bit (3.4.1) a latched multiturn overflow sets; the spec names none (a guess)."},
    Row{"continuous_low_bits", &EncoderParams::continuous_low_bits, 1, limit::kContinuousClockMaxLowBits, "2.3.1.1",
        "LOW bits between position words with a continuous clock (\"a maximum of 7 Low Bits\")."},
    Row{"driver_enable_edge", &EncoderParams::driver_enable_edge, position::kTurnaround, position::kTurnaround + 1,
        "2.3", "The falling edge that turns the encoder's driver on (the turnaround clocks)."},
    Row{"earliest_start_bit_clock", &EncoderParams::earliest_start_bit_clock, position::kTurnaround + 1,
        EncoderParams::kEarliestStartBitClockMax, "2.3.2",
        "The rising edge that may carry the start bit at the earliest (t_cal >= 10.5/f_c gives RE11); after "
        "driver_enable_edge."},
    Row{"type1_handling", choice<&EncoderParams::type1, kType1>(), 0, 0, "A2",
        "What DATA shows after a mode command it cannot take (type I): abort_high, or no_start_bit (DATA stays "
        "LOW); the figures are lost."},
    Row{"communication_command_permitted", &EncoderParams::communication_command_permitted, 0, 0, "2.10",
        "The encoder takes \"Encoder receive communication command\"; false answers A2 cause 4."},
    Row{"eib_activation", choice<&EncoderParams::eib_activation, kActivations>(), 0, 0, "3.5.7",
        "What completes an EIB's initial commissioning (a choice): reset (\"Encoder receive reset\" or power-on) "
        "or word14_write (the write of word 14)."},
    Row{"eib_activation_checks_checksum", &EncoderParams::eib_activation_checks_checksum, 0, 0, "3.5.26",
        "The EIB becomes the connected encoder only if word 47 checks."},
    Row{"eib_position_before_commissioning", choice<&EncoderParams::eib_position_before_commissioning, kEibPositions>(),
        0, 0, "A2", "A position request to an EIB not yet initiated: error_bit (F1 set, position 0) or not_supported "
        "(type I)."},
    Row{"selected_reference_mark", &EncoderParams::selected_reference_mark, 0, 65535, "2.3.4.3",
        "Equidistant reference marks (word 18, 3.5.10.2): the mark selected by hardware, counted from the first "
        "(word 19); none: the first mark crossed references."},
    Row{"error1", &EncoderParams::error1, 0, 0, "2.3.1", "F1 = 1 and F2 = 0 whatever word 0 says (a fault)."},
    Row{"error_message_1_stuck", &EncoderParams::error_message_1_stuck, 0, 0, "",
        "A failed error path: F1 stays LOW whatever the errors and forced dynamic sampling (a fault)."},
    Row{"error_message_2_stuck", &EncoderParams::error_message_2_stuck, 0, 0, "",
        "A failed error path: F2 stays HIGH, inactive (a fault)."},
    Row{"unsettled_positions", &EncoderParams::unsettled_positions, 0, 1000, "",
        "The first this many position answers after switching on or a reset carry an unsettled value (a fault)."},
    Row{"error_sources", &EncoderParams::error_sources, 0, 0xFFFF, "3.4.1", "Word 0 bits a fault keeps setting."},
    Row{"warning_sources", &EncoderParams::warning_sources, 0, 0xFFFF, "3.4.2", "Word 1 bits a fault keeps setting."},
};

// Position value 2's offset is a signed 48-bit value (3.9.24); positions and velocities as wide as
// the widest position.
constexpr std::int64_t k47 = std::int64_t{1} << (protocol::kPositionValue2BitsMax - 1);
constexpr std::int64_t k48 = std::int64_t{1} << EncoderParams::kMaxPositionBits;

using S = Sensors;
const std::array kSensorRows{
    sim::Parameter<S>{"position2_offset", &S::position2_offset, -k47, k47 - 1, "3.9.24",
                      "Position value 2 = position + offset (also stored in words 31 .. 33 of the 2.2 area)."},
    sim::Parameter<S>{"position2_reversed", &S::position2_reversed, 0, 0, "3.9.13",
                      "Position value 2 = offset - position."},
    sim::Parameter<S>{"position2_fault", &S::position2_fault, -k47, k47, "",
                      "A fault of the second position sensing: added to position value 2."},
    sim::Parameter<S>{"commutation", &S::commutation, 0, protocol::AdditionalData2Word::kCommutationBits, "2.3.5.2", "The commutation signals u v w, u the MSB."},
    sim::Parameter<S>{"acceleration", &S::acceleration, 0, 0xFFFF, "2.3.5.2", "The acceleration, as sent."},
    sim::Parameter<S>{"limit_position_1", &S::limit_position_1, 0, 0, "2.3.5.2", "Limit position signal 1."},
    sim::Parameter<S>{"limit_position_2", &S::limit_position_2, 0, 0, "2.3.5.2", "Limit position signal 2."},
    sim::Parameter<S>{"operating_status_error_sources", &S::operating_status_error_sources, 0, 0xFFFF, "2.3.5.3",
                      "The operating status error sources, as sent."},
    sim::Parameter<S>{"timestamp_unit", &S::timestamp_unit, row_bound(sim::ns(1)), row_bound(sim::ms(1)), "3.9.32",
                      "The unit of the touch probe's timestamps."},
};

using Motion = MotionProfile;
const std::array kMotionRows{
    sim::Parameter<Motion>{"start", &Motion::start, 0, k48 - 1, "", "The position at time 0, in measuring steps."},
    sim::Parameter<Motion>{"counts_per_s", &Motion::counts_per_s, -k48, k48, "",
                           "The velocity in measuring steps per second; negative counts down."},
};

}  // namespace

std::span<const sim::Parameter<EncoderParams>> encoder_parameters() { return kRows; }
std::span<const sim::Parameter<Sensors>> sensor_parameters() { return kSensorRows; }
std::span<const sim::Parameter<MotionProfile>> motion_parameters() { return kMotionRows; }

}  // namespace endatsim::slave
