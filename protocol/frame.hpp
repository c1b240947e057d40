// Bit layouts of the encoder's answers, as data (spec 2.3.1, 2.3.4). A layout is a list of
// fields in wire order; encode() and decode() are the only places that shift bits.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "protocol/mode_command.hpp"

namespace endatsim::protocol {

enum class Field : std::uint8_t { StartBit, Error1, Error2, Position, Crc, Count };

enum class BitOrder : std::uint8_t { LsbFirst, MsbFirst };

struct FieldSpec {
  Field field;
  unsigned width;
  BitOrder order;
};

std::string_view field_name(Field f);

using FieldValues = std::array<std::uint64_t, static_cast<std::size_t>(Field::Count)>;

class Layout {
 public:
  explicit Layout(std::vector<FieldSpec> fields);
  std::span<const FieldSpec> fields() const { return fields_; }
  unsigned width() const { return width_; }
  // The field that bit `index` (0 = first on the wire) belongs to.
  Field field_at(unsigned index) const;
  void encode(const FieldValues& values, std::vector<std::uint8_t>& bits) const;
  FieldValues decode(std::span<const std::uint8_t> bits) const;

 private:
  std::vector<FieldSpec> fields_;
  unsigned width_ = 0;
};

// "Encoder send position values" (2.1): S F1 position CRC;
// "... with additional data" (2.2): S F1 F2 position CRC (F2 is low-active, 2.3.1).
Layout position_frame_layout(EndatVersion command_type, unsigned position_bits);

struct PositionWord {
  bool error1 = false;  // F1: 1 = error
  bool error2 = true;   // F2: 0 = error; only sent with 2.2 mode commands
  std::uint64_t position = 0;
};

// The answer bits in wire order, start bit first, CRC computed per appendix A4.
std::vector<std::uint8_t> encode_position_frame(EndatVersion command_type, unsigned position_bits,
                                                const PositionWord& word);

}  // namespace endatsim::protocol
