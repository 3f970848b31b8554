/* `haff rods-phase`: rods Fig. 5 data, phase space (x, v, T_B) at a time. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_rods.h"
#include "haff.h"

const hd_optspec haff_rods_phase_spec = {
    HD_OPT_SPEC("rods-phase", hd_rcli_opts, HD_RCLI_RUN | HD_RCLI_T, 1, 1, "one database"),
    .head = "usage: haff rods-phase DB [--run ID] [--t T]\n"
            "Fig. 5 data: phase space of the snapshot nearest --t (default the last): columns\n"
            "body x v tb (bath temperature).\n"};

int haff_rods_phase_main(int argc, char **argv) {
  ropts o;
  rrun r;
  rsnap s;
  int rc = hd_rcli_start_at(&haff_rods_phase_spec, argc, argv, 0, &o, &r, &s);
  if (rc) return rc < 0 ? 0 : rc;
  printf("# t = %.10g\nbody\tx\tv\ttb\n", s.t);
  for (long i = 0; i < r.sc.n_rods; i++)
    printf("%ld\t%.8g\t%.8g\t%.6g\n", i, s.x[i], s.v[i], s.tb[i]);
  hd_rcli_snap_free(&s);
  return hd_rcli_close(&r);
}
