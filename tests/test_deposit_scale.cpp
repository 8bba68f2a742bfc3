// The fixed-point scale of the OpenCL deposits (opencl/deposit_scale.hpp): the largest power of two
// that keeps one step's worst case at or below 2^62, and the refusal when the smallest deposit
// would get fewer than 2^20 units.
#include "opencl/deposit_scale.hpp"

#include "common/base/errors.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace physarum::opencl {
namespace {

using V = IntrinsicVertexData<double>;

TEST(DepositScale, LargestPowerOfTwoKeepingTheWorstStepBelowTwoToThe62) {
  for (int agents : {1, 1000, 100000, 3000000})
    for (double rate : {0.01, 1.0, 3.7, 250.0})
      for (double dt : {0.001, 0.01, 0.5}) {
        const double scale = fixed_point_deposit_scale(V{rate, rate}, agents, dt);
        const double worst = agents * rate * dt;
        int exponent = 0;
        EXPECT_EQ(std::frexp(scale, &exponent), 0.5) << "a power of two";
        EXPECT_LE(worst * scale, 0x1p62) << agents << " agents, rate " << rate << ", dt " << dt;
        if (scale < 0x1p60) {
          EXPECT_GT(2.0 * worst * scale, 0x1p62) << "the largest such power";
        }
      }
}

TEST(DepositScale, CappedAtTwoToThe60AndTwoToThe40WithoutDeposits) {
  EXPECT_EQ(fixed_point_deposit_scale(V{1e-9}, 1, 1e-3), 0x1p60);
  EXPECT_EQ(fixed_point_deposit_scale(V{0.0, 0.0}, 1000, 0.01), 0x1p40);
  EXPECT_EQ(fixed_point_deposit_scale(V{1.0}, 0, 0.01), fixed_point_deposit_scale(V{1.0}, 1, 0.01))
      << "no agents: as one";
}

TEST(DepositScale, RefusesRatesSpreadSoFarThatTheSmallestDepositRounds) {
  // 2^62 / (1e6 agents * 1 * 0.01) leaves about 2^40 units per unit of deposit: a rate 2^-20 of the
  // largest still gets 2^20 units, a rate 2^-30 of it does not.
  EXPECT_NO_THROW(fixed_point_deposit_scale(V{1.0, 0x1p-19}, 1000000, 0.01));
  EXPECT_THROW(fixed_point_deposit_scale(V{1.0, 0x1p-30}, 1000000, 0.01), InputError);
  EXPECT_NO_THROW(fixed_point_deposit_scale(V{1.0, 0.0}, 1000000, 0.01)) << "a zero rate deposits nothing to round";
}

}  // namespace
}  // namespace physarum::opencl
