#include "endatsim/protocol/memory_area.hpp"
#include "endatsim/protocol/indexed_table.hpp"

#include <array>

namespace endatsim::protocol {
namespace {

using enum MemoryArea;

// Spec 2.4.1 / 2.4.2.1 MRS tables; protection bits from 3.4.3 (word 2).
constexpr std::array kAreas{
    MemoryAreaInfo{OperatingStatus, 0xB9, "Operating status", "operating_status", false, std::nullopt, kOperatingStatusWords},
    MemoryAreaInfo{Manufacturer1, 0xA1, "Parameters of the encoder manufacturer (words 4..15)", "manufacturer_1",
                   false, 0, 16},
    MemoryAreaInfo{Manufacturer2, 0xA3, "Parameters of the encoder manufacturer (words 16..31)", "manufacturer_2",
                   false, 0, 16},
    MemoryAreaInfo{Manufacturer3, 0xA5, "Parameters of the encoder manufacturer (words 32..47)", "manufacturer_3",
                   false, 0, 16},
    MemoryAreaInfo{OperatingParameters, 0xA7, "Operating parameters", "operating_parameters", false, 1, kOperatingParametersWords},
    MemoryAreaInfo{Oem1, 0xA9, "Parameters of the OEM, area 1", "oem_1", false, 2},
    MemoryAreaInfo{Oem2, 0xAB, "Parameters of the OEM, area 2", "oem_2", false, 2},
    MemoryAreaInfo{Oem3, 0xAD, "Parameters of the OEM, area 3", "oem_3", false, 2},
    MemoryAreaInfo{Oem4, 0xAF, "Parameters of the OEM, area 4", "oem_4", false, 2},
    MemoryAreaInfo{Compensation1, 0xB1, "Compensation values, area 1", "compensation_1", false, std::nullopt},
    MemoryAreaInfo{Compensation2, 0xB3, "Compensation values, area 2", "compensation_2", false, 5},
    MemoryAreaInfo{Compensation3, 0xB5, "Compensation values, area 3", "compensation_3", false, 4},
    MemoryAreaInfo{Compensation4, 0xB7, "Compensation values, area 4", "compensation_4", false, 3},
    MemoryAreaInfo{ManufacturerEndat22, 0xBD, "Parameters of the encoder manufacturer for EnDat 2.2",
                   "manufacturer_endat22", true, 0, kEndat22Words},
    MemoryAreaInfo{Section2, 0xBF, "Parameters of the section 2 memory area", "section2", true, std::nullopt},
    MemoryAreaInfo{OperatingParameters2, 0xBB, "Operating parameters 2", "operating_parameters2", true,
                   std::nullopt},
    MemoryAreaInfo{AsynchronousPosition, 0x60, "Asynchronous position value", "asynchronous_position", true,
                   std::nullopt},
};
static_assert(indexed_by(kAreas, &MemoryAreaInfo::area, MemoryArea::AsynchronousPosition),
              "kAreas: one row per memory area, in order");

}  // namespace

std::span<const MemoryAreaInfo> memory_areas() { return kAreas; }

std::uint16_t factory_write_protection() {
  std::uint16_t word2 = 0;
  for (const auto area : {Manufacturer1, Manufacturer2, Manufacturer3, ManufacturerEndat22, Compensation1, Compensation2,
                          Compensation3, Compensation4})
    if (const auto bit = info(area).protection_bit) word2 = static_cast<std::uint16_t>(word2 | 1U << *bit);
  return word2;
}

const MemoryAreaInfo& info(MemoryArea area) { return kAreas[static_cast<std::size_t>(area)]; }

std::optional<MemoryArea> memory_area_from_mrs(std::uint8_t mrs) {
  for (const auto& a : kAreas)
    if (a.mrs == mrs) return a.area;
  return std::nullopt;
}

std::optional<MemoryArea> memory_area_from_key(std::string_view key) {
  for (const auto& a : kAreas)
    if (a.key == key) return a.area;
  return std::nullopt;
}

}  // namespace endatsim::protocol
