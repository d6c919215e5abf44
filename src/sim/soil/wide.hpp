// A four-wide (AVX2) form of the soil's most exponential-bound loop, for the machines that have
// it: the blades' two mobilised shares of every arc sample, 864 exponentials a step for six
// wheels (3 lanes × 24 samples × 2 each). Each lane takes the same operations, in the same order,
// as the two-wide form of fast_math.hpp and wheel_stress.hpp (no fused multiply-adds:
// -ffp-contract=off), so a run gives the same bits whether or not its machine has AVX2 (tested
// bit for bit). Elsewhere, and on other processors, available() is false and the two-wide form
// does all the work (BENCHMARKS.md).
#pragma once

namespace marsokhod::sim::soil::wide {

// Whether this process runs the four-wide loop: x86-64 with AVX2 (decided once), unless turned
// off with use(false) (tests and benchmarks: the same run on the two-wide form alone).
bool available();
void use(bool wide);

// For k < count, four at a time while four remain: with the blade's axes (BladeFrame),
// across[k] and along[k] the signed mobilised shares 1 − e^(−|d|/K) of the displacements
// d = jt[k]·across_t + jy[k]·across_y and jt[k]·along_t + jy[k]·along_y. Returns how many
// samples it did (a multiple of 4; 0 when not available()).
int blade_shares(const double* jt, const double* jy, int count, double across_t, double across_y,
                 double along_t, double along_y, double inverse_shear_modulus_per_m,
                 double* across, double* along);

}  // namespace marsokhod::sim::soil::wide
