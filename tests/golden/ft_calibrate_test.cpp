// Golden seed-002 F/T calibration: the pseudo-inverse fit recovers an exact
// linear map, averages noise down as least squares should, and refuses
// presses that do not span the nine field dimensions.
#include "host/golden/ft_calibrate.h"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

namespace eskin::golden {
namespace {

TEST(FtCalibrate, RecoversAnExactLinearMap) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  FtMatrix c;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 9; ++j) c(i, j) = u(rng) * 0.05;
  std::vector<Vec9> b;
  std::vector<Vec6> w;
  for (int k = 0; k < 40; ++k) {
    Vec9 x;
    for (int j = 0; j < 9; ++j) x(j) = u(rng) * 500;
    b.push_back(x);
    w.push_back(c * x);
  }
  // Exact data: only rounding (condition ~10, values ~25): 1e-10 absolute.
  EXPECT_LT((ft_fit(b, w) - c).cwiseAbs().maxCoeff(), 1e-10);
}

TEST(FtCalibrate, NoiseAveragesDown) {
  // Wrench noise sigma = 0.1 over N = 2000 presses with fields of RMS
  // 500/sqrt(3): each coefficient's standard error is sigma / (RMS sqrt(N))
  // = 7.7e-6; bound 6 standard errors.
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  std::normal_distribution<double> n(0, 0.1);
  FtMatrix c = FtMatrix::Constant(0.01);
  std::vector<Vec9> b;
  std::vector<Vec6> w;
  for (int k = 0; k < 2000; ++k) {
    Vec9 x;
    for (int j = 0; j < 9; ++j) x(j) = u(rng) * 500;
    Vec6 y = c * x;
    for (int i = 0; i < 6; ++i) y(i) += n(rng);
    b.push_back(x);
    w.push_back(y);
  }
  EXPECT_LT((ft_fit(b, w) - c).cwiseAbs().maxCoeff(), 6 * 7.7e-6);
}

TEST(FtCalibrate, RejectsTooFewOrDegeneratePresses) {
  std::vector<Vec9> b(5, Vec9::Ones());
  std::vector<Vec6> w(5, Vec6::Ones());
  EXPECT_THROW(ft_fit(b, w), std::invalid_argument);  // fewer than 9
  b.assign(20, Vec9::Ones());                          // all presses alike: rank 1
  w.assign(20, Vec6::Ones());
  try {
    ft_fit(b, w);
    FAIL() << "rank-1 calibration accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("span only 1 of 9"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace eskin::golden
