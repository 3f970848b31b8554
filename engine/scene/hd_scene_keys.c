/* hd_scene_keys: the key table (SCENE_KEYS, hd_scene_keys.h) as data: hd_scene_keys[K_*], and
 * the names of the sections, the walls and the values of the KT_BOOL and KT_ENUM keys. */
#include "hd_scene_internal.h"
#include "rods.h" /* the [rods] defaults */

#include <math.h>
#include <stddef.h>

const char *const hd_scene_sec_name[N_SEC] = {"system", "dimers", "disks", "species", "walls",
                                              "init",   "run",    "log",   "rods"};

const char *const hd_scene_wall_name[4] = {"left", "right", "bottom", "top"};

static const char *const no_yes[] = {"no", "yes", NULL};
static const char *const zero_one[] = {"0", "1", NULL};
static const char *const placements[] = {"random", "lattice", NULL};
static const char *const rod_models[] = {"stochastic", "constant", NULL};
static const char *const rod_baths[] = {"mean", "unequal", NULL};

#define KEY_DEF(id, s, n, ...) [K_##id] = {.sec = s, .name = n, __VA_ARGS__},
const key_def hd_scene_keys[N_KEY] = {SCENE_KEYS(KEY_DEF)};
