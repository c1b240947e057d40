#include <gtest/gtest.h>

#include <string>

#include "endatsim/sim/time.hpp"

using namespace endatsim::sim;

TEST(TimeParse, ReadsDecimalDurationsExactly) {
  EXPECT_EQ(parse_duration("2 us"), us(2));
  EXPECT_EQ(parse_duration("1.25us"), ns(1250));
  EXPECT_EQ(parse_duration("62.5 ns"), ps(62500));
  EXPECT_EQ(parse_duration("0.000001 s"), us(1));
  EXPECT_EQ(parse_duration(" 7 ps "), ps(7));
}

TEST(TimeParse, RejectsWhatIsNotAWholeNumberOfPicoseconds) {
  EXPECT_THROW(parse_duration("0.5 ps"), std::invalid_argument);
  EXPECT_THROW(parse_duration("2"), std::invalid_argument);
  EXPECT_THROW(parse_duration("-2 us"), std::invalid_argument);
  EXPECT_THROW(parse_duration("2 parsecs"), std::invalid_argument);
  EXPECT_THROW(parse_duration("99999999999999999999999999999999 s"), std::invalid_argument);
}

TEST(TimeParse, ReadsFrequencies) {
  EXPECT_EQ(parse_frequency("2 MHz"), MHz(2));
  EXPECT_EQ(parse_frequency("200kHz"), kHz(200));
  EXPECT_EQ(parse_frequency("16000000 Hz"), MHz(16));
  EXPECT_THROW(parse_frequency("2 mhz"), std::invalid_argument);
}

TEST(TimeFormat, IsExactAndReadable) {
  EXPECT_EQ(format_time(ns(1250)), "1.25 us");
  EXPECT_EQ(format_time(ps(62500)), "62.5 ns");
  EXPECT_EQ(format_time(ps(7)), "7 ps");
  EXPECT_EQ(format_time(ps(-1500)), "-1.5 ns");
  EXPECT_EQ(format_frequency(kHz(200)), "200 kHz");
}

TEST(TimePeriod, RoundsToThePicosecond) {
  EXPECT_EQ(period_of(MHz(16)), ps(62500));
  EXPECT_EQ(period_of(MHz(128)), ps(7813));  // 7812.5 rounds up
  EXPECT_EQ(frequency_of(ps(62500)), MHz(16));
}

// A number the 128-bit arithmetic cannot hold is refused, never wrapped: a huge mantissa times
// the unit's scale, and a long fraction's divisor (reachable from a capture's samplerate).
TEST(TimeParse, RefusesNumbersBeyondTheArithmeticInsteadOfWrapping) {
  EXPECT_THROW(parse_frequency("1000000000000000000000000000000 GHz"), std::invalid_argument);
  EXPECT_THROW(parse_duration("775503514212818758233030730337 s"), std::invalid_argument);
  EXPECT_THROW(parse_frequency("0.00000000000000000000000000000000000000001 MHz"), std::invalid_argument);
  try {
    parse_duration("1.000000000000000000001 us");
    FAIL() << "21 fraction digits were accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("more than 20 digits after the decimal point"), std::string::npos) << e.what();
  }
  EXPECT_EQ(parse_duration("1.00000000000000000000 us"), us(1));  // 20 digits are fine
  EXPECT_EQ(parse_duration("4611686 s"), Time{4'611'686'000'000'000'000});  // below INT64_MAX / 2 ps
  EXPECT_THROW(parse_duration("4611687 s"), ValueTooLarge);
  EXPECT_THROW(parse_duration("775503514212818758233030730337 s"), ValueTooLarge);
  EXPECT_THROW(parse_frequency("10000000000000000000 GHz"), ValueTooLarge);
}

// A micro sign from a datasheet, or a unit in the wrong case, is refused with the fix.
TEST(TimeParse, TheMicroSignAndTheWrongCaseAreRefusedWithTheFix) {
  const auto error_of = [](auto parse, const std::string& text) {
    try {
      parse(text);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  const auto duration = [](const std::string& t) { return endatsim::sim::parse_duration(t); };
  const auto frequency = [](const std::string& t) { return endatsim::sim::parse_frequency(t); };
  EXPECT_NE(error_of(duration, "0.5 \xC2\xB5s").find("(units are ASCII: write u for the micro sign"), std::string::npos);
  EXPECT_NE(error_of(duration, "0.5 \xCE\xBCs").find("(units are ASCII: write u for the micro sign"), std::string::npos);
  EXPECT_NE(error_of(duration, "3 MS").find("(units are case-sensitive: did you mean \"ms\"?)"), std::string::npos);
  EXPECT_NE(error_of(frequency, "2 mhz").find("(units are case-sensitive: did you mean \"MHz\"?)"), std::string::npos);
  EXPECT_EQ(error_of(duration, "3 weeks").find("(units"), std::string::npos);
}
