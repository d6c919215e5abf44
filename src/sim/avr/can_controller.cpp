#include "sim/avr/can_controller.hpp"

#include <simavr/sim_interrupts.h>
#include <simavr/sim_io.h>

namespace marsokhod::sim::avr {
namespace {

// Data-space addresses (avr-libc's avr/iocan128.h) and bits of the datasheet's register tables.
constexpr avr_io_addr_t kCanGcon = 0xD8, kCanGsta = 0xD9, kCanGie = 0xDB, kCanEn2 = 0xDC,
                        kCanEn1 = 0xDD, kCanIe2 = 0xDE, kCanIe1 = 0xDF, kCanSit2 = 0xE0,
                        kCanSit1 = 0xE1, kCanTcon = 0xE5, kCanTimL = 0xE6, kCanTimH = 0xE7,
                        kCanHpMob = 0xEC, kCanPage = 0xED, kCanStMob = 0xEE, kCanCdMob = 0xEF,
                        kCanIdt4 = 0xF0, kCanIdm4 = 0xF4, kCanIdm1 = 0xF7, kCanStmL = 0xF8,
                        kCanStmH = 0xF9, kCanMsg = 0xFA;
constexpr avr_io_addr_t kFirst = kCanGcon;
constexpr avr_io_addr_t kLast = kCanMsg;
constexpr std::uint8_t kSwres = 0x01, kEnastb = 0x02, kEnfg = 0x04;
constexpr std::uint8_t kEnit = 0x80, kEnrx = 0x20, kEntx = 0x10;
constexpr std::uint8_t kRxok = 0x20, kTxok = 0x40, kDlcw = 0x80;
constexpr std::uint8_t kConmobMask = 0xC0, kConmobTx = 0x40, kConmobRx = 0x80, kIde = 0x10;
constexpr std::uint8_t kRtrBit = 0x04, kIdeMaskBit = 0x01;  // CANIDT4 RTRTAG, CANIDM4 IDEMSK
constexpr std::uint8_t kAinc = 0x08;                        // CANPAGE: 1 disables auto-increment
constexpr std::uint8_t kInterruptFlags = 0x7F;              // CANSTMOB: TXOK, RXOK, errors
constexpr int kCanItVector = 18;                            // CANIT_vect_num
constexpr std::uint64_t kCyclesPerTimerTick = 8;            // clkIO/8

std::uint16_t identifier(const std::array<std::uint8_t, 4>& bytes) {  // bytes[3] = xxx1
  return static_cast<std::uint16_t>((bytes[3] << 3) | (bytes[2] >> 5));
}

}  // namespace

CanController::CanController(avr_t* core) : core_(core) {
  for (avr_io_addr_t address = kFirst; address <= kLast; ++address) {
    avr_register_io_read(core_, address, &CanController::on_read, this);
    avr_register_io_write(core_, address, &CanController::on_write, this);
  }
  interrupt_.enable = avr_regbit_t{kCanGie, 7, 1};
  interrupt_.vector = kCanItVector;
  avr_register_vector(core_, &interrupt_);
  reset();
}

void CanController::reset() {
  mobs_ = {};
  general_ = {};
  page_ = 0;
  core_->data[kCanGie] = 0;
}

std::uint64_t CanController::timer_ticks() const {
  const std::uint64_t cycles = core_->cycle - epoch_cycle_;
  return ticks_before_epoch_ + cycles / (kCyclesPerTimerTick * (timer_divider_ + 1U));
}

std::uint16_t CanController::timer() const { return static_cast<std::uint16_t>(timer_ticks()); }

std::uint8_t CanController::on_read(avr_t* /*core*/, avr_io_addr_t address, void* self) {
  return static_cast<CanController*>(self)->read(address);
}

void CanController::on_write(avr_t* /*core*/, avr_io_addr_t address, std::uint8_t value,
                             void* self) {
  static_cast<CanController*>(self)->write(address, value);
}

std::uint8_t CanController::read(avr_io_addr_t address) {
  Mob& mob = page_mob();
  std::uint16_t enabled = 0;
  std::uint16_t pending = 0;
  for (int i = 0; i < kMobCount; ++i) {
    enabled = static_cast<std::uint16_t>(enabled | (((mobs_[i].control & kConmobMask) != 0) << i));
    pending = static_cast<std::uint16_t>(pending | (((mobs_[i].status & kInterruptFlags) != 0) << i));
  }
  switch (address) {
    case kCanGsta: return (general_[kCanGcon - kFirst] & kEnastb) ? kEnfg : 0;
    case kCanEn2: return static_cast<std::uint8_t>(enabled & 0xFF);
    case kCanEn1: return static_cast<std::uint8_t>(enabled >> 8);
    case kCanSit2: return static_cast<std::uint8_t>(pending & 0xFF);
    case kCanSit1: return static_cast<std::uint8_t>(pending >> 8);
    case kCanTimL: {
      const std::uint16_t now = timer();
      timer_high_latch_ = static_cast<std::uint8_t>(now >> 8);
      return static_cast<std::uint8_t>(now & 0xFF);
    }
    case kCanTimH: return timer_high_latch_;
    case kCanHpMob:
      for (int i = 0; i < kMobCount; ++i) {
        if (pending & (1U << i)) {
          return static_cast<std::uint8_t>(i << 4);
        }
      }
      return 0xF0;
    case kCanPage: return page_;
    case kCanStMob: return mob.status;
    case kCanCdMob: return mob.control;
    case kCanStmL: return static_cast<std::uint8_t>(mob.stamp & 0xFF);
    case kCanStmH: return static_cast<std::uint8_t>(mob.stamp >> 8);
    case kCanMsg: {
      const std::uint8_t value = mob.data[page_ & 7U];
      if (!(page_ & kAinc)) {
        page_ = static_cast<std::uint8_t>((page_ & 0xF8U) | ((page_ + 1U) & 7U));
      }
      return value;
    }
    default: break;
  }
  if (address >= kCanIdt4 && address < kCanIdm4) {
    return mob.tag[address - kCanIdt4];
  }
  if (address >= kCanIdm4 && address <= kCanIdm1) {
    return mob.mask[address - kCanIdm4];
  }
  return general_[address - kFirst];
}

void CanController::write(avr_io_addr_t address, std::uint8_t value) {
  Mob& mob = page_mob();
  switch (address) {
    case kCanGcon:
      if (value & kSwres) {
        reset();
        return;
      }
      break;
    case kCanGie: core_->data[kCanGie] = value; break;  // the interrupt's enable regbit reads it
    case kCanTcon:
      if (value != timer_divider_) {
        ticks_before_epoch_ = timer_ticks();
        epoch_cycle_ = core_->cycle;
        timer_divider_ = value;
      }
      break;
    case kCanPage: page_ = value; return;
    case kCanStMob:
      mob.status = value;  // the firmware clears the flags by writing them 0
      update_interrupt();
      return;
    case kCanCdMob:
      mob.control = value;
      if ((value & kConmobMask) == kConmobTx) {
        transmit(mob);
      }
      return;
    case kCanStmL: case kCanStmH: return;  // read-only
    case kCanMsg:
      mob.data[page_ & 7U] = value;
      if (!(page_ & kAinc)) {
        page_ = static_cast<std::uint8_t>((page_ & 0xF8U) | ((page_ + 1U) & 7U));
      }
      return;
    default: break;
  }
  if (address >= kCanIdt4 && address < kCanIdm4) {
    mob.tag[address - kCanIdt4] = value;
  } else if (address >= kCanIdm4 && address <= kCanIdm1) {
    mob.mask[address - kCanIdm4] = value;
  } else {
    general_[address - kFirst] = value;
  }
}

bool CanController::accepts(const Mob& mob, const protocol::CanFrame& frame) const {
  if ((mob.control & kConmobMask) != kConmobRx) {
    return false;
  }
  const std::uint16_t mask = identifier(mob.mask);
  if (((frame.id ^ identifier(mob.tag)) & mask) != 0) {
    return false;
  }
  if ((mob.mask[0] & kRtrBit) && (mob.tag[0] & kRtrBit)) {
    return false;  // the MOb waits for a remote frame; ours are data frames
  }
  return !((mob.mask[0] & kIdeMaskBit) && (mob.control & kIde));
}

bool CanController::deliver(const protocol::CanFrame& frame) {
  if (!(general_[kCanGcon - kFirst] & kEnastb)) {
    return false;  // the controller is off the bus
  }
  for (int i = 0; i < kMobCount; ++i) {
    Mob& mob = mobs_[i];
    if (!accepts(mob, frame)) {
      continue;
    }
    mob.tag[3] = static_cast<std::uint8_t>(frame.id >> 3);
    mob.tag[2] = static_cast<std::uint8_t>((frame.id & 7U) << 5);
    const std::uint8_t expected_dlc = mob.control & 0x0F;
    mob.control = static_cast<std::uint8_t>((mob.control & kIde) | (frame.dlc & 0x0F));
    for (std::size_t b = 0; b < frame.dlc && b < mob.data.size(); ++b) {
      mob.data[b] = frame.data[b];
    }
    mob.stamp = timer();
    mob.status = static_cast<std::uint8_t>(kRxok | (frame.dlc != expected_dlc ? kDlcw : 0));
    update_interrupt();
    return true;
  }
  return false;
}

void CanController::transmit(Mob& mob) {
  CanTransmission sent;
  sent.cycle = core_->cycle;
  sent.frame.id = identifier(mob.tag);
  sent.frame.dlc = static_cast<std::uint8_t>(mob.control & 0x0F);
  for (std::size_t b = 0; b < sent.frame.dlc && b < mob.data.size(); ++b) {
    sent.frame.data[b] = mob.data[b];
  }
  transmitted_.push_back(sent);
  mob.control = static_cast<std::uint8_t>(mob.control & ~kConmobMask);
  mob.status = static_cast<std::uint8_t>(mob.status | kTxok);
  update_interrupt();
}

void CanController::update_interrupt() {
  const std::uint8_t gie = core_->data[kCanGie];
  const std::uint16_t enabled_mobs =
      static_cast<std::uint16_t>(general_[kCanIe2 - kFirst] | (general_[kCanIe1 - kFirst] << 8));
  bool raise = false;
  for (int i = 0; i < kMobCount; ++i) {
    const std::uint8_t status = mobs_[i].status;
    const bool flagged = ((status & kRxok) && (gie & kEnrx)) || ((status & kTxok) && (gie & kEntx));
    raise = raise || (flagged && (enabled_mobs & (1U << i)));
  }
  if (raise && (gie & kEnit)) {
    avr_raise_interrupt(core_, &interrupt_);
  } else {
    avr_clear_interrupt(core_, &interrupt_);
  }
}

std::vector<CanTransmission> CanController::take_transmitted() {
  std::vector<CanTransmission> frames;
  frames.swap(transmitted_);
  return frames;
}

}  // namespace marsokhod::sim::avr
