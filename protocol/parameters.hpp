// The meaning of the parameter words (spec 3.5 parameters of the encoder manufacturer, 3.6
// operating parameters, 3.9 parameters of the encoder manufacturer for EnDat 2.2): encode and
// decode functions for the words the spec defines with worked examples, and human-readable
// strings for reports. Every function cites its section.
//
// Details the copy of D297403 this model was built from lacks (its figures, a column of some
// tables; docs/model.md) are marked "UNCERTAIN" with what was assumed; tests/parameters_test.cpp reproduces every worked
// example that survived.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "endatsim/protocol/memory_area.hpp"

namespace endatsim::protocol {
// Word numbers in their memory areas (3.4, 3.5.1, 3.6.1, 3.9.1), used by encoder, master and checker.
namespace word {
constexpr unsigned kErrors = 0, kWarnings = 1, kWriteProtection = 2, kFunctionInitialization = 3;  // B9
constexpr unsigned kVersion = 8, kOemPartition = 9, kCompensationPartition = 11, kPositionFormat = 13,
                   kEncoderType = 14, kSupportedErrors = 35, kSupportedWarnings = 36, kCommandSet = 37,
                   kCalculationTime = 39, kManufacturerChecksum = 47;  // encoder manufacturer, 3.5.1
constexpr unsigned kAdditionalData1Support = 0, kAdditionalData2Support = 1, kSection2Blocks = 24,
                   kMaxClockFrequency = 25, kEndat22Checksum = 63;  // BD, 3.9.1
constexpr unsigned kEncoderAddress = 4, kInstructions = 5;       // A7, 3.6.4 / 3.6.5
// 3.5.1: the encoder manufacturer's words 0..47 lie 16 to an area (A1, A3, A5); a word's address
// within its area.
constexpr std::uint8_t manufacturer_address(unsigned w) { return static_cast<std::uint8_t>(w % kManufacturerWordsPerArea); }
// The inverse: the manufacturer word at `address` of its area A1, A3 or A5.
constexpr unsigned manufacturer_word(MemoryArea area, std::uint8_t address) {
  return address + (area == MemoryArea::Manufacturer2   ? kManufacturerWordsPerArea
                    : area == MemoryArea::Manufacturer3 ? 2 * kManufacturerWordsPerArea
                                                        : 0U);
}
constexpr unsigned kDatumShift = 0;                              // A7 words 0..2, 3.6.2
constexpr unsigned kDiagnosticsConfiguration = 3;                // A7, 3.6.3
constexpr unsigned kTemperatureWarningThreshold = 6;             // A7, 3.6.6 (0.1 K)
constexpr unsigned kTemperatureScaling = 4, kDiagnosticStatus = 5, kMaxEncoderTemperature = 22;  // BD, 3.9.6 / 3.9.7 / 3.9.16
constexpr unsigned kDirection = 30;                              // encoder manufacturer, 3.5.16
constexpr unsigned kManufacturerDatumShift = 22, kIdNumber = 24, kSerialNumber = 27,
                   kCommissioningDiagnostics = 31;  // encoder manufacturer, 3.5.13 .. 3.5.15, 3.5.17
constexpr unsigned kSignalPeriod = 15, kDistinguishableRevolutions = 17, kReferenceMarkDistance = 18,
                   kFirstReferenceMark = 19, kMeasuringSteps = 20, kMaxVelocity = 32, kAccuracy = 33,
                   kOrderingDesignation = 40;  // encoder manufacturer, 3.5.8 .. 3.5.12, 3.5.18, 3.5.19, 3.5.25
constexpr unsigned kAdditionalFunctionsSupport = 2, kErrorMessage2Support = 6, kPosition2MeasuringSteps = 9,
                   kPosition2Accuracy = 11, kPosition2Direction = 16, kPosition2Offset = 31,
                   kComparisonBits = 26, kTimestampUnit = 45;  // BD, 3.9.4, 3.9.8, 3.9.10, 3.9.11, 3.9.13, 3.9.20, 3.9.24, 3.9.32
constexpr unsigned kInstructionSupport = 21;                     // BD, 3.9.15
constexpr unsigned kResolutionScaling = 27, kResolution = 28;    // BD, 3.9.21 / 3.9.22 (words 28/29)
constexpr unsigned kTouchProbeSupport = 44;                      // BD, 3.9.31
constexpr unsigned kTouchProbeStatus = 2, kReferencing = 11;     // BB operating parameters 2, 3.10.3 / 3.10.5
}  // namespace word
}  // namespace endatsim::protocol

namespace endatsim::protocol::parameters {

// A value of several parameter words (position value 2's offset, 3.9.24; the datum shift, 3.6.2):
// its 16-bit word `index`, 0 the least significant.
constexpr std::uint16_t word_of(std::uint64_t value, unsigned index) { return static_cast<std::uint16_t>(value >> (16 * index)); }

// Bit 15 "is always set to logical high for NVM checking" in words 8, 13, 30, 31 (3.5.4,
// 3.5.6, 3.5.16, 3.5.17); word 14 carries its NVM bit in bit 0 (3.5.7).
constexpr std::uint16_t kNvmBit15 = 0x8000;
constexpr std::uint16_t kNvmBit0 = 0x0001;

// 32-bit values spread over two words, the low word first (words 15/16, 20/21, 22/23; 3.5.8,
// 3.5.12, 3.5.13).
constexpr std::array<std::uint16_t, 2> split32(std::uint32_t v) {
  return {static_cast<std::uint16_t>(v & 0xFFFF), static_cast<std::uint16_t>(v >> 16)};
}
constexpr std::uint32_t join32(std::uint16_t low, std::uint16_t high) {
  return static_cast<std::uint32_t>(high) << 16 | low;
}

// ---- 3.4.1 / 3.4.2 operating status words 0 and 1: error and warning bits ---------------------
// Index = bit. Bits 7 .. 15 are "currently not assigned" and show as "bit 7" ... in strings.
std::span<const std::string_view> error_bit_names();    // 2^0 lighting .. 2^6 battery
std::span<const std::string_view> warning_bit_names();  // 2^0 frequency collision .. 2^8 diagnostics
constexpr std::uint16_t kEveryErrorBit = 0x007F;                    // word 0 bits 0 .. 6 (3.4.1)
constexpr std::uint16_t kEveryWarningBit = 0x01FF;                  // word 1 bits 0 .. 8 (3.4.2)
constexpr std::uint16_t kWarningTemperatureExceeded = 0x0002;       // word 1 bit 1 (3.4.2)
constexpr std::uint16_t kWarningCyclicOperation = 0x0020;           // word 1 bit 5 (3.4.2)
constexpr std::uint16_t kWarningReferencePointNotReached = 0x0010;  // word 1 bit 4 (3.4.2)
std::string bits_string(std::uint16_t word, std::span<const std::string_view> names);  // "lighting, position" or "none"

// ---- 3.10.3 operating parameters 2 word 2: status of touch probes ----------------------------------
// UNCERTAIN (3.10.1 names the word, not its bits): the model keeps the trigger status in bit 0.
constexpr std::uint16_t kTouchProbeTriggered = 0x0001;

// ---- 3.10.5 operating parameters 2 word 11: referencing ------------------------------------------
// Bit 0 = 1 and bit 1 = 0 reset RM of an incremental encoder (and set the warning "reference
// point not reached").
constexpr std::uint16_t kReferencingMask = 0x0003, kReferencingResetRm = 0x0001;

// ---- 3.6.5 operating parameters word 5: instructions --------------------------------------------
constexpr std::uint16_t kInstructionEnergySaving = 0x0001;      // bit 0: energy-saving mode
constexpr std::uint16_t kInstructionHighImpedance = 0x0002;     // bit 1: data driver at high-impedance (2.10)
constexpr std::uint16_t kInstructionNoPositionUpdate = 0x0004;  // bit 2: no updating of position values
// 3.9.15: word 21 of the EnDat 2.2 manufacturer parameters has the same bits, each set for an
// instruction the encoder does not support.
constexpr std::uint16_t kInstructionBits = kInstructionEnergySaving | kInstructionHighImpedance | kInstructionNoPositionUpdate;

// ---- 3.4.4 operating status word 3: function initialization ------------------------------------
// Each function is a bit pair stored inversely (or a single bit); the value activates it only
// after "Encoder receive reset" or power-on. A pair stored equally leaves the function at its
// factory state (the spec gives no meaning to 00 or 11): short recovery time off, every other
// function deactivated.
enum class EncoderFunction : std::uint8_t {
  ShortRecoveryTime,             // bits 0/1: 1.25 .. 3.75 us for 2.2 mode commands
  ReferencePulseInitialization,  // bits 2/3
  Oversampling,                  // bits 4/5
  CyclicOperation,               // bits 6/7: EnDat 2.2 cyclic operation
  MultiturnOverflowErrorMessage, // bit 8
  MultiturnOverflowLatch,        // bit 9
  MultiturnErrorMessages,        // bit 10: all but the overflow message
  MultiturnCounterReset,         // bits 11/12
  DiagnosticsReset,              // bit 13
};
struct FunctionBits {
  EncoderFunction function;
  std::string_view name;
  std::uint16_t mask;       // the bits of the function
  std::uint16_t activated;  // their value when activated
};
// Bits 0/1 stored inversely: 01 selects the short recovery time I, 10 the long one.
constexpr std::uint16_t kShortRecoveryTimeOn = 0x0001, kShortRecoveryTimeOff = 0x0002;
std::span<const FunctionBits> function_initialization_bits();
bool function_activated(std::uint16_t word3, EncoderFunction f);
std::uint16_t encode_function_initialization(std::span<const EncoderFunction> activated);  // others deactivated
std::string function_initialization_string(std::uint16_t word3);  // "short recovery time I, oversampling"

// ---- 3.5.4 word 8: version of the EnDat interface ----------------------------------------------
// Example "Version 4" = 8004h. Only the integer part of the version is stored.
std::uint16_t encode_version(unsigned version);  // throws std::invalid_argument above 7FFFh
unsigned decode_version(std::uint16_t word);

// ---- 3.5.5 words 9..12: memory allocation of the OEM and compensation areas --------------------
// Per area one byte: high nibble the end address, low nibble the start address, each one of the
// codes 0000 = 0, 0001 = 31, 0010 = 63, 0011 = 64, 0100 = 127, 0101 = 255, 1111 = not available.
// Word 9 low byte = OEM area 1 (MRS A9), high byte = area 2 (AB); word 10: areas 3 (AD), 4 (AF);
// words 11 and 12 likewise for the compensation areas B1, B3, B5, B7.
// Example "256 words": words 9..12 = 20FFh, FF20h, FFFFh, 20FFh (OEM areas 2 and 3 and
// compensation area 4 at addresses 0..63). The bit rows of that example as we have them lack a
// column each; the values follow from the text of the example and are unambiguous.
struct AddressRange {
  unsigned start = 0;
  unsigned end = 0;
  bool operator==(const AddressRange&) const = default;
};
using Partition = std::optional<AddressRange>;  // none: not available
std::optional<unsigned> partition_address(unsigned code);          // none for 1111 and undefined codes
std::optional<unsigned> partition_code(unsigned address);          // none for an address without a code
std::uint8_t encode_partition(const Partition& p);                 // throws for addresses without a code
Partition decode_partition(std::uint8_t byte);                     // none unless both nibbles are defined
std::uint16_t encode_partition_word(const Partition& low_area, const Partition& high_area);
std::pair<Partition, Partition> decode_partition_word(std::uint16_t word);  // {low byte, high byte}
// The eight areas words 9..12 partition, in the order of their bytes: word 9 low (OEM 1) and high
// (OEM 2), word 10 (OEM 3, 4), word 11 (compensation 1, 2), word 12 (compensation 3, 4).
inline constexpr std::array<MemoryArea, 8> kPartitionedAreas{
    MemoryArea::Oem1,          MemoryArea::Oem2,          MemoryArea::Oem3,          MemoryArea::Oem4,
    MemoryArea::Compensation1, MemoryArea::Compensation2, MemoryArea::Compensation3, MemoryArea::Compensation4};
// Where an area's partition lies: its word (9..12) and the byte's shift in it (0 low, 8 high).
struct PartitionByte {
  unsigned word = 0;
  unsigned shift = 0;
};
constexpr std::optional<PartitionByte> partition_byte(MemoryArea a) {
  for (unsigned i = 0; i < kPartitionedAreas.size(); ++i)
    if (kPartitionedAreas[i] == a)
      return PartitionByte{(i < 4 ? word::kOemPartition : word::kCompensationPartition) + i % 4 / 2, i % 2 == 0 ? 0U : 8U};
  return std::nullopt;
}
// The area's partition as the manufacturer's words (indexed by word number) give it; none for
// an area words 9..12 do not partition or make available.
Partition partition_of(std::span<const std::uint16_t> manufacturer_words, MemoryArea a);
// Words 9..12 from the partitions of the four OEM areas and the four compensation areas.
void encode_partition_words(std::span<std::uint16_t> manufacturer_words, std::span<const Partition, 4> oem,
                            std::span<const Partition, 4> compensation);

// ---- 3.5.6 word 13: clock pulses for the position value -----------------------------------------
// Example: 25-bit format = 19h, word 13 = 8019h (bit 15 = 1 for NVM checking). Start, error and
// CRC bits are not counted.
// UNCERTAIN: the extracted bit row shows five value columns where the x columns end; bits 0..5
// are taken as the count (formats above 31 bits need six; masters in the field read six).
constexpr std::uint16_t kPositionBitsMask = 0x003F;
std::uint16_t encode_position_bits(unsigned bits);  // throws outside 1 .. 63
unsigned decode_position_bits(std::uint16_t word);

// ---- 3.5.7 word 14: encoder type ---------------------------------------------------------------
// Bits 15..12 the type; bit 0 always 1 for NVM checking; bits 11..1 reserved for future types
// (2^11 JH, 2^10 AMO; the spec's example for cyclic coding is 7073h).
enum class EncoderType : std::uint8_t {
  IncrementalLinear = 0x0,                       // without distance-coded reference marks
  IncrementalLinearDistanceCoded = 0x1,
  IncrementalLinearBattery = 0x2,                // with battery buffer
  IncrementalLinearBatteryDistanceCoded = 0x3,
  AbsoluteLinear = 0x4,
  TouchProbe = 0x5,                              // "Note touch probes D1 - D11"
  AbsoluteLinearCyclicCoding = 0x6,
  NoteD1D11 = 0x7,                               // "Note D1 - D11" (the note is not in the text)
  IncrementalRotary = 0x8,                       // rotary or angle, without distance-coded marks
  IncrementalRotaryDistanceCoded = 0x9,
  IncrementalRotaryBattery = 0xA,
  IncrementalRotaryBatteryDistanceCoded = 0xB,
  Singleturn = 0xC,                              // singleturn rotary or angle encoder
  MultiturnBattery = 0xD,                        // multiturn rotary encoder with battery buffer
  MultiturnGears = 0xE,
  ExternalInterfaceBox = 0xF,
};
std::uint16_t encode_encoder_type(EncoderType type);  // type << 12 | NVM bit 0
EncoderType decode_encoder_type(std::uint16_t word);
std::string_view encoder_type_name(EncoderType type);  // the wording of the 3.5.7 table
bool is_linear(EncoderType type);

// What word 14 says about referencing (2.3.4.3): absolute types have absolute positions at
// switch-on; incremental ones (types 0..3, 8..B) after crossing one reference mark, two with
// distance-coded marks (types 1, 3, 9, B). Without distance-coded marks, word 18 != 0 gives
// the distance of equidistant marks (3.5.10.2) and word 19 the first of them (3.5.11);
// word 18 = 0 leaves one reference mark.
enum class ReferenceMarks : std::uint8_t { None, One, DistanceCoded, Equidistant };
bool is_incremental(EncoderType type);
ReferenceMarks reference_marks_of(EncoderType type, std::uint16_t word18);
std::string_view reference_marks_name(ReferenceMarks marks);  // "equidistant reference marks"

// ---- 3.5.8 words 15/16: signal period of the incremental signals ----------------------------------
// nm for linear encoders, signal periods per revolution for rotary ones; 0 for EnDat21/EnDat22.
// Examples: 20 um = 20000 = 4E20h / 0000h; 2048 periods per revolution = 0800h / 0000h.
constexpr std::array<std::uint16_t, 2> encode_signal_period(std::uint32_t v) { return split32(v); }
constexpr std::uint32_t decode_signal_period(std::uint16_t w15, std::uint16_t w16) { return join32(w15, w16); }

// ---- 3.5.9 word 17: distinguishable revolutions (multiturn only, 0 for singleturn) --------------
// Example 2048 = 0800h; 65535 means "see word 34 of the EnDat 2.2 area".
std::uint16_t encode_revolutions(std::uint32_t revolutions);  // above 65535: 65535
constexpr std::uint16_t kRevolutionsSeeEndat22Word34 = 0xFFFF;
// Revolutions word 17 holds itself: 2^16 and more read as "see word 34" (encode_revolutions).
constexpr unsigned kRevolutionBitsMax = 16;

// ---- 3.5.12 words 20/21: measuring step (nm, linear) or measuring steps per revolution ---------
// Examples: 100 nm = 0064h / 0000h; 1 800 000 steps per revolution = 1B7740h = 7740h / 001Bh.
// 0 in both words: see words 27..29 of the EnDat 2.2 area.
constexpr std::array<std::uint16_t, 2> encode_measuring_steps(std::uint32_t v) { return split32(v); }
constexpr std::uint32_t decode_measuring_steps(std::uint16_t w20, std::uint16_t w21) { return join32(w20, w21); }
// "100 nm" for linear encoders, "33554432 steps/rev" for rotary ones, and for 0
// "0 (see EnDat 2.2 words 27 .. 29)".
std::string measuring_step_string(EncoderType type, std::uint32_t value);

// ---- 3.5.13 words 22/23 and 3.6.2 operating parameters 0..2: datum shift ---------------------------
// A two's complement over the words, low word first (word 2 of the operating parameters extends
// it to 48 bits for position values above 32 bits).
std::array<std::uint16_t, 2> encode_datum_shift32(std::int64_t value);  // throws outside int32
std::int64_t decode_datum_shift32(std::uint16_t w0, std::uint16_t w1);
std::array<std::uint16_t, 3> encode_datum_shift48(std::int64_t value);  // throws outside 48 bits
// 3.6.2: operating parameters word 2 takes part for positions of more than 32 bits.
constexpr bool datum_shift_has_48_bits(unsigned position_bits) { return position_bits > 32; }
std::int64_t decode_datum_shift48(std::uint16_t w0, std::uint16_t w1, std::uint16_t w2);
// The spec's examples store a shift "by +N measuring steps" as the two's complement of N, i.e.
// as -N: "+20 mm" with 0.1 um steps = 200 000 = 30D40h -> FFFCF2C0h; "+45 degrees" with 8192
// steps per revolution = 1024 -> FFFFFC00h; 3.6.2 adds a 40 mm shift (FFF9E580h) to the
// manufacturer's FFFCF2C0h, giving FFF6D840h.
// UNCERTAIN: figures 48..53, which show which way the datum moves, are lost; the sign
// convention is taken from the example values alone.
constexpr std::int64_t datum_shift_value(std::int64_t shift_steps) { return -shift_steps; }
constexpr std::int64_t datum_shift_steps(std::int64_t value) { return -value; }
// Rounded to the nearest measuring step: 45 degrees at 8192 steps/rev = 1024.
std::int64_t angle_to_steps(double degrees, std::uint32_t steps_per_revolution);
// 3.5.13 / 3.6.2: an EnDat-compliant shift is a multiple of the measuring steps per signal
// period; rounds to the nearest multiple (3.6.2: 569 -> 568 with 4 steps per period).
std::int64_t endat_compliant_shift(std::int64_t steps, std::int64_t steps_per_signal_period);

// ---- 3.5.14 words 24..26: ID number ------------------------------------------------------------
// Words 25 (low) and 26 (high) the first six digits as a binary number, word 24 the last two
// characters in ASCII (first character in the high byte). Example "262 144 A1": 262144 =
// 40000h, word 24 = 4131h ('A' = 41h, '1' = 31h), word 25 = 0000h, word 26 = 0004h.
struct IdNumber {
  std::uint32_t number = 0;
  char suffix[2] = {' ', ' '};
  bool operator==(const IdNumber&) const = default;
};
std::array<std::uint16_t, 3> encode_id_number(const IdNumber& id);  // words 24, 25, 26
IdNumber decode_id_number(std::uint16_t w24, std::uint16_t w25, std::uint16_t w26);
// "262144 A1": the number with at least six digits, a space, the two characters (blanks and
// NULs left out). Throws std::invalid_argument for non-printable characters.
std::string id_number_string(const IdNumber& id);
// Accepts "262144 A1", "262 144 A1" and "262144-A1".
IdNumber parse_id_number(std::string_view text);

// ---- 3.5.15 words 27..29: serial number ---------------------------------------------------------
// A 32-bit binary number between two ASCII characters: word 27 = bits 7..0 | last character,
// word 28 = bits 23..8, word 29 = first character | bits 31..24. Example "(blank)2637991A":
// 2637991 = 2840A7h, words 27..29 = A741h, 2840h, 2000h (the first character is empty = 20h).
struct SerialNumber {
  char prefix = ' ';
  std::uint32_t number = 0;
  char suffix = ' ';
  bool operator==(const SerialNumber&) const = default;
};
std::array<std::uint16_t, 3> encode_serial_number(const SerialNumber& s);  // words 27, 28, 29
SerialNumber decode_serial_number(std::uint16_t w27, std::uint16_t w28, std::uint16_t w29);
// "2637991A": prefix, decimal number, suffix; blank (20h) and NUL characters left out.
std::string serial_number_string(const SerialNumber& s);

// ---- 3.5.16 word 30: direction of rotation or traverse ------------------------------------------
// Bit 15 = 1 for NVM checking, default 0 in bit 0.
// UNCERTAIN: the table lost a column; what survives names bit 0 "direction of measurement" and
// "ascending position values". Bit 0 = 0, the default, is taken as positions ascending in the
// documented direction of measurement, bit 0 = 1 as falling (docs/model-reference.md).
constexpr std::uint16_t kDirectionFalling = 0x0001;
std::uint16_t encode_direction(bool falling);
bool decode_direction_falling(std::uint16_t word);

// ---- 3.5.19 words 33/34: accuracy with respect to linear or rotational velocity -------------------
// The higher-value byte the conversion factor c_i (v_i = v_max / c_i), the lower-value byte the
// accuracy a_i in LSB. 65535 in both words: see words 11 .. 14 of the EnDat 2.2 area (3.9.11).
struct AccuracyRange {
  std::uint32_t conversion_factor = 0;  // c_i
  std::uint32_t accuracy = 0;           // a_i, in LSB
  bool operator==(const AccuracyRange&) const = default;
};
constexpr std::uint16_t kAccuracySeeEndat22 = 0xFFFF;
constexpr std::uint16_t encode_accuracy_range(std::uint8_t conversion_factor, std::uint8_t accuracy) {
  return static_cast<std::uint16_t>(conversion_factor << 8 | accuracy);
}
constexpr AccuracyRange decode_accuracy_range(std::uint16_t word) {
  return {static_cast<std::uint32_t>(word >> 8), static_cast<std::uint32_t>(word & 0xFFU)};
}
// 3.9.11: words 11 .. 14 of the EnDat 2.2 area, c_1 a_1 c_2 a_2, each a value in bits 12..0
// scaled by bits 15..13 (000 x1 .. 101 x32; 111 and the unlisted 110 not supported: none).
std::optional<std::uint32_t> decode_scaled_value(std::uint16_t word);

// ---- 3.5.22 word 37: EnDat command set ----------------------------------------------------------
// Three functions, each in a pair of bits that must be stored inversely: bit 0 = 1 / bit 1 = 0
// command set 2.2, bits 2/3 safety-relevant applications, bits 4/5 mode command "Encoder receive
// communication command". "The function is only supported if the associated bits are inversely
// saved": 2.2 with communication command = 0019h, 2.2 alone = 0029h, 2.1 only = 002Ah.
struct CommandSet {
  bool endat22 = false;
  bool safety = false;
  bool communication_command = false;
  bool operator==(const CommandSet&) const = default;
};
std::uint16_t encode_command_set(const CommandSet& c);
CommandSet decode_command_set(std::uint16_t word);      // a pair stored equally counts as not supported
bool command_set_consistent(std::uint16_t word);         // every pair stored inversely
std::string command_set_string(std::uint16_t word);     // "2.2, communication command"

// ---- 3.5.24 word 39: maximum calculation time t_cal --------------------------------------------
// Bits 15..13 the unit: 000 not supported, 001 us, 010 ms, 011 ns, 100 to be determined.
// UNCERTAIN: the column header "unit of time" spans two columns in the table as we have it but the unit
// table has three bits, so the value is taken as bits 12..0 (0 .. 8191). The spec's example
// ("linear encoder with calculation time of 1 ms") is a lost figure; this code stores 1 ms as
// ms x 1 = 4001h (the coarsest unit that holds the value exactly).
enum class TimeUnit : std::uint8_t { NotSupported = 0, Microseconds = 1, Milliseconds = 2, Nanoseconds = 3, ToBeDetermined = 4 };
struct CalculationTime {
  TimeUnit unit = TimeUnit::NotSupported;
  std::uint16_t value = 0;  // 0 .. 8191
  bool operator==(const CalculationTime&) const = default;
};
std::uint16_t encode_calculation_time(const CalculationTime& t);  // throws for value > 8191 or a unit > 4
CalculationTime decode_calculation_time(std::uint16_t word);      // units 5..7 decode as ToBeDetermined
// The coarsest of ms, us, ns that holds t exactly in 13 bits; throws if none does.
CalculationTime calculation_time_from(std::chrono::nanoseconds t);
std::optional<std::chrono::nanoseconds> calculation_time_duration(const CalculationTime& t);  // none: not given
std::string calculation_time_string(const CalculationTime& t);  // "5 us", "1 ms", "not supported"

// ---- 3.5.25 word 40: EnDat ordering designation ---------------------------------------------------
// "EnDat" and two characters, stored in ASCII (first in the high byte). Example EnDat22 = 3232h;
// 0000h = not supported yet. EnDat01/EnDat02 with, EnDat21/EnDat22 without incremental signals.
// UNCERTAIN: the overview lists the designation against words 40..42 but 3.5.25 describes only
// word 40; words 41 and 42 are left 0.
std::uint16_t encode_ordering_designation(std::string_view designation);  // "EnDat22"; throws otherwise (a space too)
std::optional<std::string> decode_ordering_designation(std::uint16_t word);  // none for 0000h
bool ordering_designation_visible(std::uint16_t word);  // both characters visible ASCII (no space)
// The second character '2' (EnDat02, EnDat22) names the EnDat 2.2 command set (HEIDENHAIN's
// newer brochure editions).
bool ordering_designation_needs_endat22(std::uint16_t word);

// ---- 3.5.26 / 3.9.37: checksums -------------------------------------------------------------------
// Word 47 = word 4 + ... + word 46; EnDat 2.2 word 63 = word 0 + ... + word 62; overflow ignored.
std::uint16_t checksum(std::span<const std::uint16_t> words, unsigned first, unsigned last);
// words: the 48 words of the encoder manufacturer (indices 0..3 ignored) / the 64 of area BD.
constexpr unsigned kManufacturerChecksumFirstWord = 4;
std::uint16_t manufacturer_checksum(std::span<const std::uint16_t> words48);
std::uint16_t endat22_checksum(std::span<const std::uint16_t> words64);

// ---- 3.9.21 / 3.9.22 EnDat 2.2 words 27..29, appendix A10: scaling of the resolution --------------
// Word 27 bits 2..0 say what words 28/29 hold for the (relative) position value, bits 10..8 the
// same for words 9/10 (position value 2): 000 see words 20/21, 001 subdivision values of a
// grating period, 010 steps in powers of 2, 011 steps in pm, 100 not supported. The example:
// 12-bit subdivision, word 27 = 0001h, words 28/29 = 1000h / 0000h.
// UNCERTAIN: the bit row of word 27 lost its alignment; the two 3-bit fields are taken as bits
// 10..8 (position value 2) and 2..0 (position), as the example's 0001h fits.
enum class ResolutionScaling : std::uint8_t {
  SeeWords20And21 = 0, GratingSubdivision = 1, PowerOfTwo = 2, Picometres = 3, NotSupported = 4
};
std::uint16_t encode_resolution_scaling(ResolutionScaling position, ResolutionScaling position2);
ResolutionScaling decode_position_scaling(std::uint16_t word27);  // codes 5..7 decode as NotSupported

// Appendix A10, 3.5.12: for the EIB and incremental encoders words 20/21 hold 0 and the weighting
// of the LSB follows from the signal period (words 15/16) and the subdivision values of a grating
// period (EnDat 2.2 words 27..29). The measuring steps per unit of words 18/19 (3.5.10, 3.5.11):
// per mm for linear encoders, per signal period for rotary ones, as steps / per; none when the
// words do not give it.
struct StepsPerUnit {
  std::uint64_t steps = 0;
  std::uint64_t per = 1;
  bool operator==(const StepsPerUnit&) const = default;
};
// words48: the encoder manufacturer's words (indices 0..3 ignored); words64: area BD, empty for 2.1.
std::optional<StepsPerUnit> steps_per_reference_unit(std::span<const std::uint16_t> words48,
                                                     std::span<const std::uint16_t> words64);
// Measuring steps per revolution of a rotary encoder: words 20/21, else (A10) signal periods x
// subdivision values; none for linear encoders or when the words do not give it.
std::optional<std::uint64_t> steps_per_revolution(std::span<const std::uint16_t> words48,
                                                  std::span<const std::uint16_t> words64);

// ---- 3.5.3 forced dynamic sampling of the error messages -------------------------------------------
// Port addresses of "Encoder send position values and receive test command" that force error
// message 1 (01h .. 07h) and error message 2 (09h .. 0Fh) until port 00h ends it. The table lost
// a column (docs/model-reference.md).
constexpr std::uint8_t kForcedError1FirstPort = 0x01, kForcedError2FirstPort = 0x09, kForcedPortsPerMessage = 7;
constexpr std::uint8_t kForcedSamplingOffPort = 0x00;

// ---- 3.9.2 / 3.9.3 EnDat 2.2 words 0 and 1: supported additional data ------------------------------
// Word 0 (additional data 1): bit 0 position value 2, 1 test values, 2 temperature sensor 1
// (external), 3 temperature sensor 2 (on board), 4 additional sensors. Word 1 (additional data 2):
// bit 0 commutation, 1 acceleration, 2 limit position signals, 3 asynchronous position value,
// 4 operating status error sources, 5 reserved, 6 position value 2 (2.3.5.2), 7 timestamp.
constexpr std::uint16_t kSupportsPositionValue2 = 0x0001, kSupportsTestValues = 0x0002,
                        kSupportsTemperature1 = 0x0004, kSupportsTemperature2 = 0x0008,
                        kSupportsAdditionalSensors = 0x0010;  // word 0
constexpr std::uint16_t kSupportsEveryAdditionalData1 = 0x001F;
constexpr std::uint16_t kSupportsAsynchronousPosition = 0x0008;  // word 1
constexpr std::uint16_t kSupportsTimestamp = 0x0080;             // word 1
// Word 1: every code of additional data 2 (bits 0 .. 4 and 7) but position value 2 (bit 6,
// protocol::kPositionValue2InAdditionalData2).
constexpr std::uint16_t kSupportsEveryAdditionalData2ButPositionValue2 = 0x001F | kSupportsTimestamp;
// ---- 3.9.4 EnDat 2.2 word 2: status of additional functions ---------------------------------------
constexpr std::uint16_t kSupportsSettableRecoveryTime = 0x0002;  // bit 1: recovery time I t_m
// ---- 3.9.6 EnDat 2.2 word 4: scaling of temperatures -------------------------------------------------
// Bits 2..0 = 000: 0.1 K; bit 15 set for NVM checking. Default 8000h.
constexpr std::uint16_t kTemperatureScalingTenthKelvin = kNvmBit15;
std::span<const std::string_view> additional_data_1_names();  // index = bit
std::span<const std::string_view> additional_data_2_names();
// Bits by name (throws std::invalid_argument naming the unknown name and the known ones).
std::uint16_t encode_additional_data_1(std::span<const std::string_view> names);
std::uint16_t encode_additional_data_2(std::span<const std::string_view> names);
std::vector<std::string_view> decode_additional_data_1(std::uint16_t word);  // names of the set bits
std::vector<std::string_view> decode_additional_data_2(std::uint16_t word);  // unassigned bits are left out
std::string additional_data_string(const std::vector<std::string_view>& names);  // "a, b" or "none"

// ---- 3.9.18 / 3.9.19 EnDat 2.2 words 24 and 25 -----------------------------------------------------
// Word 24: number of section-2 blocks (0 = no section 2). Word 25: maximum clock frequency in kHz
// (example 8 MHz = 8000 = 1F40h).
std::uint16_t encode_max_clock_frequency_khz(std::uint32_t khz);  // throws above 65535
std::string clock_frequency_string(std::uint16_t khz);           // "8 MHz", "500 kHz", "2.5 MHz"

// ---- 3.9.31 / 3.9.32 EnDat 2.2 words 44 and 45: touch probes ------------------------------------
// Word 44: the touch probe functions supported (the table of its bits is not in the text; kept
// as a raw word). Word 45 bits 15..13: the unit of the timestamp that gives the switching time:
// 000 not supported, 001 2 us, 010 1 us (example 4000h), 011 500 ns, 100 125 ns.
enum class TimestampUnit : std::uint8_t { NotSupported = 0, Us2 = 1, Us1 = 2, Ns500 = 3, Ns125 = 4 };
std::uint16_t encode_timestamp_unit(TimestampUnit unit);
TimestampUnit decode_timestamp_unit(std::uint16_t word);  // codes 5..7 decode as NotSupported
std::optional<std::chrono::nanoseconds> timestamp_unit_duration(TimestampUnit unit);
std::string timestamp_unit_string(TimestampUnit unit);    // "1 us", "not supported"

}  // namespace endatsim::protocol::parameters
