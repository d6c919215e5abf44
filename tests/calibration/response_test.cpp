// Procedure 4.8 (response): the least-squares δ on synthetic chirps (exact, too short, one
// frequency, noisy) and the procedure against the simulator's chain.
#include "calibration/response.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "calibration/procedures.hpp"
#include "core/adaptation/motor_curve.hpp"
#include "core/adaptation/no_load_estimator.hpp"
#include "sim/electrics/motor_model.hpp"
#include "motor_unit_support.hpp"

namespace marsokhod::calibration {
namespace {

using testing::mentions;

const std::vector<double> kChain{0.0, 0.20, 0.40, 0.29, 0.10};

// ŵ the procedure's chirp (or one frequency), w = Σ δ^j ŵ with the bench's indexing, plus noise.
ResponseSeries synthetic(double seconds, bool one_frequency, double noise_radps,
                         unsigned seed = 1) {
  constexpr double h = 0.0156;
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, noise_radps);
  Chirp chirp;
  chirp.duration_s = seconds;
  ResponseSeries s;
  for (double t = 0.0; t < seconds; t += h) {
    s.commanded_radps.push_back(one_frequency ? 1.2 + 0.3 * std::sin(2.0 * std::numbers::pi * 2.0 * t)
                                              : chirp(t));
  }
  s.measured_radps = predict_response(kChain, s.commanded_radps);
  for (double& w : s.measured_radps) w += noise_radps > 0.0 ? noise(random) : 0.0;
  return s;
}

TEST(ResponseFit, RecoversTheCoefficientsOfAChirp) {
  const ResponseFit fit = fit_response({synthetic(60.0, false, 0.005)}, {});
  ASSERT_TRUE(fit.problems.empty()) << fit.problems.front();
  ASSERT_EQ(fit.delta.size(), 8u);
  EXPECT_EQ(fit.delta[0], 0.0);
  for (std::size_t j = 1; j < 8; ++j) {
    EXPECT_NEAR(fit.delta[j], j < kChain.size() ? kChain[j] : 0.0, 0.01) << j;
  }
  EXPECT_NEAR(fit.sum, 0.99, 0.01);
}

TEST(ResponseFit, PredictionIsTheThesisExample) {
  // Example 4.10: ŵ³…ŵ⁶ = 0.5, 0.6, 0.65, 0.7 give ν⁷ = 0.6332 (history before ŵ³ = 0.5); ŵ⁷
  // (here 9.9) does not count, δ⁰ = 0.
  const std::vector<double> w_hat{0.5, 0.6, 0.65, 0.7, 9.9};
  const std::vector<double> nu = predict_response({0.0, 0.2452, 0.3742, 0.2798, 0.1008}, w_hat);
  EXPECT_NEAR(nu[4], 0.2452 * 0.7 + 0.3742 * 0.65 + 0.2798 * 0.6 + 0.1008 * 0.5, 1e-12);
  EXPECT_NEAR(nu[4], 0.6332, 5e-5);
}

TEST(ResponseFit, RefusesAChirpTooShort) {
  const ResponseFit fit = fit_response({synthetic(10.0, false, 0.0)}, {});
  EXPECT_TRUE(mentions(fit.problems, "too short"));
}

TEST(ResponseFit, RefusesOneFrequency) {
  // A single sinusoid determines two coefficients, not five.
  const ResponseFit fit = fit_response({synthetic(60.0, true, 0.001)}, {});
  ASSERT_FALSE(fit.problems.empty());
  EXPECT_TRUE(mentions(fit.problems, "not determined") ||
              mentions(fit.problems, "too few frequencies"))
      << fit.problems.front();
}

TEST(ResponseFit, RefusesNoisyData) {
  const ResponseFit fit = fit_response({synthetic(40.0, false, 0.2)}, {});
  EXPECT_TRUE(mentions(fit.problems, "too noisy"));
}

// The simulator's chain on the stand, from its own parts: the motor's lag (MotorModel, the
// unit's τ), the free wheel's inertia against the droop B± (torque (ω0 − ω)/B, the reflected
// rotor and the wheel) and µi's velocity window of T(con) ending at the request (the thesis'
// indexing: w^k is sampled when the request of cycle k arrives). Its least-squares δ on the
// procedure's chirp is what Procedure 4.8 on the stand must find. (sim_truth.hpp's
// (0, 0.20, 0.40, 0.29, 0.10) is the chain without the wheel's inertia.)
std::vector<double> chain_delta(const sim::MotorTruth& motor, double seconds) {
  constexpr double h = 0.0156;
  constexpr double dt = 0.0001;
  constexpr double inertia = 0.42 + 0.5 * 6.0 * 0.125 * 0.125;  // rover_mjcf.hpp
  const double window = 65536.0 / 2e6;                          // T(con = 0)
  const adaptation::MotorCurve curve(Params{}.motor_curves.front());
  sim::MotorModel model(motor);
  Chirp chirp;
  chirp.duration_s = seconds;
  chirp.period_s = h;
  chirp.end_hz = 0.45 / h;
  chirp.max_step_radps = 0.8 * 0.05 * 3.0;
  ResponseSeries series;
  std::vector<double> angle_history;  // every dt
  double angle = 0.0;
  double omega = 0.0;
  const auto cycles = static_cast<std::size_t>(seconds / h);
  const auto steps_per_cycle = static_cast<std::size_t>(std::lround(h / dt));
  const auto window_steps = static_cast<std::size_t>(std::lround(window / dt));
  for (std::size_t k = 0; k < cycles; ++k) {
    // The request of cycle k arrives: vel is sampled, then the new duty applies.
    if (angle_history.size() > window_steps) {
      series.measured_radps.push_back(
          (angle - angle_history[angle_history.size() - 1 - window_steps]) / window);
    } else {
      series.measured_radps.push_back(0.0);
    }
    const double duty = curve.duty(chirp(static_cast<double>(k) * h));
    series.commanded_radps.push_back(sim::steady_no_load_speed_radps(motor, duty, 24.0, 511));
    for (std::size_t i = 0; i < steps_per_cycle; ++i) {
      const sim::MotorLine line = model.step(duty, 24.0, 511, omega, dt);
      const double tau_m = inertia * line.droop_radps_per_nm;
      omega = line.no_load_speed_radps + (omega - line.no_load_speed_radps) * std::exp(-dt / tau_m);
      angle += omega * dt;
      angle_history.push_back(angle);
    }
  }
  // Bench order: v_m is the velocity sampled at request m (measured_radps[m]).
  series.commanded_radps.erase(series.commanded_radps.begin(), series.commanded_radps.begin() + 200);
  series.measured_radps.erase(series.measured_radps.begin(), series.measured_radps.begin() + 200);
  ResponseFitSettings settings;
  settings.period_s = h;
  return fit_response({series}, settings).delta;
}

TEST(ResponseSim, RecoversTheChainOfTheSimulatedStandWhereTheThesisTableIsOff) {
  const testing::TestUnit unit = testing::drawn_unit(31);
  const ProcedureResult result = testing::calibrate_unit(unit, "response", 60.0);
  ASSERT_TRUE(result.accepted()) << result.problems.front();
  const toml::array& responses = *result.values["response"].as_array();
  ASSERT_EQ(responses.size(), 1u);
  const toml::table& entry = *responses[0].as_table();
  EXPECT_EQ(entry["con"].value<int>(), 0);
  const toml::array& delta = *entry["delta"].as_array();
  ASSERT_EQ(delta.size(), 8u);
  // The chain of the front-left wheel (the wheels differ only by a ±2 ms lag).
  const std::vector<double> truth = chain_delta(unit.truth.motors[0], 60.0);
  // The fit sits 0.030–0.051 below the reference at δ² on units 1–6 and 31 (31 the worst; it was
  // 0.049 before the supply's current law of the twelfth session), a bias of the reference more
  // than of the fit: it moves by 0.01 for 0.1 V of the supply it assumes (24 V; the dead zone
  // makes the chain depend on U), and the bench's tether sags with the current drawn. The
  // thesis' table is 0.15 off.
  constexpr double kTolerance = 0.055;
  const std::vector<double> thesis{0.0, 0.2452, 0.3742, 0.2798, 0.1008, 0.0, 0.0, 0.0};
  double thesis_worst = 0.0;
  for (std::size_t j = 0; j < 8; ++j) {
    EXPECT_NEAR(*delta[j].value<double>(), truth[j], kTolerance) << "δ^" << j;
    thesis_worst = std::max(thesis_worst, std::abs(thesis[j] - truth[j]));
  }
  EXPECT_GT(thesis_worst, kTolerance) << "the thesis' δ would pass: the test proves nothing";
  // The fitted file loads and the driver picks it for (h, con).
  const Params fitted = config::apply_calibration_values(testing::config_file(), result.values);
  EXPECT_EQ(adaptation::select_response(fitted.responses, fitted.cycle.period_s, 0).delta.size(),
            8u);
}

// A drawn unit: on a held-out chirp, ν with the fitted δ predicts w better than the thesis' δ.
TEST(ResponseSim, PredictsAHeldOutChirpBetterThanTheNominalTable) {
  const testing::TestUnit unit = testing::drawn_unit(21);
  SimBench bench(unit.params, testing::unit_options(unit));
  ProcedureOptions procedure;
  procedure.duration_s = 60.0;
  const ProcedureResult result = run_procedure(bench, "response", procedure);
  ASSERT_TRUE(result.accepted()) << result.problems.front();
  std::vector<double> fitted;
  for (const auto& d : *result.values["response"][0]["delta"].as_array()) {
    fitted.push_back(*d.value<double>());
  }
  procedure.duration_s = 40.0;  // a different chirp: the held-out data
  const ProcedureResult held_out = run_procedure(bench, "response", procedure);
  const Recording& chirp = held_out.recordings.at(1);
  ASSERT_EQ(chirp.columns[1], "w_hat_radps");
  ASSERT_EQ(chirp.columns[2], "w_radps");
  std::vector<double> w_hat;
  std::vector<double> w;
  for (const auto& row : chirp.rows) {
    w_hat.push_back(row[1]);
    w.push_back(row[2]);
  }
  auto rms_error = [&](const std::vector<double>& delta) {
    const std::vector<double> nu = predict_response(delta, w_hat);
    double sum = 0.0;
    for (std::size_t m = 10; m < w.size(); ++m) sum += (w[m] - nu[m]) * (w[m] - nu[m]);
    return std::sqrt(sum / static_cast<double>(w.size() - 10));
  };
  const double fitted_error = rms_error(fitted);
  const double nominal_error = rms_error(unit.params.responses.front().delta);
  EXPECT_LT(fitted_error, 0.9 * nominal_error)
      << "fitted " << fitted_error << " rad/s, nominal " << nominal_error << " rad/s";
}

}  // namespace
}  // namespace marsokhod::calibration
