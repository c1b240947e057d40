#include "endatsim/scenarios/limits.hpp"

#include <algorithm>
#include <charconv>
#include <stdexcept>

#include "endatsim/scenarios/loader.hpp"
#include "endatsim/scenarios/scenario.hpp"

namespace endatsim::scenarios {
namespace {

std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) { return a > UINT64_MAX - b ? UINT64_MAX : a + b; }

std::uint64_t saturating_mul(std::uint64_t a, std::uint64_t b) {
  return a != 0 && b > UINT64_MAX / a ? UINT64_MAX : a * b;
}

std::uint64_t frames_of(const master::Operation& op) {
  return saturating_mul(std::max<std::uint64_t>(op.count, 1), 1 + std::uint64_t{op.continuous_words});
}

[[noreturn]] void refuse(const Scenario& s, const std::string& path, const std::string& message) {
  throw ScenarioError(s.file + ": at " + path + ": " + message);
}

std::uint64_t resolve(const Scenario& s, const std::optional<std::uint64_t>& asked, std::uint64_t granted,
                      const char* key, const char* option) {
  if (!asked) return granted;
  if (*asked > granted)
    refuse(s, std::string("/limits/") + key,
           "expected at most " + std::to_string(granted) + " (the limit " + key + " this run grants; " + option +
               " raises it), got " + std::to_string(*asked));
  return *asked;
}

}  // namespace

std::uint64_t script_frames(const Scenario& scenario) {
  std::uint64_t total = 0;
  for (const auto& op : scenario.script) total = saturating_add(total, frames_of(op));
  return total;
}

void set_limit(Limits& limits, const std::string& name, const std::string& text) {
  if (name == "max-time") {
    sim::Time t;
    try {
      t = sim::parse_duration(text);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("--max-time: " + std::string(e.what()));
    }
    if (t <= sim::Time::zero()) throw std::invalid_argument("--max-time expects a duration above 0, got '" + trimmed(text) + "'");
    limits.max_time = t;
    return;
  }
  std::uint64_t Limits::*field = nullptr;
  if (name == "max-kernel-events") field = &Limits::kernel_events;
  else if (name == "max-script-frames") field = &Limits::script_frames;
  else if (name == "max-events") field = &Limits::events;
  else if (name == "max-records") field = &Limits::records;
  else throw std::logic_error("set_limit: no limit " + name);
  std::uint64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc{} || end != text.data() + text.size() || text.empty() || v == 0)
    throw std::invalid_argument("--" + name + " expects an integer 1 .. 18446744073709551615, got '" + trimmed(text) + "'");
  limits.*field = v;
}

Limits resolve_limits(const Scenario& s, const Limits& granted) {
  Limits l = granted;
  l.kernel_events = resolve(s, s.limits.kernel_events, granted.kernel_events, "kernel_events", kKernelEventsOption);
  l.script_frames = resolve(s, s.limits.script_frames, granted.script_frames, "script_frames", kScriptFramesOption);
  l.events = resolve(s, s.limits.events, granted.events, "events", kEventsOption);
  l.records = resolve(s, s.limits.records, granted.records, "records", kRecordsOption);
  if (s.events.size() > l.events)
    refuse(s, "/events",
           "expected at most " + std::to_string(l.events) + " events (limit events; " + kEventsOption +
               " or limits.events changes it), got " + std::to_string(s.events.size()));
  const std::uint64_t frames = script_frames(s);
  if (frames > l.script_frames) {
    // The entry that asks for the most, so that the file shows where.
    std::size_t largest = 0;
    for (std::size_t i = 1; i < s.script.size(); ++i)
      if (frames_of(s.script[i]) > frames_of(s.script[largest])) largest = i;
    refuse(s, "/script",
           "expected at most " + std::to_string(l.script_frames) +
               " frames and polls in all (limit script_frames: count x (1 + continuous_words), max_polls; " +
               kScriptFramesOption + " or limits.script_frames changes it), got " +
               (frames == UINT64_MAX ? std::string("more than 2^64") : std::to_string(frames)) + ", " +
               std::to_string(frames_of(s.script[largest])) + " of them at /script/" + std::to_string(largest));
  }
  return l;
}

}  // namespace endatsim::scenarios
