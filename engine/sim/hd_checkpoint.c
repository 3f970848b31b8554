/* Exact checkpoints: the raw bytes of every body (state, local time, cell links, pending
 * event), the body ids, the cell heads, the clocks and the RNG state.  Restoring them and
 * rebuilding the heap (whose order is total: time, then index) continues the run bit for bit.  The
 * blob is for the same build on the same machine; a header guards against anything else. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hd_sim_internal.h"

#define HD_CKPT_MAGIC1 0x31504b4346464148ULL /* "HAFFCKP1": dimers and disks only */
#define HD_CKPT_MAGIC 0x32504b4346464148ULL  /* "HAFFCKP2": with the species table */

/* Fixed-size header of a checkpoint blob of the first version (read only). */
typedef struct ckpt_header1 {
  uint64_t magic;      /* HD_CKPT_MAGIC1 */
  uint32_t body_size;  /* sizeof(hd_body) */
  uint32_t clock_size; /* sizeof(hd_sim_clock) */
  int32_t n;           /* bodies */
  int32_t n_species[2];
  int32_t ncx, ncy;  /* cells */
  uint64_t rng_size; /* bytes of RNG state */
  double lx, ly;     /* box (must match the scene) */
} ckpt_header1;

/* Fixed-size header of a checkpoint blob. */
typedef struct ckpt_header {
  uint64_t magic;      /* HD_CKPT_MAGIC */
  uint32_t body_size;  /* sizeof(hd_body) */
  uint32_t clock_size; /* sizeof(hd_sim_clock) */
  int32_t n;           /* bodies */
  int32_t nsp;         /* species */
  int32_t n_species[HD_MAX_SPECIES];
  int32_t ncx, ncy;                             /* cells */
  uint64_t rng_size;                            /* bytes of RNG state */
  double lx, ly;                                /* box (must match the scene) */
  hd_shape shape[HD_MAX_SPECIES];               /* the species table (must match the scene's) */
  double alpha[HD_MAX_SPECIES][HD_MAX_SPECIES]; /* (unused entries 0) */
} ckpt_header;

int hd_sim_checkpoint(const hd_sim *s, void **blob, size_t *n, hd_error *err) {
  size_t ncell = (size_t)s->ncx * (size_t)s->ncy, rs = gsl_rng_size(s->rng);
  size_t total = sizeof(ckpt_header) + sizeof(hd_sim_clock) +
                 (sizeof(hd_body) + sizeof(int32_t)) * (size_t)s->n + sizeof(int32_t) * ncell + rs;
  unsigned char *p = malloc(total);
  if (!p) return hd_error_set(err, HD_ENOMEM, "out of memory for a checkpoint");
  ckpt_header h;
  memset(&h, 0, sizeof h); /* padding too: the blob is checksummed */
  h.magic = HD_CKPT_MAGIC;
  h.body_size = sizeof(hd_body);
  h.clock_size = sizeof(hd_sim_clock);
  h.n = s->n;
  h.nsp = s->nsp;
  memcpy(h.n_species, s->n_species, sizeof h.n_species);
  h.ncx = s->ncx;
  h.ncy = s->ncy;
  h.rng_size = rs;
  h.lx = s->lx;
  h.ly = s->ly;
  for (int sp = 0; sp < s->nsp; sp++) h.shape[sp] = s->shape[sp];
  memcpy(h.alpha, s->alpha, sizeof h.alpha);
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

/* What a restored state must satisfy for the engine to run it: every count, index and link in
 * range, every number finite, the cell lists a partition of the bodies, every pending event one
 * the engine can have made, no two bodies overlapping.  A checkpoint that fails is damaged
 * (hd_run.c's checksum catches a flipped bit first; this catches what a checksum cannot, a blob
 * that was written whole but wrong, and keeps a bad blob from crashing the engine).  HD_OK or
 * HD_EINPUT naming the first thing found wrong. */
static int check_state(const hd_sim *s, hd_error *err) {
  const hd_sim_clock *c = &s->c;
  if (!isfinite(c->t) || !isfinite(c->t_offset) || c->events < 0 || c->collisions < 0 ||
      c->wall_hits < 0 || c->stale < 0 || c->next_rebase < 0 || !(c->e_kin >= 0.0) ||
      !isfinite(c->e_kin) || c->slow_run < 0 || c->pile_run < 0 || !(c->dt_mean >= 0.0) ||
      !isfinite(c->dt_mean) || !(c->t_last <= c->t))
    return hd_error_set(err, HD_EINPUT, "checkpoint: clocks and counters out of range");
  int32_t n = s->n, ncell = s->ncx * s->ncy;
  int32_t count[HD_MAX_SPECIES] = {0};
  /* the box with a margin of one cell: a body is wrapped at its crossing of the box edge, so
   * at its own time it may be just past the edge */
  double x_lo = -s->cwx, x_hi = s->lx + s->cwx, y_lo = -s->cwy, y_hi = s->ly + s->cwy;
  for (int32_t i = 0; i < n; i++) {
    const hd_body *b = &s->b[i];
    if (b->species < 0 || b->species >= s->nsp)
      return hd_error_set(err, HD_EINPUT, "checkpoint: body %d has species %d", i, b->species);
    count[b->species]++;
    const hd_kin *k = &b->k;
    if (!isfinite(b->t) || !(b->t <= c->t) || !isfinite(k->vx) || !isfinite(k->vy) ||
        !isfinite(k->omega) || !(fabs(k->phi) <= 4.0) || !(k->x >= x_lo && k->x <= x_hi) ||
        !(k->y >= y_lo && k->y <= y_hi))
      return hd_error_set(err, HD_EINPUT, "checkpoint: body %d: state out of range", i);
    if (b->cell < 0 || b->cell >= ncell || (b->next < -1 || b->next >= n))
      return hd_error_set(err, HD_EINPUT, "checkpoint: body %d: cell links out of range", i);
    /* its pending events: the earlier is its key, neither before its own time */
    if (isnan(b->p_t) || isnan(b->c_t) || b->ev_t != fmin(b->p_t, b->c_t) || !(b->p_t >= b->t) ||
        !(b->c_t >= b->t) || !(b->ev_t >= c->t))
      return hd_error_set(err, HD_EINPUT, "checkpoint: body %d: event times out of range", i);
    int nd_i = s->shape[b->species].n;
    if (b->c_dir < 0 || b->c_dir > HD_WAKE || b->p_ka < 0 || b->p_ka >= nd_i)
      return hd_error_set(err, HD_EINPUT, "checkpoint: body %d: pending event out of range", i);
    if (b->p_type == HD_EV_PAIR) {
      int32_t j = b->p_partner;
      if (j < 0 || j >= n || j == i || s->b[j].species < 0 || s->b[j].species >= s->nsp ||
          b->p_kb < 0 || b->p_kb >= s->shape[s->b[j].species].n ||
          abs(hd_image_code(b->p_imx, s->b[j].wx, b->wx)) > 1 ||
          abs(hd_image_code(b->p_imy, s->b[j].wy, b->wy)) > 1)
        return hd_error_set(err, HD_EINPUT, "checkpoint: body %d: pair event out of range", i);
    } else if (b->p_type == HD_EV_WALL) {
      static const unsigned bit[4] = {HD_WALL_LEFT, HD_WALL_RIGHT, HD_WALL_BOTTOM, HD_WALL_TOP};
      if (b->p_partner < 0 || b->p_partner > 3 || !(s->walls & bit[b->p_partner]))
        return hd_error_set(err, HD_EINPUT, "checkpoint: body %d: wall event out of range", i);
    } else if (b->p_type != HD_EV_NONE || b->p_t != INFINITY) {
      return hd_error_set(err, HD_EINPUT, "checkpoint: body %d: pending event out of range", i);
    }
  }
  int same = 1;
  for (int sp = 0; sp < s->nsp; sp++) same &= count[sp] == s->n_species[sp];
  if (!same)
    return hd_error_set(err, HD_EINPUT, "checkpoint: species counts do not match the bodies");
  /* the user's numbers: a permutation of 0..n-1; the cell lists: each body once, in its cell */
  unsigned char *seen = calloc((size_t)(n > 0 ? n : 1), 1);
  if (!seen) return hd_error_set(err, HD_ENOMEM, "out of memory");
  int rc = HD_OK;
  for (int32_t i = 0; i < n && !rc; i++) {
    if (s->id[i] < 0 || s->id[i] >= n || seen[s->id[i]])
      rc = hd_error_set(err, HD_EINPUT, "checkpoint: body numbers are not 0..%d once each", n - 1);
    else
      seen[s->id[i]] = 1;
  }
  memset(seen, 0, (size_t)(n > 0 ? n : 1));
  int32_t linked = 0;
  for (int32_t cell = 0; cell < ncell && !rc; cell++) {
    int32_t j = s->head[cell];
    if (j < -1 || j >= n) rc = hd_error_set(err, HD_EINPUT, "checkpoint: cell %d: bad head", cell);
    for (; j >= 0 && !rc; j = s->b[j].next) {
      if (seen[j] || s->b[j].cell != cell)
        rc = hd_error_set(err, HD_EINPUT, "checkpoint: cell lists do not match the bodies");
      else
        seen[j] = 1, linked++;
    }
  }
  free(seen);
  if (!rc && linked != n)
    rc = hd_error_set(err, HD_EINPUT, "checkpoint: %d of %d bodies in the cell lists", linked, n);
  if (rc) return rc;
  /* the bodies in their cells (with the margin of a cell: see above), at their own time and
   * now: a body leaves its cell only at its crossing event, which is still to come (a body
   * at t = -4e225 was far away now, and took 4e6 crossings per collision to come back) */
  for (int32_t i = 0; i < n; i++) {
    const hd_body *b = &s->b[i];
    int32_t cx = b->cell % s->ncx, cy = b->cell / s->ncx;
    hd_kin now;
    hd_sim_body_now(s, i, &now);
    const hd_kin *k[2] = {&b->k, &now};
    for (int w = 0; w < 2; w++)
      if (!(k[w]->x >= (cx - 1) * s->cwx && k[w]->x <= (cx + 2) * s->cwx &&
            k[w]->y >= (cy - 1) * s->cwy && k[w]->y <= (cy + 2) * s->cwy))
        return hd_error_set(err, HD_EINPUT, "checkpoint: body %d is not in its cell%s", i,
                            w ? " now" : "");
  }
  /* the generator's position in its table (gsl's mt19937 keeps it beside the table) */
  if (gsl_rng_size(s->rng) == sizeof(unsigned long) * 624 + sizeof(int)) {
    int mti;
    memcpy(&mti, (const unsigned char *)gsl_rng_state(s->rng) + sizeof(unsigned long) * 624,
           sizeof mti);
    if (mti < 0 || mti > 624)
      return hd_error_set(err, HD_EINPUT, "checkpoint: random generator state out of range");
  }
  return HD_OK;
}

/* The header of a blob of either version, as a current one (a first-version blob holds dimers
 * and disks, with the scene's shapes); its size in *hsize.  HD_EINPUT if it is neither. */
static int read_header(const hd_sim *s, const void *blob, size_t n, ckpt_header *h, size_t *hsize,
                       hd_error *err) {
  uint64_t magic;
  if (n < sizeof magic) return hd_error_set(err, HD_EINPUT, "checkpoint is truncated");
  memcpy(&magic, blob, sizeof magic);
  memset(h, 0, sizeof *h);
  if (magic == HD_CKPT_MAGIC1) {
    ckpt_header1 o;
    if (n < sizeof o) return hd_error_set(err, HD_EINPUT, "checkpoint is truncated");
    memcpy(&o, blob, sizeof o);
    *h = (ckpt_header){
        HD_CKPT_MAGIC, o.body_size, o.clock_size, o.n,  2,    {o.n_species[0], o.n_species[1]},
        o.ncx,         o.ncy,       o.rng_size,   o.lx, o.ly, {{0}},
        {{0}}};
    for (int sp = 0; sp < s->nsp; sp++) h->shape[sp] = s->shape[sp];
    *hsize = sizeof o;
    return HD_OK;
  }
  if (n < sizeof *h) return hd_error_set(err, HD_EINPUT, "checkpoint is truncated");
  memcpy(h, blob, sizeof *h);
  *hsize = sizeof *h;
  return HD_OK;
}

int hd_sim_checkpoint_needs_trailer(const void *blob, size_t n) {
  uint64_t magic;
  if (!blob || n < sizeof magic) return 0;
  memcpy(&magic, blob, sizeof magic);
  return magic == HD_CKPT_MAGIC;
}

int hd_sim_restore_blob(hd_sim *s, const void *blob, size_t n, hd_error *err) {
  ckpt_header h;
  size_t hsize;
  int rc = read_header(s, blob, n, &h, &hsize, err);
  if (rc) return rc;
  if (h.magic != HD_CKPT_MAGIC || h.body_size != sizeof(hd_body) ||
      h.clock_size != sizeof(hd_sim_clock) || h.rng_size != gsl_rng_size(s->rng))
    return hd_error_set(err, HD_EINPUT, "checkpoint was written by another build of haff");
  if (h.lx != s->lx || h.ly != s->ly)
    return hd_error_set(err, HD_EINPUT, "checkpoint box %g x %g does not match the scene's", h.lx,
                        h.ly);
  if (h.nsp != s->nsp)
    return hd_error_set(err, HD_EINPUT, "checkpoint has %d species, the scene %d", h.nsp, s->nsp);
  for (int sp = 0; sp < s->nsp; sp++)
    if (memcmp(&h.shape[sp], &s->shape[sp], sizeof(hd_shape)))
      return hd_error_set(err, HD_EINPUT,
                          "checkpoint: species %d (%s) has another shape than the "
                          "scene's",
                          sp, s->sp_name[sp]);
  /* the counts before any size is computed from them (a negative one wrapped round) */
  int64_t total = 0;
  int bad = h.n < 0;
  for (int sp = 0; sp < s->nsp; sp++) bad |= h.n_species[sp] < 0, total += h.n_species[sp];
  if (bad || total != h.n || h.ncx < 1 || h.ncy < 1 ||
      (int64_t)h.ncx * h.ncy > (int64_t)(n / sizeof(int32_t)))
    return hd_error_set(err, HD_EINPUT, "checkpoint: body or cell counts out of range");
  size_t ncell = (size_t)h.ncx * (size_t)h.ncy;
  size_t want = hsize + sizeof(hd_sim_clock) + (sizeof(hd_body) + sizeof(int32_t)) * (size_t)h.n +
                sizeof(int32_t) * ncell + h.rng_size;
  if (n != want)
    return hd_error_set(err, HD_EINPUT, "checkpoint has %zu bytes, expected %zu", n, want);
  s->n = h.n;
  for (int sp = 0; sp < s->nsp; sp++) s->n_species[sp] = h.n_species[sp];
  s->b = hd_bodies_alloc(h.n);
  s->id = malloc(sizeof(int32_t) * (size_t)(h.n > 0 ? h.n : 1));
  if (!s->b || !s->id) return hd_error_set(err, HD_ENOMEM, "out of memory");
  rc = hd_cells_alloc(s, err);
  if (rc) return rc;
  if (s->ncx != h.ncx || s->ncy != h.ncy)
    return hd_error_set(err, HD_EINPUT, "checkpoint cell grid does not match the scene's");
  const unsigned char *q = (const unsigned char *)blob + hsize;
  memcpy(&s->c, q, sizeof s->c), q += sizeof s->c;
  memcpy(s->b, q, sizeof(hd_body) * (size_t)h.n), q += sizeof(hd_body) * (size_t)h.n;
  memcpy(s->id, q, sizeof(int32_t) * (size_t)h.n), q += sizeof(int32_t) * (size_t)h.n;
  memcpy(s->head, q, sizeof(int32_t) * ncell), q += sizeof(int32_t) * ncell;
  memcpy(gsl_rng_state(s->rng), q, h.rng_size);
  rc = check_state(s, err);
  if (rc) return rc;
  for (int32_t i = 0; i < s->n; i++) /* the rows (0 in checkpoints of older builds) */
    s->b[i].cy = s->b[i].cell / s->ncx;
  int32_t oi, oj; /* no two bodies overlap (O(N), through the cells) */
  double o = hd_sim_max_overlap(s, &oi, &oj);
  if (o > 1e-6) /* the engine's verification allows 1e-9 of a diameter at a contact */
    return hd_error_set(err, HD_EINPUT,
                        "checkpoint: bodies %d and %d overlap by %.3g of a diameter", oi, oj, o);
  rc = hd_sim_queue_init(s, err);
  if (rc) return rc;
  hd_queue_build(s->q, s->n, &s->b[0].ev_t, HD_BODY_STRIDE);
  return HD_OK;
}
