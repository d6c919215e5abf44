#include "sim/firmware/can_bus_model.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace marsokhod::sim {
namespace {

constexpr std::uint16_t kCrc15Polynomial = 0x4599;
constexpr std::uint16_t kCrc15Mask = 0x7FFF;
constexpr std::uint32_t kMaxStandardId = 0x7FF;

void append_bits(std::vector<bool>& bits, std::uint32_t value, int count) {
  for (int bit = count - 1; bit >= 0; --bit) {
    bits.push_back(((value >> bit) & 1U) != 0);
  }
}

void require_carriable(const protocol::CanFrame& frame) {
  if (frame.dlc > 8 || frame.id > kMaxStandardId) {
    throw std::invalid_argument("CAN bus: frame id " + std::to_string(frame.id) + " dlc " +
                                std::to_string(frame.dlc) +
                                " cannot be sent; a standard data frame has id ≤ 0x7FF, dlc ≤ 8");
  }
}

}  // namespace

std::vector<bool> frame_bits_before_stuffing(const protocol::CanFrame& frame) {
  require_carriable(frame);
  std::vector<bool> bits;
  bits.reserve(34 + 8 * frame.dlc);
  bits.push_back(false);  // SOF, dominant
  append_bits(bits, frame.id, 11);
  append_bits(bits, 0, 3);  // RTR (data frame), IDE (standard), r0: all dominant
  append_bits(bits, frame.dlc, 4);
  for (std::uint8_t i = 0; i < frame.dlc; ++i) {
    append_bits(bits, frame.data[i], 8);
  }
  append_bits(bits, can_crc15(bits), 15);
  return bits;
}

std::uint16_t can_crc15(const std::vector<bool>& bits) {
  std::uint16_t crc = 0;
  for (const bool bit : bits) {
    const bool feedback = bit != (((crc >> 14) & 1U) != 0);
    crc = static_cast<std::uint16_t>((crc << 1) & kCrc15Mask);
    if (feedback) {
      crc ^= kCrc15Polynomial;
    }
  }
  return crc;
}

int stuff_bit_count(const std::vector<bool>& bits) {
  int stuff_bits = 0;
  int run_length = 0;
  bool run_level = true;  // the idle bus is recessive: SOF starts a run of one
  for (const bool bit : bits) {
    if (bit == run_level) {
      ++run_length;
    } else {
      run_level = bit;
      run_length = 1;
    }
    if (run_length == kCanStuffRun) {
      ++stuff_bits;
      // The stuff bit has the opposite level and is the first bit of the next run.
      run_level = !run_level;
      run_length = 1;
    }
  }
  return stuff_bits;
}

FrameTiming frame_timing(const protocol::CanFrame& frame) {
  FrameTiming timing;
  timing.stuff_bits = stuff_bit_count(frame_bits_before_stuffing(frame));
  timing.total_bits = kCanFixedBits + 8 * frame.dlc + timing.stuff_bits;
  return timing;
}

void CanBusModel::enqueue(const protocol::CanFrame& frame, SimTimeNs ready_ns, int origin) {
  pending_.push_back({frame, origin, ready_ns, next_sequence_++, frame_timing(frame)});
}

std::optional<std::size_t> CanBusModel::winner() const {
  if (pending_.empty()) {
    return std::nullopt;
  }
  SimTimeNs earliest_ns = pending_.front().ready_ns;
  for (const Pending& frame : pending_) {
    earliest_ns = std::min(earliest_ns, frame.ready_ns);
  }
  const SimTimeNs start_ns = std::max(bus_free_ns_, earliest_ns);
  std::optional<std::size_t> best;
  for (std::size_t i = 0; i < pending_.size(); ++i) {
    const Pending& frame = pending_[i];
    if (frame.ready_ns > start_ns) {
      continue;  // not ready when arbitration starts
    }
    if (!best || frame.frame.id < pending_[*best].frame.id ||
        (frame.frame.id == pending_[*best].frame.id && frame.sequence < pending_[*best].sequence)) {
      best = i;
    }
  }
  return best;
}

std::optional<BusDelivery> CanBusModel::peek() const {
  const std::optional<std::size_t> index = winner();
  if (!index) {
    return std::nullopt;
  }
  const Pending& frame = pending_[*index];
  BusDelivery delivery;
  delivery.frame = frame.frame;
  delivery.origin = frame.origin;
  delivery.ready_ns = frame.ready_ns;
  delivery.start_ns = std::max(bus_free_ns_, frame.ready_ns);
  delivery.delivery_ns = delivery.start_ns + frame.timing.delivery_after_ns();
  delivery.bus_free_ns = delivery.start_ns + frame.timing.duration_ns();
  delivery.sequence = frame.sequence;
  return delivery;
}

BusDelivery CanBusModel::pop() {
  const std::optional<std::size_t> index = winner();
  if (!index) {
    throw std::logic_error("CAN bus: pop() with no frame pending; check pending() first");
  }
  BusDelivery delivery = *peek();
  delivery.lost = random_.bernoulli(loss_probability_);
  bus_free_ns_ = delivery.bus_free_ns;
  pending_.erase(pending_.begin() + static_cast<std::ptrdiff_t>(*index));
  return delivery;
}

std::vector<BusDelivery> CanBusModel::run_until(SimTimeNs until_ns) {
  std::vector<BusDelivery> deliveries;
  for (auto next = peek(); next && next->delivery_ns <= until_ns; next = peek()) {
    deliveries.push_back(pop());
  }
  return deliveries;
}

void CanBusModel::set_frame_loss_probability(double probability) {
  if (!(probability >= 0.0 && probability <= 1.0)) {
    throw std::invalid_argument("CAN bus: the frame loss probability must lie in 0..1");
  }
  loss_probability_ = probability;
}

}  // namespace marsokhod::sim
