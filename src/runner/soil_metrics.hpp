// What a run did to deformable ground (sim/soil), read from the soil grid when the run ends. Only a
// ground with soft soil reports these; rigid ground has no grid and reports none of them.
//
//   soil_cut_m3, soil_fill_m3   the earthwork (SoilGrid::earthwork): the volume between the final
//                               and the initial surface where the ground lies lower (ruts,
//                               trenches) and where it lies higher (banks, the soil the blades
//                               threw behind), however often soil went back and forth on the way
//   soil_disturbed_m3           cut + fill — the erosion of chapter 6.3
//   soil_compacted_m3           the volume compacted in place (cut − fill)
//   soil_mean_compaction_m      soil_compacted_m3 over the area of the cells compacted
//   soil_max_depth_m            the deepest point of the ground below its initial surface
//   soil_max_sinkage_excess_m   the most a cell's plastic sinkage exceeded its depth below the
//                               initial surface during the run (SoilGrid::max_sinkage_excess_m):
//                               how far the level the soil's pressure is reckoned from rose: by
//                               soil laid back into pressed ruts until that defect was mended
//                               (2026-12-01); now by banks pressed after they were piled
//   final_exterior_rut_depth_m  the mean over the four exterior wheels of the ground's depth
//   final_center_rut_depth_m    below its initial surface under the wheel at the end (the deepest
//                               cell centre within ±7.5 cm, half the wheel's width, of the hub in
//                               x and y): a trench's depth; the two centre wheels'
//   final_trench_depth_m        final_exterior_rut_depth_m − final_center_rut_depth_m: how much
//                               deeper the exterior wheels stand than the centre ones
//   soil_disturbed_per_m_m3     the same per metre of progress, over distance_m (the net
//   soil_compacted_per_m_m3     displacement); only when the rover got at least kMinProgressM
//                               from its start, else a ratio to noise
#pragma once

#include <map>
#include <string>
#include <vector>

#include "runner/session.hpp"

namespace marsokhod::runner {

inline constexpr double kMinProgressM = 0.05;

const std::vector<std::string>& soil_metric_names();

// Adds the metrics above to `metrics` when the rover stands on soft soil; `distance_m` is the
// run's net displacement.
void add_soil_metrics(const Session& session, double distance_m,
                      std::map<std::string, double>& metrics);

}  // namespace marsokhod::runner
