#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "endatsim/line/line.hpp"

using namespace endatsim;
using namespace endatsim::sim;
using line::ObservationPoint;

namespace {

struct EdgeTimes {
  Kernel* k;
  std::vector<Time> times;
  void on(std::uint64_t) { times.push_back(k->now()); }
};

struct Poke {
  Signal* s;
  bool v;
  void go() { s->write(v); }
};

}  // namespace

TEST(LineDelays, ClockReachesEachPointAfterItsDelaysExactly) {
  Kernel k;
  line::LineParams p;
  p.cable_length_m = 37.5;
  line::Line l(k, p);
  EdgeTimes master_pin{&k, {}}, encoder_pin{&k, {}}, encoder_logic{&k, {}};
  l.pins(ObservationPoint::MasterPins).clock.on_change(bind<&EdgeTimes::on>(&master_pin));
  l.pins(ObservationPoint::EncoderPins).clock.on_change(bind<&EdgeTimes::on>(&encoder_pin));
  l.encoder().clock_in.on_change(bind<&EdgeTimes::on>(&encoder_logic));
  Poke fall{&l.master().clock_out, false};
  k.schedule(us(1), bind<&Poke::go>(&fall));
  k.run();
  ASSERT_EQ(master_pin.times.size(), 1U);
  EXPECT_EQ(master_pin.times[0], us(1) + ns(40));  // the master's driver delay
  EXPECT_EQ(encoder_pin.times[0], us(1) + ns(40) + ps(187'500));  // 37.5 m x 5 ns/m
  EXPECT_EQ(encoder_logic.times[0], us(1) + ns(40) + ps(187'500) + ns(20));  // + the encoder's receiver delay
}

TEST(LineDelays, DefaultRoundTripEqualsTheSpecBoundForTD) {
  // 2.3.2: t_D max = (0.2 + 0.01 x L) us, with the encoder's 20 ns clock-to-data delay:
  // 40 (master driver) + 20 (encoder receiver) + 20 + 20 (encoder driver) + 100 (master receiver).
  for (double length : {0.0, 1.0, 10.0, 20.0, 50.0, 100.0, 150.0}) {
    Kernel k;
    line::LineParams p;
    p.cable_length_m = length;
    line::Line l(k, p);
    EXPECT_EQ(l.round_trip(ns(20)), ns(200) + ns(10) * static_cast<std::int64_t>(length)) << length << " m";
  }
}

TEST(LineDelays, EncoderDataReachesTheMasterAfterDriverCableAndReceiver) {
  Kernel k;
  line::LineParams p;
  p.cable_length_m = 10;
  line::Line l(k, p);
  EdgeTimes seen{&k, {}};
  l.master().data_in.on_change(bind<&EdgeTimes::on>(&seen));
  Poke high{&l.encoder().data_out, true};
  k.schedule(us(2), bind<&Poke::go>(&high));
  k.run();
  ASSERT_EQ(seen.times.size(), 1U);
  EXPECT_EQ(seen.times[0], us(2) + ns(20) + ns(50) + ns(100));  // encoder driver, 10 m, master receiver
  EXPECT_TRUE(l.master().data_in.read());
}

TEST(LineFailsafe, UndrivenDataReadsTheFailsafeLevel) {
  Kernel k;
  line::Line l(k, line::LineParams{});
  Poke release{&l.encoder().data_enable, false};
  k.schedule(us(1), bind<&Poke::go>(&release));
  k.run();
  EXPECT_TRUE(l.pins(ObservationPoint::MasterPins).data.read());
  EXPECT_TRUE(l.pins(ObservationPoint::EncoderPins).data.read());
  EXPECT_TRUE(l.master().data_in.read());
  l.set_failsafe_level(false);
  k.run();
  EXPECT_FALSE(l.master().data_in.read());
  EXPECT_FALSE(l.encoder().data_in.read());
}

TEST(LineContention, BothDriversOnIsRecordedAtEachEndWithItsTimes) {
  Kernel k;
  line::LineParams p;
  p.cable_length_m = 20;  // 100 ns one way
  line::Line l(k, p);     // the encoder drives DATA LOW at idle
  Poke on{&l.master().data_enable, true};
  Poke off{&l.master().data_enable, false};
  k.schedule(us(1), bind<&Poke::go>(&on));
  k.schedule(us(3), bind<&Poke::go>(&off));
  k.run();
  const auto& c = l.contentions();
  ASSERT_EQ(c.size(), 2U);
  EXPECT_EQ(c[0].where, ObservationPoint::MasterPins);
  EXPECT_EQ(c[0].start, us(1) + ns(30));  // master enable delay
  EXPECT_EQ(c[0].end, us(3) + ns(30));    // master disable delay
  EXPECT_EQ(c[1].where, ObservationPoint::EncoderPins);
  EXPECT_EQ(c[1].start, us(1) + ns(30) + ns(100));
  EXPECT_EQ(c[1].end, us(3) + ns(30) + ns(100));
}

// Listeners hear each contention as it begins and as it ends, paired by its sequence number; the
// log keeps only as many as its limit allows.
TEST(LineContention, ListenersHearEachContentionBeginAndEndTheLogKeepsItsLimit) {
  Kernel k;
  line::LineParams p;
  p.cable_length_m = 20;  // 100 ns one way
  line::Line l(k, p);     // the encoder drives DATA LOW at idle
  l.set_contention_log_limit(1);
  std::vector<std::pair<Time, line::Contention>> heard;
  l.on_contention([&](const line::Contention& c) { heard.emplace_back(k.now(), c); });
  Poke on{&l.master().data_enable, true};
  Poke off{&l.master().data_enable, false};
  k.schedule(us(1), bind<&Poke::go>(&on));
  k.schedule(us(3), bind<&Poke::go>(&off));
  k.run();
  ASSERT_EQ(heard.size(), 4U);
  // Master pins: begins at 1.03 us; encoder pins 100 ns later; each ends 2 us after it began.
  EXPECT_EQ(heard[0].first, us(1) + ns(30));
  EXPECT_EQ(heard[0].second.sequence, 0U);
  EXPECT_EQ(heard[0].second.end, Time::max());
  EXPECT_EQ(heard[1].first, us(1) + ns(130));
  EXPECT_EQ(heard[1].second.sequence, 1U);
  EXPECT_EQ(heard[1].second.where, ObservationPoint::EncoderPins);
  EXPECT_EQ(heard[2].first, us(3) + ns(30));
  EXPECT_EQ(heard[2].second.sequence, 0U);
  EXPECT_EQ(heard[2].second.start, us(1) + ns(30));
  EXPECT_EQ(heard[2].second.end, us(3) + ns(30));
  EXPECT_EQ(heard[3].second.sequence, 1U);
  EXPECT_EQ(heard[3].second.end, us(3) + ns(130));
  EXPECT_EQ(l.contentions_seen(), 2U);
  ASSERT_EQ(l.contentions().size(), 1U);  // the first one only
  EXPECT_EQ(l.contentions()[0].sequence, 0U);
  EXPECT_EQ(l.contentions()[0].end, us(3) + ns(30));
  EXPECT_EQ(line::Line(k, p).contention_log_limit(), line::Line::kContentionLogLimit);
}

TEST(LineParams, RejectsOutOfRangeValuesNamingTheLimit) {
  line::LineParams p;
  p.cable_length_m = -1;
  try {
    p.validate();
    FAIL() << "negative cable length accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("0 .. 300 m"), std::string::npos) << e.what();
  }
  p.cable_length_m = 10;
  p.master.receiver_delay = us(2);
  EXPECT_THROW(p.validate(), std::invalid_argument);
}

TEST(LineCable, ChangingTheCableChangesLaterEdgesOnly) {
  Kernel k;
  line::LineParams p;
  p.cable_length_m = 100;  // 500 ns one way
  line::Line l(k, p);
  EdgeTimes at_encoder{&k, {}};
  l.pins(ObservationPoint::EncoderPins).clock.on_change(bind<&EdgeTimes::on>(&at_encoder));
  Poke fall{&l.master().clock_out, false};
  Poke rise{&l.master().clock_out, true};
  struct Swap {
    line::Line* l;
    void go() { l->set_cable(10, ns(5)); }
  } swap{&l};
  k.schedule(us(1), bind<&Poke::go>(&fall));   // in flight when the cable changes
  k.schedule(us(1) + ns(100), bind<&Swap::go>(&swap));
  k.schedule(us(2), bind<&Poke::go>(&rise));   // sent after the change
  k.run();
  ASSERT_EQ(at_encoder.times.size(), 2U);
  EXPECT_EQ(at_encoder.times[0], us(1) + ns(40) + ns(500));
  EXPECT_EQ(at_encoder.times[1], us(2) + ns(40) + ns(50));
  EXPECT_EQ(l.round_trip(ns(20)), ns(300));
  EXPECT_THROW(l.set_cable(301, ns(5)), std::invalid_argument);
}

// ---- faults at one end's pins -------------------------------------------------------------

namespace {

struct Glitch {
  line::Line* l;
  line::Wire wire;
  ObservationPoint end;
  Time width;
  void go() { l->invert(wire, end, width); }
};

struct Stick {
  line::Line* l;
  line::Wire wire;
  ObservationPoint end;
  std::optional<bool> level;
  void go() { l->stick(wire, end, level); }
};

}  // namespace

TEST(LineFault, AGlitchOnDataAtTheMasterEndInvertsOnlyWhatTheMasterSees) {
  Kernel k;
  line::Line l(k, line::LineParams{});  // the encoder drives DATA LOW at idle
  EdgeTimes master_logic{&k, {}}, encoder_pins{&k, {}};
  l.master().data_in.on_change(bind<&EdgeTimes::on>(&master_logic));
  l.pins(ObservationPoint::EncoderPins).data.on_change(bind<&EdgeTimes::on>(&encoder_pins));
  Glitch g{&l, line::Wire::Data, ObservationPoint::MasterPins, ns(40)};
  k.schedule(us(1), bind<&Glitch::go>(&g));
  k.run();
  ASSERT_EQ(master_logic.times.size(), 2U);
  EXPECT_EQ(master_logic.times[0], us(1) + ns(100));  // + the master's receiver delay
  EXPECT_EQ(master_logic.times[1], us(1) + ns(140));
  EXPECT_FALSE(l.master().data_in.read());
  EXPECT_TRUE(encoder_pins.times.empty()) << "the glitch stays at its end";
}

TEST(LineFault, AGlitchOnClockAtTheEncoderEndIsTwoExtraEdgesThere) {
  Kernel k;
  line::Line l(k, line::LineParams{});
  EdgeTimes encoder_logic{&k, {}}, master_pins{&k, {}};
  l.encoder().clock_in.on_change(bind<&EdgeTimes::on>(&encoder_logic));
  l.pins(ObservationPoint::MasterPins).clock.on_change(bind<&EdgeTimes::on>(&master_pins));
  Glitch g{&l, line::Wire::Clock, ObservationPoint::EncoderPins, ns(30)};
  k.schedule(us(1), bind<&Glitch::go>(&g));
  k.run();
  ASSERT_EQ(encoder_logic.times.size(), 2U);
  EXPECT_EQ(encoder_logic.times[1] - encoder_logic.times[0], ns(30));
  EXPECT_TRUE(master_pins.times.empty());
  EXPECT_THROW(l.invert(line::Wire::Clock, ObservationPoint::EncoderPins, Time::zero()), std::invalid_argument);
}

TEST(LineFault, OverlappingGlitchesEndWithTheLaterOne) {
  Kernel k;
  line::Line l(k, line::LineParams{});
  EdgeTimes seen{&k, {}};
  l.pins(ObservationPoint::MasterPins).data.on_change(bind<&EdgeTimes::on>(&seen));
  Glitch a{&l, line::Wire::Data, ObservationPoint::MasterPins, ns(100)};
  Glitch b{&l, line::Wire::Data, ObservationPoint::MasterPins, ns(100)};
  k.schedule(us(1), bind<&Glitch::go>(&a));
  k.schedule(us(1) + ns(50), bind<&Glitch::go>(&b));
  k.run();
  ASSERT_EQ(seen.times.size(), 2U);
  EXPECT_EQ(seen.times[1], us(1) + ns(150));
}

TEST(LineFault, StuckDataIgnoresTheDriverUntilReleased) {
  Kernel k;
  line::Line l(k, line::LineParams{});
  Stick stuck{&l, line::Wire::Data, ObservationPoint::EncoderPins, true};
  Stick free{&l, line::Wire::Data, ObservationPoint::EncoderPins, std::nullopt};
  Poke low{&l.master().data_enable, false};
  k.schedule(us(1), bind<&Stick::go>(&stuck));
  k.schedule(us(2), bind<&Poke::go>(&low));
  k.run(us(3));
  EXPECT_TRUE(l.encoder().data_in.read()) << "stuck HIGH although the encoder drives LOW";
  EXPECT_FALSE(l.master().data_in.read()) << "the master end is not affected";
  k.schedule(us(1), bind<&Stick::go>(&free));
  k.run();
  EXPECT_FALSE(l.encoder().data_in.read());
}

TEST(LineFault, AMasterDriverThatReleasesLateCollidesWithTheEncoder) {
  Kernel k;
  line::LineParams p;
  p.cable_length_m = 0;
  line::Line l(k, p);
  Poke release{&l.encoder().data_enable, false};
  Poke on{&l.master().data_enable, true};
  Poke off{&l.master().data_enable, false};
  Poke encoder_on{&l.encoder().data_enable, true};
  k.schedule(us(1), bind<&Poke::go>(&release));
  k.schedule(us(2), bind<&Poke::go>(&on));
  k.schedule(us(3), bind<&Poke::go>(&off));
  k.schedule(us(4), bind<&Poke::go>(&encoder_on));
  l.set_driver_disable_delay(ObservationPoint::MasterPins, us(2));
  k.run();
  ASSERT_FALSE(l.contentions().empty());
  EXPECT_EQ(l.contentions()[0].start, us(4) + ns(20));  // the encoder's enable delay
  EXPECT_EQ(l.contentions()[0].end, us(5));
  EXPECT_THROW(l.set_driver_disable_delay(ObservationPoint::MasterPins, ms(1)), std::invalid_argument);
}

TEST(LineFault, ALateReleaseBeyondTheTransceiverLimitSurvivesACableChange) {
  Kernel k;
  line::Line l(k, line::LineParams{});
  l.set_driver_disable_delay(ObservationPoint::EncoderPins, us(5));
  EXPECT_NO_THROW(l.set_cable(60, ns(5)));
  EXPECT_EQ(l.params().encoder.disable_delay, ns(20)) << "the configured transceiver is unchanged";
}
