// The encoder's memory (spec section 3): words per memory area as the MRS codes address them,
// access rights, irreversible write protection (word 2), function initialisation (word 3) and
// what a reset activates.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "endatsim/protocol/protocol.hpp"
#include "endatsim/sim/time.hpp"

namespace endatsim::slave {

using protocol::ErrorCause;
using protocol::MemoryArea;

// Words of each area indexed by their address within the area. The encoder manufacturer's 48
// words are areas A1 (addresses 4..15 = words 4..15), A3 (words 16..31) and A5 (words 32..47);
// the operating status (B9) holds words 0..3. OEM and compensation areas are as large as
// words 9..12 make them (3.5.5); operating parameters 2 (BB) as large as the vector given.
struct MemoryImage {
  std::map<MemoryArea, std::vector<std::uint16_t>> areas;
  std::vector<std::vector<std::uint16_t>> section2_blocks;  // 256 words each (3.2)
};

// Word numbers (protocol/parameters.hpp).
namespace word = protocol::word;

// 3.4.4: word 3 bits that choose the short recovery time I for 2.2 mode commands.
using protocol::parameters::kShortRecoveryTimeOff;
using protocol::parameters::kShortRecoveryTimeOn;

// The encoder manufacturer's 48 words spread over areas A1, A3 and A5 of `image` (3.5.1).
void set_manufacturer_words(MemoryImage& image, const std::vector<std::uint16_t>& words48);
// ... and gathered again: words 0..3 and those of a missing or short area read 0.
std::vector<std::uint16_t> manufacturer_words(const MemoryImage& image);
// The OEM and compensation areas that the manufacturer's words 9..12 (`words48`) make available,
// each with as many words as its partition holds, all 0 (3.5.5).
void add_partitioned_areas(MemoryImage& image, const std::vector<std::uint16_t>& words48);

// What a memory area selection points at.
struct Selection {
  MemoryArea area = MemoryArea::OperatingStatus;
  std::uint8_t block = 0;  // section 2 block address; asynchronous position time delay
};

class Memory {
 public:
  // Throws std::invalid_argument naming the area and word when the image is inconsistent.
  explicit Memory(MemoryImage image);

  const MemoryImage& image() const { return image_; }
  // Encoder manufacturer words 4..47 by number (3.5.1).
  std::uint16_t manufacturer_word(unsigned n) const;
  std::uint16_t endat22_word(unsigned n) const;
  std::uint16_t operating_status(unsigned n) const { return image_.areas.at(MemoryArea::OperatingStatus).at(n); }
  std::uint16_t operating_parameter(unsigned n) const;
  // The instructions of word 5 (3.6.5) that take effect: those word 21 of the EnDat 2.2
  // manufacturer parameters (3.9.15) does not mark as not supported. Word 5 keeps what was written.
  std::uint16_t instructions() const;

  // 2.4.1 / 2.4.2.1 / 2.4.2.3 / A2 causes 2, 7, 11.
  std::optional<ErrorCause> check_selection(std::uint8_t mrs, std::uint8_t block, bool endat22_command) const;
  // A word read (true), or the A2 cause it is refused with (false).
  struct WordRead {
    std::uint16_t value = 0;
    std::optional<ErrorCause> error;
    explicit operator bool() const { return !error; }
  };
  WordRead read(const Selection& s, std::uint8_t address) const;
  // A2 causes 8, 9, 10, 12; words 0 and 1 can only be cleared as a whole, by 0000h that the next
  // "Encoder receive reset" carries out (3.4.1, 3.4.2).
  std::optional<ErrorCause> write(const Selection& s, std::uint8_t address, std::uint16_t value);
  std::optional<ErrorCause> check_write(const Selection& s, std::uint8_t address, std::uint16_t value) const;

  // Faults (scenario events): a word changed past the access rules, by an interrupted NVM write or a
  // corruption. Write protection bits already stored survive (3.4.3: irreversible). Throws
  // std::invalid_argument for a word the area does not hold.
  void force(const Selection& s, std::uint8_t address, std::uint16_t value);
  std::uint16_t word(const Selection& s, std::uint8_t address) const;  // any stored word; throws as force()
  // Error and warning sources set their bits in words 0 and 1; they stay until cleared.
  void latch_errors(std::uint16_t errors, std::uint16_t warnings);
  void clear_errors_and_warnings();  // 2.7.1: "Encoder send position values and receive error reset"
  // 2.7 / 3.4.3 / 3.4.4 / 3.6: "Encoder receive reset" (or power-on) activates word 2, word 3
  // and the operating parameters as written; operating parameters 2 return to their defaults.
  void activate_on_reset();
  // 3.5.7 / A2 cause 5: an EIB before initial commissioning. While open, the manufacturer areas
  // of slave/eib.hpp are writable except the words the box keeps (kEibFactoryWords).
  void set_initial_commissioning(bool open) { commissioning_ = open; }
  std::uint16_t active_function_initialization() const { return active_functions_; }
  // Whether word 3 as activated switches `f` on (3.4.4).
  bool function_activated(protocol::parameters::EncoderFunction f) const {
    return protocol::parameters::function_activated(active_functions_, f);
  }
  const std::vector<std::uint16_t>& active_operating_parameters() const { return active_operating_; }

 private:
  std::optional<std::pair<unsigned, unsigned>> address_range(const Selection& s) const;
  bool write_protected(const Selection& s) const;
  std::vector<std::uint16_t>* words(const Selection& s);
  const std::vector<std::uint16_t>* words(const Selection& s) const;

  MemoryImage image_;
  std::vector<std::uint16_t> operating_parameters2_defaults_;
  std::uint16_t active_protection_ = 0;
  std::uint16_t active_functions_ = 0;
  std::vector<std::uint16_t> active_operating_;
  bool commissioning_ = false;
  std::uint8_t clear_on_reset_ = 0;  // bit n: word n (0 errors, 1 warnings) written 0000h, cleared by the next reset
};

// The word the NVM is programming, for what a power interruption leaves of it (a fault the spec
// says nothing of; EncoderParams::interrupted_nvm_write chooses). Write protection bits already
// stored survive either way (3.4.3: irreversible): only the word being written changes.
class NvmProgramming {
 public:
  // A write of `value` to the word that will be programmed at `done_at`; a word that cannot be
  // read is not tracked.
  void begin(const Memory& memory, const Selection& s, std::uint8_t address, std::uint16_t value, sim::Time done_at);
  void applied() { if (write_) write_->applied = true; }  // the write reached the memory
  void discard() { write_.reset(); }                      // the access was discarded
  // The supply fails at `now`: a write whose time had come is programmed even if its frame had
  // not ended; one cut short keeps the old word, or with `torn` only its high byte is new.
  void interrupt(Memory& memory, sim::Time now, bool torn);

 private:
  struct Write {
    Selection selection;
    std::uint8_t address = 0;
    std::uint16_t old_value = 0, new_value = 0;
    sim::Time done_at{0};
    bool applied = false;
  };
  std::optional<Write> write_;
};

}  // namespace endatsim::slave
