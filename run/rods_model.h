/* The ring of rods as a model of the runner (run/rods_model.c; hd_model.h). */
#ifndef HD_RODS_MODEL_H
#define HD_RODS_MODEL_H

#include "hd_model.h"

/* Runs scenes with a [rods] section (hd_model_for_scene picks it when n_rods > 0). */
extern const hd_model_ops hd_model_rods;

#endif
