/* HD44780 in 4-bit mode: initialisation by instruction (datasheet figure 24) and text output. */
#include "lcd.h"

#include <avr/io.h>
#include <util/delay.h>

#define LCD_RS (1 << PA0)
#define LCD_RW (1 << PA1)
#define LCD_E (1 << PA2)
#define LCD_DATA 0xF0

static void pulse_nibble(uint8_t nibble, uint8_t rs) {
  PORTA = (uint8_t)((nibble << 4) | (rs ? LCD_RS : 0));
  PORTA |= LCD_E;
  _delay_us(1);
  PORTA &= (uint8_t)~LCD_E;
  _delay_us(1);
}

static void write_byte(uint8_t value, uint8_t rs) {
  pulse_nibble(value >> 4, rs);
  pulse_nibble(value & 0x0F, rs);
  _delay_us(50); /* 37 µs per instruction, with margin */
}

void lcd_init(void) {
  DDRA = LCD_DATA | LCD_RS | LCD_RW | LCD_E;
  PORTA = 0;
  _delay_ms(40);
  pulse_nibble(0x3, 0);
  _delay_ms(5);
  pulse_nibble(0x3, 0);
  _delay_us(150);
  pulse_nibble(0x3, 0);
  _delay_us(50);
  pulse_nibble(0x2, 0); /* 4-bit interface */
  _delay_us(50);
  write_byte(0x28, 0); /* 4 bit, 2 lines, 5x8 font */
  write_byte(0x0C, 0); /* display on, no cursor */
  write_byte(0x06, 0); /* increment, no shift */
  write_byte(0x01, 0); /* clear */
  _delay_ms(2);
}

void lcd_show(const char *text16) {
  uint8_t i;
  write_byte(0x80, 0); /* DDRAM address 0 */
  for (i = 0; i < 16; ++i) {
    write_byte((uint8_t)text16[i], 1);
  }
}
