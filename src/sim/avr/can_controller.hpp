// The AT90CAN128's CAN controller (datasheet 7679H ch. 19) for simavr, which has none: the
// general registers CANGCON…CANHPMOB, the 15 message objects behind CANPAGE (CANSTMOB, CANCDMOB,
// CANIDT, CANIDM, CANSTM, CANMSG with auto-increment) and the CAN timer, modelled through
// simavr's I/O callbacks on the data-space addresses 0xD8..0xFA.
//
// What is modelled, and the model's assumptions:
// - CANTIM counts from reset at clkIO/8/(CANTCON+1) = 2 MHz/(con+1) at 16 MHz; writing CANTCON
//   with a new value keeps the count and restarts the prescaler at the write (rewriting the value
//   in force changes nothing). Reading CANTIML latches CANTIMH.
// - Reception: a frame from the bus goes, at the cycle it is delivered, into the lowest-numbered
//   MOb enabled for reception (CONMOB = 10) whose filter passes it (CANIDM over the 11 identifier
//   bits, RTRMSK, IDEMSK); the MOb gets the identifier, the received DLC (DLCW when it differs
//   from the MOb's), the data, CANSTM = CANTIM, RXOK, and disables itself (CONMOB = 00). The CANIT
//   interrupt is raised when ENIT, ENRX and the MOb's CANIE bit are set. A frame no MOb accepts is
//   lost, as on the chip.
// - Transmission: enabling a MOb for transmission (CONMOB = 01) puts its frame on the bus at once
//   (take_transmitted() hands it over with its cycle; arbitration and bit times are the simulated
//   bus's business), and sets TXOK.
// - Not modelled: remote and extended frames' replies, time-triggered mode, error counters and
//   bus-off, listening mode, the overrun interrupt OVRIT.
#pragma once

#include <simavr/sim_avr.h>

#include <array>
#include <cstdint>
#include <vector>

#include "core/protocol/can_frame.hpp"

namespace marsokhod::sim::avr {

struct CanTransmission {
  std::uint64_t cycle = 0;
  protocol::CanFrame frame;
};

class CanController {
 public:
  static constexpr int kMobCount = 15;

  // Hooks the registers of core (initialised, not yet running); core must outlive this object.
  explicit CanController(avr_t* core);
  CanController(const CanController&) = delete;
  CanController& operator=(const CanController&) = delete;

  // A standard data frame from the bus at the core's current cycle: true if a MOb took it.
  bool deliver(const protocol::CanFrame& frame);
  // The frames the firmware sent since the last call, in order.
  std::vector<CanTransmission> take_transmitted();
  // CANTIM at the core's current cycle.
  std::uint16_t timer() const;

 private:
  struct Mob {
    std::uint8_t status = 0;   // CANSTMOB
    std::uint8_t control = 0;  // CANCDMOB
    std::array<std::uint8_t, 4> tag{};   // CANIDT4..1 (index 0 = CANIDT4)
    std::array<std::uint8_t, 4> mask{};  // CANIDM4..1
    std::uint16_t stamp = 0;
    std::array<std::uint8_t, 8> data{};
  };

  static std::uint8_t on_read(avr_t* core, avr_io_addr_t address, void* self);
  static void on_write(avr_t* core, avr_io_addr_t address, std::uint8_t value, void* self);
  std::uint8_t read(avr_io_addr_t address);
  void write(avr_io_addr_t address, std::uint8_t value);
  void reset();
  Mob& page_mob() { return mobs_[page_ >> 4 < kMobCount ? page_ >> 4 : 0]; }
  bool accepts(const Mob& mob, const protocol::CanFrame& frame) const;
  void transmit(Mob& mob);
  void update_interrupt();
  std::uint64_t timer_ticks() const;

  avr_t* core_;
  std::array<Mob, kMobCount> mobs_{};
  std::array<std::uint8_t, 0xFB - 0xD8> general_{};  // plain storage of the general registers
  std::uint8_t page_ = 0;
  std::uint8_t timer_high_latch_ = 0;
  std::uint8_t timer_divider_ = 0;      // CANTCON
  std::uint64_t epoch_cycle_ = 0;       // the cycle of the last CANTCON write
  std::uint64_t ticks_before_epoch_ = 0;
  avr_int_vector_t interrupt_{};
  std::vector<CanTransmission> transmitted_;
};

}  // namespace marsokhod::sim::avr
