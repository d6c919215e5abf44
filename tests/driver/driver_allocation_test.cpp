// The steady control cycle allocates nothing on the heap (issue #19): a replacement of the global
// operator new counts every allocation made inside Driver::step once the driver is driving. A
// program of its own, since replacing operator new replaces it for the whole program.
#include <gtest/gtest.h>

#include <cstdlib>
#include <new>
#include <vector>

#include "driver/driver.hpp"
#include "scripted_rover.hpp"

namespace {

bool counting = false;         // only inside Driver::step
std::size_t allocations = 0;  // counted while `counting`

void* allocate(std::size_t size) {
  if (counting) ++allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}

}  // namespace

void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  if (counting) ++allocations;
  return std::malloc(size == 0 ? 1 : size);
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  if (counting) ++allocations;
  return std::malloc(size == 0 ? 1 : size);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace marsokhod::driver {
namespace {

constexpr double kH = 0.0156;

class DriverAllocationTest : public ::testing::Test {
 protected:
  // One cycle; returns the allocations Driver::step made in it.
  std::size_t cycle(const OperatorInput* input) {
    allocations = 0;
    counting = true;
    const auto& requests = driver.step(t, inbox, input);
    counting = false;
    const std::size_t made = allocations;
    inbox = rover.respond(requests, kH);
    t += kH;
    return made;
  }

  Params params;
  Driver driver{params};
  testing::ScriptedRover rover;
  std::vector<protocol::CanFrame> inbox;
  double t = 0.0;
};

TEST_F(DriverAllocationTest, TheCounterSeesAnAllocation) {
  // The replacement is in force: a vector's storage is counted.
  allocations = 0;
  counting = true;
  std::vector<double>* v = new std::vector<double>(100);
  counting = false;
  EXPECT_EQ(allocations, 2u);
  delete v;
}

// Driving forward and turning with rolking running, the operator's targets every cycle (the
// cycle of driver_bench's BM_DriverStep): every stage busy, start-up done.
TEST_F(DriverAllocationTest, TheSteadyDrivingCycleAllocatesNothing) {
  const OperatorInput input = testing::driving_with_rolking();
  for (int k = 0; k < 600; ++k) cycle(&input);  // start-up (≈ 2 s) and the first strides
  ASSERT_EQ(driver.status().mode, DriverMode::kDriving);
  std::size_t total = 0;
  std::size_t gait_states_seen = 0;
  std::size_t last_state = driver.status().gait_state;
  for (int k = 0; k < 2000; ++k) {  // 31 s: rolking passes through all of its states
    total += cycle(&input);
    if (driver.status().gait_state != last_state) ++gait_states_seen;
    last_state = driver.status().gait_state;
  }
  EXPECT_GT(gait_states_seen, 4u);
  EXPECT_EQ(total, 0u) << "allocations in 2000 steady driving cycles";
  // And standing, with no operator input: the cycles of the timeout's controlled stop and rest.
  total = 0;
  for (int k = 0; k < 400; ++k) total += cycle(nullptr);
  EXPECT_TRUE(driver.status().operator_timeout);
  EXPECT_EQ(total, 0u) << "allocations in 400 standing cycles after the operator's timeout";
}

// The same on the tether (Field Experiment 1.1), where every cycle also searches D_I from the
// last one (behaviour/supply_current.hpp).
TEST_F(DriverAllocationTest, TheTethersDrivingCycleAllocatesNothing) {
  RuntimeSettings tether = driver.runtime();
  tether.supply = SupplyKind::kTether;
  driver.set_runtime(tether);
  const OperatorInput input = testing::driving_with_rolking();
  for (int k = 0; k < 600; ++k) cycle(&input);
  ASSERT_EQ(driver.status().mode, DriverMode::kDriving);
  std::size_t total = 0;
  bool bounded = false;
  for (int k = 0; k < 2000; ++k) {
    total += cycle(&input);
    bounded = bounded || driver.status().current_duty_bound < 1.0;
  }
  EXPECT_TRUE(bounded) << "the tether's bound never acted: the search was not exercised";
  EXPECT_EQ(total, 0u) << "allocations in 2000 driving cycles on the tether";
}

}  // namespace
}  // namespace marsokhod::driver
