#include "sim/avr/avr_controller.hpp"

#include <simavr/avr_adc.h>
#include <simavr/avr_ioport.h>
#include <simavr/sim_avr.h>
#include <simavr/sim_elf.h>
#include <simavr/sim_irq.h>

#include <cstdarg>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "sim/avr/at90can128_core.h"

namespace marsokhod::sim::avr {
namespace {

// A cycle timer at the target, so that a sleeping core wakes exactly there.
avr_cycle_count_t wake_up(avr_t* /*core*/, avr_cycle_count_t when, void* /*param*/) {
  return 0 * when;  // one-shot
}

// simavr reports through its global logger (file loading, warnings); failures reach the user as
// exceptions instead, so its messages are dropped.
void quiet_logger(avr_t* /*core*/, const int /*level*/, const char* /*format*/, va_list /*args*/) {}

// simavr's default sleep waits in wall-clock time (usleep) to pace a sleeping core to real time;
// here time is a value: a sleeping core skips to its next event at once.
void skip_sleep(avr_t* /*core*/, avr_cycle_count_t /*how_long*/) {}

// What elf_read_firmware allocated; avr_load_firmware copies what it keeps.
void release(elf_firmware_t& firmware) {
  std::free(firmware.flash);
  std::free(firmware.eeprom);
  std::free(firmware.fuse);
  std::free(firmware.lockbits);
  for (std::uint32_t i = 0; i < firmware.symbolcount; ++i) {
    std::free(firmware.symbol[i]);
  }
  std::free(firmware.symbol);
}

}  // namespace

std::uint64_t cycles_at(SimTimeNs time_ns) {
  return static_cast<std::uint64_t>(time_ns) * (kClockHz / 1'000'000) / 1000;
}

AvrController::AvrController(const std::string& elf_path, SimTimeNs boot_ns) : boot_ns_(boot_ns) {
  avr_global_logger_set(quiet_logger);
  if (!std::filesystem::is_regular_file(elf_path)) {
    throw std::runtime_error("firmware in the loop: no AVR image " + elf_path +
                             " (build the images with `make firmware`)");
  }
  elf_firmware_t firmware{};
  if (elf_read_firmware(elf_path.c_str(), &firmware) != 0) {
    throw std::runtime_error("firmware in the loop: cannot read the AVR image " + elf_path +
                             " (build it with `make firmware`)");
  }
  if (firmware.flashsize == 0) {
    release(firmware);
    throw std::runtime_error("firmware in the loop: " + elf_path + " holds no program for the AVR");
  }
  core_ = marsokhod_at90can128_new();
  if (core_ == nullptr || avr_init(core_) != 0) {
    release(firmware);
    throw std::runtime_error("firmware in the loop: cannot initialise the AT90CAN128 core");
  }
  core_->log = LOG_NONE;
  core_->sleep = skip_sleep;
  avr_load_firmware(core_, &firmware);
  release(firmware);
  core_->frequency = static_cast<std::uint32_t>(kClockHz);
  core_->avcc = static_cast<std::uint32_t>(kAdcReferenceMillivolts);
  core_->vcc = core_->avcc;
  can_ = std::make_unique<CanController>(core_);
  for (std::size_t port = 0; port < port_irqs_.size(); ++port) {
    for (std::size_t pin = 0; pin < 8; ++pin) {
      port_irqs_[port][pin] = avr_io_getirq(
          core_, AVR_IOCTL_IOPORT_GETIRQ(static_cast<char>('A' + port)), static_cast<int>(pin));
    }
  }
  for (std::size_t channel = 0; channel < adc_irqs_.size(); ++channel) {
    adc_irqs_[channel] =
        avr_io_getirq(core_, AVR_IOCTL_ADC_GETIRQ, ADC_IRQ_ADC0 + static_cast<int>(channel));
  }
  if (boot_ns_ > 0) {
    run_until(0);  // the start-up, before time 0
  }
}

AvrController::~AvrController() {
  can_.reset();
  if (core_ != nullptr) {
    avr_terminate(core_);
    std::free(core_);
  }
}

std::uint64_t AvrController::cycle() const { return core_->cycle; }

SimTimeNs AvrController::time_ns() const {
  return static_cast<SimTimeNs>(core_->cycle * 1000 / (kClockHz / 1'000'000)) - boot_ns_;
}

void AvrController::run_until(SimTimeNs time_ns) {
  const std::uint64_t target = cycles_at(time_ns + boot_ns_);
  if (target <= core_->cycle) {
    return;
  }
  avr_cycle_timer_register(core_, target - core_->cycle, wake_up, nullptr);
  while (core_->cycle < target) {
    const int state = avr_run(core_);
    if (state == cpu_Crashed || state == cpu_Done) {
      throw std::runtime_error("firmware in the loop: the AT90CAN128 core stopped (" +
                               std::string(state == cpu_Crashed ? "crashed" : "done") +
                               ") at cycle " + std::to_string(core_->cycle) + ", pc 0x" +
                               std::to_string(core_->pc));
    }
  }
}

bool AvrController::deliver(const protocol::CanFrame& frame) { return can_->deliver(frame); }

std::vector<TimedCanFrame> AvrController::take_transmitted() {
  std::vector<TimedCanFrame> frames;
  for (const CanTransmission& sent : can_->take_transmitted()) {
    frames.push_back({static_cast<SimTimeNs>(sent.cycle * 1000 / (kClockHz / 1'000'000)) - boot_ns_,
                      sent.frame});
  }
  return frames;
}

void AvrController::set_pin(char port, int pin, bool high) {
  if (port < 'A' || port > 'G' || pin < 0 || pin > 7) {
    throw std::invalid_argument("firmware in the loop: no pin P" + std::string(1, port) +
                                std::to_string(pin) + " on the AT90CAN128 (PA0..PG7)");
  }
  avr_raise_irq(port_irqs_[static_cast<std::size_t>(port - 'A')][static_cast<std::size_t>(pin)],
                high ? 1 : 0);
}

void AvrController::set_adc_counts(int channel, std::uint16_t counts) {
  if (channel < 0 || channel > 7 || counts > 1023) {
    throw std::invalid_argument("firmware in the loop: ADC channel " + std::to_string(channel) +
                                " (0..7) or counts " + std::to_string(counts) +
                                " (0..1023) out of range");
  }
  // simavr converts reading = mV·1023/AVCC (integer); the least voltage that reads `counts`.
  const auto millivolts =
      static_cast<std::uint32_t>((counts * kAdcReferenceMillivolts + 1022) / 1023);
  const auto index = static_cast<std::size_t>(channel);
  if (millivolts != adc_millivolts_[index]) {
    adc_millivolts_[index] = millivolts;
    avr_raise_irq(adc_irqs_[index], millivolts);
  }
}

std::uint8_t AvrController::register8(std::uint16_t address) const { return core_->data[address]; }

std::uint16_t AvrController::register16(std::uint16_t low_address) const {
  return static_cast<std::uint16_t>(core_->data[low_address] | (core_->data[low_address + 1] << 8));
}

}  // namespace marsokhod::sim::avr
