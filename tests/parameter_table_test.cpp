// The encoder's parameter rows (slave::encoder_parameters(), sim/parameter.hpp): the loader and
// the model take each key exactly within its range, the spec's ranges are the spec's numbers, and
// the schema and docs/parameters.md are what the rows generate.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "endatsim/input/parameter_input.hpp"
#include "endatsim/scenarios/parameter_docs.hpp"
#include "endatsim/slave/encoder_params.hpp"

namespace endatsim {
namespace {

using nlohmann::json;
using Row = sim::Parameter<slave::EncoderParams>;
using sim::ParameterType;

std::string slurp(const std::string& relative) {
  std::ifstream in(std::string(ENDATSIM_SOURCE_DIR) + "/" + relative, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

const Row& row(std::string_view key) {
  for (const auto& r : slave::encoder_parameters())
    if (r.key == key) return r;
  throw std::logic_error("no row " + std::string(key));
}

// Reads `value` into default parameters through the row, as the loader does.
slave::EncoderParams read(const Row& r, const json& value) {
  const std::string file = "test.json";
  slave::EncoderParams p;
  input::read_parameter(input::Node(value, "encoder." + std::string(r.key), file), r, p);
  return p;
}

// A JSON value just inside (offset 0) or just outside (offset -1 below min, +1 above max).
json at(const Row& r, std::int64_t v) {
  if (sim::type_of(r) == ParameterType::Duration) return std::to_string(v) + " ps";
  return v;
}

TEST(EncoderParameterTable, OneRowPerKeyEachWithHelpAndDefaultInsideItsRange) {
  std::set<std::string_view> keys;
  const slave::EncoderParams defaults;
  for (const auto& r : slave::encoder_parameters()) {
    EXPECT_TRUE(keys.insert(r.key).second) << "two rows for " << r.key;
    EXPECT_FALSE(r.help.empty()) << r.key;
    EXPECT_LE(r.min, r.max) << r.key;
    EXPECT_FALSE(sim::out_of_range(r, defaults, "encoder").has_value()) << r.key;
  }
  EXPECT_NO_THROW(defaults.validate());
}

// D297403 2.3.2: t_m 10 .. 30 us, the short t_m 1.25 .. 3.75 us (note 3), t_ac 0 .. 12 ms.
TEST(EncoderParameterTable, SpecRangesAreTheSpecsNumbers) {
  EXPECT_EQ(row("t_m").min, sim::us(10).count());
  EXPECT_EQ(row("t_m").max, sim::us(30).count());
  EXPECT_EQ(row("t_m_short").min, sim::ns(1250).count());
  EXPECT_EQ(row("t_m_short").max, sim::ns(3750).count());
  EXPECT_EQ(row("t_ac_read").max, sim::ms(12).count());
  EXPECT_EQ(row("t_ac_write").max, sim::ms(12).count());
  EXPECT_EQ(row("position_bits").max, 48);
  EXPECT_EQ(row("continuous_low_bits").max, 7);  // 2.3.1.1: "a maximum of 7 Low Bits"
  EXPECT_EQ(sim::range_text(row("t_m")), "10 .. 30 us");
}

// Every duration and count: the loader takes the bounds and refuses one step beyond, naming the
// key's path; the model's own check agrees.
TEST(EncoderParameterTable, LoaderAndModelTakeEachNumberAtItsBoundsAndRefuseOneStepBeyond) {
  for (const auto& r : slave::encoder_parameters()) {
    const auto type = sim::type_of(r);
    if (type != ParameterType::Duration && type != ParameterType::Count) continue;
    SCOPED_TRACE(std::string(r.key));
    for (const auto bound : {r.min, r.max}) {
      const auto p = read(r, at(r, bound));
      EXPECT_FALSE(sim::out_of_range(r, p, "encoder").has_value());
    }
    for (const auto beyond : {r.min - 1, r.max + 1}) {
      try {
        (void)read(r, at(r, beyond));
        ADD_FAILURE() << "took " << beyond;
      } catch (const input::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("encoder." + std::string(r.key)), std::string::npos) << e.what();
      }
    }
  }
}

// The model refuses a value the loader would never give it, naming the key and the range.
TEST(EncoderParameterTable, ValidateNamesTheKeyAndTheRange) {
  slave::EncoderParams p;
  p.t_m = sim::ns(9999);
  try {
    p.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "encoder t_m must be 10 .. 30 us (2.3.2), got 9.999 us");
  }
  p = {};
  p.supplement_ignore_clocks = 17;
  EXPECT_THROW(p.validate(), std::invalid_argument);
  p = {};
  p.t_st_max = sim::ns(999);
  EXPECT_THROW(p.validate(), std::invalid_argument);
}

TEST(EncoderParameterTable, ChoicesWordsAndFlagsReadAsNamed) {
  EXPECT_EQ(read(row("kind"), "touch_probe").kind, slave::EncoderKind::TouchProbe);
  EXPECT_EQ(read(row("version"), "2.1").version, protocol::EndatVersion::V2_1);
  EXPECT_EQ(read(row("type1_handling"), "no_start_bit").type1, slave::Type1Handling::NoStartBit);
  EXPECT_EQ(read(row("eib_activation"), "word14_write").eib_activation, slave::EibActivation::Word14Write);
  EXPECT_THROW((void)read(row("kind"), "rotary"), input::InputError);
  EXPECT_THROW((void)read(row("kind"), 1), input::InputError);
  EXPECT_EQ(read(row("error_sources"), "0xFFFF").error_sources, 0xFFFF);
  EXPECT_THROW((void)read(row("error_sources"), 65536), input::InputError);
  EXPECT_TRUE(read(row("error1"), true).error1);
  EXPECT_THROW((void)read(row("error1"), "yes"), input::InputError);
}

TEST(EncoderParameterTable, SchemaHoldsTheGeneratedProperties) {
  const auto schema = json::parse(slurp("schema/scenario.schema.json"));
  const auto& properties = schema["$defs"]["encoder"]["properties"];
  const auto generated = scenarios::encoder_parameter_schema();
  ASSERT_EQ(generated.size(), slave::encoder_parameters().size());
  for (const auto& [key, property] : generated.items()) {
    ASSERT_TRUE(properties.contains(key)) << key;
    EXPECT_EQ(properties[key], property)
        << key << ": schema/scenario.schema.json is out of date: regenerate with `endatsim parameters --schema`";
  }
}

TEST(EncoderParameterTable, DocsParametersIsTheGeneratedTable) {
  const std::string doc = slurp("docs/parameters.md");
  const std::string table = scenarios::parameter_tables_markdown();
  ASSERT_GE(doc.size(), table.size());
  EXPECT_EQ(doc.substr(doc.size() - table.size()), table)
      << "docs/parameters.md is out of date: regenerate its table with `endatsim parameters`";
}

}  // namespace
}  // namespace endatsim
