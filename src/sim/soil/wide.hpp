// Four-wide (AVX2) forms of the soil's hottest loops, for the machines that have it: the blades'
// two mobilised shares of every arc sample, 864 exponentials a step for six wheels (3 lanes × 24
// samples × 2 each); Bekker's power e^(n ln z) of every sample's depth (432 logarithms and
// exponentials); the shear displacement's transport along the arc and a bladed lane's six sums
// (wheel_soil.cpp); and the rim's clearance above the grid's surface at four angles of the exit
// and front searches (soft_soil.cpp), up to 16 looks at the grid each. Each lane takes the same
// operations, in the same order, as the forms they stand in for (fast_math.hpp, wheel_stress.hpp,
// wheel_soil.cpp, soft_soil.cpp; no fused multiply-adds: -ffp-contract=off), so a run gives the
// same bits whether or not its machine has AVX2 (tested bit for bit). Elsewhere, and on other
// processors, available() is false and those forms do all the work (BENCHMARKS.md).
#pragma once

namespace marsokhod::sim::soil {
struct GridSpec;  // soil_grid.hpp
}  // namespace marsokhod::sim::soil

namespace marsokhod::sim::soil::wide {

// Whether this process runs the four-wide loops: x86-64 with AVX2 (decided once), unless turned
// off with use(false) (tests and benchmarks: the same run on the two-wide forms alone).
bool available();
void use(bool wide);

// For k < count, four at a time while four remain: with the blade's axes (BladeFrame),
// across[k] and along[k] the signed mobilised shares 1 − e^(−|d|/K) of the displacements
// d = jt[k]·across_t + jy[k]·across_y and jt[k]·along_t + jy[k]·along_y. Returns how many
// samples it did (a multiple of 4). Only when available().
int blade_shares(const double* jt, const double* jy, int count, double across_t, double across_y,
                 double along_t, double along_y, double inverse_shear_modulus_per_m,
                 double* across, double* along);

// In place, four at a time from the first sample while every depth of the four is a normal
// positive double and its power's exponent is ≤ 0: values[k] = modulus · z^n, the cosine in,
// z = radius·max(cos − cos_entry, 0). Returns how many samples it did (a multiple of 4); the
// two-wide loop takes the rest. Only when available().
int bekker_stresses(double modulus_pa, double cos_entry, double radius_m, double exponent_n,
                    double* values, int count);

// A rim's clearance above the soil at four angles θ toward `side` from its bottom (sines and
// cosines given): with the rim's point p = axis + (r·sin θ)·side − (r·cos θ)·up,
// clearance = ((p_z − surface(p_x, p_y)) − bottom_m) − touch_m, the surface interpolated as
// SoilGrid::surface_m does from the grid's cell levels (SoilGrid::cell_surfaces_m), every
// operation in its order: the same bits as RimClearance::operator() in soft_soil.cpp (tested).
// Only when available().
void rim_clearances(const GridSpec& grid, const double* levels_m, const double* axis,
                    const double* side, const double* up, double radius_m, double bottom_m,
                    double touch_m, const double* sines, const double* cosines,
                    double* clearances_m);

// The shear displacement's transport along a lane's arc (WheelSoilContact::advect_lane), four
// samples at a time from the last one back, k = samples − 1, samples − 2, … in groups of four
// while a whole group lies at or above first:
//   j[k] = ((1 − fraction)·j[k − whole] + fraction·j[k − whole − 1]) + step_k,
// step_k = (spin_term − travel·cosines[k])·dt for jt, lateral_step for jy, where the sample loads
// (its step runs along its displacement, or either is 0); reads before it writes, as the
// one-by-one loop does in place (whole ≥ 0). A sample that unloads keeps the interpolated value
// and is listed in `unloading` (2k for jt, 2k + 1 for jy; room for 2·samples) for the caller's
// unloading branch. With `peak` (the tangential reload memory, else nullptr) the peaks move the
// same way, peak[k] = (1 − fraction)·peak[k − whole] + fraction·peak[k − whole − 1], and a jt
// sample whose peak is not 0 is listed too (it may reload), its interpolated value kept. Returns
// the sample it stopped at (the one-by-one loop does it and those before). Only when available().
int advect_loading(double* jt, double* jy, double* peak, const double* cosines, int samples,
                   int first, int whole, double fraction, double spin_term, double travel_mps,
                   double dt_s, double lateral_step_m, int* unloading, int& unloading_count);

// What a bladed lane's sample k sums into its wrench (WheelSoilContact::add_lane_stresses), the
// soil's strength and the blades' axes given: with σ = sigmas[k] and the shares across[k],
// along[k],
//   strength = cohesion + σ·tan φ, across = strength·across_k, along = σ·tan δ·along_k,
//   τ_t = across·across_t + along·along_t, τ_y = across·across_y + along·along_y,
//   normal = (σ·r)·area, tangential = (τ_t·r_s)·area, lateral = (τ_y·r_s)·area,
// and into the six sums fx += tangential·cos − normal·sin, fy += lateral,
// fz += normal·cos + tangential·sin, mx += (lateral·r_s)·cos, my −= tangential·r_s,
// mz += (lateral·r_s)·sin. BladedSums holds them four-wide: lane j sums the samples k ≡ j (mod 4)
// of the first count − count mod 4, in order from 0.
struct BladedSample {
  double cohesion_pa, tan_friction, tan_metal_friction;
  double across_t, across_y, along_t, along_y;
  double rim_radius_m, shear_radius_m, area;
};
struct BladedSums {
  double fx[4], fy[4], fz[4], mx[4], my[4], mz[4];
};
// Only when available().
void bladed_sums(const BladedSample& sample, const double* sines, const double* cosines,
                 const double* sigmas, const double* across, const double* along, int count,
                 BladedSums& sums);

}  // namespace marsokhod::sim::soil::wide
