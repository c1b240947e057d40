#include "endatsim/protocol/frame.hpp"

#include <stdexcept>

#include "endatsim/protocol/crc.hpp"

namespace endatsim::protocol {

std::string_view field_name(Field f) {
  switch (f) {
    case Field::StartBit: return "start bit";
    case Field::Error1: return "F1";
    case Field::Error2: return "F2";
    case Field::Position: return "position";
    case Field::Crc: return "CRC";
    case Field::Address: return "address";
    case Field::Parameter: return "parameter";
    case Field::TestValue: return "test value";
    case Field::LeadingLow: return "leading low";
    case Field::Status: return "status";
    case Field::AdditionalData: return "additional data";
    case Field::Count: break;
  }
  return "?";
}

Layout::Layout(std::vector<FieldSpec> fields) : fields_(std::move(fields)) {
  for (const FieldSpec& f : fields_) {
    if (f.width == 0 || f.width > 64) throw std::invalid_argument("field width must be 1..64");
    width_ += f.width;
  }
}

Field Layout::field_at(unsigned index) const {
  for (const FieldSpec& f : fields_) {
    if (index < f.width) return f.field;
    index -= f.width;
  }
  throw std::out_of_range("bit index beyond the layout");
}

void Layout::encode(const FieldValues& values, std::vector<std::uint8_t>& bits) const {
  for (const FieldSpec& f : fields_) {
    const std::uint64_t v = values[static_cast<std::size_t>(f.field)];
    for (unsigned i = 0; i < f.width; ++i) {
      const unsigned bit = f.order == BitOrder::LsbFirst ? i : f.width - 1 - i;
      bits.push_back(static_cast<std::uint8_t>((v >> bit) & 1U));
    }
  }
}

FieldValues Layout::decode(std::span<const std::uint8_t> bits) const {
  if (bits.size() < width_) throw std::invalid_argument("too few bits for the layout");
  FieldValues values{};
  std::size_t at = 0;
  for (const FieldSpec& f : fields_) {
    std::uint64_t v = 0;
    for (unsigned i = 0; i < f.width; ++i, ++at) {
      const unsigned bit = f.order == BitOrder::LsbFirst ? i : f.width - 1 - i;
      v |= static_cast<std::uint64_t>(bits[at] & 1U) << bit;
    }
    values[static_cast<std::size_t>(f.field)] = v;
  }
  return values;
}

Layout position_frame_layout(EndatVersion command_type, unsigned position_bits) {
  std::vector<FieldSpec> fields{{Field::StartBit, 1, BitOrder::MsbFirst}, {Field::Error1, 1, BitOrder::MsbFirst}};
  if (command_type == EndatVersion::V2_2) fields.push_back({Field::Error2, 1, BitOrder::MsbFirst});
  fields.push_back({Field::Position, position_bits, BitOrder::LsbFirst});  // 2.3.1: LSB first
  fields.push_back({Field::Crc, 5, BitOrder::MsbFirst});
  return Layout(std::move(fields));
}

std::vector<std::uint8_t> encode_position_frame(EndatVersion command_type, unsigned position_bits,
                                                const PositionWord& word, const CrcConfig& crc) {
  const bool v22 = command_type == EndatVersion::V2_2;
  FieldValues values{};
  values[static_cast<std::size_t>(Field::StartBit)] = 1;
  values[static_cast<std::size_t>(Field::Error1)] = word.error1;
  values[static_cast<std::size_t>(Field::Error2)] = word.error2;
  values[static_cast<std::size_t>(Field::Position)] = word.position;
  values[static_cast<std::size_t>(Field::Crc)] =
      make_crc_pos(position_bits, word.error1, word.error2, v22, word.position, crc);
  std::vector<std::uint8_t> bits;
  bits.reserve(position_bits + 8);
  position_frame_layout(command_type, position_bits).encode(values, bits);
  return bits;
}

namespace {

constexpr FieldSpec kStart{Field::StartBit, 1, BitOrder::MsbFirst};
constexpr FieldSpec kAddress{Field::Address, 8, BitOrder::MsbFirst};
constexpr FieldSpec kParameter{Field::Parameter, 16, BitOrder::MsbFirst};
constexpr FieldSpec kCrc{Field::Crc, kCrcBits, BitOrder::MsbFirst};

std::vector<std::uint8_t> encode(const Layout& layout, const FieldValues& values) {
  std::vector<std::uint8_t> bits;
  bits.reserve(layout.width());
  layout.encode(values, bits);
  return bits;
}

constexpr std::size_t at(Field f) { return static_cast<std::size_t>(f); }

}  // namespace

Layout parameter_frame_layout() { return Layout({kStart, kAddress, kParameter, kCrc}); }

Layout payload_layout() { return Layout({kAddress, kParameter}); }

std::vector<std::uint8_t> encode_parameter_frame(std::uint8_t address, std::uint16_t parameter, const CrcConfig& crc) {
  FieldValues v{};
  v[at(Field::StartBit)] = 1;
  v[at(Field::Address)] = address;
  v[at(Field::Parameter)] = parameter;
  v[at(Field::Crc)] = make_crc_norm(address, parameter, crc);
  return encode(parameter_frame_layout(), v);
}

Layout test_values_layout() {
  return Layout({kStart, {Field::Error1, 1, BitOrder::MsbFirst}, {Field::TestValue, kTestValueBits, BitOrder::LsbFirst},
                 kCrc});
}

std::vector<std::uint8_t> encode_test_values(bool error1, std::uint64_t test_value, const CrcConfig& crc) {
  FieldValues v{};
  v[at(Field::StartBit)] = 1;
  v[at(Field::Error1)] = error1;
  v[at(Field::TestValue)] = test_value;
  v[at(Field::Crc)] = make_crc_pos(kTestValueBits, error1, true, false, test_value, crc);
  return encode(test_values_layout(), v);
}

Layout additional_datum_layout() {
  return Layout({{Field::LeadingLow, 1, BitOrder::MsbFirst},
                 {Field::Status, 8, BitOrder::MsbFirst},
                 {Field::AdditionalData, 16, BitOrder::MsbFirst},
                 kCrc});
}

std::vector<std::uint8_t> encode_additional_datum(std::uint8_t status, std::uint16_t data, const CrcConfig& crc) {
  FieldValues v{};
  v[at(Field::Status)] = status;
  v[at(Field::AdditionalData)] = data;
  v[at(Field::Crc)] = make_crc_norm(status, data, crc);
  return encode(additional_datum_layout(), v);
}

ReceivedDatum decode_additional_datum(std::span<const std::uint8_t> bits) {
  const auto v = additional_datum_layout().decode(bits);
  return {.leading_low = v[at(Field::LeadingLow)] == 0,
          .status = static_cast<std::uint8_t>(v[at(Field::Status)]),
          .data = static_cast<std::uint16_t>(v[at(Field::AdditionalData)]),
          .crc = static_cast<std::uint8_t>(v[at(Field::Crc)])};
}

Layout answer_layout(const ModeCommandInfo& command, unsigned position_bits) {
  switch (command.answer) {
    case AnswerFormat::TestValues: return test_values_layout();
    case AnswerFormat::Parameter: return parameter_frame_layout();
    case AnswerFormat::Position: break;
  }
  return position_frame_layout(command.version, position_bits);
}

Layout supplement_layout() { return Layout({kStart, kAddress, kParameter}); }

}  // namespace endatsim::protocol
