/* A simavr core for the AT90CAN128 (Atmel datasheet 7679H, "Register Summary" and "Interrupt
 * Vectors"), which Debian's simavr 1.6 lacks: 128 KiB flash, 4 KiB SRAM from 0x100, 4 KiB EEPROM,
 * 37 vectors of 4 bytes; ports A–G, external interrupts INT0–INT7, the watchdog, the EEPROM, the
 * 10-bit ADC and timers 0–3 (timer 3's external clock on T3 = PE6). The register addresses and
 * vector numbers come from avr-libc's avr/iocan128.h, read with simavr's convention of
 * data-space addresses. The CAN controller is not here: can_controller.hpp models it through
 * simavr's I/O callbacks. Built as C: simavr's declaration macros are C designated initialisers. */
#include <simavr/avr_adc.h>
#include <simavr/avr_eeprom.h>
#include <simavr/avr_extint.h>
#include <simavr/avr_ioport.h>
#include <simavr/avr_timer.h>
#include <simavr/avr_watchdog.h>
#include <simavr/sim_avr.h>

#include "sim/avr/at90can128_core.h"

#define _AVR_IO_H_
#define __ASSEMBLER__
#define _SFR_IO8(v) ((v) + 32)
#define _SFR_IO16(v) ((v) + 32)
#define _SFR_MEM8(v) (v)
#define _SFR_MEM16(v) (v)
#define _VECTOR(v) (v)
#include MARSOKHOD_IOCAN128_H

#define WGM_OPS_16                                                                   \
  .wgm_op = {                                                                        \
      [0] = AVR_TIMER_WGM_NORMAL16(),   [1] = AVR_TIMER_WGM_FCPWM8(),                 \
      [2] = AVR_TIMER_WGM_FCPWM9(),     [3] = AVR_TIMER_WGM_FCPWM10(),                \
      [4] = AVR_TIMER_WGM_CTC(),        [5] = AVR_TIMER_WGM_FASTPWM8(),               \
      [6] = AVR_TIMER_WGM_FASTPWM9(),   [7] = AVR_TIMER_WGM_FASTPWM10(),              \
      [8] = AVR_TIMER_WGM_ICPWM(),      [9] = AVR_TIMER_WGM_OCPWM(),                  \
      [10] = AVR_TIMER_WGM_ICPWM(),     [11] = AVR_TIMER_WGM_OCPWM(),                 \
      [12] = AVR_TIMER_WGM_ICCTC(),     [14] = AVR_TIMER_WGM_ICFASTPWM(),             \
      [15] = {.kind = avr_timer_wgm_fast_pwm, .top = avr_timer_wgm_reg_ocra},         \
  }

#define COMPARE16(_t, _letter, _port, _pin)                                           \
  [AVR_TIMER_COMP##_letter] = {                                                       \
      .r_ocr = OCR##_t##_letter##L,                                                   \
      .r_ocrh = OCR##_t##_letter##H,                                                  \
      .com = AVR_IO_REGBITS(TCCR##_t##A, COM##_t##_letter##0, 0x3),                   \
      .com_pin = AVR_IO_REGBIT(PORT##_port, _pin),                                    \
      .interrupt = {.enable = AVR_IO_REGBIT(TIMSK##_t, OCIE##_t##_letter),             \
                    .raised = AVR_IO_REGBIT(TIFR##_t, OCF##_t##_letter),               \
                    .vector = TIMER##_t##_COMP##_letter##_vect}}

#define TIMER16(_t, _ext_port, _ext_pin, _icp_port, _icp_pin, _pa, _pb, _pc, _cport)  \
  {                                                                                   \
    .name = '0' + _t,                                                                 \
    .wgm = {AVR_IO_REGBIT(TCCR##_t##A, WGM##_t##0), AVR_IO_REGBIT(TCCR##_t##A, WGM##_t##1), \
            AVR_IO_REGBIT(TCCR##_t##B, WGM##_t##2), AVR_IO_REGBIT(TCCR##_t##B, WGM##_t##3)}, \
    WGM_OPS_16,                                                                       \
    .cs = {AVR_IO_REGBIT(TCCR##_t##B, CS##_t##0), AVR_IO_REGBIT(TCCR##_t##B, CS##_t##1), \
           AVR_IO_REGBIT(TCCR##_t##B, CS##_t##2)},                                     \
    .cs_div = {0, 0, 3, 6, 8, 10, AVR_TIMER_EXTCLK_CHOOSE, AVR_TIMER_EXTCLK_CHOOSE},   \
    .ext_clock_pin = AVR_IO_REGBIT(PORT##_ext_port, _ext_pin),                        \
    .r_tcnt = TCNT##_t##L, .r_tcnth = TCNT##_t##H,                                    \
    .r_icr = ICR##_t##L, .r_icrh = ICR##_t##H,                                        \
    .ices = AVR_IO_REGBIT(TCCR##_t##B, ICES##_t),                                     \
    .icp = AVR_IO_REGBIT(PORT##_icp_port, _icp_pin),                                  \
    .overflow = {.enable = AVR_IO_REGBIT(TIMSK##_t, TOIE##_t),                         \
                 .raised = AVR_IO_REGBIT(TIFR##_t, TOV##_t),                           \
                 .vector = TIMER##_t##_OVF_vect},                                      \
    .icr = {.enable = AVR_IO_REGBIT(TIMSK##_t, ICIE##_t),                              \
            .raised = AVR_IO_REGBIT(TIFR##_t, ICF##_t),                                \
            .vector = TIMER##_t##_CAPT_vect},                                          \
    .comp = {COMPARE16(_t, A, _cport, _pa), COMPARE16(_t, B, _cport, _pb),             \
             COMPARE16(_t, C, _cport, _pc)},                                           \
  }

#define TIMER8(_t, _cs_div, _port, _pin)                                               \
  {                                                                                   \
    .name = '0' + _t,                                                                 \
    .wgm = {AVR_IO_REGBIT(TCCR##_t##A, WGM##_t##0), AVR_IO_REGBIT(TCCR##_t##A, WGM##_t##1)}, \
    .wgm_op = {[0] = AVR_TIMER_WGM_NORMAL8(), [2] = AVR_TIMER_WGM_CTC(),               \
               [3] = AVR_TIMER_WGM_FASTPWM8()},                                        \
    .cs = {AVR_IO_REGBIT(TCCR##_t##A, CS##_t##0), AVR_IO_REGBIT(TCCR##_t##A, CS##_t##1), \
           AVR_IO_REGBIT(TCCR##_t##A, CS##_t##2)},                                     \
    .cs_div = _cs_div,                                                                \
    .r_tcnt = TCNT##_t,                                                               \
    .overflow = {.enable = AVR_IO_REGBIT(TIMSK##_t, TOIE##_t),                         \
                 .raised = AVR_IO_REGBIT(TIFR##_t, TOV##_t),                           \
                 .vector = TIMER##_t##_OVF_vect},                                      \
    .comp = {[AVR_TIMER_COMPA] = {                                                    \
                 .r_ocr = OCR##_t##A,                                                 \
                 .com = AVR_IO_REGBITS(TCCR##_t##A, COM##_t##A0, 0x3),                 \
                 .com_pin = AVR_IO_REGBIT(PORT##_port, _pin),                          \
                 .interrupt = {.enable = AVR_IO_REGBIT(TIMSK##_t, OCIE##_t##A),        \
                               .raised = AVR_IO_REGBIT(TIFR##_t, OCF##_t##A),          \
                               .vector = TIMER##_t##_COMP_vect}}},                     \
  }

#define CS_DIV_TIMER0 {0, 0, 3, 6, 8, 10, AVR_TIMER_EXTCLK_CHOOSE, AVR_TIMER_EXTCLK_CHOOSE}
#define CS_DIV_TIMER2 {0, 0, 3, 5, 6, 7, 8, 10}

static void at90can128_init(struct avr_t *avr);

struct at90can128_mcu {
  avr_t core;
  avr_eeprom_t eeprom;
  avr_watchdog_t watchdog;
  avr_extint_t extint;
  avr_ioport_t porta, portb, portc, portd, porte, portf, portg;
  avr_adc_t adc;
  avr_timer_t timer0, timer1, timer2, timer3;
};

static const struct at90can128_mcu kAt90can128 = {
    .core = {
        .mmcu = "at90can128",
        .ioend = RAMSTART - 1,
        .ramend = RAMEND,
        .flashend = FLASHEND,
        .e2end = E2END,
        .vector_size = 4,
        .signature = {SIGNATURE_0, SIGNATURE_1, SIGNATURE_2},
        .fuse = {0xFF, 0xD1, 0xFF}, /* docs/firmware.md: 16 MHz crystal, JTAG off (ADC4–7) */
        .lockbits = 0xFF,
        .reset_flags = {.porf = AVR_IO_REGBIT(MCUSR, PORF),
                        .extrf = AVR_IO_REGBIT(MCUSR, EXTRF),
                        .borf = AVR_IO_REGBIT(MCUSR, BORF),
                        .wdrf = AVR_IO_REGBIT(MCUSR, WDRF)},
        .init = at90can128_init,
        .rampz = RAMPZ,
    },
    AVR_EEPROM_DECLARE_NOEEPM(EE_READY_vect),
    .watchdog = {
        .wdrf = AVR_IO_REGBIT(MCUSR, WDRF),
        .wdce = AVR_IO_REGBIT(WDTCR, WDCE),
        .wde = AVR_IO_REGBIT(WDTCR, WDE),
        .wdp = {AVR_IO_REGBIT(WDTCR, WDP0), AVR_IO_REGBIT(WDTCR, WDP1),
                AVR_IO_REGBIT(WDTCR, WDP2)},
    },
    .extint = {
        AVR_EXTINT_MEGA_DECLARE(0, 'D', PD0, A), AVR_EXTINT_MEGA_DECLARE(1, 'D', PD1, A),
        AVR_EXTINT_MEGA_DECLARE(2, 'D', PD2, A), AVR_EXTINT_MEGA_DECLARE(3, 'D', PD3, A),
        AVR_EXTINT_MEGA_DECLARE(4, 'E', PE4, B), AVR_EXTINT_MEGA_DECLARE(5, 'E', PE5, B),
        AVR_EXTINT_MEGA_DECLARE(6, 'E', PE6, B), AVR_EXTINT_MEGA_DECLARE(7, 'E', PE7, B),
    },
    AVR_IOPORT_DECLARE(a, 'A', A),
    AVR_IOPORT_DECLARE(b, 'B', B),
    AVR_IOPORT_DECLARE(c, 'C', C),
    AVR_IOPORT_DECLARE(d, 'D', D),
    AVR_IOPORT_DECLARE(e, 'E', E),
    AVR_IOPORT_DECLARE(f, 'F', F),
    AVR_IOPORT_DECLARE(g, 'G', G),
    .adc = {
        .r_admux = ADMUX,
        .mux = {AVR_IO_REGBIT(ADMUX, MUX0), AVR_IO_REGBIT(ADMUX, MUX1),
                AVR_IO_REGBIT(ADMUX, MUX2), AVR_IO_REGBIT(ADMUX, MUX3),
                AVR_IO_REGBIT(ADMUX, MUX4)},
        .ref = {AVR_IO_REGBIT(ADMUX, REFS0), AVR_IO_REGBIT(ADMUX, REFS1)},
        .ref_values = {[1] = ADC_VREF_AVCC, [3] = ADC_VREF_V256},
        .adlar = AVR_IO_REGBIT(ADMUX, ADLAR),
        .r_adcsra = ADCSRA,
        .aden = AVR_IO_REGBIT(ADCSRA, ADEN),
        .adsc = AVR_IO_REGBIT(ADCSRA, ADSC),
        .adate = AVR_IO_REGBIT(ADCSRA, ADATE),
        .adps = {AVR_IO_REGBIT(ADCSRA, ADPS0), AVR_IO_REGBIT(ADCSRA, ADPS1),
                 AVR_IO_REGBIT(ADCSRA, ADPS2)},
        .r_adch = ADCH,
        .r_adcl = ADCL,
        .r_adcsrb = ADCSRB,
        .adts = {AVR_IO_REGBIT(ADCSRB, ADTS0), AVR_IO_REGBIT(ADCSRB, ADTS1),
                 AVR_IO_REGBIT(ADCSRB, ADTS2)},
        .muxmode = {[0] = AVR_ADC_SINGLE(0), [1] = AVR_ADC_SINGLE(1), [2] = AVR_ADC_SINGLE(2),
                    [3] = AVR_ADC_SINGLE(3), [4] = AVR_ADC_SINGLE(4), [5] = AVR_ADC_SINGLE(5),
                    [6] = AVR_ADC_SINGLE(6), [7] = AVR_ADC_SINGLE(7),
                    [30] = AVR_ADC_REF(1100), [31] = AVR_ADC_REF(0)},
        .adc = {.enable = AVR_IO_REGBIT(ADCSRA, ADIE),
                .raised = AVR_IO_REGBIT(ADCSRA, ADIF),
                .vector = ADC_vect},
    },
    .timer0 = TIMER8(0, CS_DIV_TIMER0, B, PB7),
    .timer1 = TIMER16(1, D, PD6, D, PD4, PB5, PB6, PB7, B),
    .timer2 = TIMER8(2, CS_DIV_TIMER2, B, PB4),
    .timer3 = TIMER16(3, E, PE6, E, PE7, PE3, PE4, PE5, E),
};

static void at90can128_init(struct avr_t *avr) {
  struct at90can128_mcu *mcu = (struct at90can128_mcu *)avr;
  avr_eeprom_init(avr, &mcu->eeprom);
  avr_extint_init(avr, &mcu->extint);
  avr_watchdog_init(avr, &mcu->watchdog);
  avr_ioport_init(avr, &mcu->porta);
  avr_ioport_init(avr, &mcu->portb);
  avr_ioport_init(avr, &mcu->portc);
  avr_ioport_init(avr, &mcu->portd);
  avr_ioport_init(avr, &mcu->porte);
  avr_ioport_init(avr, &mcu->portf);
  avr_ioport_init(avr, &mcu->portg);
  avr_adc_init(avr, &mcu->adc);
  avr_timer_init(avr, &mcu->timer0);
  avr_timer_init(avr, &mcu->timer1);
  avr_timer_init(avr, &mcu->timer2);
  avr_timer_init(avr, &mcu->timer3);
}

avr_t *marsokhod_at90can128_new(void) {
  return avr_core_allocate(&kAt90can128.core, sizeof(struct at90can128_mcu));
}
