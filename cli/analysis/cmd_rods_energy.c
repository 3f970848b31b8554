/* `haff rods-energy`: rods Figs. 1, 2, 9-11 data, energies and collisions against time. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rods.h"

#include "cli_rods.h"
#include "hd_anadb.h"
#include "haff.h"

const hd_optspec hd_cmd_rods_energy_spec = {
    HD_RCLI_SPEC("rods-energy", HD_RCLI_RUN),
    .head =
        "usage: haff rods-energy DB [--run ID]\n"
        "Figs. 1, 2, 9-11 data: per sample of a rods run (newest by default) the columns\n"
        "  t collisions cpd e_kin e_bath e_kin_over_e0 e_mode e_kin_stat coll_ideal coll_eq35\n"
        "e_kin, e_bath per rod; e_mode = e_bath / nmod (energy per vibrational mode);\n"
        "e_kin_stat = the equipartition value (docs/rods.md); coll_ideal and coll_eq35: the\n"
        "stationary collision count rate*t from the 1D ideal gas and from the paper's eq. (35).\n"};

int hd_cmd_rods_energy(int argc, char **argv) {
  ropts o;
  rrun r;
  int rc = hd_rcli_start(&hd_cmd_rods_energy_spec, argc, argv, 0, &o, &r);
  if (rc) return rc < 0 ? 0 : rc;
  const hd_scene *sc = &r.sc;
  long N = sc->n_rods, nmod = sc->rod_nmod;
  double e0 = 0.5 * sc->rod_temperature; /* E_kin(0) per rod */
  double es = hd_rods_ekin_stat(N, nmod, e0 * (double)N) / (double)N;
  double rate_i = hd_rods_rate_ideal(N, 2 * es * (double)N / (double)(N - 1));
  double rate_35 = hd_rods_rate_eq35(N, nmod) * sqrt(sc->rod_temperature);
  hd_series ser;
  hd_error err;
  if (hd_ana_samples(r.db, r.id, &ser, &err)) {
    fprintf(stderr, "haff %s: cannot read the samples of run %ld: %s\n", argv[0], r.id, err.msg);
    hd_rcli_close(&r);
    return 1;
  }
  printf("# run %ld: N=%ld gamma=%g nmod=%ld model=%s damping=%g\n", r.id, N, sc->rod_gamma, nmod,
         sc->rod_model ? "constant" : "stochastic", sc->rod_damping);
  printf("t\tcollisions\tcpd\te_kin\te_bath\te_kin_over_e0\te_mode\te_kin_stat\tcoll_ideal\t"
         "coll_eq35\n");
  for (size_t k = 0; k < ser.n; k++) {
    double t = ser.t[k];
    double ek = ser.e_tr[k], eb = ser.e_rot[k];
    printf("%.10g\t%lld\t%.8g\t%.8g\t%.8g\t%.8g\t%.8g\t%.8g\t%.8g\t%.8g\n", t,
           (long long)ser.coll[k], ser.cpd[k], ek, eb, ek / e0, eb / (double)nmod, es, rate_i * t,
           rate_35 * t);
  }
  hd_series_free(&ser);
  return hd_rcli_close(&r);
}
