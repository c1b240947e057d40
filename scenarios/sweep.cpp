#include "endatsim/scenarios/sweep.hpp"

#include "endatsim/input/json_input.hpp"
#include "endatsim/scenarios/xml.hpp"
#include "endatsim/sim/text.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <mutex>
#include <set>
#include <sstream>
#include <string_view>
#include <thread>

#include "endatsim/scenarios/interrupt.hpp"
#include "endatsim/scenarios/loader.hpp"

namespace endatsim::scenarios {
namespace {

using nlohmann::json;

constexpr std::size_t kMaxPoints = 1'000'000;

std::string trim(std::string_view s) { return std::string(sim::trim(s)); }

std::vector<std::string> split(const std::string& s, char separator) {
  std::vector<std::string> parts;
  std::size_t begin = 0;
  for (std::size_t end; (end = s.find(separator, begin)) != std::string::npos; begin = end + 1)
    parts.push_back(trim(std::string_view(s).substr(begin, end - begin)));
  parts.push_back(trim(std::string_view(s).substr(begin)));
  return parts;
}

// The values of a --grid: split on the commas outside JSON strings, arrays and objects, so that
// "a,b", [1,2] and {"x":1,"y":2} are one value each.
std::vector<std::string> split_values(const std::string& s, const std::string& context) {
  std::vector<std::string> parts;
  std::string depth;  // the open brackets, innermost last
  bool in_string = false, escaped = false;
  std::size_t begin = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      depth += c;
    } else if (c == ']' || c == '}') {
      if (depth.empty() || depth.back() != (c == ']' ? '[' : '{'))
        throw ScenarioError(context + ": unbalanced '" + std::string(1, c) + "' in the values");
      depth.pop_back();
    } else if (c == ',' && depth.empty()) {
      parts.push_back(trim(std::string_view(s).substr(begin, i - begin)));
      begin = i + 1;
    }
  }
  if (in_string) throw ScenarioError(context + ": a string without its closing '\"' in the values");
  if (!depth.empty()) throw ScenarioError(context + ": '" + depth.substr(depth.size() - 1) + "' without its closing bracket in the values");
  parts.push_back(trim(std::string_view(s).substr(begin)));
  return parts;
}

std::string value_text(const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

// Decimal steps such as 0.1 accumulate binary error; twelve digits keep "0.3" as 0.3.
double round_to_12_digits(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.12g", v);
  return std::strtod(buffer, nullptr);
}

// "START:STOP:STEP" with three numbers; anything else is not a range.
std::optional<std::vector<json>> range_values(const std::string& item, const std::string& context) {
  const auto parts = split(item, ':');
  if (parts.size() != 3) return std::nullopt;
  std::vector<json> n;
  for (const auto& p : parts) {
    n.push_back(json::parse(p, nullptr, false));
    if (!n.back().is_number()) return std::nullopt;
  }
  const double start = n[0].get<double>(), stop = n[1].get<double>(), step = n[2].get<double>();
  if (!(step > 0) || stop < start)
    throw ScenarioError(context + ": range " + item + " needs START <= STOP and STEP > 0");
  const double steps = (stop - start) / step;
  if (steps >= static_cast<double>(kMaxPoints)) throw ScenarioError(context + ": range " + item + " has too many values");
  const auto count = static_cast<std::size_t>(std::floor(steps + 1e-9)) + 1;
  const bool integral = std::all_of(n.begin(), n.end(), [](const json& j) { return j.is_number_integer(); });
  std::vector<json> values;
  for (std::size_t i = 0; i < count; ++i) {
    if (integral)
      values.emplace_back(n[0].get<std::int64_t>() + static_cast<std::int64_t>(i) * n[2].get<std::int64_t>());
    else
      values.emplace_back(round_to_12_digits(start + static_cast<double>(i) * step));
  }
  return values;
}

void check_pointer(const std::string& pointer, const std::string& context) {
  bool valid = !pointer.empty();  // "" would be the whole scenario
  try {
    if (valid) (void)json::json_pointer(pointer);
  } catch (const json::exception&) {
    valid = false;
  }
  if (!valid)
    throw ScenarioError(context + ": \"" + pointer + "\" is not a JSON pointer to a scenario key (such as /line/cable_length_m)");
}

// The reference tokens of a pointer that check_pointer accepted, unescaped (~1 is '/', ~0 '~').
std::vector<std::string> pointer_tokens(const std::string& pointer) {
  std::vector<std::string> tokens;
  for (std::size_t begin = 1;;) {
    const auto end = pointer.find('/', begin);
    std::string token = pointer.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
    std::string unescaped;
    for (std::size_t i = 0; i < token.size(); ++i) {
      if (token[i] == '~' && i + 1 < token.size()) {
        unescaped += token[i + 1] == '1' ? '/' : '~';
        ++i;
      } else {
        unescaped += token[i];
      }
    }
    tokens.push_back(std::move(unescaped));
    if (end == std::string::npos) return tokens;
    begin = end + 1;
  }
}

// The first `count` tokens as a pointer.
std::string pointer_prefix(const std::string& pointer, std::size_t count) {
  std::size_t end = 0;
  for (std::size_t k = 0; k < count && end != std::string::npos; ++k) end = pointer.find('/', end + 1);
  return count == 0 ? std::string("(the top level)") : pointer.substr(0, end);
}

std::string kind_of(const json& v) {
  if (v.is_object()) return "an object";
  if (v.is_array()) return "an array";
  if (v.is_string()) return "a string";
  if (v.is_boolean()) return "a boolean";
  if (v.is_number()) return "a number";
  return "null";
}

// A --grid pointer must name something the scenario has: every step but the last an existing
// key or element; the last an existing array element, or a key of an existing object (which
// may be missing: an optional key, judged by the loader like any other).
void check_pointer_in(const json& base, const std::string& file, const std::string& pointer) {
  const auto tokens = pointer_tokens(pointer);
  const std::string context = "--grid " + pointer + ": " + file + ": ";
  const json* node = &base;
  for (std::size_t k = 0; k < tokens.size(); ++k) {
    const std::string& token = tokens[k];
    const std::string at = pointer_prefix(pointer, k);
    const bool last = k + 1 == tokens.size();
    if (node->is_object()) {
      const auto it = node->find(token);
      if (it != node->end()) {
        node = &*it;
        continue;
      }
      if (last) return;  // a missing key of an existing object
      throw ScenarioError(context + "no key \"" + token + "\" at " + at + ", so nothing to patch at " + pointer +
                          " (give " + pointer_prefix(pointer, k + 1) + " a JSON object as its value instead)");
    }
    if (node->is_array()) {
      const bool digits = !token.empty() && token.find_first_not_of("0123456789") == std::string::npos &&
                          (token.size() == 1 || token[0] != '0');
      const std::string range = node->empty() ? "it is empty" : "it has " + std::to_string(node->size()) +
                                (node->size() == 1 ? " element, index 0" : " elements, 0 .. " + std::to_string(node->size() - 1));
      if (!digits || token.size() > 9 || std::stoul(token) >= node->size())
        throw ScenarioError(context + "no element \"" + token + "\" in the array at " + at + " (" + range +
                            "); a grid pointer must name an element that exists");
      node = &(*node)[std::stoul(token)];
      continue;
    }
    throw ScenarioError(context + at + " is " + kind_of(*node) + ", not an object or an array, so it has no \"" +
                        token + "\"");
  }
}

std::vector<std::size_t> digits_at(const std::vector<GridAxis>& grid, std::size_t index) {
  std::vector<std::size_t> digits(grid.size());
  for (std::size_t a = grid.size(); a-- > 0;) {
    digits[a] = index % grid[a].values.size();
    index /= grid[a].values.size();
  }
  return digits;
}

std::vector<json> values_at(const std::vector<GridAxis>& grid, std::size_t index) {
  const auto digits = digits_at(grid, index);
  std::vector<json> values;
  for (std::size_t a = 0; a < grid.size(); ++a) values.push_back(grid[a].values[digits[a]]);
  return values;
}

}  // namespace

std::vector<json> grid_point_values(const std::vector<GridAxis>& grid, std::size_t index) { return values_at(grid, index); }

std::size_t grid_size(const std::vector<GridAxis>& grid) {
  std::size_t n = 1;
  for (const auto& axis : grid) {
    if (axis.values.empty()) throw ScenarioError("--grid " + axis.pointer + ": no values");
    if (n > kMaxPoints / axis.values.size())
      throw ScenarioError("the grid has more than " + std::to_string(kMaxPoints) + " points");
    n *= axis.values.size();
  }
  return n;
}

namespace {

std::string describe_point(const std::vector<GridAxis>& grid, const std::vector<json>& values) {
  std::string text;
  for (std::size_t a = 0; a < grid.size(); ++a)
    text += (a == 0 ? "" : ", ") + grid[a].pointer + "=" + value_text(values[a]);
  return text;
}

// The scenario at one grid point: patched, printed and loaded, so that the loader judges every
// value and every pointer exactly as in a scenario file.
Scenario load_point(const json& base, const std::string& file, const std::vector<GridAxis>& grid, std::size_t index,
                    std::size_t total) {
  const auto values = values_at(grid, index);
  const std::string where = "grid point " + std::to_string(index + 1) + " of " + std::to_string(total) + " (" +
                            describe_point(grid, values) + ")";
  json doc = base;
  for (std::size_t a = 0; a < grid.size(); ++a) {
    try {
      doc[json::json_pointer(grid[a].pointer)] = values[a];
    } catch (const json::exception& e) {
      const std::string what = e.what();  // "[json.exception.type_error.305] message"
      const auto bracket = what.find("] ");
      throw ScenarioError(where + ": " + file + ": cannot set " + grid[a].pointer + ": " +
                          (bracket == std::string::npos ? what : what.substr(bracket + 2)));
    }
  }
  try {
    return load_scenario_text(doc.dump(), file);
  } catch (const ScenarioError& e) {
    throw ScenarioError(where + ": " + e.what());
  }
}

// Workers take the next index from a shared counter; each result lands at its own index, so
// the order of completion never shows in the output. An interruption stops them taking more.
// Calls work(i) for every i < n on up to `jobs` threads, until an interruption; rethrows the
// exception of the lowest i, so that a bad point is reported as a serial loop would. Once point i
// has failed no point after it is taken: every point before it has been taken already (they are
// taken in order) and finishes, so the lowest failure is still found.
template <class Work>
void for_each_point(std::size_t n, unsigned jobs, const Work& work) {
  std::vector<std::exception_ptr> errors(n);
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> failed{n};  // the lowest point that failed so far
  const auto worker = [&] {
    for (std::size_t i = next++; i < failed.load() && interrupt_signal() == 0; i = next++) {
      try {
        work(i);
      } catch (...) {
        errors[i] = std::current_exception();
        for (std::size_t f = failed.load(); i < f && !failed.compare_exchange_weak(f, i);) {
        }
      }
    }
  };
  {
    const std::size_t threads = std::clamp<std::size_t>(jobs, 1, std::max<std::size_t>(n, 1));
    std::vector<std::jthread> workers;
    for (std::size_t w = 0; w < threads; ++w) workers.emplace_back(worker);
  }  // the workers join here
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

// The points [first, first + count) of the grid's n.
std::vector<SweepPoint> run_points(const json& base, const std::string& file, const std::vector<GridAxis>& grid,
                                   std::size_t first, std::size_t count, const SweepOptions& options) {
  const std::size_t n = grid_size(grid);
  std::vector<SweepPoint> points(count);
  std::mutex progress_mutex;
  std::size_t done = 0;
  RunOptions run_options;
  run_options.limits = options.limits;
  run_options.engine = options.engine;
  run_options.kept = 1;  // every frame and finding is counted; a point is judged from the counts
  for_each_point(count, options.jobs, [&](std::size_t i) {
    const Scenario scenario = load_point(base, file, grid, first + i, n);
    const ScenarioResult r = run_scenario(scenario, run_options);
    points[i] = summarize(r);
    points[i].incomplete = r.incomplete;
    if (!options.progress) return;
    const std::lock_guard lock(progress_mutex);
    options.progress(++done, count);
  });
  return points;
}

std::size_t axis_of(const Sweep& sweep, const std::string& pointer, const std::string& context) {
  std::string names;
  for (std::size_t a = 0; a < sweep.grid.size(); ++a) {
    if (sweep.grid[a].pointer == pointer) return a;
    names += (a == 0 ? "" : ", ") + sweep.grid[a].pointer;
  }
  throw ScenarioError(context + " " + pointer + ": not one of the --grid pointers (" + names + ")");
}

std::string csv_cell(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string quoted = "\"";
  for (char c : s) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string join(const std::vector<std::string>& items, const std::string& separator) {
  std::string text;
  for (std::size_t i = 0; i < items.size(); ++i) text += (i == 0 ? "" : separator) + items[i];
  return text;
}

}  // namespace

GridAxis parse_grid_axis(const std::string& text) {
  const std::string context = "--grid " + text;
  const auto equals = text.find('=');
  if (equals == std::string::npos) throw ScenarioError(context + ": expected POINTER=V1,V2,... or POINTER=START:STOP:STEP");
  GridAxis axis{trim(std::string_view(text).substr(0, equals)), {}};
  check_pointer(axis.pointer, context);
  for (const auto& item : split_values(text.substr(equals + 1), context)) {
    if (item.empty()) throw ScenarioError(context + ": an empty value");
    if (auto range = range_values(item, context)) {
      axis.values.insert(axis.values.end(), range->begin(), range->end());
      continue;
    }
    // An object or array is read as a scenario file is (a key given twice, deep nesting and bad
    // syntax refused, not collapsed or taken as a string); any other value that is no JSON is a string.
    if (item.front() == '{' || item.front() == '[') {
      try {
        axis.values.push_back(input::parse(item, context));
      } catch (const input::InputError& e) {
        throw ScenarioError(e.what());
      }
      continue;
    }
    json value = json::parse(item, nullptr, false);
    axis.values.push_back(value.is_discarded() ? json(item) : std::move(value));
  }
  return axis;
}

json read_scenario_json(const std::string& path) {
  (void)load_scenario_file(path);  // every error with the loader's file, path and expectation
  std::ifstream in(path, std::ios::binary);
  return json::parse(in);
}

SweepPoint summarize(const ScenarioResult& r) {
  SweepPoint p;
  // From the run's counters, not its frames: a point keeps a few frames whatever its length.
  p.ok = r.tally.outcome(master::FrameOutcome::Ok);
  p.crc_error = r.tally.outcome(master::FrameOutcome::CrcError);
  p.other = r.tally.frames() - p.ok - p.crc_error;
  for (const auto& [check, count] : finding_counts(r.conformance)) {
    p.checks.push_back(check);  // sorted: a map's order
    p.violations += count;
  }
  p.expectations_passed = r.passed();
  p.clean = r.finished && p.crc_error == 0 && p.other == 0 && p.violations == 0 && r.positions_match &&
            r.positions_match->match;
  return p;
}

void check_grid(const json& base, const std::string& file, const std::vector<GridAxis>& grid) {
  for (std::size_t a = 0; a < grid.size(); ++a)
    for (std::size_t b = 0; b < a; ++b) {
      const std::string &first = grid[b].pointer, &second = grid[a].pointer;
      if (first == second) throw ScenarioError("--grid " + first + " is given twice");
      const bool first_inside = first.rfind(second + "/", 0) == 0, second_inside = second.rfind(first + "/", 0) == 0;
      if (first_inside || second_inside)
        throw ScenarioError("--grid " + (first_inside ? second : first) + " and --grid " + (first_inside ? first : second) +
                            ": the second lies inside the first, so one would overwrite the other");
    }
  for (const auto& axis : grid) check_pointer_in(base, file, axis.pointer);
  (void)grid_size(grid);
}

Sweep run_sweep(const json& base, const std::string& file, const std::vector<GridAxis>& grid, const SweepOptions& options) {
  check_grid(base, file, grid);
  const std::size_t n = grid_size(grid);
  // Not a structured binding: the lambdas below capture them (clang 14 cannot).
  const std::size_t first = options.points ? options.points->first : 0;
  const std::size_t end = options.points ? options.points->second : n;
  if (first > end || end > n) throw std::logic_error("run_sweep: points outside the grid");
  // Load every point before running any, so that bad input stops the sweep at once; on the
  // sweep's threads, each keeping only the point it loads. The sweep is named after point 0,
  // which a shard without it loads for the name alone (the name is read after they have joined).
  std::string name;
  const bool holds_point_0 = first == 0 && end > 0;  // an empty shard holds none
  if (!holds_point_0 && n != 0) name = load_point(base, file, grid, 0, n).name;
  for_each_point(end - first, options.jobs, [&](std::size_t k) {
    const std::size_t i = first + k;
    const Scenario s = load_point(base, file, grid, i, n);
    if (i == 0) name = s.name;
    try {
      (void)resolve_limits(s, options.limits);
    } catch (const ScenarioError& e) {
      throw ScenarioError("grid point " + std::to_string(i + 1) + " of " + std::to_string(n) + " (" +
                          describe_point(grid, values_at(grid, i)) + "): " + e.what());
    }
  });
  Sweep sweep{file, name, grid, {}};
  if ((sweep.interrupted = interrupt_signal()) != 0) return sweep;
  sweep.points = run_points(base, file, grid, first, end - first, options);
  sweep.interrupted = interrupt_signal();
  for (std::size_t i = first; i < end; ++i) sweep.points[i - first].values = values_at(grid, i);
  return sweep;
}

std::optional<double> numeric_value(const json& v) {
  if (v.is_number()) return v.get<double>();
  if (!v.is_string()) return std::nullopt;
  const auto& s = v.get_ref<const std::string&>();
  try {
    return static_cast<double>(sim::parse_frequency(s));
  } catch (const std::invalid_argument&) {
  }
  try {
    return static_cast<double>(sim::parse_duration(s).count());
  } catch (const std::invalid_argument&) {
  }
  return std::nullopt;
}

MaximumTable maximize(const Sweep& sweep, const std::string& pointer) {
  MaximumTable t;
  t.axis = axis_of(sweep, pointer, "--maximize");
  for (const auto& v : sweep.grid[t.axis].values)
    if (!numeric_value(v))
      throw ScenarioError("--maximize " + pointer + ": " + value_text(v) + " is not a number, a frequency or a duration");
  std::vector<GridAxis> others;
  for (std::size_t a = 0; a < sweep.grid.size(); ++a)
    if (a != t.axis) {
      t.others.push_back(a);
      others.push_back(sweep.grid[a]);
    }
  const std::size_t rows = grid_size(others);
  for (std::size_t row = 0; row < rows; ++row) t.rows.push_back({values_at(others, row), std::nullopt});
  std::vector<std::optional<double>> best(rows);
  for (std::size_t i = 0; i < sweep.points.size(); ++i) {
    const auto digits = digits_at(sweep.grid, i);
    std::size_t row = 0;
    for (auto a : t.others) row = row * sweep.grid[a].values.size() + digits[a];
    const SweepPoint& p = sweep.points[i];
    const double v = *numeric_value(p.values[t.axis]);
    if (!p.clean || (best[row] && *best[row] >= v)) continue;
    best[row] = v;
    t.rows[row].maximum = p.values[t.axis];
  }
  return t;
}

std::string sweep_csv(const Sweep& sweep) {
  std::ostringstream out;
  for (const auto& axis : sweep.grid) out << csv_cell(axis.pointer) << ",";
  out << "clean,expectations_passed,ok,crc_error,other,violations,checks\n";
  for (const auto& p : sweep.points) {
    for (const auto& v : p.values) out << csv_cell(value_text(v)) << ",";
    out << (p.clean ? "true" : "false") << "," << (p.expectations_passed ? "true" : "false") << "," << p.ok << ","
        << p.crc_error << "," << p.other << "," << p.violations << "," << csv_cell(join(p.checks, ";")) << "\n";
  }
  return out.str();
}

json sweep_json(const Sweep& sweep, const MaximumTable* maximum) {
  json grid = json::array(), points = json::array();
  for (const auto& axis : sweep.grid) grid.push_back(axis.pointer);
  for (const auto& p : sweep.points)
    points.push_back({{"values", p.values},
                      {"clean", p.clean},
                      {"expectations_passed", p.expectations_passed},
                      {"ok", p.ok},
                      {"crc_error", p.crc_error},
                      {"other", p.other},
                      {"violations", p.violations},
                      {"checks", p.checks}});
  for (std::size_t i = 0; i < sweep.points.size(); ++i)
    if (!sweep.points[i].incomplete.empty()) points[i]["incomplete"] = sweep.points[i].incomplete;
  json out{{"scenario", sweep.file}, {"name", sweep.name}, {"grid", grid}, {"points", points}};
  if (maximum == nullptr) return out;
  json by = json::array(), rows = json::array();
  for (auto a : maximum->others) by.push_back(sweep.grid[a].pointer);
  for (const auto& row : maximum->rows)
    rows.push_back({{"values", row.values}, {"maximum", row.maximum.value_or(json(nullptr))}});
  out["maximum"] = {{"pointer", sweep.grid[maximum->axis].pointer}, {"by", by}, {"rows", rows}};
  return out;
}

std::string maximum_text(const Sweep& sweep, const MaximumTable& maximum) {
  std::vector<std::vector<std::string>> cells(1);
  for (auto a : maximum.others) cells[0].push_back(sweep.grid[a].pointer);
  cells[0].push_back("largest clean " + sweep.grid[maximum.axis].pointer);
  for (const auto& row : maximum.rows) {
    cells.emplace_back();
    for (const auto& v : row.values) cells.back().push_back(value_text(v));
    cells.back().push_back(row.maximum ? value_text(*row.maximum) : "none");
  }
  std::vector<std::size_t> width(cells[0].size(), 0);
  for (const auto& line : cells)
    for (std::size_t c = 0; c < line.size(); ++c) width[c] = std::max(width[c], line[c].size());
  std::string text;
  for (const auto& line : cells) {
    for (std::size_t c = 0; c + 1 < line.size(); ++c) text += line[c] + std::string(width[c] - line[c].size() + 2, ' ');
    text += line.back() + "\n";
  }
  return text;
}


namespace {

// The chart: x is the one other numeric axis, y the maximum, one line per value of the series
// axis (if any).
struct ChartShape {
  std::size_t x = 0;
  std::optional<std::size_t> series;
};

ChartShape chart_shape(const Sweep& sweep, const MaximumTable& m) {
  std::vector<std::size_t> numeric, other;
  for (auto a : m.others) {
    const auto& values = sweep.grid[a].values;
    const bool numbers = std::all_of(values.begin(), values.end(), [](const json& v) { return v.is_number(); });
    (numbers ? numeric : other).push_back(a);
  }
  if (numeric.size() != 1 || other.size() > 1)
    throw ScenarioError("--svg: the chart needs exactly one numeric --grid key besides " +
                        sweep.grid[m.axis].pointer + " (the x axis) and at most one other key (one line per value)");
  return {numeric.front(), other.empty() ? std::nullopt : std::optional(other.front())};
}

struct Scale {
  double lo = 0, hi = 1;
  bool log = false;
  double from = 0, to = 1;  // pixels
  double operator()(double v) const {
    const double t = log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo)) : (v - lo) / (hi - lo);
    return from + t * (to - from);
  }
};

Scale scale_over(const std::vector<double>& values, bool allow_log, double from, double to) {
  Scale s{*std::min_element(values.begin(), values.end()), *std::max_element(values.begin(), values.end()), false,
          from, to};
  s.log = allow_log && s.lo > 0 && s.hi / s.lo >= 10;
  if (s.hi == s.lo) {
    s.lo = s.lo > 0 ? s.lo / 2 : s.lo - 1;
    s.hi = s.hi > 0 ? s.hi * 2 : s.hi + 1;
  }
  return s;
}

std::vector<double> ticks(const Scale& s) {
  std::vector<double> t;
  const double slack = (s.hi - s.lo) * 1e-9;
  if (s.log) {
    for (int k = static_cast<int>(std::floor(std::log10(s.lo))); k <= static_cast<int>(std::ceil(std::log10(s.hi))); ++k)
      for (double mantissa : {1.0, 2.0, 5.0}) {
        const double v = mantissa * std::pow(10.0, k);
        if (v >= s.lo * (1 - 1e-9) && v <= s.hi * (1 + 1e-9)) t.push_back(v);
      }
    return t;
  }
  const double raw = (s.hi - s.lo) / 6, magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double norm = raw / magnitude;
  const double step = (norm < 1.5 ? 1 : norm < 3 ? 2 : norm < 7 ? 5 : 10) * magnitude;
  for (double v = std::ceil(s.lo / step) * step; v <= s.hi + slack; v += step) t.push_back(round_to_12_digits(v));
  return t;
}

std::string number_text(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

std::string px(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f", v);
  return buffer;
}

// Tick labels in the axis' own unit: "2 MHz" for frequency strings, "1.5 us" for durations.
std::string label(const GridAxis& axis, double v) {
  const json& first = axis.values.front();
  if (!first.is_string()) return number_text(v);
  try {
    (void)sim::parse_frequency(first.get<std::string>());
    return sim::format_frequency(std::llround(v));
  } catch (const std::invalid_argument&) {
    return sim::format_time(Time{std::llround(v)});
  }
}


constexpr double kHeight = 460;
constexpr double kLeft = 90, kRight = 580, kTop = 50, kBottom = 400;
constexpr double kCharWidth = 7;  // generous for 12 px sans-serif
constexpr std::array<const char*, 6> kColours{"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};

void draw_axes(std::ostream& out, const Sweep& sweep, const MaximumTable& m, std::size_t x_axis, const Scale& x,
               const Scale& y) {
  out << "<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << kRight - kLeft << "\" height=\""
      << kBottom - kTop << "\" fill=\"none\" stroke=\"#000\"/>\n";
  for (double v : ticks(x))
    out << "<line x1=\"" << px(x(v)) << "\" y1=\"" << kTop << "\" x2=\"" << px(x(v)) << "\" y2=\"" << kBottom
        << "\" stroke=\"#ddd\"/><text x=\"" << px(x(v)) << "\" y=\"" << kBottom + 18
        << "\" text-anchor=\"middle\">" << xml_escape(number_text(v)) << "</text>\n";
  for (double v : ticks(y))
    out << "<line x1=\"" << kLeft << "\" y1=\"" << px(y(v)) << "\" x2=\"" << kRight << "\" y2=\"" << px(y(v))
        << "\" stroke=\"#ddd\"/><text x=\"" << kLeft - 6 << "\" y=\"" << px(y(v) + 4) << "\" text-anchor=\"end\">"
        << xml_escape(label(sweep.grid[m.axis], v)) << "</text>\n";
  out << "<text x=\"" << (kLeft + kRight) / 2 << "\" y=\"" << kBottom + 42 << "\" text-anchor=\"middle\">"
      << xml_escape(sweep.grid[x_axis].pointer) << "</text>\n";
  out << "<text transform=\"translate(20 " << (kTop + kBottom) / 2 << ") rotate(-90)\" text-anchor=\"middle\">"
      << xml_escape("largest clean " + sweep.grid[m.axis].pointer + (y.log ? " (log scale)" : "")) << "</text>\n";
  out << "<text x=\"" << (kLeft + kRight) / 2 << "\" y=\"28\" text-anchor=\"middle\" font-size=\"15\">"
      << xml_escape(sweep.name + ": largest " + sweep.grid[m.axis].pointer + " with clean reads") << "</text>\n";
}

// A cross: where a line has no clean point.
void draw_cross(std::ostream& out, double cx, double cy, const char* colour) {
  out << "<path d=\"M" << px(cx - 4) << "," << px(cy - 4) << " L" << px(cx + 4) << "," << px(cy + 4) << " M"
      << px(cx - 4) << "," << px(cy + 4) << " L" << px(cx + 4) << "," << px(cy - 4) << "\" stroke=\"" << colour
      << "\" stroke-width=\"2\"/>\n";
}

constexpr const char* kNoCleanText = "no clean value";

// The legend: a heading (the series key), one entry per line and, when some x has no clean
// point, what the crosses mean.
struct Legend {
  std::string heading;
  std::vector<std::string> entries;
  bool gaps = false;
  double width() const {
    std::size_t chars = heading.size();
    for (const auto& e : entries) chars = std::max(chars, e.size() + 5);
    if (gaps) chars = std::max(chars, std::string_view(kNoCleanText).size() + 5);
    return 30 + kCharWidth * static_cast<double>(chars);
  }
};

Legend legend_of(const Sweep& sweep, const MaximumTable& m, const ChartShape& shape) {
  Legend legend;
  if (!shape.series) {
    legend.entries.push_back("largest clean " + sweep.grid[m.axis].pointer);
  } else {
    legend.heading = sweep.grid[*shape.series].pointer;
    for (const auto& v : sweep.grid[*shape.series].values) legend.entries.push_back(value_text(v));
  }
  legend.gaps = std::any_of(m.rows.begin(), m.rows.end(), [](const MaximumTable::Row& r) { return !r.maximum; });
  return legend;
}

// Series that coincide must all stay visible: each is drawn narrower than the ones before it
// and with a dash pattern of its own, so that a later line over an earlier one leaves the
// earlier showing at its sides and in the gaps of the dashes.
std::string series_stroke(std::size_t k, std::size_t count) {
  static const char* const kDashes[] = {"", "10 4", "3 3", "12 3 3 3", "6 2 2 2"};
  const double width = std::min(2.0 + 1.5 * static_cast<double>(count - 1 - k), 8.0);
  std::string style = "stroke=\"" + std::string(kColours[k % kColours.size()]) + "\" stroke-width=\"" + px(width) + "\"";
  const char* dash = kDashes[k % std::size(kDashes)];
  if (*dash != '\0') style += " stroke-dasharray=\"" + std::string(dash) + "\"";
  return style;
}

double dot_radius(std::size_t k, std::size_t count) { return std::min(3.0 + 1.5 * static_cast<double>(count - 1 - k), 9.0); }

void draw_legend(std::ostream& out, const Legend& legend) {
  double y = kTop + 10;
  if (!legend.heading.empty()) {
    out << "<text x=\"" << kRight + 15 << "\" y=\"" << px(y + 4) << "\">" << xml_escape(legend.heading) << "</text>\n";
    y += 22;
  }
  for (std::size_t k = 0; k < legend.entries.size(); ++k, y += 22)
    out << "<line x1=\"" << kRight + 15 << "\" y1=\"" << px(y) << "\" x2=\"" << kRight + 40 << "\" y2=\"" << px(y)
        << "\" " << series_stroke(k, legend.entries.size()) << "/><text x=\"" << kRight + 46
        << "\" y=\"" << px(y + 4) << "\">" << xml_escape(legend.entries[k]) << "</text>\n";
  if (!legend.gaps) return;
  draw_cross(out, kRight + 27.5, y, "#555");
  out << "<text x=\"" << kRight + 46 << "\" y=\"" << px(y + 4) << "\">" << kNoCleanText << "</text>\n";
}

// (x, maximum) of the rows that belong to series value k, by x; no maximum: no clean point.
std::vector<std::pair<double, std::optional<double>>> series_line(const Sweep& sweep, const MaximumTable& m,
                                                                  const ChartShape& shape, std::size_t k) {
  const auto x_column = static_cast<std::size_t>(std::find(m.others.begin(), m.others.end(), shape.x) - m.others.begin());
  const std::size_t series_column = x_column == 0 ? 1 : 0;
  std::vector<std::pair<double, std::optional<double>>> line;
  for (const auto& row : m.rows) {
    if (shape.series && row.values[series_column] != sweep.grid[*shape.series].values[k]) continue;
    line.emplace_back(row.values[x_column].get<double>(),
                      row.maximum ? numeric_value(*row.maximum) : std::optional<double>());
  }
  std::stable_sort(line.begin(), line.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return line;
}

// One line per series value. A row without a clean point breaks the line and gets a cross on
// the bottom edge of the plot, off the scale, the series side by side; a point between two gaps
// is a dot.
void draw_series(std::ostream& out, const Sweep& sweep, const MaximumTable& m, const ChartShape& shape,
                 const Scale& x, const Scale& y) {
  const std::size_t series_count = shape.series ? sweep.grid[*shape.series].values.size() : 1;
  for (std::size_t k = 0; k < series_count; ++k) {
    const char* colour = kColours[k % kColours.size()];
    std::string points;
    std::size_t count = 0;
    const auto flush = [&] {
      if (count > 1)
        out << "<polyline fill=\"none\" " << series_stroke(k, series_count) << " points=\"" << points << "\"/>\n";
      points.clear();
      count = 0;
    };
    for (const auto& [xv, yv] : series_line(sweep, m, shape, k)) {
      if (!yv) {
        flush();
        draw_cross(out, x(xv) + 10 * (static_cast<double>(k) - static_cast<double>(series_count - 1) / 2), kBottom,
                   colour);
        continue;
      }
      points += (points.empty() ? "" : " ") + px(x(xv)) + "," + px(y(*yv));
      ++count;
      out << "<circle cx=\"" << px(x(xv)) << "\" cy=\"" << px(y(*yv)) << "\" r=\"" << px(dot_radius(k, series_count))
          << "\" fill=\"" << colour << "\"/>\n";
    }
    flush();
  }
}

}  // namespace

std::string maximum_svg(const Sweep& sweep, const MaximumTable& maximum) {
  const ChartShape shape = chart_shape(sweep, maximum);
  std::vector<double> xs, ys;
  for (const auto& v : sweep.grid[shape.x].values) xs.push_back(v.get<double>());
  for (const auto& v : sweep.grid[maximum.axis].values) ys.push_back(*numeric_value(v));
  const Scale x = scale_over(xs, false, kLeft, kRight);
  const Scale y = scale_over(ys, true, kBottom, kTop);
  const Legend legend = legend_of(sweep, maximum, shape);
  const std::string width = px(kRight + 15 + legend.width());
  std::ostringstream out;
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << kHeight
      << "\" viewBox=\"0 0 " << width << " " << kHeight << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<title>" << xml_escape(sweep.name) << "</title>\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
  draw_axes(out, sweep, maximum, shape.x, x, y);
  draw_series(out, sweep, maximum, shape, x, y);
  draw_legend(out, legend);
  out << "</svg>\n";
  return out.str();
}

}  // namespace endatsim::scenarios
