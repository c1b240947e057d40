#include "endatsim/slave/encoder.hpp"

#include <algorithm>
#include <stdexcept>

#include "endatsim/protocol/parameters.hpp"
#include "endatsim/slave/eib.hpp"

namespace endatsim::slave {
namespace {

using protocol::ErrorCause;
namespace position = protocol::frame_position;
using MC = ModeCommand;
using I = Information;

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

constexpr std::uint8_t kForcedError1First = 0x01, kForcedError2First = 0x09;  // 3.5.3 (guess, see docs/model-reference.md)
constexpr std::uint16_t kInstructionHighImpedance = 0x0002;                    // 2.10: word 5 bit 1
constexpr std::uint16_t kInstructionNoPositionUpdate = 0x0004;                  // 3.6.5: word 5 bit 2
constexpr unsigned kTouchProbeBits = 16;                                       // 2.3.4.4

using protocol::parameters::EncoderFunction;

__int128 floor_div(__int128 x, __int128 d) { return x >= 0 ? x / d : -((-x + d - 1) / d); }

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
  require(kind != EncoderKind::TouchProbe || position_bits == kTouchProbeBits,
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

// The whole measuring steps an axis moving at `counts_per_s` has made by `t`. A count changes when
// the axis crosses a step, so a negative velocity rounds toward minus infinity, as an encoder
// counting down does, not toward zero.
namespace {
__int128 steps_by(std::int64_t counts_per_s, Time t) {
  constexpr __int128 kPsPerSecond = 1'000'000'000'000;
  const __int128 n = static_cast<__int128>(counts_per_s) * t.count();
  return n >= 0 ? n / kPsPerSecond : -((-n + kPsPerSecond - 1) / kPsPerSecond);
}
}  // namespace

std::uint64_t EncoderParams::position_at(Time t) const {
  const __int128 range = __int128{1} << position_bits;
  __int128 p = static_cast<__int128>(motion.start) + steps_by(motion.counts_per_s, t);
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

Encoder::Encoder(sim::Kernel& kernel, line::Line& line, const EncoderParams& params)
    : Encoder(kernel, line.encoder(), params) {}

Encoder::Encoder(sim::Kernel& kernel, line::Line::EncoderSide pins, const EncoderParams& params)
    : kernel_(kernel), pins_(pins), params_(params),
      memory_((params.validate(), params.memory.value_or(default_memory_image(params)))),
      data_logic_(kernel, "encoder_data_logic", false), enable_logic_(kernel, "encoder_enable_logic", true),
      data_out_delay_(kernel, data_logic_, pins_.data_out, params.output_delay),
      enable_out_delay_(kernel, enable_logic_, pins_.data_enable, params.output_delay),
      recovery_timer_(kernel, sim::bind<&Encoder::on_recovery_time_elapsed>(this)),
      memory_timer_(kernel, sim::bind<&Encoder::on_memory_access_done>(this)),
      end_marker_timer_(kernel, sim::bind<&Encoder::on_end_marker_due>(this)),
      startup_timer_(kernel, sim::bind<&Encoder::on_started>(this)) {
  pins_.clock_in.on_change(sim::bind<&Encoder::on_clock>(this));
  position_bits_ = params_.position_bits;
  adopt_encoder_type();
  unsettled_left_ = params_.unsettled_positions;
  activate_functions();
  latch_bus_address_error();
  enable();  // idle: DATA driven LOW, unless word 5 puts the driver at high impedance (2.10)
  if (params_.startup_time > Time::zero()) go_offline(params_.startup_time);
}

// 3.5.7: what the encoder is follows word 14: absolute or incremental with its reference marks
// (2.3.4.3), a touch probe (2.3.4.4), or an EIB that is not yet initiated (A2 cause 5), whose
// manufacturer areas stay open for initial commissioning meanwhile.
void Encoder::adopt_encoder_type() {
  namespace pm = protocol::parameters;
  const auto type = pm::decode_encoder_type(memory_.manufacturer_word(word::kEncoderType));
  eib_not_initiated_ = type == pm::EncoderType::ExternalInterfaceBox;
  memory_.set_initial_commissioning(eib_not_initiated_);
  touch_probe_ = type == pm::EncoderType::TouchProbe;
  require(!touch_probe_ || position_bits_ == kTouchProbeBits,
          "a touch probe (word 14 type 5) sends 16 bits (2.3.4.4), but position_bits is " +
              std::to_string(position_bits_));
  reference_ = slave::reference_scheme(memory_, params_.reference_marks, params_.selected_reference_mark, position_bits_);
  incremental_ = reference_.marks != pm::ReferenceMarks::None;
  referenced_ = !incremental_;
  rm_reset_at_.reset();
  reference_offset_ = 0;
}

// 3.5.7: "the encoder type must be modified during initial commissioning according to the
// connected encoder". The EIB becomes that encoder when word 14 names another type, word 13 a
// transfer format (1 .. 48 bits; 16 for a touch probe), words 18/19 usable reference marks and,
// with eib_activation_checks_checksum, word 47 checks (3.5.26). Otherwise it stays not initiated.
// Relative positions count from here, as after switching on (2.3.4.3).
void Encoder::complete_commissioning() {
  namespace pm = protocol::parameters;
  std::vector<std::uint16_t> m(48, 0);
  for (unsigned n = 4; n < 48; ++n) m[n] = memory_.manufacturer_word(n);
  const auto type = pm::decode_encoder_type(m[word::kEncoderType]);
  const unsigned bits = pm::decode_position_bits(m[word::kPositionFormat]);
  const bool checksum_ok = !params_.eib_activation_checks_checksum || pm::manufacturer_checksum(m) == m[47];
  if (type == pm::EncoderType::ExternalInterfaceBox || bits < 1 || bits > 48 || !checksum_ok ||
      (type == pm::EncoderType::TouchProbe && bits != kTouchProbeBits))
    return;
  try {
    (void)slave::reference_scheme(memory_, params_.reference_marks, params_.selected_reference_mark, bits);
  } catch (const std::invalid_argument&) {
    return;  // words 18/19 name marks the model cannot place
  }
  position_bits_ = bits;
  adopt_encoder_type();
  reference_origin_ = reference_search_from_ = kernel_.now();
}

// A2 cause 5 (choice, docs/model-reference.md): an EIB that is not yet initiated refuses every memory access
// outside the areas initial commissioning fills (slave/eib.hpp).
std::optional<ErrorCause> Encoder::not_initiated(std::optional<MemoryArea> area) const {
  if (!eib_not_initiated_ || (area && eib_commissioning_area(*area))) return std::nullopt;
  return ErrorCause::EibNotInitialised;
}

// 2.3.3 (the figure's labels in the German brochure: "*) hochohmig"; docs/model.md §8): during
// run-up DATA is high-impedance and the encoder takes no clock; afterwards DATA is driven LOW,
// the EnDat idle level (2.3).
void Encoder::go_offline(Time duration) {
  offline_ = true;
  state_ = State::Idle;
  enable_logic_.write(false);
  startup_timer_.start(duration);
}

void Encoder::on_started() {
  offline_ = false;
  drive(false);
  enable();
}

bool Encoder::busy() const { return kernel_.now() < busy_until_; }

bool Encoder::drives_bus() const {
  // 2.10: word 5 bit 1 "data driver at high-impedance"; an encoder that another address
  // deselected stays off the bus too.
  return selected_on_bus_ && (memory_.operating_parameter(word::kInstructions) & kInstructionHighImpedance) == 0;
}

void Encoder::on_clock(std::uint64_t level) {
  if (offline_ || kernel_.now() < ready_at_) {  // running up, or t_R: not ready for the next query yet
    ++ignored_edges_;
    return;
  }
  if (level == 0) on_falling_edge();
  else on_rising_edge();
}

// ---- the frame, edge by edge ---------------------------------------------------------------

void Encoder::begin_frame() {
  // 2.2: "the position value is saved in the encoder with the falling clock edge";
  // 2.3: "with the first falling clock edge, the send block in the encoder must be deactivated".
  state_ = State::Header;
  clock_ = 1;
  mode_bits_ = 0;
  command_ = nullptr;
  pending_ = {};
  answer_.clear();
  next_bit_ = 0;
  EncoderFrame f;
  f.start = kernel_.now();
  update_reference();
  check_multiturn_overflow();
  f.position = f.true_position = latched_position(kernel_.now());
  // 3.6.5 word 5 bit 2, "no updating of position values": from the first frame after the
  // instruction the encoder keeps sending the position it latched then (our reading: the spec
  // names the instruction only), until the bit is cleared.
  if ((memory_.operating_parameter(word::kInstructions) & kInstructionNoPositionUpdate) != 0) {
    if (!frozen_position_) frozen_position_ = f.position;
    f.position = *frozen_position_;
  } else {
    frozen_position_.reset();
  }
  if (frames_.size() >= 2 * kept_frames_) frames_.erase(frames_.begin(), frames_.end() - static_cast<std::ptrdiff_t>(kept_frames_ - 1));
  frames_.push_back(f);
  ++frame_count_;
  latch_errors();
  frames_.back().error_present = error_present();
  release();
}

void Encoder::on_falling_edge() {
  recovery_timer_.cancel();
  if (state_ == State::Idle) {
    begin_frame();
    return;
  }
  ++clock_;
  EncoderFrame& f = frames_.back();
  const unsigned payload = command_ != nullptr ? command_->payload_bits : 0;
  switch (state_) {
    case State::Type1:
    case State::Answer:
      if (clock_ == params_.driver_enable_edge + payload) {
        drive(state_ == State::Type1 && params_.type1 == Type1Handling::AbortHigh);
        enable();
      }
      break;
    case State::EndOfData:
      // 2.3.1: a continuous clock is only possible with "Encoder send position values";
      // the next position is saved with the falling edge after the HIGH bit.
      if (f.command == MC::EncoderSendPositionValues) {
        f.continuous_positions.push_back(latched_position(kernel_.now()));
        ++f.continuous_words;
        state_ = State::ContinuousGap;
        gap_low_bits_ = 0;
      } else if (payload != 0) {
        f.too_many_clocks = true;  // 2.4.1: "more clock pulses than required" -> A2
      }
      break;
    default:
      break;
  }
}

void Encoder::on_rising_edge() {
  recovery_timer_.start(recovery_time());
  if (state_ == State::Idle) return;  // a rising edge without a frame: nothing to do
  EncoderFrame& f = frames_.back();
  f.clocks = clock_;
  const bool bit = pins_.data_in.read();
  switch (state_) {
    case State::Header:
      // 2.3: the encoder accepts the mode bits on the rising edges of clocks 3 .. 8.
      if (clock_ >= position::kFirstModeBit && clock_ <= position::kLastModeBit)
        mode_bits_ = static_cast<std::uint8_t>(mode_bits_ << 1 | bit);
      if (clock_ == position::kLastModeBit) decode_mode_command();
      break;
    case State::Payload:
      shift_ = shift_ << 1 | bit;
      if (++shifted_ == protocol::kPayloadBits) answer_parameter_frame();
      break;
    case State::Answer:
      emit_answer_bit();
      break;
    case State::ContinuousGap:
      if (gap_low_bits_ < params_.continuous_low_bits) {
        ++gap_low_bits_;
        drive(false);
      } else {
        load_continuous_word();
        emit_answer_bit();
      }
      break;
    case State::SupplementHunt:
      // docs/model.md §4: the line floats (fail-safe HIGH) until the master drives its lead
      // bits, so the encoder waits for a LOW before it takes a HIGH as the start bit. Right
      // after its release it still sees its own last bit, so it ignores a few edges.
      if (clock_ <= release_clock_ + params_.supplement_ignore_clocks) break;
      if (!seen_low_) seen_low_ = !bit;
      else if (bit) {
        state_ = State::Supplement;
        shift_ = 0;
        shifted_ = 0;
      }
      break;
    case State::Supplement:
      shift_ = shift_ << 1 | bit;
      if (++shifted_ == protocol::kPayloadBits) process_supplement();
      break;
    case State::SupplementDone:
      clock_after_supplement();
      break;
    default:
      break;
  }
}

// 2.4.2.1: "If a non-permissible memory area is received by the encoder or more clock pulses than
// necessary are sent, an error message is output compliant to Appendix A2": cause 2, type II, the
// MRS code and block address acknowledged inverted; the selection does not take place.
void Encoder::clock_after_supplement() {
  EncoderFrame& f = frames_.back();
  if (f.too_many_clocks) return;
  f.too_many_clocks = true;
  const auto address = static_cast<std::uint8_t>(f.supplement.value_or(0) >> 16);
  if (command_->command != MC::EncoderSendPositionValuesAndSelectionOfMemoryArea ||
      protocol::selects_additional_data(address) || f.supplement_ignored)
    return;
  f.error = ErrorCause::MrsFrameDisrupted;
  last_mrs_ = static_cast<std::uint8_t>(~address);
  last_block_ = static_cast<std::uint8_t>(~static_cast<std::uint8_t>(f.supplement.value_or(0)));
  if (in_progress_.kind == Pending::Kind::Select) {
    in_progress_ = {};
    memory_timer_.cancel();
    busy_until_ = kernel_.now();
  }
}

void Encoder::decode_mode_command() {
  EncoderFrame& f = frames_.back();
  f.mode_bits = mode_bits_;
  f.command = protocol::decode_mode_bits(mode_bits_);
  if (!f.command || (protocol::info(*f.command).version == EndatVersion::V2_2 && params_.version == EndatVersion::V2_1))
    return abort_type1(ErrorCause::ModeCommandDisrupted);
  command_ = &protocol::info(*f.command);
  if (eib_not_initiated_ && command_->answer == protocol::AnswerFormat::Position &&
      params_.eib_position_before_commissioning == EibPositionBeforeCommissioning::NotSupported)
    return abort_type1(ErrorCause::ModeCommandDisrupted);
  if (!selected_on_bus_ && *f.command != MC::EncoderReceiveCommunicationCommand) {
    state_ = State::Type1;  // 2.10: only the addressed encoder reacts; this one keeps off the bus
    return;
  }
  if (command_->payload_bits != 0) {
    state_ = State::Payload;
    shift_ = 0;
    shifted_ = 0;
    return;
  }
  answer_position();
}

void Encoder::abort_type1(ErrorCause cause) {
  EncoderFrame& f = frames_.back();
  f.type1_error = true;  // appendix A2, type I: mode command disrupted or not supported
  f.error = cause;
  state_ = State::Type1;
}

// The position as sent: the measured value in the direction word 30 chooses (3.5.16), plus the
// datum shift of operating parameters words 0..2 as activated by the last reset (3.6.2: "the
// value must be added"; 3.5.13: words 22/23 have no effect on the output), modulo 2^n ("after
// the zero position follows 2^x - 1").
std::uint64_t Encoder::output_position(std::uint64_t measured) const {
  const unsigned n = position_bits_;
  const std::uint64_t mask = n >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << n) - 1;
  // UNCERTAIN (3.5.16, its table lost a column): bit 0 = 0, the default, is taken as positions
  // rising in the documented direction of measurement, bit 0 = 1 as falling.
  const bool falling = (memory_.manufacturer_word(word::kDirection) & 1U) != 0;
  std::uint64_t p = falling ? (0 - measured) & mask : measured;
  const auto& op = memory_.active_operating_parameters();
  std::uint64_t shift = std::uint64_t{op[word::kDatumShift]} | std::uint64_t{op[word::kDatumShift + 1]} << 16;
  if (n > 32) shift |= std::uint64_t{op[word::kDatumShift + 2]} << 32;
  else if ((shift & 0x8000'0000ULL) != 0) shift |= 0xFFFF'FFFF'0000'0000ULL;  // two's complement in 32 bits
  return (p + shift) & mask;
}

__int128 Encoder::unwrapped_position(Time t) const {
  return static_cast<__int128>(params_.motion.start) + slip_ + steps_by(params_.motion.counts_per_s, t);
}

// 2.3.4.3: RM is set once the axis has crossed a reference mark as the scheme needs it (two
// with distance-coded marks, the selected one of equidistant marks) since switching on or the
// last reset; until then word 1 bit 4 warns "reference point not reached".
// What a completed write sets going besides the stored word: an EIB's commissioning (3.5.7), the
// bus address error (3.6.4), and the RM reset of operating parameters 2 word 11 (3.10.5). A 2.1
// write completes with its acknowledgment, a 2.2 one when Busy is reset (3.10).
void Encoder::written(const Selection& s, std::uint8_t address) {
  note_commissioning_write(s, address);
  latch_bus_address_error();
  // 3.10.5: bit 0 = 1 and bit 1 = 0 reset RM of an incremental encoder and set the warning
  // "reference point not reached"; "this does not influence position value and position value 2":
  // the reference found stays in use. A reference mark crossed from then on sets RM again.
  const std::uint16_t rm_reset = 0x0001, rm_reset_mask = 0x0003;
  if (s.area == MemoryArea::OperatingParameters2 && address == word::kReferencing && incremental_ &&
      (memory_.image().areas.at(MemoryArea::OperatingParameters2).at(word::kReferencing) & rm_reset_mask) == rm_reset) {
    rm_reset_at_ = kernel_.now();
    memory_.latch_errors(0, protocol::parameters::kWarningReferencePointNotReached);
  }
}

void Encoder::update_reference() {
  if (referenced_ && rm_reset_at_) {
    if (find_reference(reference_, unwrapped_position(*rm_reset_at_), unwrapped_position(kernel_.now()), position_bits_))
      rm_reset_at_.reset();
    return;
  }
  if (referenced_) return;
  const auto offset = find_reference(reference_, unwrapped_position(reference_search_from_),
                                     unwrapped_position(kernel_.now()), position_bits_);
  if (offset) {
    referenced_ = true;
    reference_offset_ = *offset;
  } else {
    memory_.latch_errors(0, protocol::parameters::kWarningReferencePointNotReached);
  }
}

// Word 0 as the error messages see it: the stored bits and an unlatched multiturn overflow.
std::uint16_t Encoder::error_word() const {
  const auto overflow = multiturn_overflow_ ? 1U << params_.multiturn_overflow_error_bit : 0U;
  return static_cast<std::uint16_t>(memory_.operating_status(word::kErrors) | overflow);
}

bool Encoder::error_message_1() const {
  const bool forced = test_port_22_ >= kForcedError1First && test_port_22_ < kForcedError1First + 7;
  return !params_.error_message_1_stuck &&
         (params_.error1 || forced || eib_not_initiated_ || bus_address_error_ ||
          (error_word() & memory_.manufacturer_word(word::kSupportedErrors)) != 0);
}

bool Encoder::error_message_2() const {
  const bool forced = test_port_22_ >= kForcedError2First && test_port_22_ < kForcedError2First + 7;
  return !params_.error_message_2_stuck &&
         (params_.error1 || forced || eib_not_initiated_ || (error_word() & memory_.endat22_word(6)) != 0);
}

bool Encoder::error_present() const {
  const auto supported = memory_.manufacturer_word(word::kSupportedErrors) | memory_.endat22_word(6);
  return params_.error1 || eib_not_initiated_ || bus_address_error_ || (error_word() & supported) != 0;
}

void Encoder::answer_position() {
  EncoderFrame& f = frames_.back();
  state_ = State::Answer;
  first_answer_clock_ = params_.earliest_start_bit_clock;
  answer_not_before_ = f.start + params_.t_cal_for(command_->version);  // 2.3.2: t_cal runs from FE1
  if (command_->answer == protocol::AnswerFormat::TestValues) {
    const auto it = params_.sensors.test_values.find(test_port_21_);
    answer_ = protocol::encode_test_values(error_message_1(), it == params_.sensors.test_values.end() ? 0 : it->second,
                                           params_.crc);
    return;
  }
  if (unsettled_left_ > 0) {  // a fault: a value from before the position settled (seeded by the frame)
    --unsettled_left_;
    const std::uint64_t mask = (std::uint64_t{1} << position_bits_) - 1;
    std::uint64_t z = (frame_count_ + 1) * 0x9E3779B97F4A7C15ULL;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    f.position = (z ^ (z >> 31)) & mask;
  }
  // 2.3.1: F2 is low-active; it is only sent with 2.2 mode commands.
  answer_ = protocol::encode_position_frame(command_->version, position_bits_,
                                            {error_message_1(), !error_message_2(), f.position}, params_.crc);
  if (command_->version != EndatVersion::V2_2) return;
  // docs/model.md §2: additional data 2 comes before additional data 1.
  if (selection_[1]) append_additional_datum(*selection_[1], 1);
  if (selection_[0]) append_additional_datum(*selection_[0], 0);
}

void Encoder::answer_parameter_frame() {
  EncoderFrame& f = frames_.back();
  f.payload = shift_;
  const auto address = static_cast<std::uint8_t>(shift_ >> 16);
  const auto parameter = static_cast<std::uint16_t>(shift_);
  std::uint16_t echo = parameter;
  std::optional<ErrorCause> error;
  Time t_ac{0};
  const bool memory_access = command_->command != MC::EncoderReceiveTestCommand &&
                             command_->command != MC::EncoderReceiveCommunicationCommand;
  const bool selection = command_->command == MC::SelectionOfMemoryArea;
  const bool parameter_access = selection || command_->command == MC::EncoderReceiveParameters ||
                                command_->command == MC::EncoderSendParameters;
  const auto area = selection ? protocol::memory_area_from_mrs(address)
                              : area_selected_ ? std::optional{selection_area_.area} : std::nullopt;
  if (const auto refused = parameter_access ? not_initiated(area) : std::nullopt) {
    error = refused;  // A2 cause 5; a reset still works: it completes the commissioning
  } else if (transmission_incomplete_) {
    // A2 cause 3: a transmission was not completed; "the error handling will be transferred with
    // the next query", the first that has an acknowledgment to carry it. The access is discarded.
    error = ErrorCause::TransmissionNotCompleted;
    transmission_incomplete_ = false;
  } else if (memory_access && busy()) {
    // 2.3.1 note 1: a 2.1 access or reset with Busy = 1 gets type II; A2 cause 8 names it ("with
    // still set active busy bit").
    error = ErrorCause::ImpermissibleAddress;
  } else {
    switch (command_->command) {
      case MC::SelectionOfMemoryArea:  // 2.4.1
        error = memory_.check_selection(address, 0, false);
        pending_ = {Pending::Kind::Select, {protocol::memory_area_from_mrs(address).value_or(MemoryArea{}), 0}, address,
                    parameter};
        t_ac = params_.t_ac_read;
        break;
      case MC::EncoderReceiveParameters:  // 2.6
        error = area_selected_ ? memory_.check_write(selection_area_, address, parameter)
                               : std::optional{ErrorCause::ImpermissibleMemoryArea};
        pending_ = {Pending::Kind::Write, selection_area_, address, parameter};
        t_ac = params_.t_ac_write;
        break;
      case MC::EncoderSendParameters:  // 2.5
        if (!area_selected_) error = ErrorCause::ImpermissibleMemoryArea;
        else if (const auto read = memory_.read(selection_area_, address)) echo = read.value;
        else error = read.error;
        t_ac = params_.t_ac_read;
        break;
      case MC::EncoderReceiveReset:  // 2.7
        pending_ = {Pending::Kind::Reset, {}, address, parameter};
        break;
      case MC::EncoderReceiveTestCommand:  // 2.8
        test_port_21_ = address;
        break;
      case MC::EncoderReceiveCommunicationCommand: {  // 2.10
        const auto own = static_cast<std::uint8_t>(memory_.operating_parameter(word::kEncoderAddress));
        const bool was_selected = selected_on_bus_;
        if (!params_.communication_command_permitted) error = ErrorCause::CommunicationCommandNotPermitted;
        else if (address == 0 && (parameter & kInstructionHighImpedance) != 0)
          error = ErrorCause::DataDriverHighImpedanceBroadcast;
        else if (address != 0 && address != own && was_selected)
          error = ErrorCause::UnknownCommunicationAddress;
        // 2.10: "only the encoder with the previously selected address reacts ... until a new
        // address is given"; the change takes effect after this frame's acknowledgment.
        bus_selection_after_frame_ = address == 0 || address == own;
        if (!was_selected && !*bus_selection_after_frame_) {
          state_ = State::Type1;  // not addressed: stays silent
          return;
        }
        // The addressed encoder takes its instruction at once and acknowledges with it; a
        // broadcast is acknowledged by the encoder active before it, then carried out (2.10).
        if (address == own && address != 0)
          memory_.write({MemoryArea::OperatingParameters, 0}, word::kInstructions, parameter);
        else if (address == 0)
          pending_ = {Pending::Kind::Write, {MemoryArea::OperatingParameters, 0}, word::kInstructions, parameter};
        break;
      }
      default:
        break;
    }
  }
  if (error) {
    // A2 type II: "the address or parameter is returned inverted". The high-impedance broadcast
    // (cause 6) is still carried out: that is what it is for (2.10).
    f.error = error;
    if (error != ErrorCause::DataDriverHighImpedanceBroadcast) pending_ = {};
    answer_ = protocol::encode_parameter_frame(static_cast<std::uint8_t>(~address), static_cast<std::uint16_t>(~echo),
                                               params_.crc);
  } else {
    answer_ = protocol::encode_parameter_frame(address, echo, params_.crc);
  }
  state_ = State::Answer;
  first_answer_clock_ = params_.earliest_start_bit_clock + protocol::kPayloadBits;
  if (!error && pending_.kind == Pending::Kind::Write)
    note_nvm_write(pending_.selection, pending_.address, pending_.value, kernel_.now() + t_ac);
  const bool in_frame = params_.t_ac_placement == MemoryAccessPlacement::InFrame;
  answer_not_before_ = kernel_.now() + (in_frame && !error ? t_ac : Time::zero());
  if (!in_frame && !error && memory_access) busy_until_ = std::max(busy_until_, kernel_.now() + t_ac);
}

void Encoder::emit_answer_bit() {
  EncoderFrame& f = frames_.back();
  if (next_bit_ == 0 && f.continuous_words == 0) {
    // docs/model.md §1: LOW until t_cal (or t_ac) has elapsed, start bit no earlier than RE11
    // (RE35 after a 2.1 parameter frame).
    if (clock_ < first_answer_clock_ || kernel_.now() < answer_not_before_) {
      drive(false);
      return;
    }
    f.start_bit_clock = clock_;
  }
  if (next_bit_ < answer_.size()) {
    drive(answer_[next_bit_++] != 0);
    return;
  }
  if (command_->supplement) {
    // docs/model.md §4: the encoder hands DATA to the master for the command supplement.
    release();
    state_ = State::SupplementHunt;
    release_clock_ = clock_;
    seen_low_ = false;
    return;
  }
  // docs/model.md §2: after the last CRC bit DATA goes HIGH and stays HIGH for t_m.
  drive(true);
  state_ = State::EndOfData;
}

void Encoder::load_continuous_word() {
  EncoderFrame& f = frames_.back();
  answer_ = protocol::encode_position_frame(EndatVersion::V2_1, position_bits_,
                                            {error_message_1(), true, f.continuous_positions.back()}, params_.crc);
  next_bit_ = 0;
  state_ = State::Answer;
}

// ---- EnDat 2.2 command supplement and additional data ------------------------------------

void Encoder::process_supplement() {
  EncoderFrame& f = frames_.back();
  f.supplement = shift_;
  state_ = State::SupplementDone;
  end_marker_timer_.start(params_.supplement_end_marker_delay);
  const auto address = static_cast<std::uint8_t>(shift_ >> 16);
  const auto parameter = static_cast<std::uint16_t>(shift_);
  const MC c = command_->command;
  const bool memory_access = c == MC::EncoderSendPositionValuesAndReceiveParameter ||
                             c == MC::EncoderSendPositionValuesAndSendParameter ||
                             (c == MC::EncoderSendPositionValuesAndSelectionOfMemoryArea &&
                              !protocol::selects_additional_data(address));
  if (memory_access && busy()) {
    f.supplement_ignored = true;  // 2.3.1 note 1: "ignored" with 2.2 commands
    return;
  }
  switch (c) {
    case MC::EncoderSendPositionValuesAndSelectionOfMemoryArea: {  // 2.4.2
      if (protocol::selects_additional_data(address)) {
        const unsigned which = (address & 0x10) != 0 ? 1 : 0;
        last_mrs_ = address;
        last_block_ = 0;
        if (address == protocol::kStopAdditionalData1 || address == protocol::kStopAdditionalData2) {
          selection_[which].reset();
          type3_[which].reset();
        } else {
          const Information i = protocol::information_of_mrs(address);
          selection_[which] = i;
          type3_[which] = type3_cause(i, which);
          if (which == 0 && selection_[1]) type3_[1] = type3_cause(*selection_[1], 1);
        }
        break;
      }
      const auto block = static_cast<std::uint8_t>(parameter);  // block address: low byte (docs/model-reference.md, guess)
      auto error = not_initiated(protocol::memory_area_from_mrs(address));  // A2 cause 5
      if (!error) error = memory_.check_selection(address, block, true);
      f.error = error;
      // A2 type II: the MRS code (block address) is acknowledged inverted.
      last_mrs_ = error ? static_cast<std::uint8_t>(~address) : address;
      last_block_ = error ? static_cast<std::uint8_t>(~block) : block;
      if (!error) {
        in_progress_ = {Pending::Kind::Select, {*protocol::memory_area_from_mrs(address), block}, address, parameter};
        start_memory_access(params_.t_ac_read);
      }
      break;
    }
    case MC::EncoderSendPositionValuesAndReceiveParameter: {  // 2.6.1
      const auto error = area_selected_ ? memory_.check_write(selection_area_, address, parameter)
                                        : std::optional{ErrorCause::ImpermissibleMemoryArea};
      f.error = error;
      in_progress_ = {error ? Pending::Kind::None : Pending::Kind::Write, selection_area_, address, parameter};
      memory_error_ = error.has_value();
      start_memory_access(params_.t_ac_write);
      if (!error) note_nvm_write(selection_area_, address, parameter, busy_until_);
      break;
    }
    case MC::EncoderSendPositionValuesAndSendParameter: {  // 2.5.1
      const auto read = area_selected_ ? memory_.read(selection_area_, address)
                                       : Memory::WordRead{.value = 0, .error = ErrorCause::ImpermissibleMemoryArea};
      const std::uint16_t value = read.value;
      const auto error = read.error;
      f.error = error;
      in_progress_ = {Pending::Kind::None, selection_area_, address, error ? parameter : value};
      memory_error_ = error.has_value();
      start_memory_access(params_.t_ac_read);
      break;
    }
    case MC::EncoderSendPositionValuesAndReceiveErrorReset:  // 2.7.1
      memory_.clear_errors_and_warnings();
      break;
    case MC::EncoderSendPositionValuesAndReceiveTestCommand:  // 2.8.1, 3.5.3
      test_port_22_ = address;
      break;
    default:
      break;
  }
}

void Encoder::start_memory_access(Time t_ac) {
  busy_until_ = kernel_.now() + t_ac;
  memory_timer_.start(t_ac);
}

void Encoder::on_memory_access_done() {
  // 2.5.1 / 2.6.1: the result appears in additional data 1 once the busy bit is reset.
  switch (in_progress_.kind) {
    case Pending::Kind::Select:
      select(in_progress_.selection);
      return;
    case Pending::Kind::Write:
      memory_.write(in_progress_.selection, in_progress_.address, in_progress_.value);
      if (nvm_write_) nvm_write_->applied = true;
      written(in_progress_.selection, in_progress_.address);
      break;
    default:
      break;
  }
  // A2 type II (4.2.2): "the address or parameter is returned inverted", for 2.1 and 2.2 alike:
  // both, as the 2.1 acknowledgment returns them (docs/model.md §3).
  memory_address_ = memory_error_ ? static_cast<std::uint8_t>(~in_progress_.address) : in_progress_.address;
  memory_value_ = memory_error_ ? static_cast<std::uint16_t>(~in_progress_.value) : in_progress_.value;
  in_progress_ = {};
}

void Encoder::on_end_marker_due() {
  if (state_ != State::SupplementDone) return;
  drive(true);
  enable();
}

std::optional<ErrorCause> Encoder::type3_cause(Information i, unsigned which) const {
  const auto& code = protocol::info(i);
  if (!code.selectable) return ErrorCause::ImpermissibleAdditionalData;  // A2 cause 13
  if (code.support_bit) {
    const auto support = memory_.endat22_word(which == 0 ? word::kAdditionalData1Support : word::kAdditionalData2Support);
    if (((support >> *code.support_bit) & 1U) == 0) return ErrorCause::UnsupportedAdditionalData;  // cause 14
  }
  // A2 cause 15 (interpretation): position value 2 requested through both additional data.
  const bool pos2_in_ai2 = i >= I::AsynchronousPositionWord1 && i <= I::AsynchronousPositionWord3 &&
                           (memory_.endat22_word(word::kAdditionalData2Support) & 0x0040) != 0;
  const bool pos2_in_ai1 = selection_[0] && *selection_[0] >= I::PositionValue2Word1 &&
                           *selection_[0] <= I::PositionValue2Word3;
  if (which == 1 && pos2_in_ai2 && pos2_in_ai1) return ErrorCause::DuplicateAdditionalData;
  return std::nullopt;
}

std::uint8_t Encoder::status_byte(Information i) const {
  using S = protocol::AdditionalDataStatus;
  std::uint8_t s = static_cast<std::uint8_t>(i);
  if ((memory_.operating_status(word::kWarnings) & memory_.manufacturer_word(word::kSupportedWarnings)) != 0)
    s |= S::kWarning;
  if (busy()) s |= S::kBusy;
  // 2.3.1 status table: RM is "already set with switch-on with absolute encoders"; an incremental
  // one sets it when its reference run is done (2.3.4.3).
  if (referenced_ && !rm_reset_at_) s |= S::kReferenceMark;
  return s;
}

void Encoder::append_additional_datum(Information selected, unsigned which) {
  EncoderFrame& f = frames_.back();
  Information code = selected;
  std::uint16_t data = 0;
  const auto& stale = params_.sensors.not_updatable;
  if (type3_[which]) {
    code = which == 0 ? I::Type3Error1 : I::Type3Error2;  // A2 type III
  } else if (std::find(stale.begin(), stale.end(), selected) != stale.end() ||
             (selected == I::Diagnosis && !diagnosis_activated()) ||
             ((eib_not_initiated_ || (incremental_ && !referenced_)) && selected >= I::PositionValue2Word1 &&
              selected <= I::PositionValue2Word3)) {
    // Type IV; an incremental encoder has no absolute position value 2 before its reference run.
    code = which == 0 ? I::Nop1 : I::Nop2;  // A2 type IV
  } else {
    data = additional_data_content(selected);
  }
  const std::uint8_t status = status_byte(code);
  f.additional_data_status.push_back(status);
  const auto bits = protocol::encode_additional_datum(status, data, params_.crc);
  answer_.insert(answer_.end(), bits.begin(), bits.end());
}

std::uint16_t Encoder::additional_data_content(Information i) {
  const Sensors& s = params_.sensors;
  const EncoderFrame& f = frames_.back();
  const auto acceleration = s.acceleration;
  const auto uvw = static_cast<std::uint16_t>((s.commutation & 0x7) << 13);
  const auto limits = static_cast<std::uint16_t>((s.limit_position_1 ? 0x8000 : 0) | (s.limit_position_2 ? 0x4000 : 0));
  switch (i) {
    case I::Diagnosis: return next_diagnosis_value();
    // 2.3.5.1: "position value 2 or test values are always updated by querying the first word".
    case I::PositionValue2Word1:
      // Incremental encoders: the absolute position, available after the reference run.
      position2_latched_ = incremental_ ? output_position(absolute_position(f.start))
                                        : (s.position2_reversed ? static_cast<std::uint64_t>(s.position2_offset) - f.true_position
                                                                : f.true_position + static_cast<std::uint64_t>(s.position2_offset));
      position2_latched_ = (position2_latched_ + static_cast<std::uint64_t>(s.position2_fault)) & 0xFFFF'FFFF'FFFFULL;
      return word_of(position2_latched_, 0);
    case I::PositionValue2Word2: return word_of(position2_latched_, 1);
    case I::PositionValue2Word3: return word_of(position2_latched_, 2);
    case I::MemoryParameterLsb: return static_cast<std::uint16_t>(memory_address_ << 8 | (memory_value_ & 0xFF));
    case I::MemoryParameterMsb: return static_cast<std::uint16_t>(memory_address_ << 8 | memory_value_ >> 8);
    case I::MrsCodeAcknowledgment: return static_cast<std::uint16_t>(last_mrs_ << 8 | last_block_);
    case I::TestCommandAcknowledgment: return static_cast<std::uint16_t>(test_port_22_ << 8);
    case I::TestValuesWord1: {
      const auto it = s.test_values.find(test_port_22_);
      test_value_latched_ = it == s.test_values.end() ? 0 : it->second;
      return word_of(test_value_latched_, 0);
    }
    case I::TestValuesWord2: return word_of(test_value_latched_, 1);
    case I::TestValuesWord3: return word_of(test_value_latched_, 2);
    case I::Temperature1: return s.temperature1;
    case I::Temperature2: return s.temperature2;
    case I::AdditionalSensors: {  // 2.3.5.1: the address rolls on every interrogation; 115 K offset
      if (s.additional_sensors.empty()) return 0;
      const unsigned address = sensor_address_++ % static_cast<unsigned>(s.additional_sensors.size());
      return protocol::diagnosis::encode_additional_sensor(address, s.additional_sensors[address]);
    }
    case I::Commutation: return uvw;
    case I::Acceleration: return acceleration;
    case I::CommutationAndAcceleration: return static_cast<std::uint16_t>(uvw | (acceleration & 0x1FFF));
    case I::LimitPositionSignals: return limits;
    case I::LimitPositionSignalsAndAcceleration: return static_cast<std::uint16_t>(limits | (acceleration & 0x3FFF));
    case I::AsynchronousPositionWord1: {
      // 2.4.2.3: the position "time delay k" before the latch; without oversampling only delay 0.
      const unsigned k = function_activated(EncoderFunction::Oversampling) ? async_time_delay_ : 0;
      async_latched_ = latched_position(f.start - std::min(f.start, params_.asynchronous_time_delay_step * k));
      return word_of(async_latched_, 0);
    }
    case I::AsynchronousPositionWord2: return word_of(async_latched_, 1);
    case I::AsynchronousPositionWord3: return word_of(async_latched_, 2);
    case I::OperatingStatusErrorSources: return s.operating_status_error_sources;
    case I::Timestamp: return timestamp(f.start);
    default: return 0;
  }
}

// ---- end of frame, reset ---------------------------------------------------------------------

Time Encoder::recovery_time() const {
  const bool v22 = state_ != State::Idle && command_ != nullptr && command_->version == EndatVersion::V2_2;
  // 3.4.4: word 3 bits 0/1 choose the short recovery time, for 2.2 mode commands only, and only
  // after the reset that activates word 3.
  return v22 && function_activated(EncoderFunction::ShortRecoveryTime) && params_.t_m_short ? *params_.t_m_short : params_.t_m;
}

void Encoder::on_recovery_time_elapsed() {
  // 2.3: "The transfer is terminated after expiry of a certain time (recovery time I)":
  // DATA falls back to LOW and the encoder is ready again after t_R.
  if (state_ == State::Idle) return;
  finish_frame();
}

void Encoder::finish_frame() {
  EncoderFrame& f = frames_.back();
  // A 2.1 parameter frame that ends before its 8 + 16 bits are in (A2 cause 3).
  if (state_ == State::Payload) transmission_incomplete_ = true;
  state_ = State::Idle;
  end_marker_timer_.cancel();
  if (bus_selection_after_frame_) selected_on_bus_ = *bus_selection_after_frame_;
  bus_selection_after_frame_.reset();
  drive(false);
  enable();
  ready_at_ = kernel_.now() + params_.t_r;
  if (f.too_many_clocks && pending_.kind != Pending::Kind::None) {
    f.error = ErrorCause::MrsFrameDisrupted;  // the access is discarded
    nvm_write_.reset();
    return;
  }
  switch (pending_.kind) {
    case Pending::Kind::Select:
      select(pending_.selection);
      break;
    case Pending::Kind::Write:
      memory_.write(pending_.selection, pending_.address, pending_.value);
      if (nvm_write_) nvm_write_->applied = true;
      written(pending_.selection, pending_.address);
      break;
    case Pending::Kind::Reset:
      reset();
      break;
    case Pending::Kind::None:
      break;
  }
  pending_ = {};
}

void Encoder::reset() {
  restart_state();
  if (params_.reset_time > Time::zero()) go_offline(params_.reset_time);
}

void Encoder::restart_state() {
  // 2.7 ("same reaction as from switching power on and off", the English brochure): additional data
  // deselected (2.4.2.2), word 2, word 3 and the operating parameters activated (3.4.3, 3.4.4, 3.6).
  memory_.activate_on_reset();
  activate_functions();
  async_time_delay_ = 0;
  selection_[0].reset();
  selection_[1].reset();
  type3_[0].reset();
  type3_[1].reset();
  area_selected_ = false;
  // 3.5.7: an EIB becomes the connected encoder at reset or power-on (EibActivation::Reset).
  if (eib_not_initiated_ && params_.eib_activation == EibActivation::Reset) complete_commissioning();
  // 2.7: "this bit is set to 0 via Encoder receive reset ... Position value 1 and position
  // value 2 are not influenced by this."
  referenced_ = !incremental_;
  rm_reset_at_.reset();
  reference_search_from_ = kernel_.now();
  test_port_21_ = test_port_22_ = 0;
  unsettled_left_ = params_.unsettled_positions;
  sensor_address_ = 0;
  diagnosis_index_ = 0;
  memory_timer_.cancel();
  busy_until_ = kernel_.now();
  in_progress_ = {};
}

// ---- faults (scenario events) ---------------------------------------------------------------

void Encoder::set_error_sources(std::uint16_t errors, std::uint16_t warnings) {
  params_.error_sources = errors;
  params_.warning_sources = warnings;
}

void Encoder::set_memory_access_times(Time read, Time write) {
  require(read >= Time::zero() && read <= kMaxFaultTime && write >= Time::zero() && write <= kMaxFaultTime,
          "memory access times must be 0 .. 10 s");
  params_.t_ac_read = read;
  params_.t_ac_write = write;
}

void Encoder::set_t_cal(Time t_cal) {
  require(t_cal >= Time::zero() && t_cal <= sim::ms(100), "t_cal must be 0 .. 100 ms (the model's limit)");
  params_.t_cal = t_cal;
  params_.t_cal_22.reset();  // the event sets the calculation time of every mode command
}

void Encoder::power_interruption(Time duration) {
  require(duration > Time::zero() && duration <= kMaxFaultTime, "a power interruption lasts 0 .. 10 s");
  interrupt_nvm_write();
  state_ = State::Idle;
  recovery_timer_.cancel();
  end_marker_timer_.cancel();
  pending_ = {};
  restart_state();  // 2.7: a reset is "the same reaction as switching the power off and on"
  // 3.6.4: only switching the power off and on, with word 4 at 0000h, clears error bit 1.
  bus_address_error_ = false;
  latch_bus_address_error();
  go_offline(duration + params_.startup_time);
}

void Encoder::corrupt_word(const Selection& s, std::uint8_t address, std::uint16_t xor_mask) {
  memory_.force(s, address, static_cast<std::uint16_t>(memory_.word(s, address) ^ xor_mask));
}

// 3.9.32: a touch probe's timestamp gives its switching time in the unit of word 45.
std::uint16_t Encoder::timestamp(Time frame_start) const {
  namespace pm = protocol::parameters;
  if (touch_probe_ && probe_switched_at_) {
    if (const auto unit = pm::timestamp_unit_duration(pm::decode_timestamp_unit(memory_.endat22_word(45))))
      return static_cast<std::uint16_t>(*probe_switched_at_ / *unit);
  }
  return static_cast<std::uint16_t>(frame_start / params_.sensors.timestamp_unit);
}

void Encoder::set_probe_deflected(bool deflected) {
  require(touch_probe_, "only a touch probe (word 14 type 5) can be deflected");
  if (deflected && !probe_deflected_) probe_switched_at_ = kernel_.now();
  probe_deflected_ = deflected;
  // UNCERTAIN (3.10.1 names operating parameters 2 word 2 "status of touch probes", no bits):
  // bit 0 follows the trigger status.
  const Selection status{MemoryArea::OperatingParameters2, 0};
  if (const auto read = memory_.read(status, word::kTouchProbeStatus))
    memory_.force(status, word::kTouchProbeStatus, static_cast<std::uint16_t>((read.value & ~1U) | (deflected ? 1U : 0U)));
}

void Encoder::set_stuck_error_messages(bool error1_stuck, bool error2_stuck) {
  params_.error_message_1_stuck = error1_stuck;
  params_.error_message_2_stuck = error2_stuck;
}

void Encoder::slip(std::int64_t steps) { slip_ += steps; }

void Encoder::set_position2_fault(std::int64_t deviation) { params_.sensors.position2_fault = deviation; }

void Encoder::note_nvm_write(const Selection& s, std::uint8_t address, std::uint16_t value, Time done_at) {
  const auto old = memory_.read(s, address);
  if (!old) return;
  nvm_write_ = NvmWrite{s, address, old.value, value, done_at, false};
}

// A write cut short keeps the old word or is torn (InterruptedNvmWrite); one whose t_ac had
// run out is programmed even if its frame had not ended yet.
void Encoder::interrupt_nvm_write() {
  if (!nvm_write_) return;
  const NvmWrite w = *nvm_write_;
  nvm_write_.reset();
  if (kernel_.now() >= w.done_at) {
    if (!w.applied) memory_.force(w.selection, w.address, w.new_value);
    return;
  }
  const bool torn = params_.interrupted_nvm_write == InterruptedNvmWrite::Torn;
  memory_.force(w.selection, w.address,
                torn ? static_cast<std::uint16_t>((w.new_value & 0xFF00) | (w.old_value & 0x00FF)) : w.old_value);
}

// 3.4.2: word 1 bit 5 reports cyclic mode while word 3 activates it.
void Encoder::latch_errors() {
  const bool cyclic = function_activated(EncoderFunction::CyclicOperation);
  const auto warnings = params_.warning_sources | (cyclic ? 0x0020 : 0) | (temperature_exceeded() ? kTemperatureExceeded : 0);
  memory_.latch_errors(params_.error_sources, static_cast<std::uint16_t>(warnings));
}

// 3.4.2 / 3.6.6: warning 2^1 is "only triggered by the internal temperature sensor" (temperature
// 2, on board: 3.9.2 word 0 bit 3) above the threshold of operating parameters word 6 (0: none),
// where word 36 says the warning is supported. "Exceeded" is read as strictly above.
bool Encoder::temperature_exceeded() const {
  const std::uint16_t threshold = memory_.active_operating_parameters()[word::kTemperatureWarningThreshold];
  const bool supported = (memory_.manufacturer_word(word::kSupportedWarnings) & kTemperatureExceeded) != 0 &&
                         (memory_.endat22_word(word::kAdditionalData1Support) & kTemperatureSensor2Support) != 0;
  return supported && threshold != 0 && params_.sensors.temperature2 > threshold;
}

// A3 / 3.6.3: the valuation numbers word 3 activates, then (bit 15) the system-specific data,
// one per interrogation, as address | value.
std::uint16_t Encoder::next_diagnosis_value() {
  const Sensors& s = params_.sensors;
  const std::uint16_t enabled = memory_.active_operating_parameters()[word::kDiagnosticsConfiguration];
  std::vector<std::uint16_t> rotation;
  for (unsigned k = 0; k < s.valuation_numbers.size(); ++k)
    if (((enabled >> k) & 1U) != 0) rotation.push_back(static_cast<std::uint16_t>((k + 1) << 8 | s.valuation_numbers[k]));
  if ((enabled & protocol::diagnosis::kSystemSpecificDataBit) != 0)
    for (const auto& [address, value] : s.system_data) rotation.push_back(static_cast<std::uint16_t>(address << 8 | value));
  if (rotation.empty()) return 0;
  return rotation[diagnosis_index_++ % rotation.size()];
}

bool Encoder::diagnosis_activated() const {
  const std::uint16_t enabled = memory_.active_operating_parameters()[word::kDiagnosticsConfiguration];
  return (enabled & protocol::diagnosis::kValuationNumberBits) != 0 ||
         ((enabled & protocol::diagnosis::kSystemSpecificDataBit) != 0 && !params_.sensors.system_data.empty());
}

void Encoder::set_sensor_values(const SensorValues& v) {
  Sensors& s = params_.sensors;
  if (v.temperature1) s.temperature1 = *v.temperature1;
  if (v.temperature2) s.temperature2 = *v.temperature2;
  if (v.additional_sensors) s.additional_sensors = *v.additional_sensors;
  if (v.valuation_numbers) s.valuation_numbers = *v.valuation_numbers;
}

// ---- word 3: function initialization (3.4.4) ----------------------------------------------------
// Reference pulse initialization, multiturn error messages and diagnostics reset are decoded but
// change nothing the model shows: "functions are initialized encoder-specifically".

bool Encoder::function_activated(EncoderFunction f) const {
  return protocol::parameters::function_activated(memory_.active_function_initialization(), f);
}

// Power-on and "Encoder receive reset": a multiturn counter reset zeroes the revolutions here
// and keeps the position within the revolution; the count goes on from there.
void Encoder::activate_functions() {
  if (params_.multiturn_bits == 0 || !function_activated(EncoderFunction::MultiturnCounterReset)) return;
  const __int128 steps_per_revolution = __int128{1} << (position_bits_ - params_.multiturn_bits);
  counter_origin_ = floor_div(unwrapped_position(kernel_.now()), steps_per_revolution) * steps_per_revolution;
}

void Encoder::select(const Selection& s) {
  selection_area_ = s;
  area_selected_ = true;
  if (s.area == MemoryArea::AsynchronousPosition) async_time_delay_ = s.block;  // 2.4.2.3
}

// EibActivation::Word14Write: the EIB becomes the connected encoder when word 14 is written.
// 3.6.4: "Error bit 1 is always set if a bit is set in this word [the encoder address, word 4].
// This can only be cleared by resetting the word to 0000h and switching the power off and on."
void Encoder::latch_bus_address_error() {
  if (memory_.operating_parameter(word::kEncoderAddress) != 0) bus_address_error_ = true;
}

void Encoder::note_commissioning_write(const Selection& s, std::uint8_t address) {
  if (eib_not_initiated_ && params_.eib_activation == EibActivation::Word14Write &&
      s.area == MemoryArea::Manufacturer1 && address == word::kEncoderType)
    complete_commissioning();
}

// 2.3.4.3: the absolute position of a referenced incremental encoder (position value 2).
std::uint64_t Encoder::absolute_position(Time t) const {
  const __int128 range = __int128{1} << position_bits_;
  __int128 p = (static_cast<__int128>(measured_position(t)) - reference_offset_) % range;
  if (p < 0) p += range;
  return static_cast<std::uint64_t>(p);
}

std::uint64_t Encoder::measured_position(Time t) const {
  const __int128 range = __int128{1} << position_bits_;
  __int128 p = (unwrapped_position(t) - counter_origin_) % range;
  if (p < 0) p += range;
  return static_cast<std::uint64_t>(p);
}

// 2.3.4.3: incremental encoders send relative positions, counted from switching on. 2.3.4.4: a
// touch probe sends 16 bits, the LSB its trigger status; the other 15 are "TBD" and sent as 0.
std::uint64_t Encoder::latched_position(Time t) const {
  if (eib_not_initiated_) return 0;  // EibPositionBeforeCommissioning::ErrorBit: no valid position
  if (touch_probe_) return probe_deflected_ ? 1 : 0;
  if (incremental_)
    return output_position(static_cast<std::uint64_t>(unwrapped_position(t) - unwrapped_position(reference_origin_)));
  return output_position(measured_position(t));
}

// The revolution counter has left 0 .. 2^M - 1 (counting up past the top or down past 0).
bool Encoder::multiturn_overflowed(Time t) const {
  const __int128 p = unwrapped_position(t) - counter_origin_;
  return params_.multiturn_bits > 0 && (p < 0 || p >= (__int128{1} << position_bits_));
}

// UNCERTAIN reading of 3.4.4: the overflow error message sets F1/F2 in the frames that latch an
// overflowed count; with the overflow latch, the error goes into word 0 (bit
// multiturn_overflow_error_bit) and stays until cleared as 3.4.1 says.
void Encoder::check_multiturn_overflow() {
  multiturn_overflow_ = false;
  if (!function_activated(EncoderFunction::MultiturnOverflowErrorMessage) || !multiturn_overflowed(kernel_.now()))
    return;
  const auto bit = static_cast<std::uint16_t>(1U << params_.multiturn_overflow_error_bit);
  if (function_activated(EncoderFunction::MultiturnOverflowLatch)) memory_.latch_errors(bit, 0);
  else multiturn_overflow_ = true;
}

}  // namespace endatsim::slave
