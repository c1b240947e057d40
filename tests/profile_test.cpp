// Encoder profiles (slave/profile.hpp, profiles/*.json): the bundled profiles are consistent,
// decode to the strings profiles/README.md documents, equal what build_profile makes of their
// parameters, and load -> save -> load round trips; malformed profiles are rejected with the
// file, the JSON path and the expectation.
//
// ENDATSIM_WRITE_PROFILES=1 endatsim_tests --gtest_filter='Profile.Bundled*' rewrites the
// bundled files from the parameters below.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <unistd.h>

#include "endatsim/slave/eib.hpp"
#include "endatsim/slave/profile.hpp"

using namespace endatsim;
using namespace std::chrono_literals;
using slave::EncoderKind;
using slave::EncoderProfile;
using slave::ProfileError;
using slave::ProfileParameters;
namespace pm = protocol::parameters;

namespace {

const std::string kProfiles = std::string(ENDATSIM_SOURCE_DIR) + "/profiles/";

std::vector<ProfileParameters> bundled_parameters() {
  std::vector<ProfileParameters> all;
  {
    ProfileParameters p;
    p.name = "rotary_singleturn_25bit";
    p.description = "Singleturn rotary encoder, 25 bits per revolution, EnDat22 at up to 16 MHz, t_cal 5 us. "
                    "Illustrative values, not a real product.";
    p.version = protocol::EndatVersion::V2_2;
    p.kind = EncoderKind::Singleturn;
    p.type = pm::EncoderType::Singleturn;
    p.position_bits = 25;
    p.oem[0] = p.oem[1] = pm::AddressRange{0, 63};
    p.id = pm::parse_id_number("1065932 02");
    p.serial = {' ', 40123456, 'A'};
    p.max_speed = 15000;                 // 3.5.18 example: 3A98h
    p.accuracy[0] = 0x0A01;              // 3.5.19 example: c1 = 10, a1 = 1 LSB
    p.accuracy[1] = 0x0132;              // c2 = 1, a2 = 50 LSB
    p.supported_errors = 0x001F;
    p.supported_warnings = 0x0187;
    p.communication_command = true;
    p.t_cal = pm::calculation_time_from(5us);
    p.ordering_designation = "EnDat22";
    p.additional_data_1 = {"position_value_2", "test_values", "temperature_1", "temperature_2", "additional_sensors"};
    p.additional_data_2 = {"commutation", "acceleration", "limit_position_signals", "asynchronous_position_value",
                           "operating_status_error_sources", "timestamp"};
    p.supported_errors_2 = 0x001F;
    p.max_clock_khz = 16000;
    all.push_back(p);
  }
  {
    ProfileParameters p;
    p.name = "rotary_multiturn_13_12_battery";
    p.description = "Multiturn rotary encoder with battery buffer: 13 bits per revolution, 4096 revolutions, "
                    "EnDat22 at up to 8 MHz; memory allocation of the 256-word example of 3.5.5. Illustrative "
                    "values, not a real product.";
    p.version = protocol::EndatVersion::V2_2;
    p.kind = EncoderKind::Multiturn;
    p.type = pm::EncoderType::MultiturnBattery;
    p.position_bits = 25;
    p.multiturn_bits = 12;
    p.oem[1] = p.oem[2] = pm::AddressRange{0, 63};
    p.compensation[3] = pm::AddressRange{0, 63};
    p.id = pm::parse_id_number("1131652 03");
    p.serial = {' ', 51234567, 'B'};
    p.max_speed = 12000;
    p.accuracy[0] = 0x0A01;
    p.accuracy[1] = 0x0132;
    p.supported_errors = 0x005F;    // with battery (bit 6)
    p.supported_warnings = 0x018F;  // with battery charge (bit 3)
    p.communication_command = true;
    p.t_cal = pm::calculation_time_from(5us);
    p.ordering_designation = "EnDat22";
    p.additional_data_1 = {"temperature_1", "temperature_2", "additional_sensors"};
    p.additional_data_2 = {"commutation", "acceleration", "operating_status_error_sources", "timestamp"};
    p.supported_errors_2 = 0x005F;
    p.max_clock_khz = 8000;  // 3.9.19 example: 1F40h
    all.push_back(p);
  }
  {
    ProfileParameters p;
    p.name = "linear_absolute";
    p.description = "Absolute linear encoder, 36-bit position in 100 nm steps, datum shift of the manufacturer "
                    "+20 mm (the example of 3.5.13: FFFCF2C0h), EnDat22 at up to 16 MHz. Illustrative values, "
                    "not a real product.";
    p.version = protocol::EndatVersion::V2_2;
    p.kind = EncoderKind::Linear;
    p.type = pm::EncoderType::AbsoluteLinear;
    p.position_bits = 36;
    p.oem[0] = pm::AddressRange{0, 127};
    p.compensation[0] = pm::AddressRange{0, 255};
    p.measuring_steps = 100;                         // nm (3.5.12 example)
    p.datum_shift = pm::datum_shift_value(200'000);  // +20 mm at 0.1 um
    p.id = pm::parse_id_number("557649 08");
    p.serial = {' ', 33445566, 'C'};
    p.max_speed = 120;        // 3.5.18 example: 120 m/min
    p.accuracy[0] = 0x2810;   // 3.5.19 example: c = 40, a = 16 LSB
    p.accuracy[1] = 0x2810;
    p.supported_errors = 0x001F;
    p.supported_warnings = 0x0187;
    p.t_cal = pm::calculation_time_from(5us);
    p.ordering_designation = "EnDat22";
    p.additional_data_1 = {"test_values", "temperature_1", "temperature_2"};
    p.additional_data_2 = {"commutation", "limit_position_signals", "operating_status_error_sources", "timestamp"};
    p.supported_errors_2 = 0x001F;
    p.max_clock_khz = 16000;
    all.push_back(p);
  }
  {
    ProfileParameters p;
    p.name = "touch_probe";
    p.description = "Touch probe with EnDat 2.2: 16-bit transfer format whose LSB is the trigger status "
                    "(2.3.4.4), the switching time as timestamp additional data in units of 1 us (3.9.32). "
                    "Illustrative values, not a real product.";
    p.version = protocol::EndatVersion::V2_2;
    p.kind = EncoderKind::TouchProbe;
    p.type = pm::EncoderType::TouchProbe;
    p.position_bits = 16;
    p.measuring_steps = 0;
    p.oem[0] = pm::AddressRange{0, 63};
    p.id = pm::parse_id_number("1264001 01");
    p.serial = {' ', 60012345, ' '};
    p.supported_errors = 0x0019;
    p.supported_warnings = 0x0083;
    p.communication_command = true;
    p.t_cal = pm::calculation_time_from(5us);
    p.ordering_designation = "EnDat22";
    p.additional_data_1 = {"temperature_1"};
    p.additional_data_2 = {"operating_status_error_sources", "timestamp"};
    p.supported_errors_2 = 0x0019;
    p.max_clock_khz = 8000;
    p.touch_probe_support = 0x0001;  // 3.9.31: the bit table is not in the text (guess: bit 0 = trigger status)
    p.timestamp_unit = pm::TimestampUnit::Us1;  // 3.9.32 example
    all.push_back(p);
  }
  {
    ProfileParameters p;
    p.name = "incremental_distance_coded";
    p.description = "Incremental linear encoder with distance-coded reference marks and 1 Vpp signals "
                    "(EnDat01, command set 2.1): 20 um signal period, 20 mm nominal increment (3.5.8, 3.5.10 "
                    "examples), 32-bit position in 100 nm steps. Illustrative values, not a real product.";
    p.version = protocol::EndatVersion::V2_1;
    p.kind = EncoderKind::Linear;
    p.type = pm::EncoderType::IncrementalLinearDistanceCoded;
    p.position_bits = 32;
    p.oem[0] = pm::AddressRange{0, 31};
    p.signal_period = 20000;          // nm
    p.reference_mark_increment = 20;  // mm
    p.measuring_steps = 100;
    p.id = pm::parse_id_number("336962 01");
    p.serial = {' ', 22001234, ' '};
    p.max_speed = 120;
    p.supported_errors = 0x0007;
    p.supported_warnings = 0x0011;
    p.t_cal = pm::calculation_time_from(5us);
    p.ordering_designation = "EnDat01";
    all.push_back(p);
  }
  {
    ProfileParameters p;
    p.name = "incremental_rotary_equidistant";
    p.description = "Incremental rotary encoder without distance-coded reference marks, EnDat22 with its signal "
                    "period stated (A10): 2048 signal periods per revolution (3.5.8 example), 4096 steps per "
                    "period, 23-bit position; equidistant reference marks every 512 signal periods, four per "
                    "revolution (3.5.10.2). Illustrative values, not a real product.";
    p.version = protocol::EndatVersion::V2_2;
    p.kind = EncoderKind::Singleturn;
    p.type = pm::EncoderType::IncrementalRotary;
    p.position_bits = 23;
    p.oem[0] = pm::AddressRange{0, 63};
    p.signal_period = 2048;            // P/rev
    p.reference_mark_increment = 512;  // P
    p.id = pm::parse_id_number("385488 02");
    p.serial = {' ', 27001234, ' '};
    p.max_speed = 12000;
    p.supported_errors = 0x0007;
    p.supported_warnings = 0x0011;     // 2^4: reference point not reached (3.4.2)
    p.t_cal = pm::calculation_time_from(5us);
    p.ordering_designation = "EnDat22";
    p.additional_data_1 = {"position_value_2", "temperature_1"};
    p.additional_data_2 = {"operating_status_error_sources"};
    p.supported_errors_2 = 0x0007;
    p.max_clock_khz = 16000;
    all.push_back(p);
  }
  return all;
}

// The EIB in factory delivery state (3.5.7); position_bits is the width of its answer before
// initial commissioning (word 13 is not saved yet).
EncoderProfile eib_factory_profile() {
  EncoderProfile p;
  p.name = "eib_factory";
  p.description = "External Interface Box in factory delivery state (3.5.7): word 14 type Fh, memory size (OEM "
                  "areas 1 and 2, 64 words each), ID and serial number, their checksum; everything else is saved "
                  "at initial commissioning. Illustrative values, not a real product.";
  p.version = protocol::EndatVersion::V2_2;
  p.kind = EncoderKind::Eib;
  p.position_bits = 32;
  p.memory = slave::eib_factory_image();
  return p;
}

// What profiles/README.md documents for each bundled profile.
const std::map<std::string, std::map<std::string, std::string>> kDocumented{
    {"rotary_singleturn_25bit",
     {{"encoder type (word 14)", "singleturn rotary or angle encoder"},
      {"position bits (word 13)", "25"},
      {"measuring step (words 20/21)", "33554432 steps/rev"},
      {"ID number (words 24..26)", "1065932 02"},
      {"serial number (words 27..29)", "40123456A"},
      {"command set (word 37)", "2.2, communication command"},
      {"t_cal (word 39)", "5 us"},
      {"ordering designation (word 40)", "EnDat22"},
      {"functions (operating status word 3)", "none activated"},
      {"additional data 1 (2.2 word 0)",
       "position_value_2, test_values, temperature_1, temperature_2, additional_sensors"},
      {"additional data 2 (2.2 word 1)",
       "commutation, acceleration, limit_position_signals, asynchronous_position_value, "
       "operating_status_error_sources, timestamp"},
      {"maximum clock frequency (2.2 word 25)", "16 MHz"}}},
    {"rotary_multiturn_13_12_battery",
     {{"encoder type (word 14)", "multiturn rotary encoder with battery buffer"},
      {"position bits (word 13)", "25"},
      {"measuring step (words 20/21)", "8192 steps/rev"},
      {"distinguishable revolutions (word 17)", "4096"},
      {"ID number (words 24..26)", "1131652 03"},
      {"serial number (words 27..29)", "51234567B"},
      {"command set (word 37)", "2.2, communication command"},
      {"t_cal (word 39)", "5 us"},
      {"ordering designation (word 40)", "EnDat22"},
      {"functions (operating status word 3)", "none activated"},
      {"additional data 1 (2.2 word 0)", "temperature_1, temperature_2, additional_sensors"},
      {"additional data 2 (2.2 word 1)", "commutation, acceleration, operating_status_error_sources, timestamp"},
      {"maximum clock frequency (2.2 word 25)", "8 MHz"}}},
    {"linear_absolute",
     {{"encoder type (word 14)", "absolute linear encoder"},
      {"position bits (word 13)", "36"},
      {"measuring step (words 20/21)", "100 nm"},
      {"ID number (words 24..26)", "557649 08"},
      {"serial number (words 27..29)", "33445566C"},
      {"command set (word 37)", "2.2"},
      {"t_cal (word 39)", "5 us"},
      {"ordering designation (word 40)", "EnDat22"},
      {"functions (operating status word 3)", "none activated"},
      {"additional data 1 (2.2 word 0)", "test_values, temperature_1, temperature_2"},
      {"additional data 2 (2.2 word 1)",
       "commutation, limit_position_signals, operating_status_error_sources, timestamp"},
      {"maximum clock frequency (2.2 word 25)", "16 MHz"}}},
    {"touch_probe",
     {{"encoder type (word 14)", "touch probe (note D1 - D11)"},
      {"position bits (word 13)", "16"},
      {"measuring step (words 20/21)", "0 (see EnDat 2.2 words 27 .. 29)"},
      {"ID number (words 24..26)", "1264001 01"},
      {"serial number (words 27..29)", "60012345"},
      {"command set (word 37)", "2.2, communication command"},
      {"t_cal (word 39)", "5 us"},
      {"ordering designation (word 40)", "EnDat22"},
      {"functions (operating status word 3)", "none activated"},
      {"additional data 1 (2.2 word 0)", "temperature_1"},
      {"additional data 2 (2.2 word 1)", "operating_status_error_sources, timestamp"},
      {"maximum clock frequency (2.2 word 25)", "8 MHz"},
      {"timestamp unit (2.2 word 45)", "1 us"}}},
    {"incremental_distance_coded",
     {{"encoder type (word 14)", "incremental linear encoder with distance-coded reference marks"},
      {"position bits (word 13)", "32"},
      {"measuring step (words 20/21)", "100 nm"},
      {"ID number (words 24..26)", "336962 01"},
      {"serial number (words 27..29)", "22001234"},
      {"command set (word 37)", "2.1"},
      {"t_cal (word 39)", "5 us"},
      {"ordering designation (word 40)", "EnDat01"},
      {"functions (operating status word 3)", "none activated"},
      {"reference marks (words 14, 18)", "distance-coded reference marks, nominal increment 20 mm"}}},
    {"incremental_rotary_equidistant",
     {{"encoder type (word 14)", "incremental rotary or angle encoder without distance-coded reference marks"},
      {"position bits (word 13)", "23"},
      {"measuring step (words 20/21)", "8388608 steps/rev"},
      {"reference marks (words 14, 18)", "equidistant reference marks every 512 signal periods"},
      {"ID number (words 24..26)", "385488 02"},
      {"serial number (words 27..29)", "27001234"},
      {"command set (word 37)", "2.2"},
      {"t_cal (word 39)", "5 us"},
      {"ordering designation (word 40)", "EnDat22"},
      {"functions (operating status word 3)", "none activated"},
      {"additional data 1 (2.2 word 0)", "position_value_2, temperature_1"},
      {"additional data 2 (2.2 word 1)", "operating_status_error_sources"},
      {"maximum clock frequency (2.2 word 25)", "16 MHz"}}},
    {"eib_factory",
     {{"encoder type (word 14)", "External Interface Box (EIB)"},
      {"position bits (word 13)", "0"},
      {"measuring step (words 20/21)", "0 (see EnDat 2.2 words 27 .. 29)"},
      {"ID number (words 24..26)", "1000000 01"},
      {"serial number (words 27..29)", "10000001"},
      {"command set (word 37)", "2.1 (bit pairs not stored inversely)"},
      {"t_cal (word 39)", "not supported"},
      {"ordering designation (word 40)", "not supported"},
      {"functions (operating status word 3)", "none activated"},
      {"additional data 1 (2.2 word 0)", "none"},
      {"additional data 2 (2.2 word 1)", "none"},
      {"maximum clock frequency (2.2 word 25)", "0 kHz"}}},
};

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string error_of(const std::string& text) {
  try {
    slave::load_profile_text(text, "bad.json");
  } catch (const ProfileError& e) {
    return e.what();
  }
  return "(accepted)";
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? s : s.replace(at, from.size(), to);
}

}  // namespace

TEST(Profile, BundledProfilesMatchTheirParameters) {
  const bool write = std::getenv("ENDATSIM_WRITE_PROFILES") != nullptr;
  for (const auto& params : bundled_parameters()) {
    const auto built = slave::build_profile(params);
    EXPECT_TRUE(slave::check_profile(built).empty()) << params.name << ": " << slave::check_profile(built).front();
    const std::string path = kProfiles + params.name + ".json";
    if (write) slave::save_profile(path, built);
    EXPECT_EQ(read_text(path), slave::profile_text(built)) << path << " differs from build_profile";
  }
}

TEST(Profile, BundledEibFactoryMatchesItsImage) {
  const auto built = eib_factory_profile();
  EXPECT_TRUE(slave::check_profile(built).empty()) << slave::check_profile(built).front();
  const std::string path = kProfiles + built.name + ".json";
  if (std::getenv("ENDATSIM_WRITE_PROFILES") != nullptr) slave::save_profile(path, built);
  EXPECT_EQ(read_text(path), slave::profile_text(built)) << path << " differs from eib_factory_image()";
}

TEST(Profile, EibFactoryStateIsChecked) {
  const std::string good = slave::profile_text(eib_factory_profile());
  EXPECT_EQ(error_of(good), "(accepted)");
  // A word saved before commissioning (word 13), the type changed, the kind without type F.
  EXPECT_EQ(error_of(replace(good, "\"0x0000\", \"0x2020\"", "\"0x0001\", \"0x2020\"")),
            "bad.json: at /memory/manufacturer_1/8: expected 0 (an EIB in factory delivery state saves only words "
            "9..12, 14, 24..29 and 47, 3.5.7), got 0001h");
  EXPECT_EQ(error_of(replace(good, "\"0xF001\"", "\"0x8001\"")),
            "bad.json: at /memory/manufacturer_1/14: expected an encoder type of kind eib (3.5.7), got 8001h");
  auto singleturn = eib_factory_profile();
  singleturn.kind = EncoderKind::Singleturn;
  EXPECT_EQ(error_of(slave::profile_text(singleturn)),
            "bad.json: at /memory/manufacturer_1/14: expected an encoder type of kind singleturn (3.5.7), got F001h");
}

TEST(Profile, IncrementalEncodersStateSignalPeriodAndUsableMarks) {
  const auto params = bundled_parameters().back();
  ASSERT_EQ(params.name, "incremental_rotary_equidistant");
  const std::string good = slave::profile_text(slave::build_profile(params));
  EXPECT_EQ(error_of(good), "(accepted)");
  // A10: no signal period (words 15/16 = 0, checksum adjusted).
  auto no_period = params;
  no_period.signal_period = 0;
  EXPECT_EQ(error_of(slave::profile_text(slave::build_profile(no_period))),
            "bad.json: at /memory/manufacturer_1/15: expected the signal period of an incremental encoder in words "
            "15/16 (3.5.8, appendix A10), got 0000h");
  // 3.5.10.2: equidistant marks in mm need the measuring step, which words 20/21 = 0 do not give.
  auto linear = bundled_parameters().at(4);
  ASSERT_EQ(linear.name, "incremental_distance_coded");
  linear.type = pm::EncoderType::IncrementalLinear;  // word 18 = 20 mm: equidistant marks
  EXPECT_EQ(error_of(slave::profile_text(slave::build_profile(linear))), "(accepted)");
  linear.measuring_steps = 0;
  EXPECT_EQ(error_of(slave::profile_text(slave::build_profile(linear))),
            "bad.json: at /memory/manufacturer_2/2: equidistant reference marks (word 18 = 20) need the measuring "
            "step: words 20/21, or the signal period (words 15/16) and the subdivision of EnDat 2.2 words 27..29 "
            "(3.5.12, A10)");
}

TEST(Profile, EveryBundledProfileIsConsistentAndDecodesAsDocumented) {
  unsigned count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kProfiles)) {
    if (entry.path().extension() != ".json") continue;
    ++count;
    const std::string path = entry.path().string();
    SCOPED_TRACE(path);
    const EncoderProfile p = slave::load_profile(path);
    EXPECT_EQ(p.name, entry.path().stem().string());
    EXPECT_TRUE(slave::check_profile(p).empty());
    const auto m = p.manufacturer_words();
    EXPECT_NE(m[14] & 0x0001, 0);
    EXPECT_EQ(pm::manufacturer_checksum(m), m[47]);
    // NVM check bits (3.5.4, 3.5.6, 3.5.7, 3.5.16, 3.5.17); an EIB saves these words only at
    // initial commissioning (3.5.7).
    for (unsigned n : {8U, 13U, 30U, 31U}) EXPECT_EQ(m[n] & 0x8000, p.kind == EncoderKind::Eib ? 0 : 0x8000) << "word " << n;
    EXPECT_EQ(m[13], p.kind == EncoderKind::Eib ? 0 : 0x8000 | p.position_bits);
    const auto e = p.endat22_words();
    EXPECT_EQ(e.empty(), p.version == protocol::EndatVersion::V2_1);
    if (!e.empty()) {
      EXPECT_EQ(pm::endat22_checksum(e), e[63]);
    }
    EXPECT_EQ(pm::command_set_consistent(m[37]), p.kind != EncoderKind::Eib);
    // The documented strings.
    ASSERT_TRUE(kDocumented.contains(p.name)) << "profile not documented in this test: " << p.name;
    const auto described = slave::describe_profile(p);
    const std::map<std::string, std::string> got(described.begin(), described.end());
    EXPECT_EQ(got, kDocumented.at(p.name));
    // It builds a memory and an encoder's parameters.
    EXPECT_NO_THROW(slave::Memory{p.memory});
    slave::EncoderParams params;
    p.apply(params);
    EXPECT_NO_THROW(params.validate());
    EXPECT_EQ(params.position_bits, p.position_bits);
    EXPECT_EQ(params.t_cal, sim::us(5));
    // load -> save is byte for byte the file; load -> save -> load is equal.
    EXPECT_EQ(slave::profile_text(p), read_text(path));
    EXPECT_EQ(slave::load_profile_text(slave::profile_text(p), path), p);
  }
  EXPECT_EQ(count, kDocumented.size());
}

TEST(Profile, SaveAndLoadRoundTripThroughAFile) {
  auto p = slave::build_profile(bundled_parameters().at(1));
  p.name = "with \"quotes\" and a section 2 block";
  p.memory.areas[protocol::MemoryArea::ManufacturerEndat22][24] = 1;  // one section 2 block (3.9.18)
  auto& e = p.memory.areas[protocol::MemoryArea::ManufacturerEndat22];
  e[63] = pm::endat22_checksum(e);
  p.memory.section2_blocks.assign(1, std::vector<std::uint16_t>(256, 0xA5A5));
  const auto dir = std::filesystem::temp_directory_path() / ("endatsim_profile_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "p.json").string();
  slave::save_profile(path, p);
  const auto loaded = slave::load_profile(path);
  EXPECT_EQ(loaded, p);
  EXPECT_EQ(loaded.memory.section2_blocks.size(), 1U);
  EXPECT_EQ(read_text(path), slave::profile_text(loaded));
  std::filesystem::remove_all(dir);
  EXPECT_THROW(slave::save_profile((dir / "missing" / "p.json").string(), p), ProfileError);
}

TEST(Profile, ErrorsNameFileJsonPathAndExpectation) {
  const std::string good = slave::profile_text(slave::build_profile(bundled_parameters().at(0)));
  EXPECT_EQ(error_of(good), "(accepted)");
  // Word 13 says 25 bits but position_bits says 24.
  EXPECT_EQ(error_of(replace(good, "\"position_bits\": 25", "\"position_bits\": 24")),
            "bad.json: at /memory/manufacturer_1/13: expected position_bits 24 in bits 0..5 (3.5.6), got 8019h");
  // A broken checksum (word 32 changed, 47 not).
  const std::string wrong_speed = replace(good, "\"0x3A98\"", "\"0x3A99\"");
  EXPECT_NE(error_of(wrong_speed).find("bad.json: at /memory/manufacturer_3/15: expected "), std::string::npos)
      << error_of(wrong_speed);
  EXPECT_NE(error_of(wrong_speed).find("= word 4 + ... + word 46 (3.5.26)"), std::string::npos);
  // Word 13 without its NVM bit.
  EXPECT_NE(error_of(replace(good, "\"0x8019\"", "\"0x0019\"")).find("at /memory/manufacturer_1/13: expected bit 15 = 1"),
            std::string::npos);
  EXPECT_EQ(error_of(replace(good, "\"0x8019\"", "\"8019\"")),
            "bad.json: at /memory/manufacturer_1/13: expected a 16-bit word as a hex string such as \"0x8019\", got "
            "string \"8019\"");
  EXPECT_EQ(error_of(replace(good, "\"0x8019\"", "\"0x18019\"")).substr(0, 42), "bad.json: at /memory/manufacturer_1/13: ex");
  EXPECT_EQ(error_of(replace(good, "\"kind\": \"singleturn\"", "\"kind\": \"rotary\"")),
            "bad.json: at /kind: expected one of \"singleturn\", \"multiturn\", \"linear\", \"touch_probe\", \"eib\", "
            "got string \"rotary\"");
  EXPECT_EQ(error_of(replace(good, "\"version\": \"2.2\"", "\"version\": \"3.0\"")),
            "bad.json: at /version: expected one of \"2.1\", \"2.2\", got string \"3.0\"");
  EXPECT_EQ(error_of(replace(good, "\"kind\": \"singleturn\"", "\"kind\": \"linear\"")),
            "bad.json: at /memory/manufacturer_1/14: expected an encoder type of kind linear (3.5.7), got C001h");
  EXPECT_EQ(error_of(replace(good, "\"version\": \"2.2\"", "\"version\": \"2.1\"")),
            "bad.json: at /memory/manufacturer_3/5: expected bit pairs stored inversely, command set 2.1 (3.5.22), got "
            "0019h");
  EXPECT_EQ(error_of(replace(good, "\"name\"", "\"nmae\"")),
            "bad.json: at /nmae: unknown key \"nmae\" (did you mean \"name\"? expected name, description, version, kind, "
            "position_bits, multiturn_bits or memory)");
  EXPECT_EQ(error_of(replace(good, "\"name\"", "\"colour\"")),
            "bad.json: at /colour: unknown key \"colour\" (expected name, description, version, kind, position_bits, "
            "multiturn_bits or memory)");
  EXPECT_EQ(error_of(replace(good, "\"operating_status\": [\"0x0000\", ", "\"operating_status\": [")),
            "bad.json: at /memory/operating_status: expected an array of 4 hex words, got array "
            "[\"0x0000\",\"0x0039\",\"0x0002\"]");
  EXPECT_NE(error_of(replace(good, "\"oem_1\"", "\"oem_3\"")).find("bad.json: at /memory: memory area oem_3 is not "
                                                                    "available per word 10"),
            std::string::npos)
      << error_of(replace(good, "\"oem_1\"", "\"oem_3\""));
  EXPECT_EQ(error_of(replace(good, "\"oem_1\"", "\"oem_9\"")).substr(0, 56),
            "bad.json: at /memory/oem_9: unknown memory area \"oem_9\" ");
  EXPECT_EQ(error_of("[]"), "bad.json: at /: expected a profile object with name, description, version, kind, "
                            "position_bits, multiturn_bits and memory, got array []");
  EXPECT_EQ(error_of("{\"name\": \"x\"}"), "bad.json: at /: missing key \"version\"");
  EXPECT_EQ(error_of("{").substr(0, 26), "bad.json: not valid JSON: ");
  EXPECT_EQ(error_of(replace(good, "\"oem_1\"", "\"oem_0\"")).substr(0, 41), "bad.json: at /memory/oem_0: unknown memor");
  auto without_oem1 = slave::build_profile(bundled_parameters().at(0));
  without_oem1.memory.areas.erase(protocol::MemoryArea::Oem1);
  EXPECT_EQ(error_of(slave::profile_text(without_oem1)),
            "bad.json: at /memory: memory area oem_1 is available per word 9 (3.5.5) but has no words");
  try {
    slave::load_profile(kProfiles + "does_not_exist.json");
    ADD_FAILURE();
  } catch (const ProfileError& err) {
    EXPECT_EQ(std::string(err.what()), kProfiles + "does_not_exist.json: cannot open the file: No such file or directory");
  }
}

// A profile is read like a scenario (one JSON reader): what the parser would take silently is refused.
TEST(Profile, TextThatParsesSilentlyIsRefused) {
  const std::string good = slave::profile_text(slave::build_profile(bundled_parameters().at(0)));
  const auto error_of = [](const std::string& text) {
    try {
      slave::load_profile_text(text, "bad.json");
    } catch (const ProfileError& e) {
      return std::string(e.what());
    }
    return std::string("loaded");
  };
  ASSERT_EQ(error_of(good), "loaded");
  EXPECT_EQ(error_of(good + std::string(1, '\0') + "garbage }}}"),
            "bad.json: not valid JSON: a NUL byte at line " + std::to_string(std::count(good.begin(), good.end(), '\n') + 1) +
                ", column 1 (a JSON file is text; expected a JSON value or the end of the file)");
  EXPECT_EQ(error_of(replace(good, "\"name\": ", "\"name\": \"first\", \"name\": ")),
            "bad.json: at /name: duplicate key \"name\" (each key may appear once per object)");
  EXPECT_EQ(error_of(replace(good, "\"description\": \"", "\"description\": " + std::string(40, '[') + "\"")),
            "bad.json: at /description/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0/0: nested deeper than 32 levels");
  const std::string name = slave::build_profile(bundled_parameters().at(0)).name;
  EXPECT_EQ(error_of(replace(good, "\"name\": \"" + name + "\"", "\"name\": null")),
            "bad.json: at /name: expected a string, got null");
  const std::string long_key = error_of(replace(good, "\"name\": ", "\"" + std::string(5000, 'k') + "\": 1, \"name\": "));
  EXPECT_LT(long_key.size(), 600U) << long_key.substr(0, 300);
  EXPECT_NE(long_key.find("unknown key"), std::string::npos) << long_key.substr(0, 300);
}

// Section 3: the OEM and compensation areas together hold at most 960 words; a profile whose
// partition words (3.5.5) make them hold 961 is refused, one that makes them hold 960 is not.
TEST(Profile, OemAndCompensationAreasOfAProfileHoldAtMost960Words) {
  using A = protocol::MemoryArea;
  const auto with_areas = [](unsigned comp2_end) {
    EncoderProfile p = slave::load_profile(std::string(ENDATSIM_SOURCE_DIR) + "/profiles/rotary_singleturn_25bit.json");
    auto& a1 = p.memory.areas.at(A::Manufacturer1);
    const pm::Partition to255 = pm::AddressRange{0, 255};
    a1[9] = pm::encode_partition_word(to255, to255);
    a1[10] = pm::encode_partition_word(to255, std::nullopt);
    a1[11] = pm::encode_partition_word(pm::AddressRange{0, 127}, pm::AddressRange{0, comp2_end});
    a1[12] = pm::encode_partition_word(std::nullopt, std::nullopt);
    for (A a : {A::Oem4, A::Compensation3, A::Compensation4}) p.memory.areas.erase(a);
    for (A a : {A::Oem1, A::Oem2, A::Oem3}) p.memory.areas[a].assign(256, 0);
    p.memory.areas[A::Compensation1].assign(128, 0);
    p.memory.areas[A::Compensation2].assign(comp2_end + 1, 0);
    return slave::check_profile(p);
  };
  const auto mentions_960 = [](const std::vector<std::string>& problems) {
    return std::any_of(problems.begin(), problems.end(),
                       [](const std::string& s) { return s.find("hold 961 words; section 3 allows at most 960") != std::string::npos; });
  };
  EXPECT_FALSE(mentions_960(with_areas(63)));  // 256 x 3 + 128 + 64 = 960
  EXPECT_TRUE(mentions_960(with_areas(64)));
}
