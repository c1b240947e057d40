#include "endatsim/slave/eib.hpp"

#include <algorithm>
#include <stdexcept>

#include "endatsim/slave/reference.hpp"

namespace endatsim::slave {

namespace pm = protocol::parameters;
using A = MemoryArea;

bool eib_commissioning_area(MemoryArea area) {
  return std::find(kEibCommissioningAreas.begin(), kEibCommissioningAreas.end(), area) != kEibCommissioningAreas.end();
}

bool eib_factory_word(unsigned manufacturer_word) {
  return std::find(kEibFactoryWords.begin(), kEibFactoryWords.end(), manufacturer_word) != kEibFactoryWords.end();
}

MemoryImage eib_factory_image(const EibFactoryData& d) {
  std::vector<std::uint16_t> m(protocol::kManufacturerWords, 0);
  pm::encode_partition_words(m, d.oem, d.compensation);
  m[word::kEncoderType] = pm::encode_encoder_type(pm::EncoderType::ExternalInterfaceBox);
  const auto id = pm::encode_id_number(d.id);
  std::copy(id.begin(), id.end(), m.begin() + word::kIdNumber);
  const auto serial = pm::encode_serial_number(d.serial);
  std::copy(serial.begin(), serial.end(), m.begin() + word::kSerialNumber);
  m[word::kManufacturerChecksum] = pm::manufacturer_checksum(m);
  MemoryImage img;
  img.areas[A::OperatingStatus].assign(protocol::info(A::OperatingStatus).fixed_words, 0);
  set_manufacturer_words(img, m);
  img.areas[A::OperatingParameters].assign(protocol::info(A::OperatingParameters).fixed_words, 0);
  add_partitioned_areas(img, m);
  img.areas[A::ManufacturerEndat22].assign(protocol::info(A::ManufacturerEndat22).fixed_words, 0);
  img.areas[A::OperatingParameters2].assign(protocol::kOperatingParameters2DefaultWords, 0);
  return img;
}

void EibCommissioning::follow_encoder_type(protocol::parameters::EncoderType type) {
  not_initiated_ = type == pm::EncoderType::ExternalInterfaceBox;
  memory_.set_initial_commissioning(not_initiated_);
}

// A2 cause 5 (choice, docs/model-reference.md): an EIB that is not yet initiated refuses every
// memory access outside the areas initial commissioning fills.
std::optional<protocol::ErrorCause> EibCommissioning::refuses(std::optional<MemoryArea> area) const {
  if (!not_initiated_ || (area && eib_commissioning_area(*area))) return std::nullopt;
  return protocol::ErrorCause::EibNotInitialised;
}

bool EibCommissioning::refuses_positions() const {
  return not_initiated_ && params_.eib_position_before_commissioning == EibPositionBeforeCommissioning::NotSupported;
}

std::optional<unsigned> EibCommissioning::completes_at_reset() const {
  if (!not_initiated_ || params_.eib_activation != EibActivation::Reset) return std::nullopt;
  return connected_encoder_bits();
}

std::optional<unsigned> EibCommissioning::completes_at_write(const Selection& s, std::uint8_t address) const {
  if (!not_initiated_ || params_.eib_activation != EibActivation::Word14Write || s.area != MemoryArea::Manufacturer1 ||
      address != word::kEncoderType)
    return std::nullopt;
  return connected_encoder_bits();
}

// 3.5.7: "the encoder type must be modified during initial commissioning according to the
// connected encoder". The EIB becomes that encoder when word 14 names another type, word 13 a
// transfer format (1 .. 48 bits; 16 for a touch probe), words 18/19 usable reference marks and,
// with eib_activation_checks_checksum, word 47 checks (3.5.26). Otherwise it stays not initiated.
std::optional<unsigned> EibCommissioning::connected_encoder_bits() const {
  const std::vector<std::uint16_t> m = manufacturer_words(memory_.image());
  const auto type = pm::decode_encoder_type(m[word::kEncoderType]);
  const unsigned bits = pm::decode_position_bits(m[word::kPositionFormat]);
  const bool checksum_ok = !params_.eib_activation_checks_checksum || pm::manufacturer_checksum(m) == m[word::kManufacturerChecksum];
  if (type == pm::EncoderType::ExternalInterfaceBox || bits < 1 || bits > EncoderParams::kMaxPositionBits || !checksum_ok ||
      (type == pm::EncoderType::TouchProbe && bits != protocol::kTouchProbeBits))
    return std::nullopt;
  try {
    (void)reference_scheme(memory_, params_.reference_marks, params_.selected_reference_mark, bits);
  } catch (const std::invalid_argument&) {
    return std::nullopt;  // words 18/19 name marks the model cannot place
  }
  return bits;
}

}  // namespace endatsim::slave
