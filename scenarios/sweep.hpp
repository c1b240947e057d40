// Parameter sweeps: one scenario run over the Cartesian product of values at JSON pointers
// (cable length x f_c x compensation, or any other key the loader knows), in parallel, with
// results in grid order whatever the number of threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "endatsim/scenarios/runner.hpp"

namespace endatsim::scenarios {

// One key of the grid: where it sits in the scenario JSON and the values it takes.
struct GridAxis {
  std::string pointer;
  std::vector<nlohmann::json> values;
};

// "POINTER=V1,V2,...". The values split at the commas outside JSON strings, arrays and objects
// ("a,b" is one value). A value is JSON when it parses as JSON (numbers, true, false, "quoted",
// [...], {...}), otherwise a string ("2 MHz"); an item "START:STOP:STEP" of three numbers is a
// range that includes STOP when the steps reach it. Throws ScenarioError for bad syntax.
GridAxis parse_grid_axis(const std::string& text);

// What one grid point gave.
struct SweepPoint {
  std::vector<nlohmann::json> values;  // one per axis, in grid order
  // The script finished, every frame other than a delay measurement is ok and equals the
  // position the encoder latched, and no check reported anything (errors or warnings).
  bool clean = false;
  bool expectations_passed = false;  // the scenario's own "expect"
  std::uint64_t ok = 0;
  std::uint64_t crc_error = 0;
  std::uint64_t other = 0;       // no_start_bit, type1_error
  std::uint64_t violations = 0;  // of any severity
  std::vector<std::string> checks;  // distinct names of the checks violated, sorted
  std::string incomplete;           // the run ended early (ScenarioResult::incomplete); not clean
};

struct Sweep {
  std::string file;
  std::string name;  // the scenario's name
  std::vector<GridAxis> grid;
  std::vector<SweepPoint> points;  // the Cartesian product, the last axis varying fastest
  // An interruption (interrupt.hpp) stops the sweep between points and the points in flight at
  // their next event boundary: the signal, and `points` holds only what ran (not for output).
  int interrupted = 0;
};

struct SweepOptions {
  unsigned jobs = 1;
  // Called after each point with (points done, points in all); from worker threads, one call
  // at a time.
  std::function<void(std::size_t, std::size_t)> progress;
  Limits limits;  // for every point's run
  Engine engine = Engine::Auto;  // for every point's run
  // Only these grid points (`sweep --shard K/N`, shard.hpp): only they are loaded, checked and
  // run, and Sweep::points holds them alone. None: every point.
  std::optional<std::pair<std::size_t, std::size_t>> points;
};

// The scenario file as JSON, after it loaded as a scenario on its own.
nlohmann::json read_scenario_json(const std::string& path);

// Throws ScenarioError, naming the pointers, when a pointer is given twice or lies inside
// another (/line and /line/cable_length_m), when it does not name an existing element of an
// array or a key of an existing object in `base` (a missing key of an existing object is
// fine: the loader judges it), or when an axis has no values or the grid is too large.
void check_grid(const nlohmann::json& base, const std::string& file, const std::vector<GridAxis>& grid);

// The number of points of a grid: the product of its axes' sizes.
std::size_t grid_size(const std::vector<GridAxis>& grid);
// The values of point `index` (the last axis varying fastest).
std::vector<nlohmann::json> grid_point_values(const std::vector<GridAxis>& grid, std::size_t index);

// check_grid, then patches `base` at the grid's pointers for every point and loads it (so the loader validates
// every value; its errors name the grid point) and checks it against options.limits, then runs all points on
// `options.jobs` threads, each point loaded again by the thread that runs it (memory stays that of
// `jobs` scenarios, whatever the grid's size).
Sweep run_sweep(const nlohmann::json& base, const std::string& file, const std::vector<GridAxis>& grid,
                const SweepOptions& options = {});

// A point from a run's counters (ScenarioResult::tally, conformance, positions_match), which
// count every frame and finding however few the run kept (RunOptions::kept).
SweepPoint summarize(const ScenarioResult& r);

// For each combination of the other axes, the largest value at `pointer` whose point is clean.
struct MaximumTable {
  std::size_t axis = 0;             // the maximized axis
  std::vector<std::size_t> others;  // the other axes, in grid order
  struct Row {
    std::vector<nlohmann::json> values;       // of the other axes
    std::optional<nlohmann::json> maximum;  // none: no clean point
  };
  std::vector<Row> rows;
};
MaximumTable maximize(const Sweep& sweep, const std::string& pointer);

// How grid values compare: numbers as they are, frequency strings in Hz, durations in ps.
std::optional<double> numeric_value(const nlohmann::json& v);

std::string sweep_csv(const Sweep& sweep);
nlohmann::json sweep_json(const Sweep& sweep, const MaximumTable* maximum);
std::string maximum_text(const Sweep& sweep, const MaximumTable& maximum);
// A line chart of the maximum over the one other numeric axis, one line per value of an
// optional third (boolean or enumerated) axis. Throws ScenarioError for any other grid shape.
std::string maximum_svg(const Sweep& sweep, const MaximumTable& maximum);

}  // namespace endatsim::scenarios
