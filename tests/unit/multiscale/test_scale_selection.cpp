// Scale selection (thesis chapter 5): the 1-D known answers of eqs. 5.11 and 5.15, found again
// by selecting the scale numerically from profiles sampled on a fine grid and differentiated by
// finite differences (no closed form on the measuring side).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include "reliefkit/multiscale/scale_selection.h"

using namespace reliefkit;

namespace {

// A geometric series of scales, `per_octave` per doubling of t.
std::vector<double> scales(double from, double to, int per_octave) {
  std::vector<double> t;
  for (double x = from; x <= to * 1.0000001; x *= std::pow(2.0, 1.0 / per_octave)) t.push_back(x);
  return t;
}

// Curvature and its arc-length derivative at x = 0 of a profile s(x), by central differences.
double curvature(const std::function<double(double)>& s, double x, double h) {
  const double d1 = (s(x + h) - s(x - h)) / (2 * h), d2 = (s(x + h) - 2 * s(x) + s(x - h)) / (h * h);
  return -d2 / std::pow(1 + d1 * d1, 1.5);
}
double curvature_derivative(const std::function<double(double)>& s, double h) {
  // d kappa / d lambda = (d kappa / dx) / sqrt(1 + s'^2)
  const double dk = (curvature(s, h, h) - curvature(s, -h, h)) / (2 * h);
  const double d1 = (s(h) - s(-h)) / (2 * h);
  return dk / std::sqrt(1 + d1 * d1);
}

}  // namespace

namespace {
// For t0 in {0.05, 0.3, 2} and gamma in {0.75, 1, 1.25}: the scale selected from strength(T),
// T = t0 + t the profile's variance at each of 8 scales per octave, passed to check.
void for_each_case(const std::function<double(double T)>& strength,
                   const std::function<void(double t0, double gamma, double selected)>& check) {
  const std::vector<double> t = scales(0.01, 100, 8);
  for (double t0 : {0.05, 0.3, 2.0})
    for (double gamma : {0.75, 1.0, 1.25}) {
      std::vector<double> f;
      for (double ti : t) f.push_back(strength(t0 + ti));
      check(t0, gamma, select_scale(t, f.data(), 1, gamma));
    }
}
}  // namespace

TEST(ScaleSelection, GaussianRidgePeaksWhereEquation511Says) {
  // Gaussians convolve into a Gaussian of summed variance.
  auto strength = [](double T) {
    auto s = [T](double x) { return std::exp(-x * x / (2 * T)) / std::sqrt(2 * M_PI * T); };
    return std::abs(curvature(s, 0, 1e-3 * std::sqrt(T)));
  };
  for_each_case(strength, [](double t0, double gamma, double selected) {
    EXPECT_NEAR(selected / ridge_optimal_scale(t0, gamma), 1.0, 0.01) << "t0 " << t0 << " gamma " << gamma;
    // The thesis' printed eq. 5.11, 2 t0 / (3 - 2 gamma), holds at gamma = 1 only.
    const double printed = 2 * t0 / (3 - 2 * gamma);
    if (gamma == 1.0) EXPECT_NEAR(selected / printed, 1.0, 0.01);
    else EXPECT_GT(std::abs(selected / printed - 1), 0.2);
  });
}

TEST(ScaleSelection, UnitStepPeaksWhereEquation515Says) {
  auto strength = [](double T) {
    auto s = [T](double x) { return 0.5 * std::erfc(-x / std::sqrt(2 * T)); };  // unit step, smoothed
    return std::abs(curvature_derivative(s, 1e-3 * std::sqrt(T)));
  };
  for_each_case(strength, [](double t0, double gamma, double selected) {
    const double truth = relief_edge_optimal_scale_unit_step(t0, gamma);
    std::printf("t0 %.2f gamma %.2f: selected %.4f, eq. 5.15 %.4f, scale-free form %.4f\n", t0, gamma, selected,
                truth, relief_edge_optimal_scale(t0, gamma));
    EXPECT_NEAR(selected / truth, 1.0, 0.01) << "t0 " << t0 << " gamma " << gamma;
  });
}

TEST(ScaleSelection, ScaleFreeStepSelectionIgnoresHeightAndUnit) {
  // The small-slope strength -s''' of a step of height H: the selected scale is the same for any
  // H, and scales with the square of the unit (t is an area), unlike eq. 5.15.
  const std::vector<double> base = scales(0.01, 100, 8);
  for (double unit : {1e-3, 1.0, 1e3})
    for (double H : {0.01, 1.0, 50.0}) {
      const double t0 = 0.3 * unit * unit;
      std::vector<double> t, f;
      for (double b : base) {
        t.push_back(b * unit * unit);
        const double T = t0 + t.back(), h = 1e-3 * std::sqrt(T);
        auto s = [T, H, unit](double x) { return H * unit * 0.5 * std::erfc(-x / std::sqrt(2 * T)); };
        f.push_back(std::abs((s(2 * h) - 2 * s(h) + 2 * s(-h) - s(-2 * h)) / (2 * h * h * h)));  // s'''(0)
      }
      const double selected = select_scale(t, f.data(), 1, 1.0) / (unit * unit);
      EXPECT_NEAR(selected / relief_edge_optimal_scale(0.3, 1.0), 1.0, 0.01) << "unit " << unit << " H " << H;
    }
}

TEST(ScaleSelection, FlatOrUnbracketedStrengths) {
  const std::vector<double> t = scales(1, 16, 2);
  const std::vector<double> zero(t.size(), 0.0), rising(t.size(), 1.0);
  EXPECT_EQ(select_scale(t, zero.data(), 1, 1.0), 0.0);
  EXPECT_EQ(select_scale(t, rising.data(), 1, 1.0), t.back());  // t^1 * 1 grows: peak beyond the range
  // A strided view: the second of two interleaved columns.
  std::vector<double> two(2 * t.size(), 0.0);
  for (size_t k = 0; k < t.size(); ++k) two[2 * k + 1] = 1.0 / (t[k] * t[k]);  // t f falls: the first scale
  EXPECT_EQ(select_scale(t, two.data() + 1, 2, 1.0), t.front());
}

// The bracketing of a scale between two levels (log σ of 1, 2, 4, 8 edge lengths): the levels around
// it and its weight, linear in log σ; outside the range the end level; one level, itself.
TEST(ScaleSelection, BracketsAScaleBetweenTwoLevels) {
  const std::vector<double> u = {0.0, std::log(2.0), std::log(4.0), std::log(8.0)};
  struct Case {
    double sigma;
    int lower, upper;
    double weight;
  };
  for (const Case& c : {Case{1.0, 0, 1, 0.0}, Case{std::sqrt(2.0), 0, 1, 0.5}, Case{2.0, 0, 1, 1.0},
                        Case{2.0 * std::pow(2.0, 0.25), 1, 2, 0.25}, Case{8.0, 2, 3, 1.0}, Case{0.5, 0, 1, 0.0},
                        Case{100.0, 2, 3, 1.0}}) {
    const ScaleBracket b = bracket_scale(u, std::log(c.sigma));
    EXPECT_EQ(b.lower, c.lower) << c.sigma;
    EXPECT_EQ(b.upper, c.upper) << c.sigma;
    EXPECT_NEAR(b.weight, c.weight, 1e-12) << c.sigma;
  }
  // Between the levels of 2 and 4 at a quarter: a quarter of the way from level 1's value to level 2's.
  EXPECT_DOUBLE_EQ(bracket_scale(u, std::log(2.0 * std::pow(2.0, 0.25))).mix(10.0, 30.0), 15.0);
  const ScaleBracket single = bracket_scale({std::log(3.0)}, std::log(5.0));
  EXPECT_EQ(single.lower, 0);
  EXPECT_EQ(single.upper, 0);
  EXPECT_EQ(single.weight, 0.0);
}
