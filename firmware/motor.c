/* Firmware of the motor controllers µ0–µ7 (AT90CAN128 at 16 MHz, chapter 3.2).
 *
 * Pins (the thesis' table): OC1B (PB6) the pulse-width modulated duty to the H-bridge, PC2 the
 * desired direction drv, T3 (PE6) the encoder's logic pulses, INT0 (PD0) the LS7184's direction
 * line (low: forward, high: reversed), TXCAN/RXCAN the bus.
 *
 * Registers and what drives them (the same rules as the simulator's emulation,
 * src/sim/firmware/motor_controller.hpp):
 * - icr, pwm, drv, eim, con: 0xi0 sets drv, eim, pwm; 0xi2 sets icr, pwm, con. Timer 1 runs
 *   phase-correct PWM with TOP = ICR1 = icr at 16 MHz, one period 2·icr/16 MHz ≈ (icr+1)/8 MHz
 *   (15.6 kHz at icr = 511), OCR1B = pwm: d = (−1)^drv·pwm/icr. ICR1 is not double-buffered,
 *   which is why the thesis changes icr only at pwm ≈ 0.
 * - tim: the CAN timer at 2 MHz/(con+1) (CANTCON = con); a response carries CANSTM, the timer's
 *   value stamped by the hardware when the request arrived, less what the timer gained while a
 *   con change waited for the interrupt (change_con).
 * - enc: Timer 3 counts the rising edges on T3, whatever the direction.
 * - dir, stp: INT0 on either edge of the direction line; with eim = 1 the interrupt sets
 *   stp = enc and dir to the line. eim = 0 masks INT0, and unmasking clears the flag a masked
 *   edge left, so a later eim = 1 does not resynchronise dir until the next change.
 * - vel: pulses of the last period T(con) = 65536·(con+1)/2 MHz, a moving window of 16 slices
 *   closed whenever tim crosses a multiple of 4096. Timer 2 at 2 MHz (16 MHz/8), extended to 32
 *   bits in software, hits the slice ends with its compare unit; saturated to 15 bits.
 * Frames the firmware cannot use (wrong DLC, reserved bits, pwm > icr, icr outside 255..2047,
 * another type) are ignored without an answer. The watchdog (1 s) resets a hung controller,
 * which stops the motor: PWM is off after reset. */
#include <avr/eeprom.h>
#include <avr/interrupt.h>
#include <avr/io.h>
#include <avr/sleep.h>
#include <avr/wdt.h>

#include "can.h"
#include "wire_layout.h"

#ifndef MK_NODE
#define MK_NODE 0
#endif

#define SLICES 16
#define SLICE_TIM_TICKS (65536UL / SLICES)
#define NODE_EEPROM_ADDRESS ((const uint8_t *)0)

static uint8_t node;
static uint16_t icr = MK_ICR_RESET;
static uint8_t con;
static uint16_t tim_offset; /* CANTIM − tim: the ticks the CAN timer gained over con changes */
static volatile uint16_t stp;
static volatile uint8_t dir;
static volatile uint16_t vel;
static uint16_t slice_pulses[SLICES];
static uint8_t next_slice;
static uint16_t enc_at_slice_start;
/* Timer 2 overflows: bits 31..8 of the 2 MHz count, which wraps after 2^32 ticks (35.8 min); all
 * comparisons are of differences. (Kept in 16 bits, the count wrapped after 8.4 s and vel froze:
 * found by scenario straight-and-spin --firmware.) */
static volatile uint32_t timer2_high;
static uint32_t slice_end;            /* Timer 2 count at which the current slice closes */
static volatile uint8_t slice_closed;  /* the main loop's sign of life for the watchdog */

static uint16_t read_u16(const uint8_t *data) { return (uint16_t)((data[0] << 8) | data[1]); }
static void write_u16(uint8_t *data, uint16_t value) {
  data[0] = (uint8_t)(value >> 8);
  data[1] = (uint8_t)value;
}

static uint16_t encoder_count(void) { return TCNT3; }

/* The 2 MHz count of Timer 2; interrupts must be off. */
static uint32_t timer2_count(void) {
  uint8_t low = TCNT2;
  uint32_t high = timer2_high;
  if ((TIFR2 & (1 << TOV2)) && low < 0x80) {
    ++high; /* overflowed before TCNT2 was read, not yet counted */
  }
  return (high << 8) | low;
}

static void close_slice(void) {
  const uint16_t enc = encoder_count();
  uint32_t window = 0;
  uint8_t i;
  slice_pulses[next_slice] = (uint16_t)(enc - enc_at_slice_start);
  enc_at_slice_start = enc;
  next_slice = (uint8_t)((next_slice + 1) % SLICES);
  for (i = 0; i < SLICES; ++i) {
    window += slice_pulses[i];
  }
  vel = window > MK_VEL_MAX ? MK_VEL_MAX : (uint16_t)window;
  slice_end += SLICE_TIM_TICKS * (con + 1U);
  slice_closed = 1;
}

/* Arms Timer 2's compare for slice_end if it lies within the current 256-count window. */
static void arm_slice_compare(uint32_t now) {
  if ((slice_end >> 8) == (now >> 8) && (uint8_t)slice_end > (uint8_t)now) {
    OCR2A = (uint8_t)slice_end;
    TIFR2 = (1 << OCF2A);
    TIMSK2 |= (1 << OCIE2A);
  }
}

/* The next slice ends where tim next crosses a multiple of 4096 (tim read now). */
static void schedule_slice(uint16_t tim_now) {
  const uint32_t now = timer2_count();
  const uint16_t remaining = (uint16_t)(SLICE_TIM_TICKS - tim_now % SLICE_TIM_TICKS);
  TIMSK2 &= (uint8_t)~(1 << OCIE2A);
  slice_end = now + (uint32_t)remaining * (con + 1U);
  arm_slice_compare(now);
}

ISR(TIMER2_OVF_vect) {
  ++timer2_high;
  const uint32_t now = timer2_high << 8;
  while ((int32_t)(slice_end - now) <= 0) {
    close_slice(); /* ends on the overflow itself (compare value 0), or armed too late */
  }
  arm_slice_compare(now);
}

ISR(TIMER2_COMP_vect) {
  TIMSK2 &= (uint8_t)~(1 << OCIE2A);
  close_slice();
}

ISR(INT0_vect) {
  stp = encoder_count();
  dir = (PIND & (1 << PD0)) ? 1 : 0;
}

static void set_eim(uint8_t eim) {
  if (eim && !(EIMSK & (1 << INT0))) {
    EIFR = (1 << INTF0); /* an edge seen while masked does not count */
    EIMSK |= (1 << INT0);
  } else if (!eim) {
    EIMSK &= (uint8_t)~(1 << INT0);
  }
}

static void set_duty(uint16_t pwm, uint8_t drv) {
  OCR1B = pwm;
  if (drv) {
    PORTC |= (1 << PC2);
  } else {
    PORTC &= (uint8_t)~(1 << PC2);
  }
}

static void control(const can_frame_t *frame) {
  const uint8_t flags = frame->data[MK_CONTROL_REQUEST_FLAGS];
  const uint16_t pwm = read_u16(frame->data + MK_CONTROL_REQUEST_PWM);
  uint8_t response[MK_DLC_CONTROL_RESPONSE];
  uint16_t velocity;
  if (frame->dlc != MK_DLC_CONTROL_REQUEST || (flags & MK_CONTROL_RESERVED_BITS) || pwm > icr) {
    return;
  }
  write_u16(response + MK_CONTROL_RESPONSE_TIM, (uint16_t)(frame->stamp - tim_offset));
  write_u16(response + MK_CONTROL_RESPONSE_ENC, encoder_count());
  write_u16(response + MK_CONTROL_RESPONSE_STP, stp);
  velocity = vel;
  response[MK_CONTROL_RESPONSE_DIR_VEL] =
      (uint8_t)((dir ? MK_DIR_BIT : 0) | ((velocity >> 8) & MK_VEL_HIGH_BITS));
  response[MK_CONTROL_RESPONSE_VEL_LOW] = (uint8_t)velocity;
  set_eim(flags & MK_EIM_BIT);
  set_duty(pwm, flags & MK_DRV_BIT);
  can_send(CAN_TX_MOB, (uint8_t)((node << 4) | MK_TYPE_CONTROL_RESPONSE), MK_DLC_CONTROL_RESPONSE,
           response);
}

/* tim runs at the new rate from the request's arrival on, as the thesis' clock would. CANTCON can
 * only be written now, after the interrupt's reaction, and the CAN timer has meanwhile counted
 * `elapsed` ticks at the old rate where the new rate would have counted elapsed·(con+1)/(new+1):
 * tim_offset takes the difference up (to within a tick of the old clock). */
static void change_con(uint8_t new_con, uint16_t stamp) {
  const uint16_t elapsed = (uint16_t)(can_time() - stamp);
  const uint16_t elapsed_at_new_rate =
      (uint16_t)(((uint32_t)elapsed * (con + 1U) + new_con / 2U) / (new_con + 1U));
  can_set_timer_divider(new_con);
  tim_offset = (uint16_t)(tim_offset + elapsed - elapsed_at_new_rate);
  con = new_con;
  schedule_slice((uint16_t)(can_time() - tim_offset));
}

static void configure(const can_frame_t *frame) {
  const uint16_t new_icr = read_u16(frame->data + MK_CONFIGURATION_REQUEST_ICR);
  const uint16_t pwm = read_u16(frame->data + MK_CONFIGURATION_REQUEST_PWM);
  const uint8_t new_con = frame->data[MK_CONFIGURATION_REQUEST_CON];
  uint8_t response[MK_DLC_CONFIGURATION_RESPONSE];
  if (frame->dlc != MK_DLC_CONFIGURATION_REQUEST || new_icr < MK_ICR_MIN ||
      new_icr > MK_ICR_MAX || pwm > new_icr) {
    return;
  }
  write_u16(response + MK_CONFIGURATION_RESPONSE_TIM, (uint16_t)(frame->stamp - tim_offset));
  if (new_con != con) {
    change_con(new_con, frame->stamp);
  }
  icr = new_icr;
  ICR1 = icr;
  OCR1B = pwm;
  can_send(CAN_TX_MOB, (uint8_t)((node << 4) | MK_TYPE_CONFIGURATION_RESPONSE),
           MK_DLC_CONFIGURATION_RESPONSE, response);
}

ISR(CANIT_vect) {
  can_frame_t frame;
  while (can_take(&frame)) {
    switch (frame.idt & 0x0F) {
      case MK_TYPE_CONTROL_REQUEST: control(&frame); break;
      case MK_TYPE_CONFIGURATION_REQUEST: configure(&frame); break;
      default: break; /* responses and unknown types: not for this firmware */
    }
  }
}

static void init_timers(void) {
  TCCR2A = (1 << CS21); /* Timer 2: normal mode, 16 MHz/8 = 2 MHz */
  TIMSK2 = (1 << TOIE2);
  DDRB |= (1 << PB6);
  DDRC |= (1 << PC2);
  ICR1 = icr;
  OCR1B = 0;
  /* Timer 1: mode 10, phase-correct PWM with TOP = ICR1, OC1B non-inverting, no prescaling. */
  TCCR1A = (1 << COM1B1) | (1 << WGM11);
  TCCR1B = (1 << WGM13) | (1 << CS10);
  /* Timer 3: normal mode, clocked by rising edges on T3. */
  TCCR3A = 0;
  TCCR3B = (1 << CS32) | (1 << CS31) | (1 << CS30);
  EICRA = (1 << ISC00); /* INT0 on any edge of the direction line; masked until eim = 1 */
}

int main(void) {
  const uint8_t stored = eeprom_read_byte(NODE_EEPROM_ADDRESS);
  node = stored < MK_MOTOR_CONTROLLER_COUNT ? stored : MK_NODE;
  init_timers();
  can_init(node);
  schedule_slice(can_time());
  wdt_enable(WDTO_1S);
  sei();
  for (;;) {
    if (slice_closed) { /* at least every T(255)/16 = 0.52 s: the timers and interrupts run */
      slice_closed = 0;
      wdt_reset();
    }
    set_sleep_mode(SLEEP_MODE_IDLE);
    sleep_mode();
  }
}
