// Vose alias table: exact implied probabilities, a chi-square goodness of fit of sampled
// frequencies, zero weights never drawn, and bad weights rejected.
#include "common/base/alias_table.hpp"
#include "common/base/errors.hpp"
#include "common/base/philox.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numeric>

namespace physarum {
namespace {

// The probability with which the table returns each index, read off its buckets: bucket i keeps i
// with probability p_i and gives its alias the rest, each bucket chosen with probability 1/n.
std::vector<double> implied_probabilities(const AliasTable& table) {
  const int n = table.size();
  std::vector<double> p(n, 0.0);
  for (int i = 0; i < n; ++i) {
    p[i] += table.probability[i] / n;
    p[table.alias[i]] += (1.0 - table.probability[i]) / n;
  }
  return p;
}

TEST(AliasTable, ImpliedProbabilitiesEqualNormalisedWeights) {
  const std::vector<std::vector<double>> cases = {
      {1.0},
      {1.0, 2.0, 3.0, 0.0, 4.0, 5.0, 0.0, 6.0, 7.0, 8.0},
      {1e-9, 1.0, 1e9},
      {0.0, 0.0, 5.0},
      std::vector<double>(37, 0.25),
  };
  for (const std::vector<double>& w : cases) {
    const AliasTable table = AliasTable::build(w);
    ASSERT_EQ(table.size(), static_cast<int>(w.size()));
    const double sum = std::accumulate(w.begin(), w.end(), 0.0);
    const std::vector<double> p = implied_probabilities(table);
    for (size_t i = 0; i < w.size(); ++i) EXPECT_NEAR(p[i], w[i] / sum, 1e-12) << "index " << i;
  }
}

TEST(AliasTable, SampledFrequenciesPassChiSquare) {
  const std::vector<double> w = {1.0, 2.0, 3.0, 0.0, 4.0, 5.0, 0.0, 6.0, 7.0, 8.0};
  const AliasTable table = AliasTable::build(w);
  const double sum = std::accumulate(w.begin(), w.end(), 0.0);
  const int draws = 200'000;
  std::vector<int> count(w.size(), 0);
  for (int i = 0; i < draws; i += 2) {  // one Philox block gives two (u1, u2) pairs
    const PhiloxWords r = random_words(2024u, 1u, static_cast<std::uint32_t>(i), 0u);
    ++count[table.sample(uniform01_double(r[0], 0u), uniform01_double(r[1], 0u))];
    ++count[table.sample(uniform01_double(r[2], 0u), uniform01_double(r[3], 0u))];
  }
  double chi_square = 0.0;
  int categories = 0;
  for (size_t i = 0; i < w.size(); ++i) {
    if (w[i] == 0.0) {
      EXPECT_EQ(count[i], 0) << "zero-weight index " << i << " was sampled";
      continue;
    }
    const double expected = draws * w[i] / sum;
    chi_square += (count[i] - expected) * (count[i] - expected) / expected;
    ++categories;
  }
  // 8 non-zero categories: 7 degrees of freedom; the 0.1% critical value of chi^2(7) is 24.32.
  ASSERT_EQ(categories, 8);
  EXPECT_LT(chi_square, 24.32);
}

TEST(AliasTable, ZeroWeightsAreNeverSampledEvenAtTheExtremes) {
  const std::vector<double> w = {0.0, 3.0, 0.0, 1.0, 0.0};
  const AliasTable table = AliasTable::build(w);
  const double extremes[] = {0.0, 1e-300, 0.2, 0.5, 0.7999999999, 0.8, std::nextafter(1.0, 0.0)};
  for (double u1 : extremes)
    for (double u2 : extremes) {
      const int i = table.sample(u1, u2);
      EXPECT_TRUE(i == 1 || i == 3) << "u1=" << u1 << " u2=" << u2 << " gave " << i;
    }
}

TEST(AliasTable, RejectsBadWeights) {
  EXPECT_THROW(AliasTable::build({}), InputError);
  EXPECT_THROW(AliasTable::build({1.0, -0.5}), InputError);
  EXPECT_THROW(AliasTable::build({1.0, std::numeric_limits<double>::quiet_NaN()}), InputError);
  EXPECT_THROW(AliasTable::build({1.0, std::numeric_limits<double>::infinity()}), InputError);
  EXPECT_THROW(AliasTable::build({0.0, 0.0}), InputError);
  try {
    AliasTable::build({1.0, 2.0, -3.0});
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("weight 2"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace physarum
