/* The AT90CAN128 core for simavr (at90can128_core.c). */
#ifndef MARSOKHOD_SIM_AVR_AT90CAN128_CORE_H
#define MARSOKHOD_SIM_AVR_AT90CAN128_CORE_H

#include <simavr/sim_avr.h>

#ifdef __cplusplus
extern "C" {
#endif

/* A fresh core, not yet initialised: the caller runs avr_init() and loads the firmware, and
 * frees it with avr_terminate() and free(). NULL when out of memory. */
avr_t *marsokhod_at90can128_new(void);

#ifdef __cplusplus
}
#endif

#endif
