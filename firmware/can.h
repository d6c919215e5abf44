/* The AT90CAN128's CAN controller as the nine firmwares use it (datasheet ch. 19): one receive
 * message object (MOb 0) whose filter passes the identifiers idt = 0xiT of one node i with the
 * lowest 3 identifier bits zero, transmit MObs 1..9, and the CAN timer CANTIM, which runs at
 * clkIO/8/(CANTCON+1) = 2 MHz/(con+1): the thesis' tim (chapter 3.2), stamped by the hardware
 * into CANSTM when a frame arrives. */
#ifndef MARSOKHOD_FIRMWARE_CAN_H
#define MARSOKHOD_FIRMWARE_CAN_H

#include <stdint.h>

typedef struct {
  uint8_t idt;      /* identifier bits 10..3 */
  uint8_t dlc;      /* as received */
  uint8_t data[8];
  uint16_t stamp;   /* CANTIM when the frame was received */
} can_frame_t;

#define CAN_RX_MOB 0
#define CAN_TX_MOB 1 /* responses; µ8's stop frames use MObs 2..9 */

/* 1 Mbit/s at 16 MHz; accepts idt 0x(node)0..0x(node)F; CANTIM at 2 MHz. */
void can_init(uint8_t node);
/* Copies the frame the receive MOb holds into *frame and re-arms the MOb: 1 if there was one. */
uint8_t can_take(can_frame_t *frame);
/* Queues a data frame with identifier idt << 3 in the given MOb (waits while it is busy). */
void can_send(uint8_t mob, uint8_t idt, uint8_t dlc, const uint8_t *data);
/* CANTIM, and the divider con of tim's 2 MHz/(con+1) (restarts the CAN timer's prescaler). */
uint16_t can_time(void);
void can_set_timer_divider(uint8_t con);

#endif
