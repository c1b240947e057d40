// Additional data 1 and 2 (spec 2.3.5): information codes I4..I0 and the status byte, as data.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace endatsim::protocol {

// Byte 0 of an additional datum: WRN RM Busy I4..I0, WRN first (2.3.5; bit weights docs/model.md §2).
struct AdditionalDataStatus {
  static constexpr std::uint8_t kWarning = 0x80;
  static constexpr std::uint8_t kReferenceMark = 0x40;
  static constexpr std::uint8_t kBusy = 0x20;
  static constexpr std::uint8_t kInformation = 0x1F;
};

// 2.3.5.2: bytes 1 and 2 of additional data 2 as one word. Commutation (I = 17, 19) has u v w in
// D7 .. D5 of byte 1, the limit position signals (I = 20, 21) L1 in D7 and L2 in D6; with
// acceleration (I = 19, 21) its data fill the bits below them.
struct AdditionalData2Word {
  static constexpr unsigned kCommutationShift = 13;
  static constexpr std::uint16_t kCommutationBits = 0x7;
  static constexpr std::uint16_t kLimitPosition1 = 0x8000;
  static constexpr std::uint16_t kLimitPosition2 = 0x4000;
  static constexpr std::uint16_t kAccelerationBesideCommutation = 0x1FFF;
  static constexpr std::uint16_t kAccelerationBesideLimits = 0x3FFF;
};

// 2.3.5: bytes 1 and 2 of an additional datum as one word. Diagnosis, memory parameters (I = 5, 6),
// the MRS code acknowledgment and the test command acknowledgment carry an address (or code) in
// byte 1 and a data byte in byte 2.
constexpr std::uint16_t make_addressed_datum(std::uint8_t address, std::uint8_t byte) {
  return static_cast<std::uint16_t>(address << 8 | byte);
}
constexpr std::uint8_t datum_address(std::uint16_t data) { return static_cast<std::uint8_t>(data >> 8); }
constexpr std::uint8_t datum_byte(std::uint16_t data) { return static_cast<std::uint8_t>(data); }
// A 16-bit parameter travels as two data bytes: I = 5 its lower-value byte (LSB), I = 6 its
// higher-value one (MSB).
constexpr std::uint8_t lsb_of(std::uint16_t parameter) { return static_cast<std::uint8_t>(parameter); }
constexpr std::uint8_t msb_of(std::uint16_t parameter) { return static_cast<std::uint8_t>(parameter >> 8); }
constexpr std::uint16_t parameter_of(std::uint8_t msb, std::uint8_t lsb) { return static_cast<std::uint16_t>(msb << 8 | lsb); }

// 2.3.5.1 (I = 0..15, additional data 1) and 2.3.5.2 (I = 16..31, additional data 2).
enum class Information : std::uint8_t {
  Nop1 = 0,
  Diagnosis = 1,
  PositionValue2Word1 = 2,
  PositionValue2Word2 = 3,
  PositionValue2Word3 = 4,
  MemoryParameterLsb = 5,
  MemoryParameterMsb = 6,
  MrsCodeAcknowledgment = 7,
  TestCommandAcknowledgment = 8,
  TestValuesWord1 = 9,
  TestValuesWord2 = 10,
  TestValuesWord3 = 11,
  Temperature1 = 12,
  Temperature2 = 13,
  AdditionalSensors = 14,
  Type3Error1 = 15,
  Nop2 = 16,
  Commutation = 17,
  Acceleration = 18,
  CommutationAndAcceleration = 19,
  LimitPositionSignals = 20,
  LimitPositionSignalsAndAcceleration = 21,
  AsynchronousPositionWord1 = 22,
  AsynchronousPositionWord2 = 23,
  AsynchronousPositionWord3 = 24,
  OperatingStatusErrorSources = 25,
  Reserved26 = 26,
  Timestamp = 27,
  Reserved28 = 28,
  Reserved29 = 29,
  Reserved30 = 30,
  Type3Error2 = 31,
};

struct InformationInfo {
  Information code;
  std::string_view name;
  std::string_view key;
  // A2 cause 13: codes that may not be selected (26, 28, 29, 30) answer with type III.
  bool selectable;
  // Bit of "Status of additional data 1/2" (EnDat 2.2 manufacturer words 0/1, 3.9.2/3.9.3) that
  // says the encoder supports the code; none = always supported (NOP, acknowledgments).
  std::optional<unsigned> support_bit;
};

std::span<const InformationInfo> information_codes();
const InformationInfo& info(Information code);
std::optional<Information> information_from_key(std::string_view key);

constexpr bool is_additional_data_2(Information i) { return static_cast<std::uint8_t>(i) >= 16; }

// Additional data 1 and additional data 2 (2.3.5): which of them an information belongs to.
enum class AdditionalDataNumber : std::uint8_t { One, Two };
constexpr AdditionalDataNumber additional_data_number(Information i) {
  return is_additional_data_2(i) ? AdditionalDataNumber::Two : AdditionalDataNumber::One;
}

// Something kept once for additional data 1 and once for additional data 2.
template <class T>
class PerAdditionalData {
  static_assert(static_cast<std::size_t>(AdditionalDataNumber::Two) == 1, "additional data 1 and 2 index two slots");

 public:
  T& operator[](AdditionalDataNumber n) { return values_[static_cast<std::size_t>(n)]; }
  const T& operator[](AdditionalDataNumber n) const { return values_[static_cast<std::size_t>(n)]; }
  // Both back to T{} (nothing selected).
  void clear() { values_ = {}; }

 private:
  std::array<T, 2> values_{};
};
// 2.4.2.2: the MRS code that selects `i`.
constexpr std::uint8_t selection_mrs(Information i) { return static_cast<std::uint8_t>(0x40 | static_cast<std::uint8_t>(i)); }
// The code an MRS code 0x40..0x5F selects.
constexpr Information information_of_mrs(std::uint8_t mrs) { return static_cast<Information>(mrs & 0x1F); }
// 2.3.5.1: position value 2 travels in words 1 .. 3 (I = 2, 3, 4), 16 bits each, as many as its
// width needs.
inline constexpr unsigned kPositionValue2WordsMax = 3;
inline constexpr unsigned kPositionValue2BitsMax = 16 * kPositionValue2WordsMax;
// The 48 bits a position value 2 may hold; the encoder counts it modulo this.
inline constexpr std::uint64_t kPositionValue2Mask = (std::uint64_t{1} << kPositionValue2BitsMax) - 1;
constexpr unsigned position_value2_words(unsigned bits) {
  constexpr unsigned kBitsPerWord = 16;
  const unsigned words = (bits + kBitsPerWord - 1) / kBitsPerWord;
  return words < kPositionValue2WordsMax ? words : kPositionValue2WordsMax;
}
// 2.3.5: a frame carries at most two additional data (additional data 1 and 2).
inline constexpr std::size_t kAdditionalDataPerFrameMax = 2;
// 3.9.3: EnDat 2.2 manufacturer word 1 bit 6, "position value 2" in additional data 2 (as
// the asynchronous position value's codes, 2.3.5.2).
constexpr std::uint16_t kPositionValue2InAdditionalData2 = 0x0040;

}  // namespace endatsim::protocol
