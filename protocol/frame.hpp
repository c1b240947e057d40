// Bit layouts of the encoder's answers, as data (spec 2.3.1, 2.3.4). A layout is a list of
// fields in wire order; encode() and decode() build and take apart whole answers from it (the
// frame engines of the master and the encoder move the bits one clock at a time).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "endatsim/protocol/crc.hpp"
#include "endatsim/protocol/mode_command.hpp"

namespace endatsim::protocol {

// The widest position value the models take, in clock pulses (word 13 allows 63, 3.5.6): as wide as
// position value 2 and the datum shift may be (48 bits, 3.9.24, 3.6.2), so that every position
// fits them and the 64-bit arithmetic of the models.
inline constexpr unsigned kPositionBitsMax = 48;
// The n low bits set: a position of n bits modulo 2^n ("after the zero position follows
// 2^x - 1", 3.5.16).
constexpr std::uint64_t position_mask(unsigned bits) {
  return bits >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << bits) - 1;
}

enum class Field : std::uint8_t {
  StartBit,
  Error1,
  Error2,
  Position,
  Crc,
  Address,         // 8 bits: address, MRS code or port address (A7 first)
  Parameter,       // 16 bits: parameter or instruction (D15 first)
  TestValue,       // 40 bits, LSB first (2.9)
  LeadingLow,      // the LOW bit that opens an additional datum (2.3.5)
  Status,          // additional datum byte 0: WRN RM Busy I4..I0
  AdditionalData,  // additional datum bytes 1 and 2
  Count
};

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
// `crc`: the generator's setup (the spec's by default; an emulator built wrong, docs/model.md §12).
std::vector<std::uint8_t> encode_position_frame(EndatVersion command_type, unsigned position_bits,
                                                const PositionWord& word, const CrcConfig& crc = {});

// 2.4 .. 2.10, docs/model.md §3: S, address/MRS/port (8), parameter (16), CRC = MakeCrcNorm.
// The same 8 + 16 bits (without S and CRC) are what the master sends after a 2.1 mode command.
Layout parameter_frame_layout();
Layout payload_layout();  // master -> encoder: address (8), parameter (16)
// Those 8 + 16 bits as one number, as frames record the 2.1 payload and the 2.2 command
// supplement: the address (MRS code, port) in bits 16 .. 23, the parameter in bits 0 .. 15.
constexpr std::uint32_t make_payload(std::uint8_t address, std::uint16_t parameter) {
  return std::uint32_t{address} << 16 | parameter;
}
constexpr std::uint8_t payload_address(std::uint32_t payload) { return static_cast<std::uint8_t>(payload >> 16); }
constexpr std::uint16_t payload_parameter(std::uint32_t payload) { return static_cast<std::uint16_t>(payload); }
std::vector<std::uint8_t> encode_parameter_frame(std::uint8_t address, std::uint16_t parameter, const CrcConfig& crc = {});

// 2.9: S F1 test value (40 bits, LSB first) CRC = MakeCrcPos over 40 bits (A4.4.2).
constexpr unsigned kTestValueBits = 40;
constexpr std::uint64_t kTestValueMax = (std::uint64_t{1} << kTestValueBits) - 1;
// 2.3.4.4: a touch probe sends 16 bits, the LSB its trigger status.
constexpr unsigned kTouchProbeBits = 16;
Layout test_values_layout();
std::vector<std::uint8_t> encode_test_values(bool error1, std::uint64_t test_value, const CrcConfig& crc = {});

// 2.3.5: a LOW bit, byte 0 (status), bytes 1 and 2, CRC over the 24 bits = MakeCrcNorm.
constexpr unsigned kAdditionalDatumBits = 30;
// Its Busy bit: after the LOW bit, WRN and RM.
constexpr unsigned kAdditionalDatumBusyBit = 3;
Layout additional_datum_layout();
std::vector<std::uint8_t> encode_additional_datum(std::uint8_t status, std::uint16_t data, const CrcConfig& crc = {});
// One additional datum's fields as received, from its first bit (the LOW bit) on.
struct ReceivedDatum {
  bool leading_low = false;  // the bit before the status byte was LOW, as sent
  std::uint8_t status = 0;
  std::uint16_t data = 0;
  std::uint8_t crc = 0;
};
ReceivedDatum decode_additional_datum(std::span<const std::uint8_t> bits);

// The encoder's answer to `command` without additional data: position, test-value or parameter frame.
Layout answer_layout(const ModeCommandInfo& command, unsigned position_bits);

// docs/model.md §4 (likely): the 2.2 command supplement is a start bit 1, then 8 + 16 bits MSB
// first, and no CRC from the master.
Layout supplement_layout();

}  // namespace endatsim::protocol
