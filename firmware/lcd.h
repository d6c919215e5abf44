/* The 16-character HD44780 display of µ8 in 4-bit mode (chapter 3.3 pins): data D4–D7 on
 * PA4–PA7, E on PA2, R/W on PA1 (held low: write only, timed by delays), RS on PA0. */
#ifndef MARSOKHOD_FIRMWARE_LCD_H
#define MARSOKHOD_FIRMWARE_LCD_H

void lcd_init(void);
/* Writes 16 characters from the first position of the first line. */
void lcd_show(const char *text16);

#endif
