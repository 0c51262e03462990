// History::factor, the time factor of every timed datum
#include <piezocontact/settings.h>

#include <cmath>
#include <gtest/gtest.h>

using piezocontact::History;

TEST(History, ConstantIsOne)
{
  const History h;
  EXPECT_EQ(h.factor(0.0), 1.0);
  EXPECT_EQ(h.factor(7.5), 1.0);
}

TEST(History, RampRisesLinearlyThenHolds)
{
  History h;
  h.kind = History::Kind::ramp;
  h.ramp_time = 0.4;
  EXPECT_EQ(h.factor(0.0), 0.0);
  EXPECT_DOUBLE_EQ(h.factor(0.1), 0.25);
  EXPECT_EQ(h.factor(0.4), 1.0);
  EXPECT_EQ(h.factor(3.0), 1.0);
}

TEST(History, SineHasItsFrequencyAndPhase)
{
  History h;
  h.kind = History::Kind::sine;
  h.frequency = 2.0;
  h.phase = M_PI / 2;
  EXPECT_NEAR(h.factor(0.0), 1.0, 1e-15);
  EXPECT_NEAR(h.factor(0.125), 0.0, 1e-15); // a quarter period later
  EXPECT_NEAR(h.factor(0.25), -1.0, 1e-15);
}

TEST(History, TableInterpolatesAndHoldsBeyondItsEnds)
{
  History h;
  h.kind = History::Kind::table;
  h.table = {{0.0, 0.0}, {1.0, 2.0}, {3.0, -2.0}};
  EXPECT_EQ(h.factor(-1.0), 0.0);
  EXPECT_DOUBLE_EQ(h.factor(0.5), 1.0);
  EXPECT_EQ(h.factor(1.0), 2.0);
  EXPECT_DOUBLE_EQ(h.factor(2.0), 0.0);
  EXPECT_DOUBLE_EQ(h.factor(2.5), -1.0);
  EXPECT_EQ(h.factor(3.0), -2.0);
  EXPECT_EQ(h.factor(10.0), -2.0);
}
