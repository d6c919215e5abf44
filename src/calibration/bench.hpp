// The calibration bench: the procedures of chapters 3.3, 4 and 5.1 talk to the rover's nine
// controllers directly, without the driver's control laws. A Bench runs in cycles of h like the
// driver: each cycle it sends a 0xi0 to µ0–µ7 with the duty cycles the procedure asks for (moved
// by chapter 3.2's rules: small steps, drv toggling only at pwm ≈ 0) and a 0x80 to µ8, and returns
// what came back, tracked into physical units by core/tracking.
//
// What a procedure needs of the rover's surroundings (on a stand with an axis along gravity, a
// laboratory supply at some voltage, a weight strapped to a wheel) it asks for with arrange():
// the simulated bench does it itself; on a real bus the operator is told what to do and the
// bench waits for them.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/params.hpp"
#include "core/protocol/can_frame.hpp"
#include "core/protocol/messages.hpp"
#include "core/tracking/motor_tracker.hpp"
#include "core/tracking/sensor_tracker.hpp"
#include "driver/frame_intake.hpp"

namespace marsokhod::bus {
class CanTransport;
}
namespace marsokhod::sim {
class SimulatedRover;
struct SimOptions;
enum class SupplyKind : std::uint8_t;
}

namespace marsokhod::calibration {

// A controller that does not answer, a bus that went away, an operator who gave up.
class BenchError : public std::runtime_error {
 public:
  using runtime_error::runtime_error;
};

// One cycle of the bench.
struct BenchSample {
  double time_s = 0.0;                    // k·h since start()
  MotorVector duty{};                     // what was sent this cycle (after the rules)
  MotorVector position_rad{};             // p̄_i (3.2), the latest known
  MotorVector velocity_radps{};           // w̄_i (3.3), the latest known
  std::array<bool, kMotorCount> fresh{};  // µi's response arrived this cycle
  // µ8's raw 10-bit readings this cycle (yaw, acc¹..³, tlt, vcc), if its response arrived.
  std::optional<protocol::MeasurementResponse> raw;
  tracking::SensorState sensors;          // converted with the configured constants (latest)
};

// Where the rover is and what surrounds it.
struct BenchSetup {
  enum class Placement : std::uint8_t { kGround, kStand };
  Placement placement = Placement::kGround;
  // On the stand: the chassis is held in the air, all wheels free, turned by roll about x1 then
  // pitch about x2 (right-hand rule; roll = +π/2 puts the left side up, +x2 along −g… see
  // SimBench). Used by Procedure 3.3 to bring one accelerometer axis along ±g.
  double stand_roll_rad = 0.0;
  double stand_pitch_rad = 0.0;
  std::optional<double> supply_v;  // a laboratory supply (tether) set to this voltage
  // A weight strapped to a wheel (Procedure 4.13): its gravity torque on the wheel has this peak.
  std::optional<std::size_t> weight_wheel;
  double weight_peak_torque_nm = 0.0;
  // Procedure 4.1: on the ground, strapped down so that neither the wheels rotate nor the joints
  // incline (the simulated bench blocks every wheel; the axles then cannot move over the ground).
  bool strapped_down = false;
  // Procedure 3.4: the exterior axles (0 front, 1 rear) turned by hand to this roll θ relative to
  // the center axle and held there; beyond ±30° the axle rests on its stop. nullopt: let go.
  std::array<std::optional<double>, 2> axle_tilt_rad{};
  // What the operator of a real rover must do to get here ("Put the rover on its left side…").
  std::string instruction;
};

// The stand with all six wheels free, powered from the laboratory supply set to Ū (the motor
// procedures of chapter 4). The instruction says so and goes on with `then`: the rest of the
// sentence and what the wheels will do (" (Procedure 4.4). The wheels will speed up …").
BenchSetup stand_at_nominal_supply(const Params& params, std::string_view then);

class Bench {
 public:
  explicit Bench(const Params& params);
  virtual ~Bench();
  Bench(const Bench&) = delete;
  Bench& operator=(const Bench&) = delete;

  // Configures µ0–µ7 (0xi2: icr, pwm = 0, con) and arms µ8's dead man's switch (0x82, the
  // configured dog); throws BenchError naming the controllers that did not acknowledge.
  // icr ∈ 255..2047, con ∈ 0..255 (std::invalid_argument otherwise). Can be called again to
  // change icr or con (the motors are stopped first).
  void start(int icr, int con);
  // One cycle with these duty cycles wanted (clamped to [−1, 1]; the rules of chapter 3.2 move
  // the sent ones toward them). Throws BenchError before start() or when the bus went away.
  const BenchSample& cycle(const MotorVector& wanted_duty);
  // Cycles for `seconds` (rounded to whole cycles, at least one) holding `wanted_duty`; returns
  // every sample.
  std::vector<BenchSample> hold(const MotorVector& wanted_duty, double seconds);
  // Brings every motor to d = 0 by the rules, then waits until all shafts are still (or 3 s).
  void stop();

  // Asks for a setup (see BenchSetup): the simulated bench makes it so; on a real bus the operator is
  // told setup.instruction (and the supply voltage, the weight) and the bench waits for them.
  // The motors are stopped first.
  virtual void arrange(const BenchSetup& setup) = 0;
  // The supply voltage at the power distribution board by an independent instrument (Procedure
  // 3.5's multimeter): the simulator's true terminal voltage; on a real rover the operator types
  // the multimeter's reading. Throws BenchError when the operator gives up.
  virtual double measure_supply_v() = 0;
  // "simulator (seed 7, tether)" or "socketcand://host:29536/can0": for the calibration file.
  virtual std::string source() const = 0;

  const Params& params() const { return params_; }
  double period_s() const { return params_.cycle.period_s; }
  int icr() const { return icr_; }
  int con() const { return con_; }
  const BenchSample& last() const { return sample_; }
  double time_s() const { return sample_.time_s; }
  bool started() const { return started_; }
  std::uint64_t missed_responses() const { return missed_; }

 protected:
  // Puts `requests` on the bus now and returns every frame that arrived during the following
  // period_s (the responses). The simulated bench advances its rover by exactly period_s; the
  // real one waits in real time.
  virtual std::vector<protocol::CanFrame> exchange(const std::vector<protocol::CanFrame>& requests,
                                                   double period_s) = 0;

 private:
  void take(const std::vector<protocol::CanFrame>& frames);
  // Cycles with zero duty and no control requests until every controller acknowledged the
  // configuration and µ8 the dead man's switch.
  void configure();

  Params params_;
  driver::FrameIntake intake_;
  int icr_ = 511;
  int con_ = 0;
  bool started_ = false;
  tracking::AllMotorsTracker motors_;
  tracking::SensorTracker sensors_;
  MotorVector sent_duty_{};
  BenchSample sample_;
  std::array<bool, kMotorCount + 1> expected_{};
  std::uint64_t cycles_ = 0;
  std::uint64_t missed_ = 0;
};

// The simulated rover on a bench of its own (time as a value, as fast as the machine allows),
// with the options' terrain, supply and seed (sim_bench_options() gives the laboratory's: flat
// hard ground, the tether at 24 V). arrange() places it on the stand, sets the tether's voltage
// and straps weights to wheels through the simulator's own API, then lets it settle for 1 s. On a
// soft soil, setting the rover down from the stand first rakes the ground level
// (RoverPhysics::level_soil), as an operator would before each run of Procedure 5.1.
class SimBench final : public Bench {
 public:
  // `params` are the bench's (the driver side's, perhaps calibrated already); the simulated unit is
  // built from `rover_params` (the configuration's nominal values), as the real rover does not
  // change with its calibration file. Without them the unit is built from `params`.
  SimBench(const Params& params, const sim::SimOptions& options);
  SimBench(const Params& params, const sim::SimOptions& options, const Params& rover_params);
  ~SimBench() override;

  void arrange(const BenchSetup& setup) override;
  double measure_supply_v() override;
  std::string source() const override;
  sim::SimulatedRover& rover();

 protected:
  std::vector<protocol::CanFrame> exchange(const std::vector<protocol::CanFrame>& requests,
                                           double period_s) override;

 private:
  std::unique_ptr<Params> rover_params_;  // the simulator keeps a pointer to them
  std::unique_ptr<sim::SimulatedRover> rover_;
  std::uint64_t seed_ = 0;
  sim::SupplyKind supply_;
  std::string soft_soil_;  // the soil's name on a soft-soil ground, else empty
  std::int64_t period_us_ = 0;
  std::int64_t steps_ = 0;
};

// The laboratory: flat hard ground, the tether supply at 24 V, the unit drawn from `seed`.
sim::SimOptions sim_bench_options(std::uint64_t seed);

// A real (or remote) bus: requests go out every h of real time; arrange() prints the
// instruction on `out` and waits for a line on `in` ("q" gives up with a BenchError).
class BusBench final : public Bench {
 public:
  BusBench(const Params& params, std::unique_ptr<bus::CanTransport> transport, std::istream& in,
           std::ostream& out);
  ~BusBench() override;

  void arrange(const BenchSetup& setup) override;
  double measure_supply_v() override;
  std::string source() const override;

 protected:
  std::vector<protocol::CanFrame> exchange(const std::vector<protocol::CanFrame>& requests,
                                           double period_s) override;

 private:
  std::unique_ptr<bus::CanTransport> transport_;
  std::istream* in_;
  std::ostream* out_;
};

}  // namespace marsokhod::calibration
