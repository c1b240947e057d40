// Memory areas and their MRS codes (spec 2.4.1, 2.4.2.1, 2.4.2.3, 3.1, 3.2), as data.
#pragma once

#include <cstddef>

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace endatsim::protocol {

// Section 3: the memory areas for compensation values and for OEM parameters "must consist of a
// maximum of 960 words in total (1920 bytes)".
inline constexpr std::size_t kPartitionedWordsMax = 960;
// 2.4: an address is one byte, so no area holds more than 256 words; a section 2 block holds
// them all (3.2).
inline constexpr std::size_t kAreaWordsMax = 256;
// 2.4.2: a block address is one byte, so section 2 has at most 256 blocks (3.9.18 word 24).
inline constexpr std::size_t kSection2BlocksMax = 256;
// 3.4, 3.6, 3.9.1: the operating status holds words 0 .. 3, the operating parameters 0 .. 15,
// the EnDat 2.2 parameters of the encoder manufacturer 0 .. 63.
inline constexpr std::uint16_t kOperatingStatusWords = 4, kOperatingParametersWords = 16, kEndat22Words = 64;
// 3.10.1: operating parameters 2 assign words 0 .. 12 (I/O, touch probes, referencing, word 12
// preset by HEIDENHAIN) of up to 256; the model's default images hold words 0 .. 15.
inline constexpr std::uint16_t kOperatingParameters2DefaultWords = 16;

enum class MemoryArea : std::uint8_t {
  OperatingStatus,          // B9: words 0..3 (3.4)
  Manufacturer1,            // A1: words 4..15 of the encoder manufacturer's 48 words (3.5)
  Manufacturer2,            // A3: words 16..31
  Manufacturer3,            // A5: words 32..47
  OperatingParameters,      // A7: 16 words (3.6)
  Oem1,                     // A9 .. AF: parameters of the OEM, partitioned by words 9 and 10 (3.5.5)
  Oem2,
  Oem3,
  Oem4,
  Compensation1,            // B1 .. B7: compensation values, partitioned by words 11 and 12
  Compensation2,
  Compensation3,
  Compensation4,
  ManufacturerEndat22,      // BD: 64 words (3.9), selectable only with a 2.2 mode command
  Section2,                 // BF + block address: 256 words per block (3.2)
  OperatingParameters2,     // BB: 256 words, volatile (3.10)
  AsynchronousPosition,     // 60 + time delay as address (2.4.2.3)
};

// Bit of word 2 (write protection status, 3.4.3) that protects an area; none = never writable
// through its own protection bit.
struct MemoryAreaInfo {
  MemoryArea area;
  std::uint8_t mrs;
  std::string_view name;
  std::string_view key;
  bool endat22_only;                         // 2.4.2.1 / A2 cause 7: only with a 2.2 mode command
  std::optional<unsigned> protection_bit;   // word 2 bit (3.4.3)
  // The words it always holds (3.4: 4, 3.5 and 3.6: 16, 3.9: 64); 0: as words 9 .. 12 partition
  // it (3.5.5), per block (3.2) or up to kAreaWordsMax (operating parameters 2, 3.10).
  std::uint16_t fixed_words = 0;
};

std::span<const MemoryAreaInfo> memory_areas();
// 3.4.3: the section 2 memory area has a protection bit per block: bit 6 block 0, bit 7 block 1,
// bit 8 block 2, bit 9 blocks 3 .. n.
inline constexpr unsigned kProtectSection2Block0 = 6, kProtectSection2BlocksFrom3 = 9;
constexpr unsigned section2_protection_bit(unsigned block) {
  return block < kProtectSection2BlocksFrom3 - kProtectSection2Block0 ? kProtectSection2Block0 + block
                                                                      : kProtectSection2BlocksFrom3;
}
// 3.4.3: "The write protection for parameters of the encoder manufacturer and if applicable the
// write protection for compensation values are factory set to active and cannot be reset": word 2
// as an encoder leaves the factory, the protection bits of those areas.
std::uint16_t factory_write_protection();
const MemoryAreaInfo& info(MemoryArea area);
std::optional<MemoryArea> memory_area_from_mrs(std::uint8_t mrs);
std::optional<MemoryArea> memory_area_from_key(std::string_view key);
inline std::uint8_t mrs_of(MemoryArea area) { return info(area).mrs; }

// 3.5.1: the encoder manufacturer's 48 words lie 16 to an area, words 0..15 in A1 (of which 4..15
// are defined), 16..31 in A3, 32..47 in A5; the area of a word (its address there is
// word::manufacturer_address).
constexpr unsigned kManufacturerWords = 48, kManufacturerWordsPerArea = 16;
constexpr unsigned kFirstManufacturerWord = 4;  // 3.5.1 defines words 4 .. 47; A1's 0 .. 3 are unused
constexpr MemoryArea manufacturer_area(unsigned word) {
  return word < kManufacturerWordsPerArea       ? MemoryArea::Manufacturer1
         : word < 2 * kManufacturerWordsPerArea ? MemoryArea::Manufacturer2
                                                : MemoryArea::Manufacturer3;
}

// 2.4.2.1 / A2 cause 2: a 2.1 MRS code reads 101x xxx1; 010x xxxx and 011x xxxx are 2.2 codes
// (additional data selection, 2.4.2.2, and the asynchronous position, 2.4.2.3).
constexpr bool is_endat21_mrs_code(std::uint8_t mrs) { return (mrs & 0xE1) == 0xA1; }
constexpr bool is_endat22_mrs_code(std::uint8_t mrs) { return (mrs & 0xE0) == 0x40 || (mrs & 0xE0) == 0x60; }

// 2.4.2.2: MRS codes 0x40 + I select additional data 1 (I = 0..15), 0x50 + (I - 16) additional
// data 2 (I = 16..31); 0x4F and 0x5F stop sending.
constexpr bool selects_additional_data(std::uint8_t mrs) { return (mrs & 0xE0) == 0x40; }
constexpr std::uint8_t kStopAdditionalData1 = 0x4F;
constexpr std::uint8_t kStopAdditionalData2 = 0x5F;
// 2.4.2.1: a 2.2 "selection of memory area" names the area's block in its supplement; the model
// reads the block address from the parameter's low byte (docs/model-reference.md: a guess).
constexpr std::uint8_t block_address_of(std::uint16_t parameter) { return static_cast<std::uint8_t>(parameter); }
constexpr bool stops_additional_data(std::uint8_t mrs) { return mrs == kStopAdditionalData1 || mrs == kStopAdditionalData2; }

}  // namespace endatsim::protocol
