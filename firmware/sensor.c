/* Firmware of the sensor controller µ8 (AT90CAN128 at 16 MHz, chapter 3.3).
 *
 * Pins (the thesis' table): ADC0 yaw rate, ADC1–ADC3 acceleration along x1..x3, ADC4/ADC5 tilt
 * of the front/rear axle, ADC6 supply voltage; PB6 green LED led⁰ (on = high), PE3 white LED
 * led¹ (pull-up: on = low); the HD44780 on port A (lcd.h).
 *
 * The ADC (AVCC reference, 16 MHz/128 = 125 kHz, 104 µs a conversion) converts ADC0..ADC6 in a
 * ring in the background; a response carries the latest reading of each channel.
 * 0x80 → 0x81: sets the LEDs and the eight characters, restarts the dead man's switch, and
 * answers yaw, acc¹⁻³, one tilt channel and vcc; the tilt channel alternates with every 0x81,
 * front (j = 0) first.
 * 0x82 → 0x83: sets dog (0 disables); arming a disabled switch restarts its timer.
 * Dead man's switch: Timer 1 at 16 MHz/64 overflows every 65536·64/16 MHz = 0.262144 s, counted
 * from the 0x80's arrival (its CAN time stamp); after dog overflows without a 0x80 µ8 sends 0xi0
 * with drv = 0, eim = 1, pwm = 0 to µ0–µ7 (MObs 2..9), and again at every overflow while the
 * silence lasts: a stop frame the bus lost reaches its motor one overflow later. A MOb whose last
 * stop frame is still waiting for the bus is skipped, so the interrupt never waits on the bus.
 * LCD: the eight characters and the supply voltage U = 0.06768·vcc − 41.0823 V (Procedure 3.5),
 * or, after a second without 0x80, the idle text scrolling. Frames µ8 cannot use are ignored. */
#include <avr/interrupt.h>
#include <avr/io.h>
#include <avr/sleep.h>
#include <avr/wdt.h>

#include "can.h"
#include "lcd.h"
#include "wire_layout.h"

#define ADC_CHANNELS 7
#define CHANNEL_TILT_FRONT 4
#define CHANNEL_TILT_REAR 5
#define CHANNEL_SUPPLY 6
#define IDLE_AFTER_OVERFLOWS 4 /* 4·0.262144 s ≥ 1 s without a 0x80 */
#define STOP_FIRST_MOB 2

static const char idle_text[] = "Pleasure in the job puts perfection in the work.   ";
static volatile uint16_t readings[ADC_CHANNELS];
static uint8_t channel;
static uint8_t tilt_channel; /* j of the next response */
static uint8_t dog;
static uint8_t overflows_since_request; /* saturates at 255 */
static volatile uint8_t idle_overflows = IDLE_AFTER_OVERFLOWS;
static volatile uint8_t display_dirty = 1;
/* The watchdog's food: set every 1024 conversions (107 ms) by the ADC interrupt, which runs
 * whatever the bus does. (Timer 1 would not do: a 0x80 every 15.6 ms keeps restarting it, and the
 * first firmware, fed on its overflows, was reset by its watchdog a second into driving, which
 * disarmed the dead man's switch.) */
static volatile uint8_t conversions_done;
static char characters[MK_LCD_CHARACTERS] = {' ', ' ', ' ', ' ', ' ', ' ', ' ', ' '};
static volatile uint16_t displayed_vcc;

ISR(ADC_vect) {
  static uint16_t conversions;
  if (++conversions == 1024) {
    conversions = 0;
    conversions_done = 1;
  }
  readings[channel] = ADC;
  channel = (uint8_t)((channel + 1) % ADC_CHANNELS);
  ADMUX = (uint8_t)((1 << REFS0) | channel);
  ADCSRA |= (1 << ADSC);
}

/* Restarts the switch as of the request's arrival: Timer 1 (4 µs a count) starts at the time
 * that has passed since, measured on the CAN timer (0.5 µs a count at CANTCON = 0), so the
 * interrupt's reaction time does not postpone the stop. */
static void restart_dead_man(uint16_t stamp) {
  const uint16_t elapsed = (uint16_t)(can_time() - stamp);
  GTCCR = (1 << PSR310); /* restart Timer 1's prescaler too */
  TCNT1 = elapsed / 8;
  TIFR1 = (1 << TOV1);
  overflows_since_request = 0;
}

static void stop_motors(void) {
  uint8_t node;
  const uint8_t stop[MK_DLC_CONTROL_REQUEST] = {MK_EIM_BIT, 0, 0};
  /* MObs 2..9 busy: CANEN2 holds MObs 0..7, CANEN1 MObs 8..14 (one read, no shifts per MOb) */
  uint16_t busy = (uint16_t)(((uint16_t)CANEN1 << 8 | CANEN2) >> STOP_FIRST_MOB);
  for (node = 0; node < MK_MOTOR_CONTROLLER_COUNT; ++node, busy >>= 1) {
    if (!(busy & 1)) {
      can_send((uint8_t)(STOP_FIRST_MOB + node), (uint8_t)(node << 4 | MK_TYPE_CONTROL_REQUEST),
               MK_DLC_CONTROL_REQUEST, stop);
    }
  }
}

ISR(TIMER1_OVF_vect) {
  if (idle_overflows < 255) {
    ++idle_overflows;
    display_dirty = 1;
  }
  if (dog != 0) {
    if (overflows_since_request < 255) ++overflows_since_request;
    if (overflows_since_request >= dog) stop_motors();
  }
}

static void set_leds(uint8_t green, uint8_t white) {
  if (green) PORTB |= (1 << PB6); else PORTB &= (uint8_t)~(1 << PB6);
  if (white) PORTE &= (uint8_t)~(1 << PE3); else PORTE |= (1 << PE3);
}

static void measure(void) {
  static const uint8_t order[6] = {0, 1, 2, 3, 0xFF, CHANNEL_SUPPLY};
  uint16_t values[MK_MEASUREMENT_READINGS];
  uint8_t response[MK_DLC_MEASUREMENT_RESPONSE];
  uint8_t i;
  for (i = 0; i < MK_MEASUREMENT_READINGS; ++i) {
    const uint8_t adc = order[i] == 0xFF
                            ? (tilt_channel ? CHANNEL_TILT_REAR : CHANNEL_TILT_FRONT) : order[i];
    values[i] = readings[adc];
    response[i] = (uint8_t)(values[i] >> 2);
  }
  response[MK_MEASUREMENT_LOW_BITS_1] =
      (uint8_t)(((values[0] & 3) << 6) | ((values[1] & 3) << 4) | ((values[2] & 3) << 2) |
                (values[3] & 3));
  response[MK_MEASUREMENT_LOW_BITS_2] =
      (uint8_t)(((values[4] & 3) << 6) | ((values[5] & 3) << 4) | (tilt_channel & 1));
  displayed_vcc = values[5];
  tilt_channel ^= 1;
  can_send(CAN_TX_MOB, (MK_SENSOR_NODE << 4) | MK_TYPE_MEASUREMENT_RESPONSE,
           MK_DLC_MEASUREMENT_RESPONSE, response);
}

static void measurement_request(const can_frame_t *frame) {
  uint8_t i;
  char text[MK_LCD_CHARACTERS];
  if (frame->dlc != MK_DLC_MEASUREMENT_REQUEST) {
    return;
  }
  for (i = 0; i < MK_LCD_CHARACTERS; ++i) {
    const uint8_t character = i < 2 ? (frame->data[i] & MK_ASCII_BITS) : frame->data[i];
    if (character < MK_LCD_CHAR_MIN || character > MK_LCD_CHAR_MAX) {
      return;
    }
    text[i] = (char)character;
  }
  restart_dead_man(frame->stamp);
  for (i = 0; i < MK_LCD_CHARACTERS; ++i) {
    characters[i] = text[i];
  }
  set_leds(frame->data[0] & MK_LED_BIT, frame->data[1] & MK_LED_BIT);
  idle_overflows = 0;
  display_dirty = 1;
  measure();
}

static void dead_man_request(const can_frame_t *frame) {
  const uint8_t new_dog = frame->data[MK_DEAD_MAN_REQUEST_DOG];
  if (frame->dlc != MK_DLC_DEAD_MAN_REQUEST) {
    return;
  }
  if (dog == 0 && new_dog > 0) {
    restart_dead_man(frame->stamp);
  }
  dog = new_dog;
  can_send(CAN_TX_MOB, (MK_SENSOR_NODE << 4) | MK_TYPE_DEAD_MAN_RESPONSE,
           MK_DLC_DEAD_MAN_RESPONSE, 0);
}

ISR(CANIT_vect) {
  can_frame_t frame;
  while (can_take(&frame)) {
    switch (frame.idt & 0x0F) {
      case MK_TYPE_MEASUREMENT_REQUEST: measurement_request(&frame); break;
      case MK_TYPE_DEAD_MAN_REQUEST: dead_man_request(&frame); break;
      default: break;
    }
  }
}

/* "TEXTTEXT  24.57V": U = 0.06768·vcc − 41.0823 V in centivolts, rounded. */
static void compose(char *line, const char *text, uint16_t vcc) {
  int32_t centivolts = ((int32_t)6768 * vcc - 4108230L + 500) / 1000;
  uint8_t i;
  uint8_t negative = centivolts < 0;
  for (i = 0; i < MK_LCD_CHARACTERS; ++i) line[i] = text[i];
  for (i = 8; i < 15; ++i) line[i] = ' ';
  line[15] = 'V';
  if (negative) centivolts = -centivolts;
  for (i = 14; i >= 8; --i) {
    if (i == 12) { line[i] = '.'; continue; }
    line[i] = (char)('0' + centivolts % 10);
    centivolts /= 10;
    if (centivolts == 0 && i < 12) break;
  }
  if (negative && i > 8) line[i - 1] = '-';
}

static void refresh_display(void) {
  char line[16];
  uint8_t i;
  cli();
  const uint8_t idle = idle_overflows >= IDLE_AFTER_OVERFLOWS;
  const uint8_t offset = idle_overflows;
  compose(line, characters, displayed_vcc);
  display_dirty = 0;
  sei();
  if (idle) {
    for (i = 0; i < 16; ++i) {
      line[i] = idle_text[(uint8_t)(offset + i) % (sizeof idle_text - 1)];
    }
  }
  lcd_show(line);
}

int main(void) {
  DDRB |= (1 << PB6);
  DDRE |= (1 << PE3);
  set_leds(0, 0);
  can_init(MK_SENSOR_NODE);
  ADMUX = (1 << REFS0);
  ADCSRA = (1 << ADEN) | (1 << ADIE) | (1 << ADPS2) | (1 << ADPS1) | (1 << ADPS0);
  ADCSRA |= (1 << ADSC);
  TCCR1A = 0;
  TCCR1B = (1 << CS11) | (1 << CS10); /* 16 MHz/64 */
  TIMSK1 = (1 << TOIE1);
  wdt_enable(WDTO_1S);
  sei();
  lcd_init(); /* 45 ms of waiting; the bus is served meanwhile */
  for (;;) {
    if (conversions_done) {
      conversions_done = 0;
      wdt_reset();
    }
    if (display_dirty) {
      refresh_display();
    }
    set_sleep_mode(SLEEP_MODE_IDLE);
    sleep_mode();
  }
}
