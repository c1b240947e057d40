// How an incremental encoder gains absolute positions (2.3.4.3): the reference marks as data,
// derived from word 14 (one mark or distance-coded marks) and words 18/19 (equidistant marks,
// 3.5.10.2, 3.5.11), and the search for the crossing that sets RM.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "endatsim/sim/int128.hpp"
#include "endatsim/protocol/parameters.hpp"
#include "endatsim/slave/memory.hpp"

namespace endatsim::slave {

struct ReferenceScheme {
  protocol::parameters::ReferenceMarks marks = protocol::parameters::ReferenceMarks::None;
  // One, DistanceCoded: mark positions within the range (EncoderParams::reference_marks).
  std::vector<std::uint64_t> positions;
  unsigned crossings = 1;  // 2.3.4.3: two sequential marks with distance-coded marks
  // Equidistant: the first mark (word 19) and the distance (word 18), in measuring steps; the
  // marks repeat every `distance` up to the end of the range, in every range.
  std::uint64_t first = 0;
  std::uint64_t distance = 0;
  // 2.3.4.3 "Depending on the encoder, reference marks can be selected using the hardware":
  // the index of the selected mark; none: every mark references, the first one crossed is taken
  // as the first mark (EncoderParams::selected_reference_mark).
  std::optional<std::uint64_t> selected;
};

// From the active word 14 and words 15..21 (and BD 27..29 for the A10 scaling). Throws
// std::invalid_argument when words 18/19 give equidistant marks that the memory cannot convert
// into measuring steps, or whose first mark lies beyond the range.
ReferenceScheme reference_scheme(const Memory& memory, const std::vector<std::uint64_t>& mark_positions,
                                 std::optional<std::uint64_t> selected, unsigned position_bits);

// Moving from unwrapped position `from` to `to` (the model's motion is monotonic), is a
// reference mark crossed as the scheme needs it (marks in (min, max])? The answer is the
// number of measuring steps the absolute position lies below the measured one: 0, or with
// equidistant marks and no selection, the first mark crossed taken as the first mark.
std::optional<sim::Int128> find_reference(const ReferenceScheme& scheme, sim::Int128 from, sim::Int128 to, unsigned position_bits);

}  // namespace endatsim::slave
