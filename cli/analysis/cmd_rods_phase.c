/* `haff rods-phase`: rods Fig. 5 data, phase space (x, v, T_B) at a time. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_rods.h"
#include "haff.h"

const hd_optspec hd_cmd_rods_phase_spec = {
    HD_RCLI_SPEC("rods-phase", HD_RCLI_RUN | HD_RCLI_T),
    .head = "usage: haff rods-phase DB [--run ID] [--t T]\n"
            "Fig. 5 data: phase space of the snapshot nearest --t (default the last): columns\n"
            "body x v tb (bath temperature).\n"};

/* The table of one snapshot (hd_rcli_at_fn). */
static int phase(const char *cmd, const ropts *o, const rrun *r, const rsnap *s) {
  (void)cmd, (void)o; /* it prints the whole snapshot and cannot fail */
  printf("# t = %.10g\nbody\tx\tv\ttb\n", s->t);
  for (long i = 0; i < r->sc.n_rods; i++)
    printf("%ld\t%.8g\t%.8g\t%.6g\n", i, s->x[i], s->v[i], s->tb[i]);
  return 0;
}

int hd_cmd_rods_phase(int argc, char **argv) {
  return hd_rcli_main_at(&hd_cmd_rods_phase_spec, argc, argv, 0, phase);
}
