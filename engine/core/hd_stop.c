/* The process's stop request (hd_stop.h). */
#include "hd_stop.h"

volatile sig_atomic_t hd_stop_requested = 0;
