// Philox4x32-10 wrapper: Random123's published known answers and the open-interval uniforms.
#include "common/base/philox.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

namespace physarum {
namespace {

// The three philox4x32 10 lines of Random123's examples/kat_vectors (counter[4] key[2] -> result[4]).
// librandom123-dev ships no kat_vectors file, so they are restated here from the upstream file.
TEST(Philox, RandomOneTwoThreeKnownAnswers) {
  struct Case {
    std::array<std::uint32_t, 4> counter;
    std::array<std::uint32_t, 2> key;
    PhiloxWords expected;
  };
  const Case cases[] = {
      {{0u, 0u, 0u, 0u}, {0u, 0u}, {0x6627e8d5u, 0xe169c58du, 0xbc57ac4cu, 0x9b00dbd8u}},
      {{0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu},
       {0xffffffffu, 0xffffffffu},
       {0x408f276du, 0x41c83b0eu, 0xa20bc7c6u, 0x6d5451fdu}},
      {{0x243f6a88u, 0x85a308d3u, 0x13198a2eu, 0x03707344u},
       {0xa4093822u, 0x299f31d0u},
       {0xd16cfe09u, 0x94fdccebu, 0x5001e420u, 0x24126ea1u}},
  };
  for (const Case& c : cases) EXPECT_EQ(philox4x32_10(c.counter, c.key), c.expected);
}

TEST(Philox, ProjectPackingPutsSeedAndStreamInTheKey) {
  // random_words(seed, stream, step, purpose, index) must be the raw block with counter
  // (step, purpose, index, 0) and key (seed, stream): the pi-digits vector rearranged.
  EXPECT_EQ(random_words(0xa4093822u, 0x299f31d0u, 0x243f6a88u, 0x85a308d3u, 0x13198a2eu)[0],
            philox4x32_10({0x243f6a88u, 0x85a308d3u, 0x13198a2eu, 0u}, {0xa4093822u, 0x299f31d0u})[0]);
  EXPECT_EQ(random_words(0u, 0u, 0u, 0u, 0u), (PhiloxWords{0x6627e8d5u, 0xe169c58du, 0xbc57ac4cu, 0x9b00dbd8u}));
  // Different streams, steps or purposes give different blocks.
  EXPECT_NE(random_words(1, 2, 3, 4), random_words(1, 3, 3, 4));
  EXPECT_NE(random_words(1, 2, 3, 4), random_words(1, 2, 4, 4));
  EXPECT_NE(random_words(1, 2, 3, 4), random_words(1, 2, 3, 5));
}

TEST(Philox, FloatUniformIsStrictlyInsideTheUnitInterval) {
  const float lo = uniform01_float(0u), hi = uniform01_float(0xffffffffu);
  EXPECT_GT(lo, 0.0f);
  EXPECT_LT(hi, 1.0f);
  EXPECT_EQ(lo, std::ldexp(1.0f, -24));
  EXPECT_EQ(hi, 1.0f - std::ldexp(1.0f, -24));
  EXPECT_TRUE(std::isfinite(-std::log(lo)));
  EXPECT_TRUE(std::isfinite(-std::log(1.0f - hi)));
  // Exactness: the value is (2k+1) 2^-24 with k = w >> 9, for every k (checked on a stride).
  for (std::uint64_t w = 0; w <= 0xffffffffu; w += 0x10001u * 7) {
    const std::uint32_t k = static_cast<std::uint32_t>(w) >> 9;
    EXPECT_EQ(static_cast<double>(uniform01_float(static_cast<std::uint32_t>(w))), (2.0 * k + 1.0) * std::ldexp(1.0, -24));
  }
}

TEST(Philox, DoubleUniformIsStrictlyInsideTheUnitInterval) {
  const double lo = uniform01_double(0u, 0u), hi = uniform01_double(0xffffffffu, 0xffffffffu);
  EXPECT_GT(lo, 0.0);
  EXPECT_LT(hi, 1.0);
  EXPECT_EQ(lo, std::ldexp(1.0, -53));
  EXPECT_EQ(hi, 1.0 - std::ldexp(1.0, -53));
  // The first word supplies the high bits.
  EXPECT_GT(uniform01_double(0x80000000u, 0u), 0.5);
  EXPECT_LT(uniform01_double(0x7fffffffu, 0xffffffffu), 0.5);
}

TEST(Philox, UniformsHaveTheRightMeanAndVariance) {
  // 4 x 50,000 draws: mean 1/2 and variance 1/12 within 5 standard errors.
  const int blocks = 50'000;
  double sum = 0.0, sum_sq = 0.0, dsum = 0.0;
  for (int i = 0; i < blocks; ++i) {
    const PhiloxWords w = random_words(12345u, 7u, static_cast<std::uint32_t>(i), 1u);
    for (std::uint32_t x : w) {
      const double u = uniform01_float(x);
      sum += u;
      sum_sq += u * u;
    }
    dsum += uniform01_double(w[0], w[1]) + uniform01_double(w[2], w[3]);
  }
  const double n = 4.0 * blocks;
  const double mean = sum / n, variance = sum_sq / n - mean * mean;
  EXPECT_NEAR(mean, 0.5, 5.0 * std::sqrt(1.0 / 12.0 / n));
  EXPECT_NEAR(variance, 1.0 / 12.0, 5.0 * std::sqrt(1.0 / 180.0 / n));
  EXPECT_NEAR(dsum / (2.0 * blocks), 0.5, 5.0 * std::sqrt(1.0 / 12.0 / (2.0 * blocks)));
}

}  // namespace
}  // namespace physarum
