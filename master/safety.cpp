// The safety functions of the master (safety.hpp): the start-up checks before the axis is
// released and the checks of every frame read afterwards.
#include "endatsim/master/safety.hpp"
#include "endatsim/sim/parameter.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "endatsim/master/frame_engine.hpp"
#include "endatsim/master/master_params.hpp"
#include "endatsim/master/parameter_book.hpp"
#include "endatsim/master/startup.hpp"
#include "endatsim/protocol/parameters.hpp"
#include "endatsim/sim/int128.hpp"

namespace endatsim::master {
namespace {

namespace pm = protocol::parameters;
using MC = protocol::ModeCommand;
using I = protocol::Information;
using P = Operation::Purpose;

using sim::require;

// a - b as a signed distance on a ring of 2^bits positions.
std::int64_t ring_distance(std::uint64_t a, std::uint64_t b, unsigned bits) {
  const std::uint64_t mask = protocol::position_mask(bits);
  const std::uint64_t d = (a - b) & mask;
  const std::uint64_t half = std::uint64_t{1} << (bits - 1);
  return d >= half ? static_cast<std::int64_t>(d) - static_cast<std::int64_t>(half) * 2 : static_cast<std::int64_t>(d);
}

std::uint64_t magnitude(std::int64_t v) { return v < 0 ? static_cast<std::uint64_t>(-v) : static_cast<std::uint64_t>(v); }

// Known results (A4 examples; the vectors of docs/model.md §12, computed with one published master's
// open-source CRC code and an independent LFSR).
constexpr CrcVector kCrcVectors[] = {
    {25, false, true, true, 104462, 3},  // A4.4.2 MakeCrcPos example
    {31, false, false, true, 0x7FFFFFFF, 22},
    {36, false, false, true, 0x512345678ULL, 13},
    {48, false, false, true, 0xABCD12345678ULL, 11},
};

}  // namespace

std::string_view to_string(SafetyFunction f) {
  switch (f) {
    case SafetyFunction::ErrorMessages: return "error_messages";
    case SafetyFunction::PositionValue2: return "position_value_2";
    case SafetyFunction::ForcedDynamicSampling: return "forced_dynamic_sampling";
    case SafetyFunction::CrcSelfTest: return "crc_self_test";
    case SafetyFunction::StartupPositions: return "startup_positions";
    case SafetyFunction::Checksums: return "checksums";
    case SafetyFunction::Acknowledgements: return "acknowledgements";
    case SafetyFunction::FollowingError: return "following_error";
    case SafetyFunction::CommandSet: return "command_set";
  }
  return "?";
}

std::uint64_t MotionSetpoint::at(Time t, unsigned position_bits) const {
  // Counted as the encoder counts a moving axis: whole steps toward minus infinity, so that a
  // negative velocity gives the same position on both sides between two steps.
  const sim::Int128 range = sim::Int128{1} << position_bits;
  sim::Int128 p = static_cast<sim::Int128>(start) + sim::counts_after(counts_per_s, t.count());
  p %= range;
  if (p < 0) p += range;
  return static_cast<std::uint64_t>(p);
}

bool SafetyParams::enabled(SafetyFunction f) const {
  switch (f) {
    case SafetyFunction::ErrorMessages: return error_messages;
    case SafetyFunction::PositionValue2: return position_value_2;
    case SafetyFunction::ForcedDynamicSampling: return forced_dynamic_sampling;
    case SafetyFunction::CrcSelfTest: return crc_self_test;
    case SafetyFunction::StartupPositions: return startup_positions;
    case SafetyFunction::Checksums: return checksums;
    case SafetyFunction::Acknowledgements: return acknowledgements;
    case SafetyFunction::FollowingError: return following_error;
    case SafetyFunction::CommandSet: return command_set;
  }
  return false;
}

void SafetyParams::validate() const {
  require(forced_error1_port != pm::kForcedSamplingOffPort && forced_error2_port != pm::kForcedSamplingOffPort &&
              forced_error1_port != forced_error2_port,
          "safety forced_error1_port and forced_error2_port must differ and not be 0 (0 switches forcing off, 3.5.3)");
  if (auto why = sim::first_out_of_range(safety_parameters(), *this, "master safety")) throw std::invalid_argument(*why);
  require(startup_max_reads >= startup_repetitions,
          "safety startup_max_reads must be startup_repetitions (" + std::to_string(startup_repetitions) +
              ") .. 10000, got " + std::to_string(startup_max_reads));
}

std::size_t SafetyReport::count(SafetyFunction f) const {
  return static_cast<std::size_t>(
      std::count_if(findings.begin(), findings.end(), [f](const SafetyFinding& x) { return x.function == f; }));
}

std::span<const CrcVector> crc_known_results() { return kCrcVectors; }

std::optional<std::uint32_t> Position2Parameters::accuracy_at(double steps_per_s) const {
  if (measuring_steps == 0 || max_velocity == 0) return std::nullopt;
  // rpm from steps per revolution; m/min from the measuring step in nm (3.5.12, 3.5.18).
  const double speed = linear ? std::abs(steps_per_s) * measuring_steps * 1e-9 * 60
                              : std::abs(steps_per_s) * 60 / measuring_steps;
  for (const Range& r : ranges)
    if (r.conversion_factor != 0 && speed <= static_cast<double>(max_velocity) / r.conversion_factor) return r.accuracy;
  return std::nullopt;
}

Position2Parameters position2_parameters(const std::vector<std::uint16_t>& m, const std::vector<std::uint16_t>& e) {
  Position2Parameters p;
  namespace word = protocol::word;
  p.linear = pm::is_linear(pm::decode_encoder_type(m[word::kEncoderType]));
  p.measuring_steps = pm::decode_measuring_steps(m[word::kMeasuringSteps], m[word::kMeasuringSteps + 1]);
  p.max_velocity = m[word::kMaxVelocity];
  if (m[word::kAccuracy] != pm::kAccuracySeeEndat22 || m[word::kAccuracy + 1] != pm::kAccuracySeeEndat22) {
    for (unsigned w : {word::kAccuracy, word::kAccuracy + 1}) {
      const auto r = pm::decode_accuracy_range(m[w]);
      p.ranges.push_back({r.conversion_factor, r.accuracy});
    }
  } else {
    for (unsigned w : {word::kPosition2Accuracy, word::kPosition2Accuracy + 2}) {  // 3.9.11: c_i, a_i
      const auto c = pm::decode_scaled_value(e[w]), a = pm::decode_scaled_value(e[w + 1]);
      if (c && a) p.ranges.push_back({*c, *a});
    }
  }
  p.reversed = pm::decode_direction_falling(e[word::kPosition2Direction]);  // 3.9.13 as 3.5.16
  p.comparison_bits = e[word::kComparisonBits];
  const unsigned offset = word::kPosition2Offset;  // 3.9.24: 48 bits, two's complement, the low word first
  p.offset = pm::decode_datum_shift48(e[offset], e[offset + 1], e[offset + 2]);
  return p;
}

// ---- the start-up checks -------------------------------------------------------------------

// Everything switched on, in the order a safety-oriented start-up runs it: the master's own CRC
// evaluation, the encoder's parameters (checksums; what the position comparison needs), the
// error paths, then the position read several times; the axis is released only after all.
void SafetyFunctions::plan_startup(const FunctionContext& ctx, Sequence& plan) {
  const SafetyParams& s = params_;
  const auto frame = [&plan](MC c, std::uint8_t address, P purpose) { plan.frame(c, address, 0, purpose); };
  const auto kind = [&](Operation::Kind k) { plan.add(k).command = ctx.operation.command; };
  if (s.crc_self_test) kind(Operation::Kind::CrcSelfTest);
  if (s.command_set) {
    frame(MC::SelectionOfMemoryArea, mrs_of(protocol::MemoryArea::Manufacturer3), P::None);
    frame(MC::EncoderSendParameters, protocol::word::manufacturer_address(protocol::word::kCommandSet), P::CommandSet);
  }
  if (s.checksums || s.position_value_2) {
    kind(Operation::Kind::VerifyChecksum);
    kind(Operation::Kind::ReadEndat22Area);
  }
  if (s.forced_dynamic_sampling) {
    // 3.5.3: force each error message, see it active in the next 2.2 query, then port 0 again.
    const auto query = MC::EncoderSendPositionValuesWithAdditionalData;
    frame(MC::EncoderSendPositionValuesAndReceiveTestCommand, s.forced_error1_port, P::ForcedTest);
    frame(query, 0, P::ForcedError1);
    frame(MC::EncoderSendPositionValuesAndReceiveTestCommand, s.forced_error2_port, P::ForcedTest);
    frame(query, 0, P::ForcedError2);
    frame(MC::EncoderSendPositionValuesAndReceiveTestCommand, pm::kForcedSamplingOffPort, P::ForcedTest);
    frame(query, 0, P::ForcedOff);
  }
  kind(Operation::Kind::StartupPositions);
  if (s.position_value_2)  // 2.3.5.1: additional data 1 = position value 2, word 1 (it latches words 2, 3)
    frame(MC::EncoderSendPositionValuesAndSelectionOfMemoryArea, protocol::selection_mrs(I::PositionValue2Word1), P::None);
  monitor_.report().axis_released = false;
}

Planned SafetyFunctions::plan(const FunctionContext& ctx, Sequence& plan) {
  switch (ctx.operation.kind) {
    case Operation::Kind::SafetyStartup:
      plan_startup(ctx, plan);
      return {Planned::What::Expanded};
    case Operation::Kind::CrcSelfTest:
      monitor_.run_crc_self_test(ctx.params.crc, ctx.position_bits, ctx.now);
      return {Planned::What::Done};
    case Operation::Kind::StartupPositions:
      // Started over whenever the operation is (after a delay measurement that came between).
      monitor_.begin_startup_positions();
      return {Planned::What::Frames, params_.startup_positions ? params_.startup_max_reads : 1};
    default: return {};
  }
}

void SafetyFunctions::on_frame(FrameResult& f, const FunctionContext& ctx) {
  monitor_.on_frame(f, ctx.operation.purpose, ctx.position_bits);
}

bool SafetyFunctions::ends_operation(const FrameResult& f, const FunctionContext& ctx, bool last) {
  return ctx.operation.kind == Operation::Kind::StartupPositions && monitor_.startup_position_read(f, ctx.position_bits, last);
}

// 3.4.1: word 0 says which error it was.
std::optional<StatusRead> SafetyFunctions::status_read_due() const {
  if (!monitor_.error_sources_due()) return std::nullopt;
  return StatusRead{protocol::word::kErrors, P::ErrorSources};
}

// The English brochure, "Safety Techniques": "the CRC generation in the receiver chip ... must be
// ensured through a targeted execution of bit sequences with known result": each known sequence
// must pass, and with one bit of its CRC inverted must fail. Vectors at the master's own width come
// from the A4 algorithm.
void SafetyMonitor::run_crc_self_test(const CrcCheck& crc, unsigned position_bits, Time now) {
  std::vector<CrcVector> vectors(crc_known_results().begin(), crc_known_results().end());
  vectors.push_back({position_bits, false, true, true, 0x5A5A5A5A5A5AULL & ((std::uint64_t{1} << position_bits) - 1), 0});
  vectors.back().crc = protocol::make_crc_pos(position_bits, false, true, true, vectors.back().position);
  for (const CrcVector& v : vectors) {
    const std::uint8_t computed = expected_crc_pos(crc, v.bits, v.error1, v.error2, v.endat22, v.position);
    const bool good = crc_passes(crc, v.crc, computed);
    const bool bad_rejected = !crc_passes(crc, static_cast<std::uint8_t>(v.crc ^ 0x01), computed);
    if (good && bad_rejected) continue;
    find(SafetyFunction::CrcSelfTest, now, std::to_string(v.bits) + "-bit sequence of known CRC " + std::to_string(v.crc) + ": " +
             (!good ? "rejected (the evaluation computes " + std::to_string(computed) + ")"
                    : "a CRC with one bit inverted was accepted"));
  }
  // A parameter frame of known result: MRS B9h with the parameter 1234h has CRC 10 (A4).
  constexpr std::uint16_t kKnownParameter = 0x1234;
  constexpr std::uint8_t kKnownCrc = 10;
  const std::uint8_t b9 = mrs_of(protocol::MemoryArea::OperatingStatus);
  const std::uint8_t computed = protocol::make_crc_norm(b9, kKnownParameter, crc.generator);
  const bool norm_ok = crc_passes(crc, kKnownCrc, computed) && !crc_passes(crc, static_cast<std::uint8_t>(kKnownCrc ^ 0x01), computed);
  if (!norm_ok)
    find(SafetyFunction::CrcSelfTest, now,
         "parameter CRC of B9h / 1234h (known " + std::to_string(kKnownCrc) + ") evaluated wrong");
}

void SafetyMonitor::begin_startup_positions() {
  report_.startup_reads = 0;
  startup_agreeing_ = 0;
}

// Multiple transmission at start-up: `startup_repetitions` consecutive values that agree (after
// the commanded motion between them, within the tolerance) release the axis; a careless master
// releases it with its first value.
bool SafetyMonitor::startup_position_read(const FrameResult& f, unsigned position_bits, bool last_read) {
  const SafetyParams& s = params_;
  ++report_.startup_reads;
  if (f.outcome != FrameOutcome::Ok || f.error_detected) {
    startup_agreeing_ = 0;
  } else if (const double moved = static_cast<double>(s.setpoint.counts_per_s) *
                                  static_cast<double>((f.start - startup_previous_at_).count()) / static_cast<double>(sim::kPsPerSecond);
             startup_agreeing_ == 0 ||
             std::abs(static_cast<double>(ring_distance(f.position, startup_previous_, position_bits)) - moved) >
                 static_cast<double>(s.startup_tolerance)) {
    if (startup_agreeing_ != 0)
      find(SafetyFunction::StartupPositions, f,
           "position " + std::to_string(f.position) + " differs from the previous " + std::to_string(startup_previous_) +
               " by more than " + std::to_string(s.startup_tolerance) + " LSB");
    startup_agreeing_ = 1;
  } else {
    ++startup_agreeing_;
  }
  startup_previous_ = f.position;
  startup_previous_at_ = f.start;
  const unsigned needed = s.startup_positions ? s.startup_repetitions : 1;
  if (startup_agreeing_ >= needed) {
    static constexpr SafetyFunction kBlocking[] = {SafetyFunction::CrcSelfTest, SafetyFunction::Checksums,
                                                   SafetyFunction::ForcedDynamicSampling, SafetyFunction::CommandSet};
    const bool blocked = std::any_of(std::begin(kBlocking), std::end(kBlocking),
                                     [this](SafetyFunction x) { return report_.count(x) != 0; });
    report_.axis_released = !blocked;
    if (!blocked) {
      report_.released_at = f.end;
      report_.release_frame = f.index;
      report_.release_position = f.position;
    }
    return true;
  }
  if (last_read)
    find(SafetyFunction::StartupPositions, f,
         "no " + std::to_string(needed) + " agreeing position values in " + std::to_string(report_.startup_reads) +
             " reads: the axis stays blocked");
  return false;
}

// ---- the checks of every frame ---------------------------------------------------------------

void SafetyMonitor::find(SafetyFunction function, const FrameResult& f, std::string message) {
  report_.findings.push_back(SafetyFinding{function, f.end, f.index, std::move(message)});
}

void SafetyMonitor::find(SafetyFunction function, Time now, std::string message) {
  report_.findings.push_back(SafetyFinding{function, now, std::nullopt, std::move(message)});
}

void SafetyMonitor::on_frame(FrameResult& f, Operation::Purpose purpose, unsigned position_bits) {
  purpose_ = purpose;
  position_bits_ = position_bits;
  if (purpose == P::ErrorSources && f.outcome == FrameOutcome::Ok) report_.error_sources = f.echo_parameter;
  const bool position_answer = protocol::info(f.command).answer == protocol::AnswerFormat::Position;
  check_acknowledgement(f);
  check_command_set(f);
  if (!position_answer || f.outcome != FrameOutcome::Ok) return;
  check_error_messages(f);
  check_forced_sampling(f);
  if (purpose == P::None || purpose == P::Endat22Msb) {
    check_following_error(f);
    check_position_value_2(f);
  }
  last_good_ = {f.position, f.start};
}

// 2.3.1: F1 is high-active, F2 low-active and sent only with 2.2 mode commands; a master that
// evaluates both catches an error whose one path has failed, and sees when they disagree.
void SafetyMonitor::check_error_messages(FrameResult& f) {
  const bool v22 = protocol::info(f.command).version == protocol::EndatVersion::V2_2;
  const bool use_f2 = params_.error_messages && v22;
  f.error_detected = f.error1 || (use_f2 && !f.error2);
  for (const auto& d : f.additional_data)
    if (d.crc_ok && d.information() == I::OperatingStatusErrorSources) report_.operating_status_error_sources = d.data;
  if (forcing_ || purpose_ == P::ForcedTest) return;  // 3.5.3: forced on purpose
  if (!params_.error_messages) return;
  const bool disagree = use_f2 && f.error1 == f.error2;
  if (disagree && !disagree_state_)
    find(SafetyFunction::ErrorMessages, f,
         std::string("error messages disagree: F1 ") + (f.error1 ? "active" : "inactive") + ", F2 " +
             (f.error2 ? "inactive" : "active") + " (one error path has failed)");
  if (f.error_detected && !error_state_) {
    find(SafetyFunction::ErrorMessages, f,
         std::string("error message: F1 = ") + (f.error1 ? "1" : "0") + (v22 ? std::string(", F2 = ") + (f.error2 ? "1" : "0") : ""));
    error_sources_due_ = params_.read_error_sources;
  }
  disagree_state_ = disagree;
  error_state_ = f.error_detected;
}

// 2.3 and 3.5.22: word 37 declares the communication command with bits 4 and 5 stored inversely;
// an encoder that supports it, or whose word 37 did not come back, is not released.
void SafetyMonitor::check_command_set(const FrameResult& f) {
  if (purpose_ != P::CommandSet) return;
  if (f.outcome != FrameOutcome::Ok) {
    find(SafetyFunction::CommandSet, f, "word 37 (3.5.22) could not be read: the axis stays blocked");
    return;
  }
  if (protocol::parameters::decode_command_set(f.echo_parameter).communication_command)
    find(SafetyFunction::CommandSet, f,
         "word 37 = " + protocol::parameters::command_set_string(f.echo_parameter) +
             ": an encoder supporting \"Encoder receive communication command\" must not be used for safety-oriented "
             "applications (2.3); the axis stays blocked");
}

void SafetyMonitor::check_forced_sampling(const FrameResult& f) {
  const P purpose = purpose_;
  if (purpose == P::ForcedTest) {
    forced_sent_at_ = f.end;
    forcing_ = protocol::payload_address(f.supplement.value_or(0)) != 0;
    return;
  }
  if (purpose != P::ForcedError1 && purpose != P::ForcedError2 && purpose != P::ForcedOff) return;
  const Time after = forced_sent_at_ ? f.start - *forced_sent_at_ : Time::zero();
  const Time deadline = params_.forced_sampling_deadline;
  const auto fail = [&](const std::string& what) { find(SafetyFunction::ForcedDynamicSampling, f, what); };
  if (after > deadline)
    fail("the query came " + sim::format_time(after) + " after the test command, later than " + sim::format_time(deadline));
  if (purpose == P::ForcedError1 && !f.error1)
    fail("error message 1 did not switch to its active level (HIGH) when forced (3.5.3)");
  if (purpose == P::ForcedError2 && f.error2)
    fail("error message 2 did not switch to its active level (LOW) when forced (3.5.3)");
  if (purpose == P::ForcedOff && (f.error1 || !f.error2))
    fail("an error message stayed active after forced sampling was switched off (port 0)");
}

void SafetyMonitor::check_following_error(const FrameResult& f) {
  if (!params_.following_error) return;
  const std::uint64_t setpoint = params_.setpoint.at(f.start, position_bits_);
  const std::int64_t lag = ring_distance(f.position, setpoint, position_bits_);
  const bool beyond = magnitude(lag) > params_.following_error_limit;
  if (beyond && !lag_state_)
    find(SafetyFunction::FollowingError, f,
         "following error " + std::to_string(lag) + " LSB (position " + std::to_string(f.position) + ", set-point " +
             std::to_string(setpoint) + ", limit " + std::to_string(params_.following_error_limit) + ")");
  lag_state_ = beyond;
}

// 2.6 (echo) and 2.6.1 (I = 5 / 6 after Busy): the encoder acknowledges what it wrote.
void SafetyMonitor::check_acknowledgement(const FrameResult& f) {
  if (!params_.acknowledgements) return;
  const auto sent_address = protocol::payload_address(f.payload.value_or(0));
  const auto sent_value = protocol::payload_parameter(f.payload.value_or(0));
  if (f.command == MC::EncoderReceiveParameters &&
      (f.outcome == FrameOutcome::Ok || f.outcome == FrameOutcome::EchoMismatch) &&
      (f.echo_address != sent_address || f.echo_parameter != sent_value))
    find(SafetyFunction::Acknowledgements, f,
         "2.1 write of " + std::to_string(sent_value) + " to address " + std::to_string(sent_address) +
             " acknowledged as " + std::to_string(f.echo_parameter) + " at " + std::to_string(f.echo_address));
  // The write frame's own additional data come before its supplement: the acknowledgment follows.
  if (f.command == MC::EncoderSendPositionValuesAndReceiveParameter && f.supplement && f.outcome == FrameOutcome::Ok) {
    acknowledgement_due_ = Written{protocol::payload_address(*f.supplement), protocol::payload_parameter(*f.supplement)};
    return;
  }
  if (!acknowledgement_due_ || f.outcome != FrameOutcome::Ok) return;
  for (const auto& d : f.additional_data) {
    const bool lsb = d.information() == I::MemoryParameterLsb, msb = d.information() == I::MemoryParameterMsb;
    if (!d.crc_ok || d.busy() || (!lsb && !msb)) continue;
    const std::uint16_t written = acknowledgement_due_->value;
    const auto want = lsb ? protocol::lsb_of(written) : protocol::msb_of(written);
    const auto address = protocol::datum_address(d.data), byte = protocol::datum_byte(d.data);
    if (address != acknowledgement_due_->address || byte != want)
      find(SafetyFunction::Acknowledgements, f,
           std::string("2.2 write acknowledged (I = ") + (lsb ? "5" : "6") + ") as address " + std::to_string(address) +
               ", byte " + std::to_string(byte) + "; written: address " + std::to_string(acknowledgement_due_->address) +
               ", byte " + std::to_string(want));
    acknowledgement_due_.reset();
  }
}

// 3.5.26 / 3.9.37: word 47 = sum of words 4 .. 46, word 63 = sum of words 0 .. 62, overflow ignored.
void SafetyFunctions::endat22_area_read(const FunctionContext& ctx, bool read) {
  const bool endat22 = read;  // words 0 .. 63 came in; false: the encoder has no 2.2 area
  bool all_read = false;
  const std::vector<std::uint16_t> e = ctx.book.endat22_words(all_read);
  const bool complete = endat22 && all_read;
  const std::uint16_t sum = protocol::parameters::endat22_checksum(e);
  const std::uint16_t stored = e[protocol::word::kEndat22Checksum];
  if (endat22) {
    monitor_.report().checksum63_stored = stored;
    monitor_.report().checksum63_computed = sum;
  }
  const auto& checksum = ctx.checksum.result();
  if (checksum) {
    monitor_.report().checksum47_stored = checksum->stored;
    monitor_.report().checksum47_computed = checksum->computed;
  }
  const bool ok47 = checksum && checksum->ok();
  if (params_.checksums) {
    if (!ok47)
      monitor_.find(SafetyFunction::Checksums, ctx.now, checksum && checksum->complete ? "word 47 " + std::to_string(checksum->stored) + " but words 4 .. 46 sum to " +
                                                  std::to_string(checksum->computed) + " (3.5.26)"
                                            : "the words 4 .. 47 could not all be read");
    if (endat22 && !complete) monitor_.find(SafetyFunction::Checksums, ctx.now, "the words of the EnDat 2.2 area could not all be read");
    else if (endat22 && stored != sum)
      monitor_.find(SafetyFunction::Checksums, ctx.now, "word 63 of the EnDat 2.2 area " + std::to_string(stored) + " but words 0 .. 62 sum to " + std::to_string(sum) +
               " (3.9.37)");
  }
  if (params_.position_value_2) {
    if (complete && checksum && checksum->complete)
      monitor_.set_position2_parameters(position2_parameters(ctx.checksum.words(), e));
    else
      monitor_.find(SafetyFunction::PositionValue2, ctx.now, "the encoder's parameters for the comparison could not be read");
  }
}

void SafetyMonitor::check_position_value_2(const FrameResult& f) {
  if (!params_.position_value_2 || !position2_parameters_) return;
  for (const auto& d : f.additional_data) {
    if (!d.crc_ok || d.information() < I::PositionValue2Word1 || d.information() > I::PositionValue2Word3) continue;
    const unsigned k = static_cast<unsigned>(d.information()) - static_cast<unsigned>(I::PositionValue2Word1);
    if (k == 0) {
      double velocity = 0;
      if (last_good_ && f.start > last_good_->second)
        velocity = static_cast<double>(ring_distance(f.position, last_good_->first, position_bits_)) * static_cast<double>(sim::kPsPerSecond) /
                   static_cast<double>((f.start - last_good_->second).count());
      position2_ = Position2Read{f.position, f.start, f.index, velocity, 0, 0};
    }
    if (!position2_ || position2_->words != k) {
      position2_.reset();
      continue;
    }
    position2_->value |= std::uint64_t{d.data} << (16 * k);
    ++position2_->words;
  }
  const unsigned words = protocol::position_value2_words(position_bits_);
  if (!position2_ || position2_->words < words) return;
  const Position2Read r = *position2_;
  position2_.reset();
  const Position2Parameters& p = *position2_parameters_;
  const auto accuracy = p.accuracy_at(r.velocity);
  if (!accuracy) {
    ++report_.comparisons_out_of_range;
    return;
  }
  ++report_.position_comparisons;
  // 3.9.24: position value 2 = position value 1 + offset (3.9.13: or minus it, reversed).
  const std::uint64_t expected = p.reversed ? static_cast<std::uint64_t>(p.offset) - r.position1
                                            : r.position1 + static_cast<std::uint64_t>(p.offset);
  const std::int64_t deviation = ring_distance(r.value, expected, position_bits_);
  // UNCERTAIN (3.9.20): N bits "relevant for the comparison" read as a comparison at the
  // resolution of the N most significant bits: deviations below 2^(bits - N) LSB do not count.
  std::uint64_t tolerance = *accuracy;
  if (p.comparison_bits > 0 && p.comparison_bits < position_bits_)
    tolerance = std::max<std::uint64_t>(tolerance, std::uint64_t{1} << (position_bits_ - p.comparison_bits));
  if (magnitude(deviation) > tolerance)
    find(SafetyFunction::PositionValue2, f,
         "position value 2 " + std::to_string(r.value) + " deviates " + std::to_string(deviation) +
             " LSB from position value 1 " + std::to_string(r.position1) + " (frame #" + std::to_string(r.frame) +
             "), more than the stored accuracy " + std::to_string(tolerance) + " LSB at " +
             std::to_string(static_cast<long long>(r.velocity)) + " steps/s");
}

}  // namespace endatsim::master
