#include "endatsim/slave/memory.hpp"

#include "endatsim/protocol/parameters.hpp"
#include "endatsim/slave/eib.hpp"

#include <stdexcept>
#include <string>
#include <utility>

namespace endatsim::slave {
namespace {

using Area = MemoryArea;

std::string area_key(Area a) { return std::string(protocol::info(a).key); }

std::size_t fixed_size(Area a) { return protocol::info(a).fixed_words; }

bool factory_protected(Area a) {
  switch (a) {
    case Area::Manufacturer1:
    case Area::Manufacturer2:
    case Area::Manufacturer3:
    case Area::ManufacturerEndat22:  // 3.4.3: "factory set to active and cannot be reset"
    case Area::Compensation1:        // 3: "available exclusively to the encoder manufacturer"
    case Area::Compensation2:
    case Area::Compensation3:
    case Area::Compensation4:
    case Area::AsynchronousPosition: return true;
    default: return false;
  }
}

}  // namespace

void set_manufacturer_words(MemoryImage& image, const std::vector<std::uint16_t>& words48) {
  if (words48.size() != protocol::kManufacturerWords) throw std::invalid_argument("the encoder manufacturer has 48 words (3.5.1)");
  for (unsigned first = 0; first < protocol::kManufacturerWords; first += protocol::kManufacturerWordsPerArea)
    image.areas[protocol::manufacturer_area(first)].assign(words48.begin() + first,
                                                           words48.begin() + first + protocol::kManufacturerWordsPerArea);
}

void add_partitioned_areas(MemoryImage& image, const std::vector<std::uint16_t>& words48) {
  for (const Area a : protocol::parameters::kPartitionedAreas)
    if (const auto range = protocol::parameters::partition_of(words48, a)) image.areas[a].assign(range->end + 1, 0);
}

std::vector<std::uint16_t> manufacturer_words(const MemoryImage& image) {
  std::vector<std::uint16_t> w(protocol::kManufacturerWords, 0);
  for (unsigned n = protocol::parameters::kManufacturerChecksumFirstWord; n < protocol::kManufacturerWords; ++n) {
    const auto it = image.areas.find(protocol::manufacturer_area(n));
    const unsigned address = word::manufacturer_address(n);
    if (it != image.areas.end() && address < it->second.size()) w[n] = it->second[address];
  }
  return w;
}

Memory::Memory(MemoryImage image) : image_(std::move(image)) {
  for (Area a : {Area::OperatingStatus, Area::Manufacturer1, Area::Manufacturer2, Area::Manufacturer3,
                 Area::OperatingParameters}) {
    const auto it = image_.areas.find(a);
    if (it == image_.areas.end() || it->second.size() != fixed_size(a))
      throw std::invalid_argument("memory area " + area_key(a) + " must have " + std::to_string(fixed_size(a)) +
                                  " words");
  }
  for (const auto& [a, w] : image_.areas) {
    if (fixed_size(a) != 0 && w.size() != fixed_size(a))
      throw std::invalid_argument("memory area " + area_key(a) + " must have " + std::to_string(fixed_size(a)) +
                                  " words, got " + std::to_string(w.size()));
    if (a == Area::OperatingParameters2 && (w.empty() || w.size() > protocol::kAreaWordsMax))
      throw std::invalid_argument("memory area operating_parameters2 must have 1 .. " + std::to_string(protocol::kAreaWordsMax) + " words");
    if (a == Area::Section2 || a == Area::AsynchronousPosition)
      throw std::invalid_argument("memory area " + area_key(a) + " is not given as words of its own");
    if (const auto p = protocol::parameters::partition_byte(a)) {
      const auto range = address_range({a, 0});
      if (!range) throw std::invalid_argument("memory area " + area_key(a) + " is not available per word " +
                                              std::to_string(p->word) + " (3.5.5)");
      if (w.size() != range->second + 1)
        throw std::invalid_argument("memory area " + area_key(a) + " must have " + std::to_string(range->second + 1) +
                                    " words (addresses up to " + std::to_string(range->second) + ", word " +
                                    std::to_string(p->word) + "), got " + std::to_string(w.size()));
    }
  }
  std::size_t partitioned = 0;
  for (Area a : protocol::parameters::kPartitionedAreas)
    if (const auto it = image_.areas.find(a); it != image_.areas.end()) partitioned += it->second.size();
  if (partitioned > protocol::kPartitionedWordsMax)
    throw std::invalid_argument("the OEM and compensation areas hold " + std::to_string(partitioned) +
                                " words; section 3 allows at most " + std::to_string(protocol::kPartitionedWordsMax) +
                                " in total (words 9 .. 12, 3.5.5)");
  for (Area a : protocol::parameters::kPartitionedAreas)
    if (address_range({a, 0}) && !image_.areas.contains(a))
      throw std::invalid_argument("memory area " + area_key(a) + " is available per word " +
                                  std::to_string(protocol::parameters::partition_byte(a)->word) + " (3.5.5) but has no words");
  const unsigned blocks = image_.areas.contains(Area::ManufacturerEndat22) ? endat22_word(word::kSection2Blocks) : 0;
  if (image_.section2_blocks.size() != blocks)
    throw std::invalid_argument("section 2 memory has " + std::to_string(image_.section2_blocks.size()) +
                                " blocks, but word 24 of the EnDat 2.2 manufacturer area says " + std::to_string(blocks));
  for (const auto& b : image_.section2_blocks)
    if (b.size() != protocol::kAreaWordsMax)
      throw std::invalid_argument("every section 2 block must have " + std::to_string(protocol::kAreaWordsMax) + " words (3.2)");
  if (const auto it = image_.areas.find(Area::OperatingParameters2); it != image_.areas.end())
    operating_parameters2_defaults_ = it->second;
  activate_on_reset();
}

std::uint16_t Memory::manufacturer_word(unsigned n) const {
  if (n < protocol::kFirstManufacturerWord || n >= protocol::kManufacturerWords)
    throw std::out_of_range("encoder manufacturer words are " + std::to_string(protocol::kFirstManufacturerWord) + " .. " +
                            std::to_string(protocol::kManufacturerWords - 1));
  return image_.areas.at(protocol::manufacturer_area(n)).at(word::manufacturer_address(n));
}

std::uint16_t Memory::endat22_word(unsigned n) const {
  const auto it = image_.areas.find(Area::ManufacturerEndat22);
  return it == image_.areas.end() ? 0 : it->second.at(n);
}

std::uint16_t Memory::instructions() const {
  const auto unsupported = endat22_word(word::kInstructionSupport);
  return operating_parameter(word::kInstructions) & protocol::parameters::kInstructionBits & ~unsupported;
}

std::uint16_t Memory::operating_parameter(unsigned n) const {
  return image_.areas.at(Area::OperatingParameters).at(n);
}

std::optional<std::pair<unsigned, unsigned>> Memory::address_range(const Selection& s) const {
  if (const auto p = protocol::parameters::partition_byte(s.area)) {
    const auto range = protocol::parameters::decode_partition(static_cast<std::uint8_t>(manufacturer_word(p->word) >> p->shift));
    if (!range || range->start > range->end) return std::nullopt;
    return std::pair{range->start, range->end};
  }
  switch (s.area) {
    case Area::OperatingStatus: return std::pair{0U, unsigned{protocol::kOperatingStatusWords} - 1};
    case Area::Manufacturer1:  // 2.4.1: address area 04h .. 0Fh
      return std::pair{protocol::kFirstManufacturerWord, protocol::kManufacturerWordsPerArea - 1};
    case Area::Section2:
      if (s.block >= image_.section2_blocks.size()) return std::nullopt;
      return std::pair{0U, static_cast<unsigned>(protocol::kAreaWordsMax - 1)};
    case Area::AsynchronousPosition: return std::nullopt;  // selects a time delay, holds no words
    default: {
      const auto* w = words(s);
      if (w == nullptr) return std::nullopt;
      return std::pair{0U, static_cast<unsigned>(w->size() - 1)};
    }
  }
}

std::vector<std::uint16_t>* Memory::words(const Selection& s) {
  return const_cast<std::vector<std::uint16_t>*>(std::as_const(*this).words(s));
}

const std::vector<std::uint16_t>* Memory::words(const Selection& s) const {
  if (s.area == Area::Section2)
    return s.block < image_.section2_blocks.size() ? &image_.section2_blocks[s.block] : nullptr;
  const auto it = image_.areas.find(s.area);
  return it == image_.areas.end() ? nullptr : &it->second;
}

std::optional<ErrorCause> Memory::check_selection(std::uint8_t mrs, std::uint8_t block, bool endat22_command) const {
  // A2 cause 2: a 2.1 MRS code must read 101x xxx1; 010x xxxx and 011x xxxx only with 2.2.
  if (!protocol::is_endat21_mrs_code(mrs) && !(endat22_command && protocol::is_endat22_mrs_code(mrs)))
    return ErrorCause::MrsFrameDisrupted;
  const auto area = protocol::memory_area_from_mrs(mrs);
  if (!area) return ErrorCause::ImpermissibleMemoryArea;
  if (protocol::info(*area).endat22_only && !endat22_command) return ErrorCause::ImpermissibleMemoryArea;
  if (*area == Area::Section2) {
    if (image_.section2_blocks.empty()) return ErrorCause::ImpermissibleMemoryArea;
    if (block >= image_.section2_blocks.size()) return ErrorCause::ImpermissibleBlockAddress;
    return std::nullopt;
  }
  if (*area == Area::AsynchronousPosition)
    return image_.areas.contains(Area::ManufacturerEndat22) &&
                   (endat22_word(word::kAdditionalData2Support) & protocol::parameters::kSupportsAsynchronousPosition) != 0
               ? std::nullopt
               : std::optional{ErrorCause::ImpermissibleMemoryArea};
  if (!address_range({*area, 0})) return ErrorCause::ImpermissibleMemoryArea;
  return std::nullopt;
}

Memory::WordRead Memory::read(const Selection& s, std::uint8_t address) const {
  const auto range = address_range(s);
  // Words 9 .. 12 declare the partitioned areas (3.5.5); a corrupted one may declare more than is
  // stored. What is not stored is not available either.
  const auto* stored = words(s);
  if (!range || address < range->first || address > range->second || stored == nullptr || address >= stored->size())
    return {.value = 0, .error = s.area == Area::OperatingParameters2 ? ErrorCause::UnknownCommunicationAddress
                                                                      : ErrorCause::ImpermissibleAddress};
  return {.value = (*stored)[address], .error = std::nullopt};
}

bool Memory::write_protected(const Selection& s) const {
  if (factory_protected(s.area)) return true;
  const auto bit = protocol::info(s.area).protection_bit;
  if (s.area == Area::Section2) {
    return ((active_protection_ >> protocol::section2_protection_bit(s.block)) & 1U) != 0;
  }
  return bit && ((active_protection_ >> *bit) & 1U) != 0;
}

std::optional<ErrorCause> Memory::write(const Selection& s, std::uint8_t address, std::uint16_t value) {
  if (const auto e = check_write(s, address, value)) return e;
  // 3.4.1 / 3.4.2: errors and warnings are deleted by writing 0000h to word 0 (1) "and sending the
  // mode command Encoder receive reset": the write is accepted, the word clears with the reset.
  if (s.area == Area::OperatingStatus && (address == word::kErrors || address == word::kWarnings)) {
    clear_on_reset_ |= static_cast<std::uint8_t>(1U << address);
    return std::nullopt;
  }
  words(s)->at(address) = value;
  return std::nullopt;
}

std::optional<ErrorCause> Memory::check_write(const Selection& s, std::uint8_t address, std::uint16_t value) const {
  if (const auto word = read(s, address); !word) return word.error;
  if (commissioning_ && eib_commissioning_area(s.area)) {
    // 3.5.7: "other parameters must be saved during initial commissioning".
    const bool factory = s.area != Area::ManufacturerEndat22 && eib_factory_word(word::manufacturer_word(s.area, address));
    return factory ? std::optional{ErrorCause::WriteProtected} : std::nullopt;
  }
  if (write_protected(s)) return ErrorCause::WriteProtected;
  if (s.area == Area::OperatingStatus) {
    if ((address == word::kErrors || address == word::kWarnings) && value != 0) return ErrorCause::ImpermissibleAddress;
    if (address == word::kWriteProtection && (active_protection_ & ~value) != 0)
      return ErrorCause::WriteProtectionCleared;
  }
  return std::nullopt;
}

std::uint16_t Memory::word(const Selection& s, std::uint8_t address) const {
  const auto* w = words(s);
  if (w == nullptr || address >= w->size())
    throw std::invalid_argument("memory area " + std::string(protocol::info(s.area).key) + " holds no word at address " +
                                std::to_string(address));
  return (*w)[address];
}

void Memory::force(const Selection& s, std::uint8_t address, std::uint16_t value) {
  (void)word(s, address);
  auto* w = words(s);
  if (s.area == Area::OperatingStatus && address == word::kWriteProtection) value |= (*w)[address];
  (*w)[address] = value;
}

void Memory::latch_errors(std::uint16_t errors, std::uint16_t warnings) {
  auto& status = image_.areas.at(Area::OperatingStatus);
  status[word::kErrors] |= errors;
  status[word::kWarnings] |= warnings;
}

void Memory::clear_errors_and_warnings() {
  auto& status = image_.areas.at(Area::OperatingStatus);
  status[word::kErrors] = 0;
  status[word::kWarnings] = 0;
}

void Memory::activate_on_reset() {
  auto& status = image_.areas.at(Area::OperatingStatus);
  for (const unsigned w : {word::kErrors, word::kWarnings})
    if ((clear_on_reset_ >> w) & 1U) status[w] = 0;
  clear_on_reset_ = 0;
  active_protection_ = status[word::kWriteProtection];
  active_functions_ = status[word::kFunctionInitialization];
  active_operating_ = image_.areas.at(Area::OperatingParameters);
  if (!operating_parameters2_defaults_.empty())
    image_.areas[Area::OperatingParameters2] = operating_parameters2_defaults_;
}

void NvmProgramming::begin(const Memory& memory, const Selection& s, std::uint8_t address, std::uint16_t value,
                           sim::Time done_at) {
  const auto old = memory.read(s, address);
  if (!old) return;
  write_ = Write{s, address, old.value, value, done_at, false};
}

void NvmProgramming::interrupt(Memory& memory, sim::Time now, bool torn) {
  if (!write_) return;
  const Write w = *write_;
  write_.reset();
  if (now >= w.done_at) {
    if (!w.applied) memory.force(w.selection, w.address, w.new_value);
    return;
  }
  // A torn word (encoder.interrupted_nvm_write "torn", 3.4.3): the high byte new, the low byte old.
  constexpr std::uint16_t kHighByte = 0xFF00;
  memory.force(w.selection, w.address,
               torn ? static_cast<std::uint16_t>((w.new_value & kHighByte) | (w.old_value & ~kHighByte)) : w.old_value);
}

}  // namespace endatsim::slave
