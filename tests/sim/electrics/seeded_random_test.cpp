#include "sim/electrics/seeded_random.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace marsokhod::sim {
namespace {

std::vector<double> draws(std::uint64_t seed, int count) {
  SeededRandom random(seed);
  std::vector<double> values;
  for (int i = 0; i < count; ++i) {
    values.push_back(random.uniform());
  }
  return values;
}

TEST(SimSeededRandom, EqualSeedsGiveEqualSequences) {
  EXPECT_EQ(draws(42, 100), draws(42, 100));
  EXPECT_NE(draws(42, 100), draws(43, 100));
}

TEST(SimSeededRandom, UniformStaysInItsInterval) {
  SeededRandom random(7);
  for (int i = 0; i < 10000; ++i) {
    const double value = random.uniform(-2.0, 3.0);
    ASSERT_GE(value, -2.0);
    ASSERT_LT(value, 3.0);
  }
}

TEST(SimSeededRandom, NormalHasItsMeanAndSpread) {
  SeededRandom random(11);
  constexpr int kCount = 20000;
  double sum = 0.0;
  double sum_of_squares = 0.0;
  for (int i = 0; i < kCount; ++i) {
    const double value = random.normal(5.0, 2.0);
    sum += value;
    sum_of_squares += value * value;
  }
  const double mean = sum / kCount;
  const double sigma = std::sqrt(sum_of_squares / kCount - mean * mean);
  // Standard error of the mean 2/√20000 = 0.014; of σ about 0.01.
  EXPECT_NEAR(mean, 5.0, 0.05);
  EXPECT_NEAR(sigma, 2.0, 0.05);
}

TEST(SimSeededRandom, BernoulliEdgesDoNotDraw) {
  SeededRandom a(3);
  SeededRandom b(3);
  EXPECT_FALSE(a.bernoulli(0.0));
  EXPECT_TRUE(a.bernoulli(1.0));
  EXPECT_EQ(a.uniform(), b.uniform());  // neither edge consumed a draw
}

TEST(SimSeededRandom, DerivedSeedsDifferPerStream) {
  EXPECT_NE(derive_seed(1, 0), derive_seed(1, 1));
  EXPECT_NE(derive_seed(1, 0), derive_seed(2, 0));
  EXPECT_EQ(derive_seed(9, 4), derive_seed(9, 4));
}

}  // namespace
}  // namespace marsokhod::sim
