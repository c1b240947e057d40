#include "endatsim/protocol/parameters.hpp"
#include "endatsim/protocol/indexed_table.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace endatsim::protocol::parameters {

namespace {
constexpr std::string_view kErrorBits[] = {"lighting",   "signal amplitude", "position", "overvoltage",
                                           "undervoltage", "overcurrent",     "battery"};
constexpr std::string_view kWarningBits[] = {"frequency collision", "temperature exceeded",
                                             "light-source control reserve", "battery charge",
                                             "reference point not reached", "cyclic mode",
                                             "limit position", "standby", "diagnostics"};
}  // namespace

std::span<const std::string_view> error_bit_names() { return kErrorBits; }
std::span<const std::string_view> warning_bit_names() { return kWarningBits; }

std::string bits_string(std::uint16_t word, std::span<const std::string_view> names) {
  std::string s;
  for (unsigned b = 0; b < 16; ++b) {
    if (((word >> b) & 1U) == 0) continue;
    s += (s.empty() ? "" : ", ") + (b < names.size() ? std::string(names[b]) : "bit " + std::to_string(b));
  }
  return s.empty() ? "none" : s;
}
namespace {

std::uint16_t u16(unsigned v) { return static_cast<std::uint16_t>(v); }

bool printable(char c) { return c >= 0x20 && c < 0x7F; }

void require_printable(char c, const char* what) {
  if (!printable(c) && c != '\0')
    throw std::invalid_argument(std::string(what) + " characters must be printable ASCII (appendix A6), got code " +
                                std::to_string(static_cast<unsigned char>(c)));
}

// 3.5.14 / 3.5.15: a blank or NUL character stands for "empty".
void append_char(std::string& s, char c) {
  if (c != ' ' && c != '\0') s += c;
}

constexpr std::array<std::string_view, 5> kAdditionalData1{"position_value_2", "test_values", "temperature_1",
                                                           "temperature_2", "additional_sensors"};
constexpr std::array<std::string_view, 8> kAdditionalData2{"commutation",
                                                           "acceleration",
                                                           "limit_position_signals",
                                                           "asynchronous_position_value",
                                                           "operating_status_error_sources",
                                                           "reserved_5",
                                                           "position_value_2",
                                                           "timestamp"};

std::uint16_t encode_names(std::span<const std::string_view> table, std::span<const std::string_view> names,
                           const char* word) {
  std::uint16_t w = 0;
  for (const auto name : names) {
    const auto it = std::find(table.begin(), table.end(), name);
    if (it == table.end()) {
      std::string known;
      for (const auto k : table) known += (known.empty() ? "" : ", ") + std::string(k);
      throw std::invalid_argument("unknown additional datum \"" + std::string(name) + "\" for " + word + " (one of " +
                                  known + ")");
    }
    w = u16(w | 1U << (it - table.begin()));
  }
  return w;
}

std::vector<std::string_view> decode_names(std::span<const std::string_view> table, std::uint16_t word) {
  std::vector<std::string_view> names;
  for (std::size_t bit = 0; bit < table.size(); ++bit)
    if ((word >> bit) & 1U) names.push_back(table[bit]);
  return names;
}

}  // namespace

// 3.5.4
std::uint16_t encode_version(unsigned version) {
  if (version > 0x7FFF) throw std::invalid_argument("word 8 (3.5.4): version must be 0 .. 32767");
  return u16(kNvmBit15 | version);
}
unsigned decode_version(std::uint16_t word) { return word & 0x7FFFU; }

// 3.5.5
std::optional<unsigned> partition_address(unsigned code) {
  switch (code) {
    case 0x0: return 0;
    case 0x1: return 31;
    case 0x2: return 63;
    case 0x3: return 64;
    case 0x4: return 127;
    case 0x5: return 255;
    default: return std::nullopt;
  }
}

std::optional<unsigned> partition_code(unsigned address) {
  for (unsigned code = 0; code <= 5; ++code)
    if (partition_address(code) == address) return code;
  return std::nullopt;
}

std::uint8_t encode_partition(const Partition& p) {
  if (!p) return 0xFF;
  const auto start = partition_code(p->start);
  const auto end = partition_code(p->end);
  if (!start || !end || p->start > p->end)
    throw std::invalid_argument("memory allocation (3.5.5): start and end must be 0, 31, 63, 64, 127 or 255 with "
                                "start <= end, got " +
                                std::to_string(p->start) + " .. " + std::to_string(p->end));
  return static_cast<std::uint8_t>(*end << 4 | *start);
}

Partition decode_partition(std::uint8_t byte) {
  const auto start = partition_address(byte & 0xFU);
  const auto end = partition_address(byte >> 4U);
  if (!start || !end) return std::nullopt;
  return AddressRange{*start, *end};
}

std::uint16_t encode_partition_word(const Partition& low_area, const Partition& high_area) {
  return u16(static_cast<unsigned>(encode_partition(high_area)) << 8 | encode_partition(low_area));
}

std::pair<Partition, Partition> decode_partition_word(std::uint16_t word) {
  return {decode_partition(static_cast<std::uint8_t>(word & 0xFF)), decode_partition(static_cast<std::uint8_t>(word >> 8))};
}

Partition partition_of(std::span<const std::uint16_t> manufacturer_words, MemoryArea a) {
  const auto at = partition_byte(a);
  if (!at || at->word >= manufacturer_words.size()) return std::nullopt;
  return decode_partition(static_cast<std::uint8_t>(manufacturer_words[at->word] >> at->shift));
}

void encode_partition_words(std::span<std::uint16_t> manufacturer_words, std::span<const Partition, 4> oem,
                            std::span<const Partition, 4> compensation) {
  manufacturer_words[word::kOemPartition] = encode_partition_word(oem[0], oem[1]);
  manufacturer_words[word::kOemPartition + 1] = encode_partition_word(oem[2], oem[3]);
  manufacturer_words[word::kCompensationPartition] = encode_partition_word(compensation[0], compensation[1]);
  manufacturer_words[word::kCompensationPartition + 1] = encode_partition_word(compensation[2], compensation[3]);
}

// 3.5.6
std::uint16_t encode_position_bits(unsigned bits) {
  if (bits < 1 || bits > kPositionBitsMask)
    throw std::invalid_argument("word 13 (3.5.6): clock pulses for the position value must be 1 .. 63, got " +
                                std::to_string(bits));
  return u16(kNvmBit15 | bits);
}
unsigned decode_position_bits(std::uint16_t word) { return word & kPositionBitsMask; }

// 3.5.7
std::uint16_t encode_encoder_type(EncoderType type) {
  return u16(static_cast<unsigned>(type) << 12 | kNvmBit0);
}
EncoderType decode_encoder_type(std::uint16_t word) { return static_cast<EncoderType>(word >> 12); }

std::string_view encoder_type_name(EncoderType type) {
  switch (type) {
    case EncoderType::IncrementalLinear: return "incremental linear encoder without distance-coded reference marks";
    case EncoderType::IncrementalLinearDistanceCoded:
      return "incremental linear encoder with distance-coded reference marks";
    case EncoderType::IncrementalLinearBattery:
      return "incremental linear encoder with battery buffer, without distance-coded reference marks";
    case EncoderType::IncrementalLinearBatteryDistanceCoded:
      return "incremental linear encoder with battery buffer, with distance-coded reference marks";
    case EncoderType::AbsoluteLinear: return "absolute linear encoder";
    case EncoderType::TouchProbe: return "touch probe (note D1 - D11)";
    case EncoderType::AbsoluteLinearCyclicCoding: return "absolute linear encoder with cyclic coding";
    case EncoderType::NoteD1D11: return "note D1 - D11";
    case EncoderType::IncrementalRotary:
      return "incremental rotary or angle encoder without distance-coded reference marks";
    case EncoderType::IncrementalRotaryDistanceCoded:
      return "incremental rotary or angle encoder with distance-coded reference marks";
    case EncoderType::IncrementalRotaryBattery:
      return "incremental rotary or angle encoder with battery buffer, without distance-coded reference marks";
    case EncoderType::IncrementalRotaryBatteryDistanceCoded:
      return "incremental rotary or angle encoder with battery buffer, with distance-coded reference marks";
    case EncoderType::Singleturn: return "singleturn rotary or angle encoder";
    case EncoderType::MultiturnBattery: return "multiturn rotary encoder with battery buffer";
    case EncoderType::MultiturnGears: return "multiturn rotary encoder with gears";
    case EncoderType::ExternalInterfaceBox: return "External Interface Box (EIB)";
  }
  return "unknown";
}

bool is_linear(EncoderType type) { return static_cast<unsigned>(type) < 8 && type != EncoderType::NoteD1D11; }

// 2.3.4.3 / 3.5.7: the incremental types and those of them with distance-coded reference marks.
namespace {
struct TypeMarks {
  EncoderType type;
  bool distance_coded;
};
constexpr TypeMarks kIncrementalTypes[] = {
    {EncoderType::IncrementalLinear, false},         {EncoderType::IncrementalLinearDistanceCoded, true},
    {EncoderType::IncrementalLinearBattery, false},  {EncoderType::IncrementalLinearBatteryDistanceCoded, true},
    {EncoderType::IncrementalRotary, false},         {EncoderType::IncrementalRotaryDistanceCoded, true},
    {EncoderType::IncrementalRotaryBattery, false},  {EncoderType::IncrementalRotaryBatteryDistanceCoded, true},
};
const TypeMarks* incremental_entry(EncoderType type) {
  for (const auto& t : kIncrementalTypes)
    if (t.type == type) return &t;
  return nullptr;
}
}  // namespace

bool is_incremental(EncoderType type) { return incremental_entry(type) != nullptr; }

ReferenceMarks reference_marks_of(EncoderType type, std::uint16_t word18) {
  const auto* t = incremental_entry(type);
  if (t == nullptr) return ReferenceMarks::None;
  if (t->distance_coded) return ReferenceMarks::DistanceCoded;
  return word18 != 0 ? ReferenceMarks::Equidistant : ReferenceMarks::One;
}

std::string_view reference_marks_name(ReferenceMarks marks) {
  switch (marks) {
    case ReferenceMarks::None: return "none (absolute)";
    case ReferenceMarks::One: return "one reference mark";
    case ReferenceMarks::DistanceCoded: return "distance-coded reference marks";
    case ReferenceMarks::Equidistant: return "equidistant reference marks";
  }
  return "none (absolute)";
}

// 3.5.9
std::uint16_t encode_revolutions(std::uint32_t revolutions) {
  return revolutions >= kRevolutionsSeeEndat22Word34 ? kRevolutionsSeeEndat22Word34 : u16(revolutions);
}

// 3.5.12
std::string measuring_step_string(EncoderType type, std::uint32_t value) {
  if (value == 0) return "0 (see EnDat 2.2 words 27 .. 29)";
  return std::to_string(value) + (is_linear(type) ? " nm" : " steps/rev");
}

// 3.5.13 / 3.6.2
std::array<std::uint16_t, 2> encode_datum_shift32(std::int64_t value) {
  if (value < INT32_MIN || value > INT32_MAX)
    throw std::invalid_argument("datum shift (3.5.13): two words hold -2^31 .. 2^31-1, got " + std::to_string(value));
  return split32(static_cast<std::uint32_t>(value));
}

std::int64_t decode_datum_shift32(std::uint16_t w0, std::uint16_t w1) {
  return static_cast<std::int32_t>(join32(w0, w1));
}

std::array<std::uint16_t, 3> encode_datum_shift48(std::int64_t value) {
  constexpr std::int64_t kLimit = std::int64_t{1} << 47;
  if (value < -kLimit || value >= kLimit)
    throw std::invalid_argument("datum shift (3.6.2): three words hold -2^47 .. 2^47-1, got " + std::to_string(value));
  const auto u = static_cast<std::uint64_t>(value);
  return {u16(u & 0xFFFF), u16((u >> 16) & 0xFFFF), u16((u >> 32) & 0xFFFF)};
}

std::int64_t decode_datum_shift48(std::uint16_t w0, std::uint16_t w1, std::uint16_t w2) {
  std::uint64_t u = static_cast<std::uint64_t>(w2) << 32 | join32(w0, w1);
  if (u & (std::uint64_t{1} << 47)) u |= 0xFFFF'0000'0000'0000ULL;  // sign-extend bit 47
  return static_cast<std::int64_t>(u);
}

std::int64_t angle_to_steps(double degrees, std::uint32_t steps_per_revolution) {
  return std::llround(degrees / 360.0 * static_cast<double>(steps_per_revolution));
}

std::int64_t endat_compliant_shift(std::int64_t steps, std::int64_t steps_per_signal_period) {
  if (steps_per_signal_period <= 0) throw std::invalid_argument("steps per signal period must be positive");
  const std::int64_t p = steps_per_signal_period;
  const std::int64_t sign = steps < 0 ? -1 : 1;
  const std::int64_t a = steps * sign;
  return sign * ((a + p / 2) / p * p);
}

// 3.5.14
std::array<std::uint16_t, 3> encode_id_number(const IdNumber& id) {
  require_printable(id.suffix[0], "ID number");
  require_printable(id.suffix[1], "ID number");
  const auto [low, high] = split32(id.number);
  return {u16(static_cast<unsigned char>(id.suffix[0]) << 8 | static_cast<unsigned char>(id.suffix[1])), low, high};
}

IdNumber decode_id_number(std::uint16_t w24, std::uint16_t w25, std::uint16_t w26) {
  IdNumber id;
  id.number = join32(w25, w26);
  id.suffix[0] = static_cast<char>(w24 >> 8);
  id.suffix[1] = static_cast<char>(w24 & 0xFF);
  return id;
}

std::string id_number_string(const IdNumber& id) {
  require_printable(id.suffix[0], "ID number");
  require_printable(id.suffix[1], "ID number");
  std::string digits = std::to_string(id.number);
  if (digits.size() < 6) digits.insert(0, 6 - digits.size(), '0');
  std::string suffix;
  append_char(suffix, id.suffix[0]);
  append_char(suffix, id.suffix[1]);
  return suffix.empty() ? digits : digits + " " + suffix;
}

IdNumber parse_id_number(std::string_view text) {
  const auto fail = [&] {
    throw std::invalid_argument("an ID number such as \"262144 A1\" or \"262144-A1\" (3.5.14), got \"" +
                                std::string(text) + "\"");
  };
  IdNumber id;
  std::size_t i = 0;
  std::uint64_t number = 0;
  unsigned digits = 0;
  // Digits, optionally grouped by single spaces ("262 144"), as long as a digit follows.
  while (i < text.size()) {
    if (text[i] >= '0' && text[i] <= '9') {
      number = number * 10 + static_cast<unsigned>(text[i] - '0');
      if (++digits > 10 || number > UINT32_MAX) fail();
      ++i;
    } else if (text[i] == ' ' && digits > 0 && i + 3 < text.size() && text[i + 1] >= '0' && text[i + 1] <= '9' &&
               text[i + 2] >= '0' && text[i + 2] <= '9' && text[i + 3] >= '0' && text[i + 3] <= '9' &&
               (i + 4 == text.size() || text[i + 4] == ' ' || text[i + 4] == '-')) {
      ++i;  // a thousands separator
    } else {
      break;
    }
  }
  if (digits == 0) fail();
  id.number = static_cast<std::uint32_t>(number);
  if (i == text.size()) return id;
  if (text[i] != ' ' && text[i] != '-') fail();
  const std::string_view rest = text.substr(i + 1);
  if (rest.size() != 2 || !printable(rest[0]) || !printable(rest[1])) fail();
  id.suffix[0] = rest[0];
  id.suffix[1] = rest[1];
  return id;
}

// 3.5.15
std::array<std::uint16_t, 3> encode_serial_number(const SerialNumber& s) {
  require_printable(s.prefix, "serial number");
  require_printable(s.suffix, "serial number");
  const std::uint32_t n = s.number;
  return {u16((n & 0xFF) << 8 | static_cast<unsigned char>(s.suffix)), u16((n >> 8) & 0xFFFF),
          u16(static_cast<unsigned>(static_cast<unsigned char>(s.prefix)) << 8 | (n >> 24))};
}

SerialNumber decode_serial_number(std::uint16_t w27, std::uint16_t w28, std::uint16_t w29) {
  SerialNumber s;
  s.suffix = static_cast<char>(w27 & 0xFF);
  s.prefix = static_cast<char>(w29 >> 8);
  s.number = static_cast<std::uint32_t>(w29 & 0xFF) << 24 | static_cast<std::uint32_t>(w28) << 8 | (w27 >> 8U);
  return s;
}

std::string serial_number_string(const SerialNumber& s) {
  require_printable(s.prefix, "serial number");
  require_printable(s.suffix, "serial number");
  std::string out;
  append_char(out, s.prefix);
  out += std::to_string(s.number);
  append_char(out, s.suffix);
  return out;
}

// 3.5.16
std::optional<std::uint32_t> decode_scaled_value(std::uint16_t word) {
  constexpr unsigned kScaleShift = 13, kLargestScale = 5;  // x32
  const unsigned scale = word >> kScaleShift;
  if (scale > kLargestScale) return std::nullopt;
  return static_cast<std::uint32_t>(word & ((1U << kScaleShift) - 1)) << scale;
}

std::uint16_t encode_direction(bool falling) { return u16(kNvmBit15 | (falling ? kDirectionFalling : 0U)); }
bool decode_direction_falling(std::uint16_t word) { return (word & kDirectionFalling) != 0; }

// 3.5.22
std::uint16_t encode_command_set(const CommandSet& c) {
  const auto pair = [](bool on, unsigned bit) { return on ? 1U << bit : 1U << (bit + 1); };
  return u16(pair(c.endat22, 0) | pair(c.safety, 2) | pair(c.communication_command, 4));
}

CommandSet decode_command_set(std::uint16_t word) {
  const auto on = [word](unsigned bit) { return ((word >> bit) & 3U) == 1U; };
  return {on(0), on(2), on(4)};
}

bool command_set_consistent(std::uint16_t word) {
  for (unsigned bit : {0U, 2U, 4U}) {
    const unsigned pair = (word >> bit) & 3U;
    if (pair != 1U && pair != 2U) return false;
  }
  return true;
}

std::string command_set_string(std::uint16_t word) {
  const CommandSet c = decode_command_set(word);
  std::string s = c.endat22 ? "2.2" : "2.1";
  if (c.safety) s += ", safety-relevant applications";
  if (c.communication_command) s += ", communication command";
  if (!command_set_consistent(word)) s += " (bit pairs not stored inversely)";
  return s;
}

// 3.4.4
namespace {
using F = EncoderFunction;
constexpr std::array<FunctionBits, 9> kFunctionBits{{
    {F::ShortRecoveryTime, "short recovery time I", kShortRecoveryTimeOn | kShortRecoveryTimeOff, kShortRecoveryTimeOn},
    {F::ReferencePulseInitialization, "reference pulse initialization", 0x000C, 0x0004},
    {F::Oversampling, "oversampling", 0x0030, 0x0010},
    {F::CyclicOperation, "EnDat 2.2 cyclic operation", 0x00C0, 0x0040},
    {F::MultiturnOverflowErrorMessage, "multiturn overflow error message", 0x0100, 0x0100},
    {F::MultiturnOverflowLatch, "multiturn overflow latch", 0x0200, 0x0200},
    {F::MultiturnErrorMessages, "multiturn error messages", 0x0400, 0x0400},
    {F::MultiturnCounterReset, "multiturn counter reset", 0x1800, 0x0800},
    {F::DiagnosticsReset, "diagnostics reset", 0x2000, 0x2000},
}};
static_assert(indexed_by(kFunctionBits, &FunctionBits::function, EncoderFunction::DiagnosticsReset),
              "kFunctionBits: one row per encoder function, in order");
}  // namespace

std::span<const FunctionBits> function_initialization_bits() { return kFunctionBits; }

bool function_activated(std::uint16_t word3, EncoderFunction f) {
  const auto& b = kFunctionBits[static_cast<std::size_t>(f)];
  return (word3 & b.mask) == b.activated;
}

std::uint16_t encode_function_initialization(std::span<const EncoderFunction> activated) {
  std::uint16_t w = 0;
  for (const auto& b : kFunctionBits) {
    const bool on = std::find(activated.begin(), activated.end(), b.function) != activated.end();
    w = u16(w | (on ? b.activated : b.mask & ~b.activated));
  }
  return w;
}

std::string function_initialization_string(std::uint16_t word3) {
  std::string s;
  for (const auto& b : kFunctionBits) {
    if (!function_activated(word3, b.function)) continue;
    if (!s.empty()) s += ", ";
    s += b.name;
  }
  return s.empty() ? "none activated" : s;
}

// 3.5.24
std::uint16_t encode_calculation_time(const CalculationTime& t) {
  if (t.value > 0x1FFF) throw std::invalid_argument("word 39 (3.5.24): the calculation time must be 0 .. 8191 units");
  if (static_cast<unsigned>(t.unit) > 4) throw std::invalid_argument("word 39 (3.5.24): unknown unit of time");
  return u16(static_cast<unsigned>(t.unit) << 13 | t.value);
}

CalculationTime decode_calculation_time(std::uint16_t word) {
  const unsigned unit = word >> 13U;
  return {unit > 4 ? TimeUnit::ToBeDetermined : static_cast<TimeUnit>(unit), u16(word & 0x1FFFU)};
}

CalculationTime calculation_time_from(std::chrono::nanoseconds t) {
  const auto n = t.count();
  if (n >= 0) {
    if (n % 1'000'000 == 0 && n / 1'000'000 <= 0x1FFF)
      return {TimeUnit::Milliseconds, u16(static_cast<unsigned>(n / 1'000'000))};
    if (n % 1'000 == 0 && n / 1'000 <= 0x1FFF) return {TimeUnit::Microseconds, u16(static_cast<unsigned>(n / 1'000))};
    if (n <= 0x1FFF) return {TimeUnit::Nanoseconds, u16(static_cast<unsigned>(n))};
  }
  throw std::invalid_argument("word 39 (3.5.24): " + std::to_string(n) +
                              " ns is not a whole number of 0 .. 8191 ns, us or ms");
}

std::optional<std::chrono::nanoseconds> calculation_time_duration(const CalculationTime& t) {
  switch (t.unit) {
    case TimeUnit::Nanoseconds: return std::chrono::nanoseconds(t.value);
    case TimeUnit::Microseconds: return std::chrono::microseconds(t.value);
    case TimeUnit::Milliseconds: return std::chrono::milliseconds(t.value);
    default: return std::nullopt;
  }
}

std::string calculation_time_string(const CalculationTime& t) {
  switch (t.unit) {
    case TimeUnit::Nanoseconds: return std::to_string(t.value) + " ns";
    case TimeUnit::Microseconds: return std::to_string(t.value) + " us";
    case TimeUnit::Milliseconds: return std::to_string(t.value) + " ms";
    case TimeUnit::NotSupported: return "not supported";
    case TimeUnit::ToBeDetermined: return "unit to be determined (" + std::to_string(t.value) + ")";
  }
  return "unknown";
}

// 3.5.25
namespace {
constexpr std::string_view kOrderingPrefix = "EnDat";  // the five characters word 40 does not store
bool graphic(char c) { return c > 0x20 && c < 0x7F; }  // a visible ASCII character
}

std::uint16_t encode_ordering_designation(std::string_view designation) {
  const std::size_t n = kOrderingPrefix.size();
  if (designation.size() != n + 2 || designation.substr(0, n) != kOrderingPrefix || !graphic(designation[n]) ||
      !graphic(designation[n + 1]))
    throw std::invalid_argument("word 40 (3.5.25): an ordering designation is \"EnDat\" and two characters, such as "
                                "\"EnDat22\", got \"" +
                                std::string(designation) + "\"");
  return u16(static_cast<unsigned char>(designation[n]) << 8 | static_cast<unsigned char>(designation[n + 1]));
}

bool ordering_designation_visible(std::uint16_t word) {
  return graphic(static_cast<char>(word >> 8)) && graphic(static_cast<char>(word & 0xFF));
}

bool ordering_designation_needs_endat22(std::uint16_t word) { return (word & 0xFF) == '2'; }

std::optional<std::string> decode_ordering_designation(std::uint16_t word) {
  if (word == 0) return std::nullopt;
  std::string s(kOrderingPrefix);
  s += static_cast<char>(word >> 8);
  s += static_cast<char>(word & 0xFF);
  return s;
}

// 3.5.26 / 3.9.37
std::uint16_t checksum(std::span<const std::uint16_t> words, unsigned first, unsigned last) {
  if (last >= words.size() || first > last) throw std::out_of_range("checksum: word range outside the area");
  unsigned sum = 0;
  for (unsigned i = first; i <= last; ++i) sum += words[i];
  return u16(sum & 0xFFFF);
}
std::uint16_t manufacturer_checksum(std::span<const std::uint16_t> words48) {
  return checksum(words48, kManufacturerChecksumFirstWord, word::kManufacturerChecksum - 1);
}
std::uint16_t endat22_checksum(std::span<const std::uint16_t> words64) { return checksum(words64, 0, word::kEndat22Checksum - 1); }

// 3.9.2 / 3.9.3
std::span<const std::string_view> additional_data_1_names() { return kAdditionalData1; }
std::span<const std::string_view> additional_data_2_names() { return kAdditionalData2; }
std::uint16_t encode_additional_data_1(std::span<const std::string_view> names) {
  return encode_names(kAdditionalData1, names, "EnDat 2.2 word 0");
}
std::uint16_t encode_additional_data_2(std::span<const std::string_view> names) {
  return encode_names(kAdditionalData2, names, "EnDat 2.2 word 1");
}
std::vector<std::string_view> decode_additional_data_1(std::uint16_t word) { return decode_names(kAdditionalData1, word); }
std::vector<std::string_view> decode_additional_data_2(std::uint16_t word) { return decode_names(kAdditionalData2, word); }

std::string additional_data_string(const std::vector<std::string_view>& names) {
  if (names.empty()) return "none";
  std::string s;
  for (const auto n : names) s += (s.empty() ? "" : ", ") + std::string(n);
  return s;
}

// 3.9.19
std::uint16_t encode_max_clock_frequency_khz(std::uint32_t khz) {
  if (khz > 0xFFFF) throw std::invalid_argument("EnDat 2.2 word 25 (3.9.19): at most 65535 kHz");
  return u16(khz);
}

std::string clock_frequency_string(std::uint16_t khz) {
  if (khz < 1000 || khz % 100 != 0) return std::to_string(khz) + " kHz";
  std::string s = std::to_string(khz / 1000);
  if (khz % 1000 != 0) s += "." + std::to_string(khz % 1000 / 100);
  return s + " MHz";
}

// 3.9.32
std::uint16_t encode_timestamp_unit(TimestampUnit unit) { return u16(static_cast<unsigned>(unit) << 13); }

TimestampUnit decode_timestamp_unit(std::uint16_t word) {
  const unsigned code = word >> 13U;
  return code <= 4 ? static_cast<TimestampUnit>(code) : TimestampUnit::NotSupported;
}

std::optional<std::chrono::nanoseconds> timestamp_unit_duration(TimestampUnit unit) {
  using std::chrono::nanoseconds;
  switch (unit) {
    case TimestampUnit::Us2: return nanoseconds(2000);
    case TimestampUnit::Us1: return nanoseconds(1000);
    case TimestampUnit::Ns500: return nanoseconds(500);
    case TimestampUnit::Ns125: return nanoseconds(125);
    case TimestampUnit::NotSupported: break;
  }
  return std::nullopt;
}

std::string timestamp_unit_string(TimestampUnit unit) {
  const auto d = timestamp_unit_duration(unit);
  if (!d) return "not supported";
  return d->count() >= 1000 ? std::to_string(d->count() / 1000) + " us" : std::to_string(d->count()) + " ns";
}

// 3.9.21 / 3.9.22 / A10
std::uint16_t encode_resolution_scaling(ResolutionScaling position, ResolutionScaling position2) {
  return u16(static_cast<unsigned>(position2) << 8 | static_cast<unsigned>(position));
}

ResolutionScaling decode_position_scaling(std::uint16_t word27) {
  const unsigned code = word27 & 0x7U;
  return code > 4 ? ResolutionScaling::NotSupported : static_cast<ResolutionScaling>(code);
}

namespace {
// A10: the subdivision values per grating period (EnDat 2.2 words 28/29), when word 27 says so.
std::optional<std::uint64_t> grating_subdivision(std::span<const std::uint16_t> words64) {
  if (words64.size() <= word::kResolution + 1 ||
      decode_position_scaling(words64[word::kResolutionScaling]) != ResolutionScaling::GratingSubdivision)
    return std::nullopt;
  const std::uint64_t values = join32(words64[word::kResolution], words64[word::kResolution + 1]);
  return values == 0 ? std::nullopt : std::optional{values};
}
std::uint32_t measuring_steps_of(std::span<const std::uint16_t> words48) {
  return decode_measuring_steps(words48[word::kMeasuringSteps], words48[word::kMeasuringSteps + 1]);
}
std::uint32_t signal_period_of(std::span<const std::uint16_t> words48) {
  return decode_signal_period(words48[word::kSignalPeriod], words48[word::kSignalPeriod + 1]);
}
}  // namespace

std::optional<std::uint64_t> steps_per_revolution(std::span<const std::uint16_t> words48,
                                                  std::span<const std::uint16_t> words64) {
  if (is_linear(decode_encoder_type(words48[word::kEncoderType]))) return std::nullopt;
  if (const std::uint64_t steps = measuring_steps_of(words48); steps != 0) return steps;
  const std::uint64_t periods = signal_period_of(words48);
  const auto subdivision = grating_subdivision(words64);
  if (periods == 0 || !subdivision) return std::nullopt;
  return periods * *subdivision;
}

std::optional<StepsPerUnit> steps_per_reference_unit(std::span<const std::uint16_t> words48,
                                                     std::span<const std::uint16_t> words64) {
  const std::uint64_t step_nm = measuring_steps_of(words48);
  const std::uint64_t period = signal_period_of(words48);  // nm or P/rev
  const auto subdivision = grating_subdivision(words64);
  if (is_linear(decode_encoder_type(words48[word::kEncoderType]))) {
    constexpr std::uint64_t kNmPerMm = 1'000'000;
    if (step_nm != 0) return StepsPerUnit{kNmPerMm, step_nm};
    if (period != 0 && subdivision) return StepsPerUnit{kNmPerMm * *subdivision, period};  // step = period / subdivision
    return std::nullopt;
  }
  if (period == 0) return std::nullopt;  // marks in signal periods need the signal period
  if (step_nm != 0) return StepsPerUnit{step_nm, period};  // steps/rev over periods/rev
  if (subdivision) return StepsPerUnit{*subdivision, 1};
  return std::nullopt;
}

}  // namespace endatsim::protocol::parameters
