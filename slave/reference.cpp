#include "endatsim/slave/reference.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace endatsim::slave {
namespace {

namespace pm = protocol::parameters;
using pm::ReferenceMarks;

using sim::floor_div;

// Marks at m + k * range crossed in (lo, hi].
__int128 crossings_of(std::uint64_t m, __int128 lo, __int128 hi, __int128 range) {
  const auto mark = static_cast<__int128>(m);
  return floor_div(hi - mark, range) - floor_div(lo - mark, range);
}

std::vector<std::uint16_t> manufacturer_words(const Memory& memory) { return slave::manufacturer_words(memory.image()); }

std::vector<std::uint16_t> endat22_words(const Memory& memory) {
  const auto it = memory.image().areas.find(MemoryArea::ManufacturerEndat22);
  return it == memory.image().areas.end() ? std::vector<std::uint16_t>{} : it->second;
}

std::uint64_t in_steps(std::uint64_t value, const pm::StepsPerUnit& scale) {
  return (value * scale.steps + scale.per / 2) / scale.per;  // to the nearest measuring step
}

// Equidistant marks: first + k * distance below the range, k = 0 .. count - 1.
std::uint64_t marks_per_range(const ReferenceScheme& s, __int128 range) {
  return static_cast<std::uint64_t>((range - 1 - static_cast<__int128>(s.first)) / s.distance) + 1;
}

// The first equidistant mark crossed from `from` towards `to`, as (unwrapped position, index k).
std::optional<std::pair<__int128, std::uint64_t>> first_equidistant_mark(const ReferenceScheme& s, __int128 from,
                                                                         __int128 to, __int128 range) {
  const std::uint64_t count = marks_per_range(s, range);
  const __int128 base = floor_div(from - static_cast<__int128>(s.first), range) * range + s.first;
  const auto within = static_cast<std::uint64_t>(from - base);  // 0 .. range - 1 beyond the range's first mark
  std::uint64_t k = within / s.distance;
  __int128 mark = 0;
  if (to > from) {  // the lowest mark above `from`
    ++k;
    mark = k < count ? base + static_cast<__int128>(k * s.distance) : base + range;
    if (k >= count) k = 0;
    if (mark > to) return std::nullopt;
  } else {  // the highest mark at or below `from`
    k = std::min(k, count - 1);
    mark = base + static_cast<__int128>(k * s.distance);
    if (mark <= to) return std::nullopt;
  }
  return std::pair{mark, k};
}

}  // namespace

ReferenceScheme reference_scheme(const Memory& memory, const std::vector<std::uint64_t>& mark_positions,
                                 std::optional<std::uint64_t> selected, unsigned position_bits) {
  const auto m = manufacturer_words(memory);
  ReferenceScheme s;
  s.marks = pm::reference_marks_of(pm::decode_encoder_type(m[word::kEncoderType]), m[word::kReferenceMarkDistance]);
  s.selected = selected;
  switch (s.marks) {
    case ReferenceMarks::None: return s;
    case ReferenceMarks::One:
    case ReferenceMarks::DistanceCoded:
      s.positions = mark_positions;
      s.crossings = s.marks == ReferenceMarks::DistanceCoded ? 2 : 1;
      return s;
    case ReferenceMarks::Equidistant: break;
  }
  const auto scale = pm::steps_per_reference_unit(m, endat22_words(memory));
  if (!scale)
    throw std::invalid_argument("equidistant reference marks (word 18 = " + std::to_string(m[word::kReferenceMarkDistance]) +
                                ") need the measuring step: words 20/21, or the signal period (words 15/16) and the "
                                "subdivision of EnDat 2.2 words 27..29 (3.5.12, A10)");
  // 3.5.11: word 19 is given for linear encoders only; rotary ones count from position 0.
  const bool linear = pm::is_linear(pm::decode_encoder_type(m[word::kEncoderType]));
  s.distance = std::max<std::uint64_t>(1, in_steps(m[word::kReferenceMarkDistance], *scale));
  s.first = linear ? in_steps(m[word::kFirstReferenceMark], *scale) : 0;
  const __int128 range = __int128{1} << position_bits;
  if (static_cast<__int128>(s.first) >= range)
    throw std::invalid_argument("the first reference mark (word 19 = " + std::to_string(m[word::kFirstReferenceMark]) + " mm, " +
                                std::to_string(s.first) + " steps) lies beyond the " + std::to_string(position_bits) +
                                "-bit range (3.5.11)");
  if (selected && *selected >= marks_per_range(s, range))
    throw std::invalid_argument("selected_reference_mark " + std::to_string(*selected) + " does not exist: " +
                                std::to_string(marks_per_range(s, range)) + " equidistant marks in the range");
  return s;
}

std::optional<__int128> find_reference(const ReferenceScheme& s, __int128 from, __int128 to, unsigned position_bits) {
  const __int128 range = __int128{1} << position_bits;
  const __int128 lo = std::min(from, to), hi = std::max(from, to);
  switch (s.marks) {
    case ReferenceMarks::None: return 0;
    case ReferenceMarks::One:
    case ReferenceMarks::DistanceCoded: {
      __int128 crossed = 0;
      for (std::uint64_t m : s.positions) crossed += crossings_of(m, lo, hi, range);
      return crossed >= s.crossings ? std::optional<__int128>{0} : std::nullopt;
    }
    case ReferenceMarks::Equidistant: break;
  }
  if (s.selected)  // only the selected mark counts; it sits where it is: no offset
    return crossings_of(s.first + *s.selected * s.distance, lo, hi, range) > 0 ? std::optional<__int128>{0}
                                                                                 : std::nullopt;
  const auto mark = first_equidistant_mark(s, from, to, range);
  if (!mark) return std::nullopt;
  return static_cast<__int128>(mark->second * s.distance);
}

}  // namespace endatsim::slave
