// The worst case of each row of the timing table in a run: the measured value that came closest
// to its limit, or went furthest past it, with that limit and the margin between them. The
// conformance table shows it for every judged row, also when every occasion passed, so that a
// master that passes by 1 ns is told apart from one that passes by 1 us.
//
// Rows are judged on every frame and every clock phase, so noting is cheap: numbers only, text
// is made when the table is.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "endatsim/checker/decision.hpp"

namespace endatsim::checker {

enum class Unit : std::uint8_t { Duration, Frequency, Count };

// Whose limit: the spec's (for rows with an envelope, what any compliant encoder may do), or
// the declared encoder's.
enum class LimitOf : std::uint8_t { Spec, ThisEncoder };
inline constexpr std::size_t kLimitsOf = static_cast<std::size_t>(LimitOf::ThisEncoder) + 1;
std::string_view to_string(LimitOf of);

struct WorstCase {
  LimitOf of = LimitOf::Spec;
  std::string measured;  // "980 ns"
  std::string limit;     // ">= 1 us"
  std::string margin;    // "-20 ns": negative outside the limit
  bool inside = true;
};

class RowMargins {
 public:
  explicit RowMargins(std::size_t rows) : worst_(rows) {}

  // A time judged against its limit.
  void note(std::size_t row, const Judgement& j, LimitOf of = LimitOf::Spec) {
    note(row, j.measured.count(), j.limit.count(), j.bound, Unit::Duration, of);
  }
  // A frequency in hertz or a count of clocks against its limit.
  void note(std::size_t row, std::int64_t measured, std::int64_t limit, Bound bound, Unit unit,
            LimitOf of = LimitOf::Spec);

  // The spec's worst case first, then this encoder's; empty when the row noted nothing.
  std::vector<WorstCase> worst(std::size_t row) const;

 private:
  struct Extreme {
    std::int64_t measured, limit;
    Bound bound;
    Unit unit;
    std::int64_t margin() const { return bound == Bound::AtMost ? limit - measured : measured - limit; }
  };
  std::vector<std::array<std::optional<Extreme>, kLimitsOf>> worst_;  // indexed by LimitOf
};

// The least margin of a run of occasions on one row, noted once: a frame's clock phases are judged
// by the hundred. The first of equal margins stays, as RowMargins::note keeps it, so noting the
// run's least gives the same worst case as noting each occasion.
class LeastMargin {
 public:
  void add(const Judgement& j) {
    if (!least_ || j.margin() < least_->margin()) least_ = j;
  }
  void note_to(RowMargins& margins, std::size_t row, LimitOf of = LimitOf::Spec) const {
    if (least_) margins.note(row, *least_, of);
  }

 private:
  std::optional<Judgement> least_;
};

}  // namespace endatsim::checker
