// The worst case of a row: the smallest margin to its limit over every occasion, kept apart for
// the spec's limit and the declared encoder's.
#include "endatsim/checker/row_margins.hpp"

#include <gtest/gtest.h>

#include <random>

namespace endatsim {
namespace {

using checker::Bound;
using checker::LimitOf;
using checker::RowMargins;
using checker::Unit;
using sim::ns;
using sim::ps;

TEST(RowMargins, KeepsTheSmallestMarginOfEachLimitAndNamesWhoseItIs) {
  RowMargins m(2);
  m.note(0, checker::at_least(ns(120), ns(100), sim::Time::zero()));
  m.note(0, checker::at_least(ns(101), ns(100), sim::Time::zero()));
  m.note(0, checker::at_least(ns(150), ns(100), sim::Time::zero()));
  m.note(0, checker::at_most(ns(101), ns(90), sim::Time::zero()), LimitOf::ThisEncoder);
  const auto w = m.worst(0);
  ASSERT_EQ(w.size(), 2U);
  EXPECT_EQ(w[0].of, LimitOf::Spec);
  EXPECT_EQ(w[0].measured, "101 ns");
  EXPECT_EQ(w[0].limit, ">= 100 ns");
  EXPECT_EQ(w[0].margin, "+1 ns");
  EXPECT_TRUE(w[0].inside);
  EXPECT_EQ(w[1].of, LimitOf::ThisEncoder);
  EXPECT_EQ(w[1].limit, "<= 90 ns");
  EXPECT_EQ(w[1].margin, "-11 ns");
  EXPECT_FALSE(w[1].inside);
  EXPECT_TRUE(m.worst(1).empty());
}

TEST(RowMargins, MoreThanALimitIsOutsideAtAMarginOfZero) {
  RowMargins m(1);
  m.note(0, checker::more_than(ns(125), ns(125), sim::Time::zero()));
  const auto w = m.worst(0);
  ASSERT_EQ(w.size(), 1U);
  EXPECT_EQ(w[0].limit, "> 125 ns");
  EXPECT_EQ(w[0].margin, "0 ps");
  EXPECT_FALSE(w[0].inside);
  m.note(0, checker::more_than(ns(125) + ps(1), ns(125), sim::Time::zero()));
  EXPECT_FALSE(m.worst(0)[0].inside);  // the worse occasion stays
}

TEST(RowMargins, FrequenciesAndCountsKeepTheirUnits) {
  RowMargins m(2);
  m.note(0, 8'000'001, 8'000'000, Bound::AtMost, Unit::Frequency);
  m.note(1, 40, 41, Bound::AtLeast, Unit::Count);
  EXPECT_EQ(m.worst(0)[0].measured, "8.000001 MHz");
  EXPECT_EQ(m.worst(0)[0].margin, "-1 Hz");
  EXPECT_EQ(m.worst(1)[0].limit, ">= 41 clocks");
  EXPECT_EQ(m.worst(1)[0].margin, "-1 clock");
}

// A frame's phases are noted as one run (LeastMargin): the worst case is the one noting each
// would have kept, the first of equal margins included, between runs as within one.
TEST(LeastMargin, NotingARunsLeastKeepsTheWorstCaseOfNotingEachOccasion) {
  std::mt19937 random(7);
  // Few margins and many limits: equal margins of different occasions, told apart by their text;
  // the margins fall from run to run, so that later runs hold new worst cases.
  std::uniform_int_distribution<int> margin(-2, 2), limit(100, 109), kind(0, 1);
  RowMargins each(1), runs(1);
  for (int run = 0; run < 200; ++run) {
    checker::LeastMargin least;
    const int length = run % 6;  // empty runs too
    for (int i = 0; i < length; ++i) {
      const sim::Time l = ns(limit(random)), m = ns(margin(random) - run / 4);
      const checker::Judgement j = kind(random) == 0 ? checker::at_least(l + m, l, sim::Time::zero())
                                                     : checker::at_most(l - m, l, sim::Time::zero());
      each.note(0, j);
      least.add(j);
    }
    least.note_to(runs, 0);
    const auto a = each.worst(0), b = runs.worst(0);
    ASSERT_EQ(a.size(), b.size()) << "run " << run;
    for (std::size_t k = 0; k < a.size(); ++k) {
      EXPECT_EQ(a[k].measured, b[k].measured) << "run " << run;
      EXPECT_EQ(a[k].limit, b[k].limit) << "run " << run;
      EXPECT_EQ(a[k].margin, b[k].margin) << "run " << run;
    }
  }
  EXPECT_EQ(each.worst(0).at(0).margin, "-51 ns");
}

}  // namespace
}  // namespace endatsim
