/* The byte layouts of the nine controllers' CAN frames (chapter 3.2–3.3 tables; docs/design.md's
 * "Bit layouts"): the one source of truth shared by the C firmware (firmware/) and the C++ codec
 * (core/protocol/codec.hpp, wire.hpp). Plain C90 integer constants, no includes, so that
 * avr-gcc and the host compilers read the same file.
 *
 * idt = 0xiT: node i (0..8) in the high nibble, type T (0..3) in the low one; CAN ID = idt << 3.
 * Multi-byte fields are big-endian (the thesis' tables list _h before _l). */
#ifndef MARSOKHOD_WIRE_LAYOUT_H
#define MARSOKHOD_WIRE_LAYOUT_H

#define MK_MOTOR_CONTROLLER_COUNT 8 /* µ0–µ7 */
#define MK_SENSOR_NODE 8            /* µ8 */
#define MK_MAX_CAN_ID 0x7FF         /* 11-bit standard identifier */
#define MK_CAN_ID(node, type) ((((node) << 4) | (type)) << 3)

/* Type nibble T. µ8's types share the numbers 0..3 with the motor controllers'. */
#define MK_TYPE_CONTROL_REQUEST 0
#define MK_TYPE_CONTROL_RESPONSE 1
#define MK_TYPE_CONFIGURATION_REQUEST 2
#define MK_TYPE_CONFIGURATION_RESPONSE 3
#define MK_TYPE_MEASUREMENT_REQUEST 0
#define MK_TYPE_MEASUREMENT_RESPONSE 1
#define MK_TYPE_DEAD_MAN_REQUEST 2
#define MK_TYPE_DEAD_MAN_RESPONSE 3

/* Fixed data lengths. */
#define MK_DLC_CONTROL_REQUEST 3
#define MK_DLC_CONTROL_RESPONSE 8
#define MK_DLC_CONFIGURATION_REQUEST 5
#define MK_DLC_CONFIGURATION_RESPONSE 2
#define MK_DLC_MEASUREMENT_REQUEST 8
#define MK_DLC_MEASUREMENT_RESPONSE 8
#define MK_DLC_DEAD_MAN_REQUEST 1
#define MK_DLC_DEAD_MAN_RESPONSE 0

/* Ranges of the chapter 3.2–3.3 tables. */
#define MK_ICR_MIN 255
#define MK_ICR_RESET 511 /* the thesis' compromise */
#define MK_ICR_MAX 2047
#define MK_VEL_MAX 0x7FFF /* 15 bit */
#define MK_ADC_MAX 1023   /* 10-bit ADC of µ8 */
#define MK_LCD_CHAR_MIN 32
#define MK_LCD_CHAR_MAX 127
#define MK_LCD_CHARACTERS 8

/* 0xi0 control request: byte 0 flags, bytes 1–2 pwm. */
#define MK_CONTROL_REQUEST_FLAGS 0
#define MK_CONTROL_REQUEST_PWM 1
#define MK_DRV_BIT 0x01
#define MK_EIM_BIT 0x02
#define MK_CONTROL_RESERVED_BITS 0xFC /* bits 7..2 */

/* 0xi1 control response: tim, enc, stp; byte 6 dir | vel_h (7 bits); byte 7 vel_l. */
#define MK_CONTROL_RESPONSE_TIM 0
#define MK_CONTROL_RESPONSE_ENC 2
#define MK_CONTROL_RESPONSE_STP 4
#define MK_CONTROL_RESPONSE_DIR_VEL 6
#define MK_CONTROL_RESPONSE_VEL_LOW 7
#define MK_DIR_BIT 0x80
#define MK_VEL_HIGH_BITS 0x7F

/* 0xi2 configuration request: icr, pwm, con. 0xi3 configuration response: tim. */
#define MK_CONFIGURATION_REQUEST_ICR 0
#define MK_CONFIGURATION_REQUEST_PWM 2
#define MK_CONFIGURATION_REQUEST_CON 4
#define MK_CONFIGURATION_RESPONSE_TIM 0

/* 0x80 measurement request: bytes 0–1 led in bit 7 and ASCII in bits 6..0, bytes 2–7 ASCII. */
#define MK_LED_BIT 0x80
#define MK_ASCII_BITS 0x7F

/* 0x81 measurement response: high 8 bits of yaw, acc¹, acc², acc³, tlt, vcc in bytes 0–5;
 * b6 low bits of yaw 7–6, acc¹ 5–4, acc² 3–2, acc³ 1–0; b7 tlt 7–6, vcc 5–4, j in bit 0. */
#define MK_MEASUREMENT_READINGS 6
#define MK_MEASUREMENT_LOW_BITS_1 6
#define MK_MEASUREMENT_LOW_BITS_2 7
#define MK_TILT_CHANNEL_BIT 0x01
#define MK_STATUS_RESERVED_BITS 0x0E /* bits 3..1 of b7 */

/* 0x82 dead man request: dog in byte 0. Timer 1 at 16 MHz/64 overflows every
 * 65536·64/16 MHz = 0.262144 s, µ8's unit of dog. */
#define MK_DEAD_MAN_REQUEST_DOG 0
#define MK_DEAD_MAN_TICK_US 262144L

#endif /* MARSOKHOD_WIRE_LAYOUT_H */
