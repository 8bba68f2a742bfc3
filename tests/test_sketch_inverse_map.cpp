// The sketch's inverse map (common/sketch/inverse_map.hpp) against known answers: an exact power
// law is inverted to rounding, a noisy fold is pooled into a monotone map, the range and the
// diffusion factor kappa follow from their definitions; and the shipped training data
// (tools/sketch/training/*.csv) follow the scaling of the equations, area ~ 1 / rate.
#include "common/base/errors.hpp"
#include "common/sketch/inverse_map.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

namespace physarum {
namespace {

// Area = 0.001 / rate at rates 0.05 .. 0.5 (two seeds each, equal).
void power_law(std::vector<double>& rate, std::vector<double>& area) {
  for (double r = 0.05; r < 0.51; r *= 1.25)
    for (int seed = 0; seed < 2; ++seed) rate.push_back(r), area.push_back(0.001 / r);
}

TEST(SketchInverseMap, AnExactPowerLawIsInvertedToRounding) {
  std::vector<double> rate, area;
  power_law(rate, area);
  const RateMap map(rate, area, "spot area");
  EXPECT_NEAR(map.smallest(), 0.001 / rate[rate.size() - 1], 1e-15);
  EXPECT_NEAR(map.largest(), 0.001 / 0.05, 1e-12);
  // Between the trained points too: a power law is a straight line in log-log, which PCHIP keeps.
  for (const double a : {0.0025, 0.005, 0.0123, 0.019}) EXPECT_NEAR(*map.rate_for(a), 0.001 / a, 1e-9 * 0.001 / a) << a;
  EXPECT_LT(map.cross_validated_error(), 1e-9);
  // Outside the trained range there is no rate.
  EXPECT_FALSE(map.rate_for(0.0009).has_value());
  EXPECT_FALSE(map.rate_for(0.03).has_value());
}

TEST(SketchInverseMap, ANoisyFoldIsPooledIntoAMonotoneMap) {
  std::vector<double> rate, area;
  power_law(rate, area);
  // One rate's spots measured too big, above its slower neighbour's: the raw curve folds back.
  area[6] = area[7] = 0.001 / rate[2];
  const RateMap map(rate, area, "spot area");
  double last = std::numeric_limits<double>::infinity();
  for (double a = map.smallest(); a <= map.largest(); a *= 1.01) {
    const double r = *map.rate_for(a);
    EXPECT_LE(r, last) << a;  // a bigger spot never needs a faster reaction
    last = r;
  }
  // Unpooled, two rates would share one area: the deliberately broken check fails on the fold.
  EXPECT_GT(area[6], area[4]);
}

TEST(SketchInverseMap, TooFewRatesOrAFlatCurveAreRefused) {
  EXPECT_THROW(RateMap({0.1, 0.2}, {0.01, 0.005}, "spot area"), InputError);
  EXPECT_THROW(RateMap({0.1, 0.2, 0.3, 0.4}, {0.01, 0.01, 0.01, 0.01}, "spot area"), InputError);
}

TEST(SketchInverseMap, KappaCentresAWantedRangeInTheTrainedOne) {
  std::vector<double> rate, area;
  power_law(rate, area);
  const RateMap map(rate, area, "spot area");  // areas 0.00209 .. 0.02
  EXPECT_EQ(*scale_for_range(map, 0.003, 0.01, 1.0), 1.0);
  // Ten times bigger spots than trained: kappa = the ratio of the two ranges' geometric centres.
  const double k = *scale_for_range(map, 0.03, 0.1, 1.0);
  EXPECT_NEAR(k, std::sqrt(0.03 * 0.1) / std::sqrt(map.smallest() * map.largest()), 1e-12);
  EXPECT_GE(0.03 / k, map.smallest());
  EXPECT_LE(0.1 / k, map.largest());
  // Lengths scale as sqrt(kappa): the same centring on squared lengths.
  const double kl = *scale_for_range(map, 1.0, 2.0, 0.5);
  EXPECT_NEAR(kl, std::sqrt(1.0 * 4.0) / std::sqrt(map.smallest() * map.smallest() * map.largest() * map.largest()), 1e-9);
  // A wanted span wider than the trained one has no kappa.
  EXPECT_FALSE(scale_for_range(map, 0.001, 0.1, 1.0).has_value());
}

TEST(SketchInverseMap, TheTrainingFileIsReadWithItsProvenanceSkipped) {
  const std::string csv =
      "# made by a test\nrate,seed,steps,spots,spot_area,spacing\n0.1,1,100,12,0.01,0.2\n0.2,1,50,30,,\n";
  const std::vector<TrainingRun> runs = read_training_runs(csv, "test.csv");
  ASSERT_EQ(runs.size(), 1u);  // the run without a measured area is left out
  EXPECT_EQ(runs[0].rate, 0.1);
  EXPECT_EQ(runs[0].spots, 12);
  EXPECT_EQ(runs[0].spacing, 0.2);
  EXPECT_THROW(read_training_runs("rate,seed\n0.1,1\n", "test.csv"), InputError);
  try {
    read_training_runs("rate,seed,steps,spots,spot_area,spacing\n-1,1,1,1,0.1,0.1\n", "t.csv");
    ADD_FAILURE() << "a negative rate was taken";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("t.csv:2: rate '-1' is not a number > 0"), std::string::npos) << e.what();
  }
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The shipped training data: the equations make a spot's area go as D / rate, so log area against
// log rate has slope -1 where the mesh resolves the spots and the square holds many; the data must
// show it (the mesh's cells make the smallest spots a little smaller, hence the band), the map must
// span more than a factor 10 of areas, and predict a left-out rate within 10 %.
TEST(SketchInverseMap, TheShippedTrainingDataFollowTheScalingOfTheEquations) {
  for (const char* name : {"turing_spots", "meinhardt_spots"}) {
    const std::string path = std::string(PHYSARUM_SOURCE_DIR) + "/tools/sketch/training/" + name + ".csv";
    const std::vector<TrainingRun> runs = read_training_runs(read_file(path), path);
    ASSERT_GE(runs.size(), 10u) << path;
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    std::vector<double> rate, area;
    for (const TrainingRun& r : runs) {
      const double x = std::log(r.rate), y = std::log(r.spot_area);
      sx += x, sy += y, sxx += x * x, sxy += x * y;
      rate.push_back(r.rate), area.push_back(r.spot_area);
    }
    const double n = static_cast<double>(runs.size());
    const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    EXPECT_GT(slope, -1.2) << name;
    EXPECT_LT(slope, -0.9) << name;
    const RateMap map(rate, area, "spot area");
    EXPECT_GT(map.largest() / map.smallest(), 10.0) << name;
    EXPECT_LT(map.cross_validated_error(), 0.10) << name;
    std::cout << name << ": area ~ rate^" << slope << ", areas " << map.smallest() << " .. " << map.largest()
              << " m^2, leave-one-out rate error " << 100 * map.cross_validated_error() << " %\n";
  }
}

}  // namespace
}  // namespace physarum
