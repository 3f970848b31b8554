/* What the files of engine/scene share (not part of the public API: hd_scene.h is). */
#ifndef HD_SCENE_INTERNAL_H
#define HD_SCENE_INTERNAL_H

#include "hd_scene.h"

/* ---- the short forms of `shape = ...` ------------------------------------------------------- */

/* Numbers a short form takes after its name, besides the optional spacing S. */
#define HD_SCENE_FORM_MAX_PARAM 2

/* A number of a short form and its range: "NAME must be ..." when out of it. */
typedef struct hd_scene_form_param {
  const char *name;     /* as the help text and the messages write it: "A", "N", "ANGLE" */
  double lo, hi;        /* range (hi INFINITY: none above) */
  int lo_open, hi_open; /* the range excludes lo, hi */
  int whole;            /* a whole number */
  const char *note;     /* appended to the range message (NULL: nothing) */
} hd_scene_form_param;

/* One short form of `shape = NAME [numbers] [S]` of a [species NAME] section: every place that
 * knows the short forms (the parser, its messages, the canonical text, the docs' key table, the
 * body built) reads this row.  Every disk of the body has the section's `d` and `m`. */
typedef struct hd_scene_form {
  const char *name;                                   /* the first word: "bent" */
  int nparam;                                         /* numbers after the name, all required */
  hd_scene_form_param param[HD_SCENE_FORM_MAX_PARAM]; /* each, in order */
  int spacing; /* 1: an optional last number S > 0, the centre spacing (default d) */
  /* The disks' centres in the body frame, from the form's numbers v[0 .. nparam - 1] (in range)
   * and the spacing s (S, or d): fills x[], y[] and returns how many (1 .. HD_MAX_BODY_DISKS). */
  int (*build)(const double *v, double s, double *x, double *y);
  const char *help; /* one line, as docs/scene-keys.md's list of short forms gives it */
} hd_scene_form;

/* The short forms, in the order of the help text; the last row has name NULL. */
extern const hd_scene_form hd_scene_forms[];

/* S, the optional last number of a form with `spacing`. */
extern const hd_scene_form_param hd_scene_form_spacing;

/* The form's syntax as the help text writes it ("bent ANGLE [S]") into buf (n bytes). */
void hd_scene_form_syntax(const hd_scene_form *f, char *buf, size_t n);

/* Every form's syntax joined into buf (n bytes): each one `quote`d (e.g. "`" or ""), between
 * them `sep`, before the last `last_sep` ("linear N [S], triangle [S] or bent ANGLE [S]"). */
void hd_scene_forms_list(const char *quote, const char *sep, const char *last_sep, char *buf,
                         size_t n);

/* Why a value is out of the range of q, after q's name: "must be in (0, 180] degrees". */
void hd_scene_form_param_why(const hd_scene_form_param *q, char *buf, size_t n);

#endif
