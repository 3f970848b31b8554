/* Exact checkpoints: the raw bytes of every body (state, local time, cell links, pending
 * event), the body ids, the cell heads, the clocks and the RNG state.  Restoring them and
 * rebuilding the heap (whose order is total: time, then index) continues the run bit for bit.  The
 * blob is for the same build on the same machine; a header guards against anything else. */
#include <stdlib.h>
#include <string.h>

#include "hd_sim_internal.h"

#define HD_CKPT_MAGIC 0x31504b4346464148ULL /* "HAFFCKP1" */

/* Fixed-size header of a checkpoint blob. */
typedef struct ckpt_header {
  uint64_t magic;      /* HD_CKPT_MAGIC */
  uint32_t body_size;  /* sizeof(hd_body) */
  uint32_t clock_size; /* sizeof(hd_sim_clock) */
  int32_t n;           /* bodies */
  int32_t n_species[HD_NSPECIES];
  int32_t ncx, ncy;  /* cells */
  uint64_t rng_size; /* bytes of RNG state */
  double lx, ly;     /* box (must match the scene) */
} ckpt_header;

int hd_sim_checkpoint(const hd_sim *s, void **blob, size_t *n, hd_error *err) {
  size_t ncell = (size_t)s->ncx * (size_t)s->ncy, rs = gsl_rng_size(s->rng);
  size_t total = sizeof(ckpt_header) + sizeof(hd_sim_clock) +
                 (sizeof(hd_body) + sizeof(int32_t)) * (size_t)s->n + sizeof(int32_t) * ncell + rs;
  unsigned char *p = malloc(total);
  if (!p) return hd_error_set(err, HD_ENOMEM, "out of memory for a checkpoint");
  ckpt_header h = {HD_CKPT_MAGIC,
                   sizeof(hd_body),
                   sizeof(hd_sim_clock),
                   s->n,
                   {s->n_species[0], s->n_species[1]},
                   s->ncx,
                   s->ncy,
                   rs,
                   s->lx,
                   s->ly};
  unsigned char *q = p;
  memcpy(q, &h, sizeof h), q += sizeof h;
  memcpy(q, &s->c, sizeof s->c), q += sizeof s->c;
  memcpy(q, s->b, sizeof(hd_body) * (size_t)s->n), q += sizeof(hd_body) * (size_t)s->n;
  memcpy(q, s->id, sizeof(int32_t) * (size_t)s->n), q += sizeof(int32_t) * (size_t)s->n;
  memcpy(q, s->head, sizeof(int32_t) * ncell), q += sizeof(int32_t) * ncell;
  memcpy(q, gsl_rng_state(s->rng), rs);
  *blob = p;
  *n = total;
  return HD_OK;
}

int hd_sim_restore_blob(hd_sim *s, const void *blob, size_t n, hd_error *err) {
  ckpt_header h;
  if (n < sizeof h) return hd_error_set(err, HD_EINPUT, "checkpoint is truncated");
  memcpy(&h, blob, sizeof h);
  if (h.magic != HD_CKPT_MAGIC || h.body_size != sizeof(hd_body) ||
      h.clock_size != sizeof(hd_sim_clock) || h.rng_size != gsl_rng_size(s->rng))
    return hd_error_set(err, HD_EINPUT, "checkpoint was written by another build of haff");
  if (h.lx != s->lx || h.ly != s->ly)
    return hd_error_set(err, HD_EINPUT, "checkpoint box %g x %g does not match the scene's", h.lx,
                        h.ly);
  size_t ncell = (size_t)h.ncx * (size_t)h.ncy;
  size_t want = sizeof h + sizeof(hd_sim_clock) +
                (sizeof(hd_body) + sizeof(int32_t)) * (size_t)h.n + sizeof(int32_t) * ncell +
                h.rng_size;
  if (n != want)
    return hd_error_set(err, HD_EINPUT, "checkpoint has %zu bytes, expected %zu", n, want);
  s->n = h.n;
  s->n_species[0] = h.n_species[0];
  s->n_species[1] = h.n_species[1];
  s->b = hd_bodies_alloc(h.n);
  s->id = malloc(sizeof(int32_t) * (size_t)(h.n > 0 ? h.n : 1));
  if (!s->b || !s->id) return hd_error_set(err, HD_ENOMEM, "out of memory");
  int rc = hd_cells_alloc(s, err);
  if (rc) return rc;
  if (s->ncx != h.ncx || s->ncy != h.ncy)
    return hd_error_set(err, HD_EINPUT, "checkpoint cell grid does not match the scene's");
  const unsigned char *q = (const unsigned char *)blob + sizeof h;
  memcpy(&s->c, q, sizeof s->c), q += sizeof s->c;
  memcpy(s->b, q, sizeof(hd_body) * (size_t)h.n), q += sizeof(hd_body) * (size_t)h.n;
  memcpy(s->id, q, sizeof(int32_t) * (size_t)h.n), q += sizeof(int32_t) * (size_t)h.n;
  memcpy(s->head, q, sizeof(int32_t) * ncell), q += sizeof(int32_t) * ncell;
  memcpy(gsl_rng_state(s->rng), q, h.rng_size);
  for (int32_t i = 0; i < s->n; i++) /* the rows (0 in checkpoints of older builds) */
    s->b[i].cy = s->b[i].cell / s->ncx;
  rc = hd_sim_queue_init(s, err);
  if (rc) return rc;
  hd_queue_build(s->q, s->n, &s->b[0].ev_t, HD_BODY_STRIDE);
  return HD_OK;
}
