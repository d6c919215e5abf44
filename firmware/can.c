/* AT90CAN128 CAN controller: MOb set-up, reception into can_frame_t, transmission. */
#include "can.h"

#include <avr/io.h>

#define MOB_COUNT 15
#define CONMOB_RX (1 << CONMOB1)
#define CONMOB_TX (1 << CONMOB0)

static void select_mob(uint8_t mob) { CANPAGE = (uint8_t)(mob << 4); } /* INDX 0, auto-increment */

void can_init(uint8_t node) {
  uint8_t mob;
  CANGCON = (1 << SWRES);
  for (mob = 0; mob < MOB_COUNT; ++mob) {
    select_mob(mob);
    CANSTMOB = 0;
    CANCDMOB = 0;
  }
  CANBT1 = 0x02; /* datasheet table: 16 MHz, 1 Mbit/s, 8 Tq per bit */
  CANBT2 = 0x04;
  CANBT3 = 0x13;
  select_mob(CAN_RX_MOB);
  CANIDT1 = (uint8_t)(node << 4);
  CANIDT2 = 0;
  CANIDT3 = 0;
  CANIDT4 = 0;
  CANIDM1 = 0xF0;                                /* the node nibble must match */
  CANIDM2 = 0xE0;                                /* and identifier bits 2..0 be zero */
  CANIDM3 = 0;
  CANIDM4 = (1 << IDEMSK) | (1 << RTRMSK);       /* standard data frames only */
  CANCDMOB = CONMOB_RX | 8;
  CANIE2 = (1 << CAN_RX_MOB);
  CANGIE = (1 << ENIT) | (1 << ENRX);
  CANGCON = (1 << ENASTB);
  while (!(CANGSTA & (1 << ENFG))) {
  }
}

uint8_t can_take(can_frame_t *frame) {
  uint8_t i;
  select_mob(CAN_RX_MOB);
  if (!(CANSTMOB & (1 << RXOK))) {
    return 0;
  }
  frame->idt = CANIDT1;
  frame->dlc = CANCDMOB & 0x0F;
  for (i = 0; i < 8; ++i) {
    frame->data[i] = i < frame->dlc ? CANMSG : 0;
  }
  frame->stamp = CANSTML;
  frame->stamp |= (uint16_t)CANSTMH << 8;
  CANSTMOB = 0;
  CANCDMOB = CONMOB_RX | 8; /* the MOb disables itself after a reception */
  return 1;
}

void can_send(uint8_t mob, uint8_t idt, uint8_t dlc, const uint8_t *data) {
  uint8_t i;
  /* the previous frame of this MOb is still pending (CANEN2: MObs 0..7, CANEN1: 8..14) */
  volatile uint8_t *const enabled = mob < 8 ? &CANEN2 : &CANEN1;
  const uint8_t bit = (uint8_t)(1 << (mob & 7));
  while (*enabled & bit) {
  }
  select_mob(mob);
  CANSTMOB = 0;
  CANIDT1 = idt;
  CANIDT2 = 0;
  CANIDT3 = 0;
  CANIDT4 = 0;
  for (i = 0; i < dlc; ++i) {
    CANMSG = data[i];
  }
  CANCDMOB = (uint8_t)(CONMOB_TX | dlc);
}

uint16_t can_time(void) {
  uint16_t time = CANTIML;
  return time | (uint16_t)((uint16_t)CANTIMH << 8);
}

void can_set_timer_divider(uint8_t con) { CANTCON = con; }
