#include "runner/soil_metrics.hpp"

#include "sim/physics/rover_mjcf.hpp"
#include "sim/soil/soft_soil.hpp"

namespace marsokhod::runner {
namespace {

// The mean over `wheels` of the ground's depth below its initial surface under each hub.
template <std::size_t N>
double mean_rut_depth_m(const sim::soil::SoilGrid& grid, const sim::GroundTruth& truth,
                        const std::array<MotorIndex, N>& wheels) {
  constexpr double kHalfSpanM = 0.5 * sim::kWheelWidthM;
  double sum = 0.0;
  for (MotorIndex wheel : wheels) {
    const auto& hub = truth.wheel_position_m[wheel];
    sum += grid.max_depth_m(hub[0] - kHalfSpanM, hub[1] - kHalfSpanM, hub[0] + kHalfSpanM,
                            hub[1] + kHalfSpanM);
  }
  return sum / static_cast<double>(N);
}

}  // namespace

const std::vector<std::string>& soil_metric_names() {
  static const std::vector<std::string> names = {
      "soil_cut_m3",          "soil_fill_m3",           "soil_disturbed_m3",
      "soil_compacted_m3",    "soil_mean_compaction_m", "soil_max_depth_m",
      "soil_max_sinkage_excess_m",
      "final_exterior_rut_depth_m", "final_center_rut_depth_m", "final_trench_depth_m",
      "soil_disturbed_per_m_m3", "soil_compacted_per_m_m3"};
  return names;
}

void add_soil_metrics(const Session& session, double distance_m,
                      std::map<std::string, double>& m) {
  const sim::soil::SoftSoil* soil = session.rover().soft_soil();
  if (soil == nullptr) return;
  const sim::soil::SoilGrid& grid = soil->grid();
  const sim::soil::SoilVolumes& v = grid.volumes();
  const sim::soil::Earthwork earthwork = grid.earthwork();
  const double disturbed = earthwork.cut_m3 + earthwork.fill_m3;
  const double area = grid.compacted_area_m2();
  m["soil_cut_m3"] = earthwork.cut_m3;
  m["soil_fill_m3"] = earthwork.fill_m3;
  m["soil_disturbed_m3"] = disturbed;
  m["soil_compacted_m3"] = v.compacted_m3;
  m["soil_mean_compaction_m"] = area > 0.0 ? v.compacted_m3 / area : 0.0;
  m["soil_max_depth_m"] = grid.deepest_m();
  m["soil_max_sinkage_excess_m"] = grid.max_sinkage_excess_m();
  const sim::GroundTruth truth = session.rover().truth();
  m["final_exterior_rut_depth_m"] = mean_rut_depth_m(
      grid, truth, std::array{kFrontLeft, kFrontRight, kBackLeft, kBackRight});
  m["final_center_rut_depth_m"] =
      mean_rut_depth_m(grid, truth, std::array{kCenterLeft, kCenterRight});
  m["final_trench_depth_m"] = m["final_exterior_rut_depth_m"] - m["final_center_rut_depth_m"];
  if (distance_m >= kMinProgressM) {
    m["soil_disturbed_per_m_m3"] = disturbed / distance_m;
    m["soil_compacted_per_m_m3"] = v.compacted_m3 / distance_m;
  }
}

}  // namespace marsokhod::runner
