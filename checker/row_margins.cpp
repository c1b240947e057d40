#include "endatsim/checker/row_margins.hpp"

#include "endatsim/sim/time.hpp"

namespace endatsim::checker {

namespace {

std::string format(std::int64_t value, Unit unit) {
  switch (unit) {
    case Unit::Duration: return sim::format_time(sim::Time(value));
    case Unit::Frequency: return sim::format_frequency(value);
    case Unit::Count: return std::to_string(value) + (value == 1 || value == -1 ? " clock" : " clocks");
  }
  return "?";
}

std::string_view relation(Bound b) {
  switch (b) {
    case Bound::AtLeast: return ">= ";
    case Bound::MoreThan: return "> ";
    case Bound::AtMost: return "<= ";
  }
  return "?";
}

}  // namespace

std::string_view to_string(LimitOf of) { return of == LimitOf::Spec ? "spec" : "this encoder"; }

void RowMargins::note(std::size_t row, std::int64_t measured, std::int64_t limit, Bound bound, Unit unit, LimitOf of) {
  const Extreme e{measured, limit, bound, unit};
  auto& worst = worst_.at(row)[static_cast<std::size_t>(of)];
  // Ties keep the first occasion, so the same run always names the same one.
  if (!worst || e.margin() < worst->margin()) worst = e;
}

std::vector<WorstCase> RowMargins::worst(std::size_t row) const {
  std::vector<WorstCase> out;
  for (const LimitOf of : {LimitOf::Spec, LimitOf::ThisEncoder}) {
    const auto& w = worst_.at(row)[static_cast<std::size_t>(of)];
    if (!w) continue;
    const std::int64_t m = w->margin();
    // "More than" a limit is met only strictly: a margin of 0 is outside it.
    const bool inside = w->bound == Bound::MoreThan ? m > 0 : m >= 0;
    out.push_back({of, format(w->measured, w->unit), std::string(relation(w->bound)) + format(w->limit, w->unit),
                   (m > 0 ? "+" : "") + format(m, w->unit), inside});
  }
  return out;
}

}  // namespace endatsim::checker
