// The rover's CAN bus at 1 Mbit/s (chapter 3): who sends when, and how long each frame takes.
//
// A classic CAN 2.0A data frame on the wire is
//   SOF(1) ID(11) RTR(1) IDE(1) r0(1) DLC(4) DATA(8n) CRC(15) | CRC-del(1) ACK(1) ACK-del(1)
//   EOF(7) IFS(3)  =  47 + 8n bits  + stuff bits
// where a stuff bit of opposite level follows every 5 equal bits from SOF through the CRC (the
// stuff bit counts toward the next run). The CRC is CAN's CRC-15, polynomial 0x4599, over SOF
// through DATA before stuffing. frame_timing counts the stuff bits of the actual frame, so an
// 8-byte frame takes 111 µs plus 0..24 µs; a cycle of 18 frames (9 requests, 9 responses) about
// 1.7 ms.
//
// Arbitration: when the bus falls idle (after the IFS) every node with a frame ready competes and
// the lowest identifier wins; frames that become ready during a transmission wait for the next
// idle. A frame reaches its receivers at the end of its EOF; the bus is free 3 bits later.
// Ties (equal identifiers: only the driver could send two) go to the frame enqueued first.
// The loss fault drops a frame after it has used the bus (a corrupted frame nobody accepts).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/protocol/can_frame.hpp"
#include "sim/electrics/seeded_random.hpp"
#include "sim/firmware/sim_time.hpp"

namespace marsokhod::sim {

inline constexpr SimTimeNs kCanBitTimeNs = 1000;  // 1 Mbit/s
inline constexpr int kCanFixedBits = 47;          // a data frame without data and stuff bits
inline constexpr int kCanIfsBits = 3;
inline constexpr int kCanStuffRun = 5;

// SOF through the CRC sequence, unstuffed, dominant = false (0). Requires dlc ≤ 8, id ≤ 0x7FF.
std::vector<bool> frame_bits_before_stuffing(const protocol::CanFrame& frame);

// CRC-15 of CAN over the given bits (SOF through DATA).
std::uint16_t can_crc15(const std::vector<bool>& bits);

// Stuff bits the transmitter inserts into bits (SOF through CRC).
int stuff_bit_count(const std::vector<bool>& bits);

struct FrameTiming {
  int stuff_bits = 0;
  int total_bits = 0;  // 47 + 8·dlc + stuff_bits, IFS included
  SimTimeNs duration_ns() const { return total_bits * kCanBitTimeNs; }
  // SOF to the end of EOF: when receivers take the frame.
  SimTimeNs delivery_after_ns() const { return (total_bits - kCanIfsBits) * kCanBitTimeNs; }
};

// Throws std::invalid_argument if dlc > 8 or id > 0x7FF.
FrameTiming frame_timing(const protocol::CanFrame& frame);

// Who put a frame on the bus: a controller 0..8 or the onboard computer (the driver).
inline constexpr int kDriverOrigin = -1;

struct BusDelivery {
  protocol::CanFrame frame;
  int origin = kDriverOrigin;
  SimTimeNs ready_ns = 0;      // when its sender had it ready
  SimTimeNs start_ns = 0;      // SOF: won arbitration
  SimTimeNs delivery_ns = 0;   // end of EOF: receivers have it
  SimTimeNs bus_free_ns = 0;   // end of IFS
  bool lost = false;           // the loss fault: used the bus, reached nobody
  std::uint64_t sequence = 0;  // enqueue order, unique
};

class CanBusModel {
 public:
  explicit CanBusModel(std::uint64_t seed = 0) : random_(seed) {}

  // A frame its sender has ready from ready_ns on. Throws std::invalid_argument for a frame the
  // bus cannot carry (dlc > 8, id > 0x7FF).
  void enqueue(const protocol::CanFrame& frame, SimTimeNs ready_ns, int origin = kDriverOrigin);

  // The frame that wins the next arbitration and its times, if any frame is pending; nothing is
  // committed (frames enqueued later with an earlier ready time may still change it).
  std::optional<BusDelivery> peek() const;
  // Commits peek(): the frame is sent; the loss fault is drawn here. Precondition: pending() > 0.
  BusDelivery pop();

  // Pops every frame delivered by until_ns, for a bus nobody answers on.
  std::vector<BusDelivery> run_until(SimTimeNs until_ns);

  std::size_t pending() const { return pending_.size(); }
  SimTimeNs bus_free_ns() const { return bus_free_ns_; }
  // Throws std::invalid_argument unless 0 ≤ probability ≤ 1.
  void set_frame_loss_probability(double probability);
  double frame_loss_probability() const { return loss_probability_; }

 private:
  struct Pending {
    protocol::CanFrame frame;
    int origin;
    SimTimeNs ready_ns;
    std::uint64_t sequence;
    FrameTiming timing;
  };
  std::optional<std::size_t> winner() const;

  std::vector<Pending> pending_;
  SimTimeNs bus_free_ns_ = 0;
  std::uint64_t next_sequence_ = 0;
  double loss_probability_ = 0.0;
  SeededRandom random_;
};

}  // namespace marsokhod::sim
