/* libFuzzer target: checkpoint restore (engine/sim/hd_checkpoint.c, engine/rods/rods.c), below the
 * checksum that hd_run.c puts over a whole checkpoint, so that what the models check is what is
 * fuzzed.  Input: one byte that picks the model (even: the 2D scene below, odd: the rods ring),
 * then the model's blob (the rods ring with constant eps: the stochastic model's sampler takes
 * a second to build under the sanitizers), as hd_sim_checkpoint / hd_rods_checkpoint write it for
 * that scene.  A blob that restores is run for up to 200 collisions and checkpointed again: a
 * restore that accepts a state the engine cannot run is a bug, as is a crash in the restore itself.
 * Seeds: tests/fuzz/corpus/checkpoint/ (real blobs of these scenes); crashes found are kept
 * there and replayed by tests/test_resume.c (fuzz_corpus_replays). */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "hd_model.h"
#include "hd_scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* The scenes whose blobs the input holds (index = first byte & 1). */
static const char *const fuzz_ckpt_scenes[2] = {
    "[system]\nbox = 12 12\nseed = 3\n[dimers]\ncount = 3\nalpha = 0.9\n[disks]\ncount = 3\n"
    "alpha = 0.8\n[walls]\nsides = left right\n[run]\nstop_events = 1000\n",
    "[system]\nseed = 4\n[rods]\ncount = 6\nmodel = constant\neps = 0.9\n[run]\n"
    "stop_events = 1000\n"};

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static hd_scene sc[2];
  static int loaded;
  if (!loaded) {
    hd_error err;
    for (int k = 0; k < 2; k++)
      if (hd_scene_load_string(&sc[k], fuzz_ckpt_scenes[k], "fuzz.ini", NULL, 0, &err)) abort();
    loaded = 1;
  }
  if (size < 1) return 0;
  const hd_scene *s = &sc[data[0] & 1];
  const hd_model_ops *ops = hd_model_for_scene(s);
  void *m = NULL;
  hd_error err;
  if (ops->alloc_restore(&m, s, data + 1, size - 1, &err) != HD_OK) return 0;
  /* a state far hotter than the scenes' (T ~ 1) is run by the engine, but slowly: a body at
   * 1e194 crosses a cell every 1e-195 in time, 4e6 events without a collision (HD_SIM_BUSY) per
   * call; it is not stepped (slow, not wrong: issue 17 item 7 is about such runs) */
  hd_sample_row sample;
  ops->sample(m, &sample); /* energies per body, from the bodies */
  int steps = sample.e_tr + sample.e_rot < 1e6 ? 200 : 0;
  for (int k = 0; k < steps; k++) {
    hd_collision_row row;
    int rc = ops->next(m, INFINITY, &row, &err);
    if (rc != HD_OK) break; /* idle, busy (many events, no collision), collapse: all fine */
  }
  ops->sample(m, &sample);
  void *blob = NULL;
  size_t n = 0;
  if (ops->checkpoint(m, &blob, &n, &err) == HD_OK) free(blob);
  ops->free(m);
  return 0;
}
