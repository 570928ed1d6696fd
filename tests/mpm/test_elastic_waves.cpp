// Elastic verification: axial vibration of a bar (period and amplitude against the analytic
// first mode, error falling with refinement) and a column settling under gravity.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "mpm/driver.h"
#include "support.h"

namespace mpm_lig::mpm {
namespace {

// cases/mpm/bar_vibration.json
constexpr double kLength = 1.0, kWaveSpeed = 10.0, kV0 = 0.01;
const double kOmega = kPi * kWaveSpeed / (2.0 * kLength);

struct BarResult {
  double period_error;     // relative, mean period from zero crossings
  double amplitude_error;  // relative, largest |A(t)| over the run
};

//! Runs the bar with `cells` cells along it and tracks the modal amplitude
//! A(t) = sum m u sin(pi X/2L) / sum m sin^2(pi X/2L) of the point displacements u.
BarResult run_bar(int cells, const std::string& shape) {
  MpmProblem c = testing::load_case("bar_vibration", [&](nlohmann::json& j) {
    const double h = kLength / cells;
    j["mesh"]["size"] = {kLength + 2 * h, h};
    j["mesh"]["cells"] = {cells + 2, 1};
    j["bodies"][0]["box"]["max"] = {kLength, h};
    j["boundary_conditions"][1]["nodes"]["box"]["max"] = {kLength + 2 * h, h};
    j["analysis"]["shape_function"] = shape;
    j["output"]["fields"] = false;
  });
  std::vector<double> times, amplitude;
  run_case<2>(std::move(c), "", [&](const Solver<2>& s) {
    const auto& p = s.particles();
    double num = 0.0, den = 0.0;
    for (std::size_t k = 0; k < p.size(); ++k) {
      const double mode = std::sin(0.5 * kPi * p.reference[k].x() / kLength);
      num += p.mass[k] * (p.position[k].x() - p.reference[k].x()) * mode;
      den += p.mass[k] * mode * mode;
    }
    times.push_back(s.time());
    amplitude.push_back(num / den);
  });
  // Downward zero crossings of A(t) (A = a sin(omega t) starts upward), linearly interpolated.
  std::vector<double> crossings;
  double peak = 0.0;
  for (std::size_t k = 1; k < times.size(); ++k) {
    peak = std::max(peak, std::abs(amplitude[k]));
    if (amplitude[k - 1] > 0.0 && amplitude[k] <= 0.0) {
      const double f = amplitude[k - 1] / (amplitude[k - 1] - amplitude[k]);
      crossings.push_back(times[k - 1] + f * (times[k] - times[k - 1]));
    }
  }
  EXPECT_GE(crossings.size(), 2u);
  const double period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  const double exact_period = 2.0 * kPi / kOmega, exact_amplitude = kV0 / kOmega;
  return {std::abs(period / exact_period - 1.0), std::abs(peak / exact_amplitude - 1.0)};
}

TEST(BarVibration, PeriodAndAmplitudeWithinOnePercentAndConverge) {
  for (const std::string shape : {"linear", "gimp"}) {
    const BarResult coarse = run_bar(10, shape);
    const BarResult fine = run_bar(20, shape);
    RecordProperty(shape + "_period_error_10", std::to_string(coarse.period_error));
    RecordProperty(shape + "_period_error_20", std::to_string(fine.period_error));
    std::printf("%s: period error %.3e (10 cells) %.3e (20 cells); amplitude error %.3e %.3e\n",
                shape.c_str(), coarse.period_error, fine.period_error, coarse.amplitude_error,
                fine.amplitude_error);
    EXPECT_LT(coarse.period_error, 0.01) << shape;
    EXPECT_LT(fine.period_error, 0.01) << shape;
    EXPECT_LT(coarse.amplitude_error, 0.01) << shape;
    EXPECT_LT(fine.amplitude_error, 0.01) << shape;
    EXPECT_LT(fine.period_error, coarse.period_error) << shape;
  }
}

struct ColumnResult {
  double stress_error_v, stress_error_h;  // max over points, relative to rho g H
  double base_reaction_error;             // |reaction of the base - weight| / weight
  double time_step;
};

//! The column of cases/mpm/elastic_column.json, in 2D or as a 3D prism, compared at the end
//! with sigma_v = -rho g (H - Y), sigma_h = K0 sigma_v, Y the initial height of the point.
template <int D>
ColumnResult run_column(double mass_scaling) {
  MpmProblem c = testing::load_case("elastic_column", [&](nlohmann::json& j) {
    j["output"]["fields"] = false;
    j["analysis"]["mass_scaling"] = mass_scaling;
    if (D == 3) {
      j["dimension"] = 3;
      j["mesh"] = {{"origin", {0, 0, 0}}, {"size", {0.1, 0.1, 1.2}}, {"cells", {1, 1, 24}}};
      j["bodies"][0]["box"] = {{"min", {0, 0, 0}}, {"max", {0.1, 0.1, 1.0}}};
      j["boundary_conditions"] = {
          {{"type", "fixed"}, {"nodes", {{"face", "z-"}}}},
          {{"type", "roller"}, {"nodes", {{"face", "x-"}}}, {"direction", "x"}},
          {{"type", "roller"}, {"nodes", {{"face", "x+"}}}, {"direction", "x"}},
          {{"type", "roller"}, {"nodes", {{"face", "y-"}}}, {"direction", "y"}},
          {{"type", "roller"}, {"nodes", {{"face", "y+"}}}, {"direction", "y"}}};
      j["gravity"] = {0, 0, -9.81};
    }
  });
  const double rho = 2000.0, g = 9.81, height = 1.0, nu = 0.25, width = 0.1;
  const double k0 = nu / (1.0 - nu), bottom = rho * g * height;
  const double weight = bottom * std::pow(width, D - 1);
  ColumnResult r{0.0, 0.0, 0.0, 0.0};
  const MpmCase spec = c.spec;  // c's materials move into the run
  run_case<D>(std::move(c), "", [&](const Solver<D>& s) {
    r.time_step = s.dt();
    if (s.steps() != main_stage_steps(spec, s.dt()))
      return;
    const auto& p = s.particles();
    for (std::size_t k = 0; k < p.size(); ++k) {
      const double sigma_v = -rho * g * (height - p.reference[k][D - 1]);
      r.stress_error_v =
          std::max(r.stress_error_v, std::abs(p.stress[k](D - 1, D - 1) - sigma_v) / bottom);
      r.stress_error_h =
          std::max(r.stress_error_h, std::abs(p.stress[k](0, 0) - k0 * sigma_v) / bottom);
    }
    // The base (constraint 0) carries the whole weight.
    r.base_reaction_error = std::abs(s.constraints().reaction(0)[D - 1] - weight) / weight;
  });
  std::printf(
      "column %dD, mass scaling %g: max |sigma_v - rho g h| / (rho g H) = %.3e, "
      "sigma_h (K0) %.3e, base reaction error %.3e\n",
      D, mass_scaling, r.stress_error_v, r.stress_error_h, r.base_reaction_error);
  return r;
}

void expect_column_at_rest(const ColumnResult& r) {
  EXPECT_LT(r.stress_error_v, 0.02);
  EXPECT_LT(r.stress_error_h, 0.02);
  EXPECT_LT(r.base_reaction_error, 0.01);
}

TEST(ElasticColumn, VerticalStressIsTheWeightAbove) {
  expect_column_at_rest(run_column<2>(1.0));
}

TEST(ElasticColumn, ThreeDimensional) {
  expect_column_at_rest(run_column<3>(1.0));
}

TEST(ElasticColumn, MassScalingKeepsTheStaticAnswerWithLargerSteps) {
  const ColumnResult plain = run_column<2>(1.0), scaled = run_column<2>(4.0);
  expect_column_at_rest(scaled);
  EXPECT_NEAR(scaled.time_step / plain.time_step, 2.0, 1e-12);
}

TEST(ElasticColumn, PrescribedVelocityCompressesUniformly) {
  // Weightless column compressed by its top node row moving down at v ramped over 0.5 s:
  // oedometric, so sigma_yy = -M u / H everywhere and the top reaction is that times width.
  const double v = 1e-3, ramp = 0.5, height = 1.0, width = 0.1;
  const double youngs = 1e7, nu = 0.25;
  const double m = youngs * (1 - nu) / ((1 + nu) * (1 - 2 * nu));
  MpmProblem c = testing::load_case("elastic_column", [&](nlohmann::json& j) {
    j["output"]["fields"] = false;
    j["gravity"] = {0, 0};
    // Linear: with GIMP the points of the top cell come out stiffer by u/h (3.5 % here), as
    // the material surface moves away from the prescribed node row (README, method).
    j["analysis"]["shape_function"] = "linear";
    j["boundary_conditions"].push_back(
        {{"type", "velocity"},
         // Every node from the top of the column up: with GIMP the top points also reach
         // the node row above it.
         {"nodes", {{"box", {{"min", {0, height}}, {"max", {width, 1.2}}}}}},
         {"direction", "y"},
         {"velocity", -v},
         {"function", {{"type", "ramp"}, {"time", ramp}}}});
  });
  double worst = 0.0, reaction_error = 0.0, strain = 0.0;
  const MpmCase spec = c.spec;  // c's materials move into the run
  run_case<2>(std::move(c), "", [&](const Solver<2>& s) {
    if (s.steps() != main_stage_steps(spec, s.dt()))
      return;
    // Displacement of the top: the integral of the ramped velocity up to the last step's start
    // (the step uses the velocity at its start time).
    const double t = s.time() - s.dt();
    const double u = v * (t > ramp ? t - 0.5 * ramp : t * t / (2 * ramp)) + v * s.dt();
    strain = u / height;
    const double sigma = -m * strain;
    for (const Mat3& stress : s.particles().stress)
      worst = std::max(worst, std::abs(stress(1, 1) - sigma) / std::abs(sigma));
    reaction_error =
        std::abs(s.constraints().reaction(3)[1] - sigma * width) / std::abs(sigma * width);
  });
  std::printf("prescribed velocity: strain %.3e, max stress error %.3e, top reaction error %.3e\n",
              strain, worst, reaction_error);
  EXPECT_LT(worst, 0.01);
  EXPECT_LT(reaction_error, 0.01);
}

}  // namespace
}  // namespace mpm_lig::mpm
