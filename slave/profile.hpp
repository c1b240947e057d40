// Encoder profiles: a named memory image with the few encoder parameters it implies, as JSON
// (profiles/*.json; the format is described in profiles/README.md).
//
//   {
//     "name": "rotary_singleturn_25bit",
//     "description": "free text",
//     "version": "2.2",                     // command set: "2.1" or "2.2"
//     "kind": "singleturn",                 // "singleturn", "multiturn", "linear", "touch_probe" or "eib"
//     "position_bits": 25,                  // = word 13
//     "multiturn_bits": 0,
//     "memory": {                           // protocol::info(MemoryArea).key -> 16-bit words
//       "operating_status": ["0x0000", "0x0000", "0x0039", "0x0002"],
//       "manufacturer_1": [... 16 words, index = word number 0..15, 0..3 unused = 0 ...],
//       ...
//       "section2_blocks": [[... 256 words ...]]   // optional
//     }
//   }
//
// load_profile checks the format (errors name the file, the JSON path and what was expected)
// and the consistency of the image (check_profile); save_profile writes the same format, so
// that a loaded profile saves byte for byte as it was.
#pragma once

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "endatsim/input/json_input.hpp"
#include "endatsim/protocol/parameters.hpp"
#include "endatsim/slave/encoder.hpp"

namespace endatsim::slave {

class ProfileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct EncoderProfile {
  std::string name;
  std::string description;
  EndatVersion version = EndatVersion::V2_2;
  EncoderKind kind = EncoderKind::Singleturn;
  unsigned position_bits = protocol::encoder_default::kPositionBits;
  unsigned multiturn_bits = 0;
  MemoryImage memory;

  // Sets kind, version, position_bits, multiturn_bits and memory, and t_cal from word 39 when
  // the word gives a time (3.5.24).
  void apply(EncoderParams& p) const;
  // The 48 words of the encoder manufacturer (3.5.1) and the 64 of area BD (3.9.1, empty for 2.1).
  std::vector<std::uint16_t> manufacturer_words() const;
  std::vector<std::uint16_t> endat22_words() const;
};

bool operator==(const EncoderProfile& a, const EncoderProfile& b);

// One memory area's array of words in a file, read and checked as the file's kind needs (a
// profile: the area's exact size in hex words; a scenario: up to 256 words that replace the
// default image's). `area` is none for a block of section 2.
using AreaWordsReader = std::function<std::vector<std::uint16_t>(const input::Node& words, std::optional<MemoryArea> area)>;
// An object of memory area key (protocol::info(MemoryArea).key) -> array of words, and
// "section2_blocks", read into `image` (3.1); `words_text` says what a word is ("hex words").
void read_memory_areas(const input::Node& n, MemoryImage& image, std::string_view words_text, const AreaWordsReader& words);

EncoderProfile load_profile(const std::string& path);
EncoderProfile load_profile_text(const std::string& text, const std::string& file_name);
std::string profile_text(const EncoderProfile& profile);
void save_profile(const std::string& path, const EncoderProfile& profile);  // throws ProfileError

// What is inconsistent, each as "JSON path: expectation, got value"; empty when the image is
// consistent: sizes (as slave::Memory checks them), NVM check bits of words 8, 13, 14, 30 and
// 31, word 13 = position_bits, word 14 against kind, word 17 against multiturn_bits, words 20/21
// (or the A10 scaling) against the rotary resolution, word 37 against version, word 40, the
// signal period and equidistant reference marks of incremental encoders (A10, 3.5.10.2), the
// EnDat 2.2 area present exactly for 2.2, checksums of words 47 and BD 63. Kind "eib": the
// factory delivery state of 3.5.7 (word 14 type Fh; only words 9..12, 14, 24..29 and 47 saved).
std::vector<std::string> check_profile(const EncoderProfile& profile);

// For reports: (label, value) pairs decoded from the parameter words, e.g.
// {"ID number", "749144 01"}, {"t_cal (word 39)", "5 us"}.
std::vector<std::pair<std::string, std::string>> describe_profile(const EncoderProfile& profile);

// A consistent profile from its parameters; the words not named here are 0, the checksums are
// computed. Used to make the bundled profiles (tests/profile_test.cpp keeps them equal).
struct ProfileParameters {
  std::string name;
  std::string description;
  EndatVersion version = EndatVersion::V2_2;
  EncoderKind kind = EncoderKind::Singleturn;
  protocol::parameters::EncoderType type = protocol::parameters::EncoderType::Singleturn;
  unsigned position_bits = protocol::encoder_default::kPositionBits;
  unsigned multiturn_bits = 0;
  unsigned interface_version = image_default::kInterfaceVersion;  // word 8
  protocol::parameters::Partition oem[4];               // words 9, 10
  protocol::parameters::Partition compensation[4];      // words 11, 12
  std::uint32_t signal_period = 0;                      // words 15/16
  std::uint16_t reference_mark_increment = 0;           // word 18
  std::uint32_t measuring_steps = 0;                    // words 20/21 (0: 2^(position - multiturn bits) when rotary)
  std::int64_t datum_shift = 0;                         // stored value of words 22/23 and operating parameters 0..2
  protocol::parameters::IdNumber id;                    // words 24..26
  protocol::parameters::SerialNumber serial;            // words 27..29
  bool falling = false;                                 // word 30 (3.5.16)
  std::uint16_t max_speed = 0;                          // word 32
  std::uint16_t accuracy[2] = {0, 0};                   // words 33, 34
  std::uint16_t supported_errors = 0;                   // word 35
  std::uint16_t supported_warnings = 0;                 // word 36
  bool communication_command = false;                   // word 37
  protocol::parameters::CalculationTime t_cal;          // word 39
  std::string ordering_designation;                     // word 40, "" = 0000h
  // EnDat 2.2 area (version 2.2 only)
  std::vector<std::string_view> additional_data_1;      // BD word 0
  std::vector<std::string_view> additional_data_2;      // BD word 1
  std::uint16_t additional_functions = 0;               // BD word 2
  std::uint16_t supported_errors_2 = 0;                 // BD word 6
  std::uint32_t max_clock_khz = 0;                      // BD word 25
  std::uint16_t touch_probe_support = 0;                // BD word 44 (3.9.31)
  protocol::parameters::TimestampUnit timestamp_unit = protocol::parameters::TimestampUnit::NotSupported;  // BD word 45
  std::uint16_t write_protection = protocol::factory_write_protection();  // operating status word 2
  std::uint16_t function_initialization = kShortRecoveryTimeOff;  // operating status word 3
};
EncoderProfile build_profile(const ProfileParameters& p);

}  // namespace endatsim::slave
