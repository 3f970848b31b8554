/* hd_sweepfile: the sweep files of `haff sweep` (README "Studies"), read into their axes,
 * seeds and listed points; no file system beyond reading the file, no scene loaded (the
 * command checks every point against its base scene).
 *
 *   [sweep]  scene = BASE.ini (relative to the sweep file), seeds = LIST (optional)
 *   [axes]   SECTION.KEY = LIST       one axis per key: the full grid of their values
 *   [points] point = S.K=V S.K=V ...  or a listed set of points (not both)
 *
 * A LIST is values separated by blanks, or a range FROM:TO:STEP (TO included).  A value with
 * blanks is written in double quotes ("linear 3"), in a LIST and in a point (S.K="linear 3").
 * Comments: a line starting with ; or #, and ; or # at the start of a value or after a blank
 * (outside double quotes).  A UTF-8 byte order mark at the start is skipped; lines end with \n
 * or \r\n; a NUL byte or another control character (but tab) is refused.  Every refusal is one
 * line "NAME:LINE: [section] key: why".  Read with libinih (hd_sweepfile.c says how). */
#ifndef HD_SWEEPFILE_H
#define HD_SWEEPFILE_H

#include <stddef.h>

#include "hd_error.h"

#define HD_SWEEP_MAX_AXES 32
#define HD_SWEEP_MAX_VALUES 100000
#define HD_SWEEP_MAX_BYTES (64L << 20) /* a larger file is refused */

/* One axis: its key ("section.key"; "seeds" for the seeds), its values as strings (as given
 * to --set, quotes removed) and the line that gave them. */
typedef struct hd_sweep_axis {
  char *key;
  char **v;
  int n;
  long line;
} hd_sweep_axis;

/* A parsed sweep file. */
typedef struct hd_sweepfile {
  char *scene;                         /* [sweep] scene as written; NULL when not given */
  long scene_line;                     /* its line, 0 when not given */
  hd_sweep_axis ax[HD_SWEEP_MAX_AXES]; /* [axes], in file order */
  int nax;                             /* how many */
  hd_sweep_axis seeds;                 /* [sweep] seeds: integers, n = 0 when not given */
  char **points;                       /* [points] point = ...: each as written */
  long *pt_line;                       /* the line of each */
  int npoints;                         /* how many */
} hd_sweepfile;

/* Parses len bytes of text (NUL bytes refused, not ended at) named name in messages into *s.
 * HD_OK, or HD_EINPUT / HD_ENOMEM with "name:LINE: [section] key: why" in err and *s freed.
 * Checks the syntax and what needs no scene: known sections and keys, no duplicates, a scene
 * given, [axes] or [points] (not both), LISTs well formed (ranges FROM <= TO, STEP > 0, at
 * most HD_SWEEP_MAX_VALUES values, none twice), seeds non-negative integers below 2^64. */
int hd_sweepfile_parse(hd_sweepfile *s, const char *text, size_t len, const char *name,
                       hd_error *err);

/* Reads the file path and parses it (name: path).  A directory, an unreadable file or one of
 * more than HD_SWEEP_MAX_BYTES is HD_EINPUT "path: why". */
int hd_sweepfile_read(hd_sweepfile *s, const char *path, hd_error *err);

/* Frees what s holds (s itself is the caller's); s is then empty. */
void hd_sweepfile_free(hd_sweepfile *s);

/* Splits a point's overrides text ("S.K=V S.K=\"V W\" ...": blank-separated, double quotes
 * group and are removed) into at most max words, written into *buf (malloc'd, free() it;
 * NULL on failure) with words[k] pointing into it.  Returns the count, or -1 (an unclosed
 * quote, or out of memory). */
int hd_sweep_split(const char *text, char **buf, const char **words, int max);

/* Writes "key=value" into out (size bytes), the value in double quotes when it holds a blank
 * (hd_sweep_split reads it back).  Returns the length snprintf would. */
int hd_sweep_format_set(char *out, size_t size, const char *key, const char *value);

#endif
