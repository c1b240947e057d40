#include "endatsim/slave/profile.hpp"

#include "endatsim/input/json_input.hpp"
#include "endatsim/input/parameter_input.hpp"
#include "endatsim/input/suggest.hpp"
#include "endatsim/slave/eib.hpp"
#include "endatsim/slave/reference.hpp"
#include "endatsim/sim/text.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace endatsim::slave {
namespace {

namespace pm = protocol::parameters;
using input::json;
using input::Node;
using Area = MemoryArea;

std::string word_string(std::uint16_t w) { return sim::hex_0x(w, 4); }

std::string kind_key(EncoderKind k) { return std::string(kEncoderKindNames[static_cast<std::size_t>(k)]); }

std::string version_key(EndatVersion v) { return std::string(kEndatVersionNames[static_cast<std::size_t>(v)]); }

// The profile's encoder keys are the scenario's rows (encoder_parameters()): one type, range and
// message for both.
const sim::Parameter<EncoderParams>& encoder_row(std::string_view key) {
  for (const auto& row : encoder_parameters())
    if (row.key == key) return row;
  throw std::logic_error("no encoder parameter row \"" + std::string(key) + "\"");
}

// 3.5.9 word 17 of a multiturn encoder with `multiturn_bits` bits of revolutions.
std::uint16_t revolutions_word(unsigned multiturn_bits) {
  return pm::encode_revolutions(1U << std::min(multiturn_bits, pm::kRevolutionBitsMax));
}

std::string area_path(Area a) { return "/memory/" + std::string(protocol::info(a).key); }

// The JSON path of word n of the encoder manufacturer (3.5.1: A1 words 0..15, A3 16..31, A5 32..47).
std::string manufacturer_path(unsigned n) {
  return area_path(protocol::manufacturer_area(n)) + "/" + std::to_string(word::manufacturer_address(n));
}

std::vector<std::uint16_t> as_words(const Node& n, std::size_t min, std::size_t max) {
  const std::string count = min == max ? std::to_string(min) : std::to_string(min) + " .. " + std::to_string(max);
  if (!n.raw().is_array() || n.raw().size() < min || n.raw().size() > max) n.fail("an array of " + count + " hex words");
  std::vector<std::uint16_t> w;
  for (std::size_t i = 0; i < n.raw().size(); ++i) w.push_back(n.item(i).as_hex_word());
  return w;
}

// How many words each area holds in the file: fixed ones, OEM and compensation areas as words
// 9..12 make them (slave::Memory checks those), operating parameters 2 up to 256.
std::pair<std::size_t, std::size_t> size_limits(Area a) {
  const std::size_t fixed = protocol::info(a).fixed_words;
  return fixed != 0 ? std::pair{fixed, fixed} : std::pair<std::size_t, std::size_t>{1, protocol::kAreaWordsMax};
}

// A profile's keys, in the order its file and messages give them; all but two are required.
const std::vector<std::string> kProfileKeys{"name", "description", "version", "kind", "position_bits", "multiturn_bits", "memory"};
bool optional_profile_key(const std::string& key) { return key == "description" || key == "multiturn_bits"; }

// "name, description, ... and memory" (`last` "and") or "... or memory".
std::string profile_keys_text(const std::string& last) {
  std::string text;
  for (std::size_t i = 0; i < kProfileKeys.size(); ++i)
    text += (i == 0 ? "" : i + 1 == kProfileKeys.size() ? " " + last + " " : ", ") + kProfileKeys[i];
  return text;
}

EncoderProfile read_profile(const json& root, const std::string& file) {
  const Node r(root, "", file);
  if (!root.is_object()) r.fail("a profile object with " + profile_keys_text("and"));
  for (const auto& [key, value] : root.items())
    if (std::find(kProfileKeys.begin(), kProfileKeys.end(), key) == kProfileKeys.end())
      Node(value, "/" + key, file).fail_raw("unknown key \"" + input::trimmed(key) + "\" (" + input::did_you_mean(key, kProfileKeys) +
                                            "expected " + profile_keys_text("or") + ")");
  for (const auto& key : kProfileKeys)
    if (!optional_profile_key(key) && !root.contains(key)) r.fail_raw("missing key \"" + key + "\"");
  EncoderProfile p;
  p.name = r.child("name").as_string();
  if (p.name.empty()) r.child("name").fail("a non-empty name");
  if (root.contains("description")) p.description = r.child("description").as_string();
  EncoderParams e;
  for (const char* key : {"version", "kind", "position_bits", "multiturn_bits"})
    if (root.contains(key)) input::read_parameter(r.child(key), encoder_row(key), e);
  p.version = e.version;
  p.kind = e.kind;
  p.position_bits = e.position_bits;
  p.multiturn_bits = e.multiturn_bits;
  if (p.multiturn_bits >= p.position_bits)
    r.child("multiturn_bits").fail("an integer 0 .. " + std::to_string(p.position_bits - 1) + " (fewer than position_bits)");

  const Node m = r.child("memory");
  read_memory_areas(m, p.memory, "hex words", [](const Node& words, std::optional<Area> area) {
    const auto [min, max] = area ? size_limits(*area) : std::pair{protocol::kAreaWordsMax, protocol::kAreaWordsMax};
    return as_words(words, min, max);
  });
  for (Area a : {Area::OperatingStatus, Area::Manufacturer1, Area::Manufacturer2, Area::Manufacturer3,
                 Area::OperatingParameters})
    if (!p.memory.areas.contains(a)) m.fail_raw("missing memory area \"" + std::string(protocol::info(a).key) + "\"");
  const auto problems = check_profile(p);
  if (!problems.empty()) throw ProfileError(file + ": at " + problems.front());
  return p;
}

void write_words(std::ostringstream& out, const std::vector<std::uint16_t>& w, const std::string& indent) {
  out << '[';
  if (w.size() <= 8) {
    for (std::size_t i = 0; i < w.size(); ++i) out << (i ? ", " : "") << '"' << word_string(w[i]) << '"';
    out << ']';
    return;
  }
  for (std::size_t i = 0; i < w.size(); ++i) {
    if (i % 8 == 0) out << (i ? ",\n" : "\n") << indent << "  ";
    else out << ", ";
    out << '"' << word_string(w[i]) << '"';
  }
  out << '\n' << indent << ']';
}

// A10 / 3.5.8: an incremental encoder states its signal period whatever its ordering
// designation; 3.5.10.2 / 3.5.11: equidistant marks in words 18/19 must convert into
// measuring steps and lie within the range.
void check_reference_marks(const EncoderProfile& p, const std::vector<std::uint16_t>& m, std::vector<std::string>& problems) {
  const auto type = pm::decode_encoder_type(m[word::kEncoderType]);
  if (!pm::is_incremental(type)) return;
  if (pm::decode_signal_period(m[word::kSignalPeriod], m[word::kSignalPeriod + 1]) == 0)
    problems.push_back(manufacturer_path(word::kSignalPeriod) + ": expected the signal period of an incremental encoder in words 15/16 "
                       "(3.5.8, appendix A10), got 0000h");
  if (pm::reference_marks_of(type, m[word::kReferenceMarkDistance]) != pm::ReferenceMarks::Equidistant) return;
  try {
    (void)reference_scheme(Memory(p.memory), {}, std::nullopt, p.position_bits);
  } catch (const std::invalid_argument& e) {
    problems.push_back(manufacturer_path(word::kReferenceMarkDistance) + ": " + e.what());
  }
}

}  // namespace

void read_memory_areas(const input::Node& n, MemoryImage& image, std::string_view words_text, const AreaWordsReader& words) {
  if (!n.raw().is_object()) n.fail("an object of memory area -> array of " + std::string(words_text));
  for (const auto& [key, value] : n.raw().items()) {
    const Node item = n.child(key);
    if (key == "section2_blocks") {
      if (!value.is_array() || value.size() > protocol::kSection2BlocksMax)
        item.fail("an array of at most " + std::to_string(protocol::kSection2BlocksMax) + " blocks of " +
                  std::to_string(protocol::kAreaWordsMax) + " " + std::string(words_text));
      image.section2_blocks.clear();
      for (std::size_t i = 0; i < value.size(); ++i) image.section2_blocks.push_back(words(item.item(i), std::nullopt));
      continue;
    }
    const auto area = protocol::memory_area_from_key(key);
    if (!area || *area == Area::Section2 || *area == Area::AsynchronousPosition)
      item.fail_raw("unknown memory area \"" + key +
                    "\" (expected operating_status, manufacturer_1 .. 3, operating_parameters, oem_1 .. 4, "
                    "compensation_1 .. 4, manufacturer_endat22, operating_parameters2 or section2_blocks)");
    image.areas[*area] = words(item, *area);
  }
}

void EncoderProfile::apply(EncoderParams& p) const {
  p.kind = kind;
  p.version = version;
  p.position_bits = position_bits;
  p.multiturn_bits = multiturn_bits;
  p.memory = memory;
  if (const auto t = pm::calculation_time_duration(pm::decode_calculation_time(manufacturer_words()[word::kCalculationTime]))) p.t_cal = *t;
}

std::vector<std::uint16_t> EncoderProfile::manufacturer_words() const {
  return slave::manufacturer_words(memory);
}

std::vector<std::uint16_t> EncoderProfile::endat22_words() const {
  const auto it = memory.areas.find(Area::ManufacturerEndat22);
  return it == memory.areas.end() ? std::vector<std::uint16_t>{} : it->second;
}

bool operator==(const EncoderProfile& a, const EncoderProfile& b) {
  return a.name == b.name && a.description == b.description && a.version == b.version && a.kind == b.kind &&
         a.position_bits == b.position_bits && a.multiturn_bits == b.multiturn_bits &&
         a.memory.areas == b.memory.areas && a.memory.section2_blocks == b.memory.section2_blocks;
}

std::vector<std::string> check_profile(const EncoderProfile& p) {
  std::vector<std::string> problems;
  const auto expect = [&](bool ok, const std::string& path, const std::string& expected, std::uint16_t got) {
    if (!ok) problems.push_back(path + ": expected " + expected + ", got " + sim::hex_h(got, 4));
  };
  try {
    const Memory memory(p.memory);
  } catch (const std::exception& e) {
    problems.push_back("/memory: " + std::string(e.what()));
    return problems;
  }
  const auto& a1 = p.memory.areas.at(Area::Manufacturer1);
  for (unsigned i = 0; i < protocol::kFirstManufacturerWord; ++i) expect(a1[i] == 0, area_path(Area::Manufacturer1) + "/" + std::to_string(i),
                                          "0 (words 0..3 of A1 are not used; 3.5.1 starts at word 4)", a1[i]);
  const auto m = p.manufacturer_words();
  // 3.5.5: an OEM or compensation area is in the image exactly when words 9..12 make it available.
  for (const Area a : pm::kPartitionedAreas)
    if (pm::partition_of(m, a) && !p.memory.areas.contains(a))
      problems.push_back("/memory: expected area " + std::string(protocol::info(a).key) + ", which word " +
                         std::to_string(pm::partition_byte(a)->word) + " makes available (3.5.5)");
  const auto type = pm::decode_encoder_type(m[word::kEncoderType]);
  const bool multiturn_type = type == pm::EncoderType::MultiturnBattery || type == pm::EncoderType::MultiturnGears;
  const bool probe_type = type == pm::EncoderType::TouchProbe;
  const bool eib_type = type == pm::EncoderType::ExternalInterfaceBox;
  const bool type_ok = p.kind == EncoderKind::Linear       ? pm::is_linear(type) && !probe_type
                       : p.kind == EncoderKind::Multiturn  ? multiturn_type
                       : p.kind == EncoderKind::TouchProbe ? probe_type
                       : p.kind == EncoderKind::Eib        ? eib_type
                                                           : !pm::is_linear(type) && !multiturn_type && !probe_type && !eib_type;
  expect(type_ok, manufacturer_path(word::kEncoderType), "an encoder type of kind " + kind_key(p.kind) + " (3.5.7)", m[word::kEncoderType]);
  expect((m[word::kEncoderType] & pm::kNvmBit0) != 0, manufacturer_path(word::kEncoderType), "bit 0 = 1 for NVM checking (3.5.7)", m[word::kEncoderType]);
  if (p.kind == EncoderKind::Eib) {
    // 3.5.7: in factory delivery state an EIB holds word 14, the memory size, ID and serial
    // number and (choice) their checksum; the other words are saved at initial commissioning.
    for (unsigned n = pm::kManufacturerChecksumFirstWord; n < word::kManufacturerChecksum; ++n)
      expect(n == word::kEncoderType || eib_factory_word(n) || m[n] == 0, manufacturer_path(n),
             "0 (an EIB in factory delivery state saves only words 9..12, 14, 24..29 and 47, 3.5.7)", m[n]);
  } else {
    for (unsigned n : {word::kVersion, word::kPositionFormat, word::kDirection, word::kCommissioningDiagnostics})
      expect((m[n] & pm::kNvmBit15) != 0, manufacturer_path(n), "bit 15 = 1 for NVM checking (3.5)", m[n]);
    expect(pm::decode_position_bits(m[word::kPositionFormat]) == p.position_bits, manufacturer_path(word::kPositionFormat),
           "position_bits " + std::to_string(p.position_bits) + " in bits 0..5 (3.5.6)", m[word::kPositionFormat]);
    const auto commands = pm::decode_command_set(m[word::kCommandSet]);
    expect(pm::command_set_consistent(m[word::kCommandSet]) && commands.endat22 == (p.version == EndatVersion::V2_2),
           manufacturer_path(word::kCommandSet), "bit pairs stored inversely, command set " + version_key(p.version) + " (3.5.22)",
           m[word::kCommandSet]);
    check_reference_marks(p, m, problems);
  }
  const std::uint16_t revolutions = p.kind == EncoderKind::Multiturn ? revolutions_word(p.multiturn_bits) : 0;
  expect(m[word::kDistinguishableRevolutions] == revolutions, manufacturer_path(word::kDistinguishableRevolutions),
         sim::hex_h(revolutions, 4) + " distinguishable revolutions (3.5.9)", m[word::kDistinguishableRevolutions]);
  if (p.kind != EncoderKind::Linear) {
    const std::uint64_t steps = pm::steps_per_revolution(m, p.endat22_words()).value_or(0);
    const std::uint64_t expected = std::uint64_t{1} << (p.position_bits - p.multiturn_bits);
    if (steps != 0 && steps != expected)
      problems.push_back(manufacturer_path(word::kMeasuringSteps) + ": expected " + std::to_string(expected) +
                         " measuring steps per revolution in words 20/21 (3.5.12), got " + std::to_string(steps));
  }
  if (const std::uint16_t d = m[word::kOrderingDesignation]; d != 0) {
    const bool needs22 = pm::ordering_designation_needs_endat22(d);
    expect(pm::ordering_designation_visible(d) && (!needs22 || p.version == EndatVersion::V2_2), manufacturer_path(word::kOrderingDesignation),
           "\"EnDat\" and two printable characters, x2 only with version 2.2 (3.5.25)", m[word::kOrderingDesignation]);
  }
  expect(pm::manufacturer_checksum(m) == m[word::kManufacturerChecksum], manufacturer_path(word::kManufacturerChecksum),
         sim::hex_h(pm::manufacturer_checksum(m), 4) + " = word " + std::to_string(pm::kManufacturerChecksumFirstWord) +
             " + ... + word " + std::to_string(word::kManufacturerChecksum - 1) + " (3.5.26)", m[word::kManufacturerChecksum]);
  const auto e = p.endat22_words();
  if (p.version == EndatVersion::V2_2 && e.empty())
    problems.push_back("/memory: expected area manufacturer_endat22 for version 2.2 (3.9)");
  if (p.version == EndatVersion::V2_1 && !e.empty())
    problems.push_back(area_path(Area::ManufacturerEndat22) + ": expected no EnDat 2.2 area for version 2.1 (3.9)");
  if (!e.empty())
    expect(pm::endat22_checksum(e) == e[word::kEndat22Checksum], area_path(Area::ManufacturerEndat22) + "/" + std::to_string(word::kEndat22Checksum),
           sim::hex_h(pm::endat22_checksum(e), 4) + " = word 0 + ... + word " + std::to_string(word::kEndat22Checksum - 1) +
               " (3.9.37)", e[word::kEndat22Checksum]);
  return problems;
}

std::vector<std::pair<std::string, std::string>> describe_profile(const EncoderProfile& p) {
  const auto m = p.manufacturer_words();
  const auto type = pm::decode_encoder_type(m[word::kEncoderType]);
  std::vector<std::pair<std::string, std::string>> d;
  d.emplace_back("encoder type (word 14)", std::string(pm::encoder_type_name(type)));
  d.emplace_back("position bits (word 13)", std::to_string(pm::decode_position_bits(m[word::kPositionFormat])));
  d.emplace_back("measuring step (words 20/21)", pm::measuring_step_string(type, pm::decode_measuring_steps(m[word::kMeasuringSteps], m[word::kMeasuringSteps + 1])));
  if (p.kind == EncoderKind::Multiturn) d.emplace_back("distinguishable revolutions (word 17)", std::to_string(m[word::kDistinguishableRevolutions]));
  if (pm::is_incremental(type)) {  // 2.3.4.3, 3.5.10, 3.5.11
    const auto marks = pm::reference_marks_of(type, m[word::kReferenceMarkDistance]);
    std::string text(pm::reference_marks_name(marks));
    const std::string unit = pm::is_linear(type) ? " mm" : " signal periods";
    if (marks == pm::ReferenceMarks::DistanceCoded) text += ", nominal increment " + std::to_string(m[word::kReferenceMarkDistance]) + unit;
    if (marks == pm::ReferenceMarks::Equidistant) text += " every " + std::to_string(m[word::kReferenceMarkDistance]) + unit;
    d.emplace_back("reference marks (words 14, 18)", text);
  }
  const unsigned id = word::kIdNumber, serial = word::kSerialNumber;
  d.emplace_back("ID number (words 24..26)", pm::id_number_string(pm::decode_id_number(m[id], m[id + 1], m[id + 2])));
  d.emplace_back("serial number (words 27..29)",
                 pm::serial_number_string(pm::decode_serial_number(m[serial], m[serial + 1], m[serial + 2])));
  d.emplace_back("command set (word 37)", pm::command_set_string(m[word::kCommandSet]));
  d.emplace_back("t_cal (word 39)", pm::calculation_time_string(pm::decode_calculation_time(m[word::kCalculationTime])));
  d.emplace_back("ordering designation (word 40)", pm::decode_ordering_designation(m[word::kOrderingDesignation]).value_or("not supported"));
  d.emplace_back("functions (operating status word 3)", pm::function_initialization_string(p.memory.areas.at(Area::OperatingStatus).at(word::kFunctionInitialization)));
  const auto e = p.endat22_words();
  if (!e.empty()) {
    d.emplace_back("additional data 1 (2.2 word 0)",
                   pm::additional_data_string(pm::decode_additional_data_1(e[word::kAdditionalData1Support])));
    d.emplace_back("additional data 2 (2.2 word 1)",
                   pm::additional_data_string(pm::decode_additional_data_2(e[word::kAdditionalData2Support])));
    d.emplace_back("maximum clock frequency (2.2 word 25)", pm::clock_frequency_string(e[word::kMaxClockFrequency]));
    if (p.kind == EncoderKind::TouchProbe)
      d.emplace_back("timestamp unit (2.2 word 45)", pm::timestamp_unit_string(pm::decode_timestamp_unit(e[word::kTimestampUnit])));
  }
  return d;
}

EncoderProfile load_profile_text(const std::string& text, const std::string& file_name) {
  try {
    return read_profile(input::parse(text, file_name), file_name);
  } catch (const input::InputError& e) {
    throw ProfileError(e.what());
  } catch (const json::exception& e) {
    throw ProfileError(file_name + ": " + e.what());
  }
}

EncoderProfile load_profile(const std::string& path) {
  std::string text;
  try {
    text = input::read_file(path, {"encoder profile", "an"});
  } catch (const input::InputError& e) {
    throw ProfileError(e.what());
  }
  return load_profile_text(text, path);
}

std::string profile_text(const EncoderProfile& p) {
  std::ostringstream out;
  out << "{\n";
  out << "  \"name\": " << json(p.name).dump() << ",\n";
  out << "  \"description\": " << json(p.description).dump() << ",\n";
  out << "  \"version\": \"" << version_key(p.version) << "\",\n";
  out << "  \"kind\": \"" << kind_key(p.kind) << "\",\n";
  out << "  \"position_bits\": " << p.position_bits << ",\n";
  out << "  \"multiturn_bits\": " << p.multiturn_bits << ",\n";
  out << "  \"memory\": {";
  bool first = true;
  for (const auto& [area, words] : p.memory.areas) {  // std::map: in the order of MemoryArea
    out << (first ? "\n" : ",\n") << "    \"" << protocol::info(area).key << "\": ";
    write_words(out, words, "    ");
    first = false;
  }
  if (!p.memory.section2_blocks.empty()) {
    out << (first ? "\n" : ",\n") << "    \"section2_blocks\": [";
    for (std::size_t b = 0; b < p.memory.section2_blocks.size(); ++b) {
      out << (b ? ",\n" : "\n") << "      ";
      write_words(out, p.memory.section2_blocks[b], "      ");
    }
    out << "\n    ]";
  }
  out << "\n  }\n}\n";
  return out.str();
}

void save_profile(const std::string& path, const EncoderProfile& profile) {
  const std::string text = profile_text(profile);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw ProfileError(path + ": cannot open the file for writing");
  out << text;
  out.close();
  if (!out) throw ProfileError(path + ": cannot write the file");
}

EncoderProfile build_profile(const ProfileParameters& p) {
  EncoderProfile profile;
  profile.name = p.name;
  profile.description = p.description;
  profile.version = p.version;
  profile.kind = p.kind;
  profile.position_bits = p.position_bits;
  profile.multiturn_bits = p.multiturn_bits;
  std::vector<std::uint16_t> m(protocol::kManufacturerWords, 0);
  m[word::kVersion] = pm::encode_version(p.interface_version);
  pm::encode_partition_words(m, p.oem, p.compensation);
  m[word::kPositionFormat] = pm::encode_position_bits(p.position_bits);
  m[word::kEncoderType] = pm::encode_encoder_type(p.type);
  const auto period = pm::encode_signal_period(p.signal_period);
  m[word::kSignalPeriod] = period[0];
  m[word::kSignalPeriod + 1] = period[1];
  if (p.kind == EncoderKind::Multiturn) m[word::kDistinguishableRevolutions] = revolutions_word(p.multiturn_bits);
  m[word::kReferenceMarkDistance] = p.reference_mark_increment;
  std::uint32_t steps = p.measuring_steps;
  // 2.3.4.4: a touch probe sends a trigger status, not measuring steps.
  if (steps == 0 && p.kind != EncoderKind::Linear && p.kind != EncoderKind::TouchProbe) steps = std::uint32_t{1} << (p.position_bits - p.multiturn_bits);
  const auto s = pm::encode_measuring_steps(steps);
  m[word::kMeasuringSteps] = s[0];
  m[word::kMeasuringSteps + 1] = s[1];
  const auto shift = pm::encode_datum_shift48(p.datum_shift);
  m[word::kManufacturerDatumShift] = shift[0];
  m[word::kManufacturerDatumShift + 1] = shift[1];
  const auto id = pm::encode_id_number(p.id);
  std::copy(id.begin(), id.end(), m.begin() + word::kIdNumber);
  const auto serial = pm::encode_serial_number(p.serial);
  std::copy(serial.begin(), serial.end(), m.begin() + word::kSerialNumber);
  m[word::kDirection] = pm::encode_direction(p.falling);
  m[word::kCommissioningDiagnostics] = pm::kNvmBit15;  // 3.5.17: external commissioning diagnostics not supported
  m[word::kMaxVelocity] = p.max_speed;
  m[word::kAccuracy] = p.accuracy[0];
  m[word::kAccuracy + 1] = p.accuracy[1];
  m[word::kSupportedErrors] = p.supported_errors;
  m[word::kSupportedWarnings] = p.supported_warnings;
  m[word::kCommandSet] = pm::encode_command_set({p.version == EndatVersion::V2_2, false, p.communication_command});
  m[word::kCalculationTime] = pm::encode_calculation_time(p.t_cal);
  m[word::kOrderingDesignation] = p.ordering_designation.empty() ? 0 : pm::encode_ordering_designation(p.ordering_designation);
  m[word::kManufacturerChecksum] = pm::manufacturer_checksum(m);
  auto& areas = profile.memory.areas;
  areas[Area::OperatingStatus] = {0, 0, p.write_protection, p.function_initialization};
  set_manufacturer_words(profile.memory, m);
  // 3.6.2: the factory setting of the operating parameters holds the manufacturer's datum shift.
  std::vector<std::uint16_t> op(protocol::kOperatingParametersWords, 0);
  op[word::kDatumShift] = shift[0];
  op[word::kDatumShift + 1] = shift[1];
  if (pm::datum_shift_has_48_bits(p.position_bits)) op[word::kDatumShift + 2] = shift[2];
  areas[Area::OperatingParameters] = op;
  add_partitioned_areas(profile.memory, m);
  if (p.version == EndatVersion::V2_2) {
    std::vector<std::uint16_t> e(protocol::kEndat22Words, 0);
    e[word::kAdditionalData1Support] = pm::encode_additional_data_1(p.additional_data_1);
    e[word::kAdditionalData2Support] = pm::encode_additional_data_2(p.additional_data_2);
    e[word::kAdditionalFunctionsSupport] = p.additional_functions;
    e[word::kErrorMessage2Support] = p.supported_errors_2;
    e[word::kMaxClockFrequency] = pm::encode_max_clock_frequency_khz(p.max_clock_khz);
    e[word::kTouchProbeSupport] = p.touch_probe_support;
    e[word::kTimestampUnit] = pm::encode_timestamp_unit(p.timestamp_unit);
    e[word::kEndat22Checksum] = pm::endat22_checksum(e);
    areas[Area::ManufacturerEndat22] = e;
    areas[Area::OperatingParameters2].assign(protocol::kOperatingParameters2DefaultWords, 0);
  }
  return profile;
}

}  // namespace endatsim::slave
