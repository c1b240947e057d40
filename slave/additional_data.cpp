#include "endatsim/slave/additional_data.hpp"

#include <algorithm>

#include "endatsim/protocol/parameters.hpp"

namespace endatsim::slave {
namespace {

using protocol::ErrorCause;
using I = Information;
namespace pm = protocol::parameters;

using protocol::parameters::word_of;

bool is_position_value2(Information i) { return i >= I::PositionValue2Word1 && i <= I::PositionValue2Word3; }

}  // namespace

using N = protocol::AdditionalDataNumber;

AdditionalData::AdditionalData(const EncoderParams& params, const Memory& memory, const PositionSource& positions)
    : params_(params), memory_(memory), positions_(positions) {}

// 2.4.2.2; the selection is acknowledged with its MRS code and block address 0 (I = 7).
void AdditionalData::select(std::uint8_t mrs) {
  const N which = protocol::additional_data_number(protocol::information_of_mrs(mrs));
  mrs_ = mrs;
  block_ = 0;
  if (protocol::stops_additional_data(mrs)) {
    selection_[which].reset();
    type3_[which].reset();
    return;
  }
  const Information i = protocol::information_of_mrs(mrs);
  selection_[which] = i;
  type3_[which] = type3_cause(i, which);
  if (which == N::One && selection_[N::Two]) type3_[N::Two] = type3_cause(*selection_[N::Two], N::Two);
}

void AdditionalData::acknowledge_mrs(std::uint8_t mrs, std::uint8_t block) {
  mrs_ = mrs;
  block_ = block;
}

void AdditionalData::acknowledge_memory_access(std::uint8_t address, std::uint16_t value) {
  memory_address_ = address;
  memory_value_ = value;
}

void AdditionalData::restart() {
  asynchronous_time_delay_ = 0;
  selection_.clear();
  type3_.clear();
  test_port_ = 0;
  sensor_address_ = 0;
  diagnosis_index_ = 0;
}

void AdditionalData::append(std::vector<std::uint8_t>& answer, std::vector<std::uint8_t>& statuses, Time frame_start,
                            std::uint64_t true_position, bool busy) {
  for (const N which : {N::Two, N::One})
    if (selection_[which]) append_datum(answer, statuses, which, frame_start, true_position, busy);
}

void AdditionalData::append_datum(std::vector<std::uint8_t>& answer, std::vector<std::uint8_t>& statuses,
                                  N which, Time frame_start, std::uint64_t true_position, bool busy) {
  const Information selected = *selection_[which];
  Information code = selected;
  std::uint16_t data = 0;
  if (type3_[which]) code = which == N::One ? I::Type3Error1 : I::Type3Error2;  // A2 type III
  else if (answers_nop(selected)) code = which == N::One ? I::Nop1 : I::Nop2;   // A2 type IV
  else data = content(selected, frame_start, true_position);
  const std::uint8_t status = status_byte(code, busy);
  statuses.push_back(status);
  const auto bits = protocol::encode_additional_datum(status, data, params_.crc);
  answer.insert(answer.end(), bits.begin(), bits.end());
}

// A2 type IV: an information the encoder cannot update now (cause 16), diagnosis that operating
// parameters word 3 does not activate (3.6.3), and position value 2 without an absolute position
// (an incremental encoder before its reference run, 2.3.4.3; an EIB not yet initiated).
bool AdditionalData::answers_nop(Information i) const {
  const auto& stale = params_.sensors.not_updatable;
  return std::find(stale.begin(), stale.end(), i) != stale.end() || (i == I::Diagnosis && !diagnosis_activated()) ||
         (is_position_value2(i) && !(positions_.valid() && positions_.absolute_known()));
}

std::optional<ErrorCause> AdditionalData::type3_cause(Information i, N which) const {
  const auto& code = protocol::info(i);
  if (!code.selectable) return ErrorCause::ImpermissibleAdditionalData;  // A2 cause 13
  if (code.support_bit) {
    const auto support = memory_.endat22_word(which == N::One ? word::kAdditionalData1Support : word::kAdditionalData2Support);
    if (((support >> *code.support_bit) & 1U) == 0) return ErrorCause::UnsupportedAdditionalData;  // cause 14
  }
  // A2 cause 15 (interpretation): position value 2 requested through both additional data.
  const bool pos2_in_ai2 = i >= I::AsynchronousPositionWord1 && i <= I::AsynchronousPositionWord3 &&
                           (memory_.endat22_word(word::kAdditionalData2Support) & protocol::kPositionValue2InAdditionalData2) != 0;
  const bool pos2_in_ai1 = selection_[N::One] && is_position_value2(*selection_[N::One]);
  if (which == N::Two && pos2_in_ai2 && pos2_in_ai1) return ErrorCause::DuplicateAdditionalData;
  return std::nullopt;
}

std::uint8_t AdditionalData::status_byte(Information i, bool busy) const {
  using S = protocol::AdditionalDataStatus;
  auto s = static_cast<std::uint8_t>(i);
  if ((memory_.operating_status(word::kWarnings) & memory_.manufacturer_word(word::kSupportedWarnings)) != 0)
    s |= S::kWarning;
  if (busy) s |= S::kBusy;
  // 2.3.1 status table: RM is "already set with switch-on with absolute encoders"; an incremental
  // one sets it when its reference run is done (2.3.4.3).
  if (positions_.reference_mark()) s |= S::kReferenceMark;
  return s;
}

bool AdditionalData::frame_invariant() const {
  for (const auto which : {protocol::AdditionalDataNumber::One, protocol::AdditionalDataNumber::Two}) {
    const std::optional<Information>& i = selection_[which];
    if (!i) continue;
    switch (*i) {
      case I::Temperature1:
      case I::Temperature2:
      case I::Commutation:
      case I::Acceleration:
      case I::CommutationAndAcceleration:
      case I::LimitPositionSignals:
      case I::LimitPositionSignalsAndAcceleration:
      case I::OperatingStatusErrorSources:
      case I::MrsCodeAcknowledgment:
      case I::TestCommandAcknowledgment:
        continue;
      default:
        return false;
    }
  }
  return true;
}

std::uint16_t AdditionalData::content(Information i, Time frame_start, std::uint64_t true_position) {
  const Sensors& s = params_.sensors;
  const auto acceleration = s.acceleration;
  using W = protocol::AdditionalData2Word;
  const auto uvw = static_cast<std::uint16_t>((s.commutation & W::kCommutationBits) << W::kCommutationShift);
  const auto limits = static_cast<std::uint16_t>((s.limit_position_1 ? W::kLimitPosition1 : 0) |
                                                 (s.limit_position_2 ? W::kLimitPosition2 : 0));
  switch (i) {
    case I::Diagnosis: return next_diagnosis_value();
    case I::PositionValue2Word1: return position_value2(frame_start, true_position);
    case I::PositionValue2Word2: return word_of(position2_latched_, 1);
    case I::PositionValue2Word3: return word_of(position2_latched_, 2);
    case I::MemoryParameterLsb: return protocol::make_addressed_datum(memory_address_, protocol::lsb_of(memory_value_));
    case I::MemoryParameterMsb: return protocol::make_addressed_datum(memory_address_, protocol::msb_of(memory_value_));
    case I::MrsCodeAcknowledgment: return protocol::make_addressed_datum(mrs_, block_);
    case I::TestCommandAcknowledgment: return protocol::make_addressed_datum(test_port_, 0);
    case I::TestValuesWord1: {
      const auto it = s.test_values.find(test_port_);
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
    case I::CommutationAndAcceleration: return static_cast<std::uint16_t>(uvw | (acceleration & W::kAccelerationBesideCommutation));
    case I::LimitPositionSignals: return limits;
    case I::LimitPositionSignalsAndAcceleration: return static_cast<std::uint16_t>(limits | (acceleration & W::kAccelerationBesideLimits));
    case I::AsynchronousPositionWord1: {
      // 2.4.2.3: the position "time delay k" before the latch; without oversampling only delay 0.
      const bool oversampling = memory_.function_activated(pm::EncoderFunction::Oversampling);
      const unsigned k = oversampling ? asynchronous_time_delay_ : 0;
      asynchronous_latched_ = positions_.latched(frame_start - std::min(frame_start, params_.asynchronous_time_delay_step * k));
      return word_of(asynchronous_latched_, 0);
    }
    case I::AsynchronousPositionWord2: return word_of(asynchronous_latched_, 1);
    case I::AsynchronousPositionWord3: return word_of(asynchronous_latched_, 2);
    case I::OperatingStatusErrorSources: return s.operating_status_error_sources;
    case I::Timestamp: return positions_.timestamp(frame_start);
    default: return 0;
  }
}

// Position value 2 (48 bits, 3.9.24): position + offset, or offset - position (3.9.13), plus a
// fault of the second position sensing; an incremental encoder's absolute position once
// referenced (2.3.4.3).
std::uint16_t AdditionalData::position_value2(Time frame_start, std::uint64_t true_position) {
  const Sensors& s = params_.sensors;
  const auto offset = static_cast<std::uint64_t>(s.position2_offset);
  position2_latched_ = positions_.incremental() ? positions_.absolute_output(frame_start)
                       : s.position2_reversed   ? offset - true_position
                                                : true_position + offset;
  position2_latched_ = (position2_latched_ + static_cast<std::uint64_t>(s.position2_fault)) & protocol::kPositionValue2Mask;
  return word_of(position2_latched_, 0);
}

// A3 / 3.6.3: the valuation numbers word 3 activates, then (bit 15) the system-specific data,
// one per interrogation, as address | value.
std::uint16_t AdditionalData::next_diagnosis_value() {
  const Sensors& s = params_.sensors;
  const std::uint16_t enabled = memory_.active_operating_parameters()[word::kDiagnosticsConfiguration];
  std::vector<std::uint16_t> rotation;
  for (unsigned k = 0; k < s.valuation_numbers.size(); ++k)
    if (((enabled >> k) & 1U) != 0)
      rotation.push_back(protocol::make_addressed_datum(protocol::diagnosis::valuation_number_address(k + 1), s.valuation_numbers[k]));
  if ((enabled & protocol::diagnosis::kSystemSpecificDataBit) != 0)
    for (const auto& [address, value] : s.system_data) rotation.push_back(protocol::make_addressed_datum(address, value));
  if (rotation.empty()) return 0;
  return rotation[diagnosis_index_++ % rotation.size()];
}

bool AdditionalData::diagnosis_activated() const {
  const std::uint16_t enabled = memory_.active_operating_parameters()[word::kDiagnosticsConfiguration];
  return (enabled & protocol::diagnosis::kValuationNumberBits) != 0 ||
         ((enabled & protocol::diagnosis::kSystemSpecificDataBit) != 0 && !params_.sensors.system_data.empty());
}

}  // namespace endatsim::slave
