/* `haff movie DB [--run ID] -o run.mp4|run.gif [--color speed|density|species] [--fps N]
 * [--size PX]`: a movie of a run's frames ([log] frames_every or frames_every_time) in the style
 * of the dimer paper's Fig. 1: every disk drawn as its disk (a dimer as its two), coloured by its
 * body's speed, by the local density around it or by its species; axes in units of the disk
 * diameter d (x / d, y / d), each frame stamped with its time t and cpd.  gnuplot (pngcairo)
 * draws the frames into a temporary folder, ffmpeg encodes them; the folder is removed after.
 *
 * Colours (a cooling gas slows down and clusters: scales of the frame itself, so that the
 * structure stays visible while the energy falls by decades):
 *   speed    |V| of the body over the frame's rms |V|, on [0, 3];
 *   density  bodies whose centres lie within 5 diameters (periodic images included), over the
 *            frame's mean count in such a disc, on [0, 3];
 *   species  one colour per species (the run's species table; without one, dimers and disks),
 *            from the Okabe-Ito palette (distinct for colour-blind readers), named in a key.
 * The unit of length d: the dimers' disk diameter, else the disks', else the first species'
 * largest disk.  A ring of rods is refused (exit 2): drawn as a strip of disks it is unreadable;
 * rods-phase and rods-density show its evolution.
 * Positions are wrapped into the box (a disk over an edge is cut there, not drawn twice). */
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include "haff.h"
#include "hd_body.h"
#include "hd_db.h"
#include "hd_framedb.h"
#include "hd_opt.h"
#include "hd_scene.h"

/* SIGINT, SIGTERM or SIGHUP while the movie is made (movie_signal): the child running is sent
 * the same signal, the temporary folder removed, and haff movie ends with status 1 (a killed
 * movie used to leave its haff-movie-* folder behind). */
static volatile sig_atomic_t movie_stop = 0;
static volatile pid_t movie_child = 0;
static void movie_signal(int sig) {
  movie_stop = sig;
  if (movie_child > 0) kill(movie_child, sig);
}

/* Runs argv (a program and its arguments) with stdout to /dev/null; its exit status, 127 if it
 * cannot be run, or -1 (killed). */
static int run_prog(char *const argv[]) {
  pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    /* the descriptor, not the stream: bin/haff's stdout is a stream of its own (haff_out.c) */
    int null = open("/dev/null", O_WRONLY);
    if (null < 0 || dup2(null, STDOUT_FILENO) < 0) _exit(127);
    execvp(argv[0], argv);
    _exit(127);
  }
  movie_child = pid;
  if (movie_stop) kill(pid, (int)movie_stop);
  int st;
  pid_t w;
  while ((w = waitpid(pid, &st, 0)) < 0 && errno == EINTR) continue;
  movie_child = 0;
  if (w != pid) return -1;
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* How bodies are coloured (--color). */
enum { COLOR_SPEED, COLOR_DENSITY, COLOR_SPECIES };

/* Colour values of the n bodies of a frame (speed or density mode) into val. */
static void colour(int density, long n, const double *x, const double *y, const float *vx,
                   const float *vy, double lx, double ly, double reach, double *val) {
  if (!density) {
    double s2 = 0;
    for (long i = 0; i < n; i++) s2 += (double)vx[i] * vx[i] + (double)vy[i] * vy[i];
    double rms = sqrt(s2 / (double)(n > 0 ? n : 1));
    for (long i = 0; i < n; i++) val[i] = rms > 0 ? hypot((double)vx[i], (double)vy[i]) / rms : 0;
    return;
  }
  /* neighbours within reach on a periodic grid of cells at least reach wide */
  long cx = (long)fmax(1, floor(lx / reach)), cy = (long)fmax(1, floor(ly / reach));
  long *head = malloc((size_t)(cx * cy) * sizeof *head), *next = malloc((size_t)n * sizeof *next);
  if (!head || !next) {
    for (long i = 0; i < n; i++) val[i] = 1;
    free(head);
    free(next);
    return;
  }
  for (long c = 0; c < cx * cy; c++) head[c] = -1;
  for (long i = 0; i < n; i++) {
    long a = (long)floor(x[i] / lx * (double)cx), b = (long)floor(y[i] / ly * (double)cy);
    a = ((a % cx) + cx) % cx, b = ((b % cy) + cy) % cy;
    next[i] = head[a * cy + b];
    head[a * cy + b] = i;
  }
  double mean = (double)n * M_PI * reach * reach / (lx * ly), r2 = reach * reach;
  for (long i = 0; i < n; i++) {
    long a = (long)floor(x[i] / lx * (double)cx), b = (long)floor(y[i] / ly * (double)cy);
    a = ((a % cx) + cx) % cx, b = ((b % cy) + cy) % cy;
    long count = 0, cells[9], nc = 0;
    for (long da = -1; da <= 1; da++) /* the 3 x 3 cells around, each once (a grid may be
                                         narrower than 3 cells) */
      for (long db = -1; db <= 1; db++) {
        long cell = ((((a + da) % cx) + cx) % cx) * cy + ((((b + db) % cy) + cy) % cy), seen = 0;
        for (long q = 0; q < nc; q++) seen |= cells[q] == cell;
        if (!seen) cells[nc++] = cell;
      }
    for (long q = 0; q < nc; q++)
      for (long j = head[cells[q]]; j >= 0; j = next[j]) {
        double dx = remainder(x[j] - x[i], lx), dy = remainder(y[j] - y[i], ly);
        if (dx * dx + dy * dy <= r2) count++;
      }
    val[i] = (double)count / mean;
  }
  free(head);
  free(next);
}

/* Everything a movie needs to know of its run. */
typedef struct movie {
  const char *dbpath, *outpath, *tmp;
  int64_t run;
  int color, fps, size, gif; /* color: COLOR_SPEED, COLOR_DENSITY or COLOR_SPECIES */
  double unit;               /* the unit of length d of the axes (see the top) */
  double lx, ly;
  hd_scene sc;
  int *kinds;           /* body kinds, from the initial states */
  long n;               /* bodies */
  hd_shape dimer, disk; /* the scene's [dimers] and [disks], as the engine has them */
  int nsp;              /* species of the run's species table (schema version 3), 0 if none */
  hd_shape sp[HD_MAX_SPECIES];       /* their shapes (hd_db_read_species) */
  int64_t first[HD_MAX_SPECIES + 1]; /* bodies first[s] .. first[s + 1] - 1 are of species s */
  char spname[HD_MAX_SPECIES][64];   /* their names (species.name), for --color species */
} movie;

/* The species index of body i for --color species: its species in the run's species table, or
 * for a run without one 0 for a dimer and 1 for a disk. */
static int body_species(const movie *m, long i) {
  for (int s = 0; s < m->nsp; s++)
    if (i >= m->first[s] && i < m->first[s + 1]) return s;
  return m->kinds[i] == HD_KIND_DIMER ? 0 : 1;
}

/* The shape of body i (not a rod): its species' in the run's species table, or for a run without
 * one the scene's [dimers] or [disks] by its stored kind. */
static const hd_shape *body_shape(const movie *m, long i) {
  for (int s = 0; s < m->nsp; s++)
    if (i >= m->first[s] && i < m->first[s + 1]) return &m->sp[s];
  return m->kinds[i] == HD_KIND_DIMER ? &m->dimer : &m->disk;
}

/* Reads the run, its box and scene and its bodies' kinds.  0 or an exit code (said). */
static int read_run(sqlite3 *h, movie *m) {
  hd_framedb_run run;
  hd_error err;
  int rc = hd_framedb_run_read(h, m->run, &run, &err);
  if (rc) {
    fprintf(stderr, "haff movie: %s: %s%s\n", m->dbpath, rc == HD_EIO ? "read runs: " : "",
            err.msg);
    return rc == HD_EINPUT ? 2 : 1;
  }
  m->run = run.id;
  m->lx = run.box_x;
  m->ly = run.box_y;
  int code = 0;
  char name[64];
  snprintf(name, sizeof name, "run %lld scene", (long long)m->run);
  if (hd_scene_load_stored(&m->sc, run.scene, name, &err)) {
    fprintf(stderr, "haff movie: %s: %s\n", m->dbpath, err.msg);
    code = 2;
  }
  free(run.scene);
  if (code) return code;
  if (m->sc.n_rods > 0) {
    fprintf(stderr,
            "haff movie: %s: run %lld is a ring of rods, which a movie of disks does not show: "
            "use haff rods-phase or haff rods-density (or haff export xyz)\n",
            m->dbpath, (long long)m->run);
    return 2;
  }
  if (!(m->lx > 0 && m->ly > 0)) {
    fprintf(stderr, "haff movie: %s: run %lld: box unknown\n", m->dbpath, (long long)m->run);
    return 1;
  }
  m->n = hd_scene_bodies(&m->sc);
  m->kinds = calloc((size_t)(m->n > 0 ? m->n : 1), sizeof *m->kinds);
  if (!m->kinds) return 1;
  if (hd_framedb_kinds(h, m->run, m->kinds, m->n, HD_KIND_DIMER, HD_KIND_DISK, &err)) {
    fprintf(stderr, "haff movie: %s: read states: %s\n", m->dbpath, err.msg);
    return 1;
  }
  hd_shape_dimer(&m->dimer, m->sc.dimer_d, m->sc.dimer_a, m->sc.dimer_m);
  hd_shape_disk(&m->disk, m->sc.disk_sigma, m->sc.disk_mass);
  int64_t count[HD_MAX_SPECIES];
  if (hd_db_read_species(h, m->run, m->sp, count, HD_MAX_SPECIES, &m->nsp, &err)) {
    fprintf(stderr, "haff movie: %s: %s\n", m->dbpath, err.msg);
    return 1;
  }
  m->first[0] = 0;
  for (int k = 0; k < m->nsp; k++) m->first[k + 1] = m->first[k] + count[k];
  for (int k = 0; k < m->nsp; k++) snprintf(m->spname[k], sizeof m->spname[k], "species %d", k);
  sqlite3_stmt *q = NULL; /* the names, where the species table has them */
  if (m->nsp > 0 &&
      sqlite3_prepare_v2(h, "SELECT idx, name FROM species WHERE run = ? ORDER BY idx", -1, &q,
                         NULL) == SQLITE_OK) {
    sqlite3_bind_int64(q, 1, m->run);
    for (int k = 0; k < m->nsp && sqlite3_step(q) == SQLITE_ROW; k++) {
      const unsigned char *nm = sqlite3_column_text(q, 1);
      if (nm) snprintf(m->spname[k], sizeof m->spname[k], "%s", (const char *)nm);
    }
  }
  sqlite3_finalize(q);
  m->unit = m->sc.n_dimers > 0  ? m->sc.dimer_d
            : m->sc.n_disks > 0 ? m->sc.disk_sigma
            : m->nsp > 0        ? m->sp[0].d
                                : 1;
  if (!(m->unit > 0)) m->unit = 1;
  return 0;
}

/* Writes the frames' data files and the gnuplot script into m->tmp; *frames their count. */
static int write_frames(sqlite3 *h, const movie *m, long *frames) {
  hd_framedb *st = NULL;
  hd_error err;
  *frames = 0;
  int rc = hd_framedb_open(h, m->run, &st, &err);
  if (rc == HD_EINPUT) { /* a database from before the frames table */
    fprintf(stderr,
            "haff movie: %s: run %lld has no frames: run it with [log] frames_every or "
            "frames_every_time\n",
            m->dbpath, (long long)m->run);
    return 2;
  }
  if (rc) {
    fprintf(stderr, "haff movie: %s: read frames: %s\n", m->dbpath, err.msg);
    return 1;
  }
  char path[4200];
  snprintf(path, sizeof path, "%s/movie.gp", m->tmp);
  FILE *gp = fopen(path, "w");
  double *x = malloc((size_t)(m->n + 1) * sizeof *x), *y = malloc((size_t)(m->n + 1) * sizeof *y);
  double *phi = malloc((size_t)(m->n + 1) * sizeof *phi),
         *val = malloc((size_t)(m->n + 1) * sizeof *val);
  float *vx = malloc((size_t)(m->n + 1) * sizeof *vx),
        *vy = malloc((size_t)(m->n + 1) * sizeof *vy);
  int code = 0;
  if (!gp || !x || !y || !phi || !val || !vx || !vy) {
    fprintf(stderr, "haff movie: %s: %s\n", path, gp ? "out of memory" : strerror(errno));
    code = 1;
  }
  double w = m->size, hgt = m->size;
  if (m->lx >= m->ly)
    hgt = 2 * fmax(40, round(0.5 * m->size * m->ly / m->lx)) + 60;
  else
    w = 2 * fmax(40, round(0.5 * m->size * m->lx / m->ly));
  double u = m->unit;
  /* Okabe-Ito: distinct for colour-blind readers (the figures' palette, plots/style.gp) */
  static const char *const okabe[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                      "#E69F00", "#56B4E9", "#000000", "#777777"};
  if (!code) {
    fprintf(gp,
            "set terminal pngcairo size %.0f,%.0f font 'DejaVu Sans,10'\nset encoding utf8\n"
            "set size ratio -1\nset xrange [0:%.17g]\nset yrange [0:%.17g]\n"
            "set xtics out nomirror\nset ytics out nomirror\nset border lw 1.5\n"
            "set xlabel '%s' offset 0,0.5\nset ylabel '%s' offset 1.5,0\n"
            "set style fill solid 1.0 noborder\n",
            w, hgt, m->lx / u, m->ly / u, "x / d", "y / d");
    if (m->color == COLOR_SPECIES) {
      fprintf(gp, "unset colorbox\nset key outside top center horizontal samplen 1\n");
      int ns = m->nsp > 0 ? m->nsp : 2;
      fprintf(gp, "keys = \"");
      for (int k = 0; k < ns; k++) {
        if (m->nsp == 0 && ((k == 0 && m->sc.n_dimers == 0) || (k == 1 && m->sc.n_disks == 0)))
          continue; /* only the kinds the run has */
        fprintf(gp, "keyentry with boxes fc rgb '%s' title '%s', ", okabe[k % 8],
                m->nsp > 0 ? m->spname[k]
                : k == 0   ? "dimer"
                           : "disk");
      }
      fprintf(gp, "\"\n");
    } else
      fprintf(gp,
              "unset key\nset cbrange [0:3]\nset cblabel '%s'\n"
              "set palette defined (0 '#30123b', 0.15 '#3e4a89', 0.35 '#26828e', 0.55 "
              "'#35b779', 0.8 '#b5de2b', 1 '#fde725')\n",
              m->color == COLOR_DENSITY ? "local density / mean (within 5 d)" : "|V| / rms |V|");
  }
  double reach = 5 * (m->sc.n_dimers > 0 ? m->sc.dimer_d : m->sc.disk_sigma);
  int s = 0;
  hd_framedb_frame fr;
  while (!code && !movie_stop && (s = hd_framedb_next(st, &fr, &err)) == 1) {
    double t = fr.t, cpd = fr.cpd;
    long n = fr.n;
    const unsigned char *data = fr.data;
    if (n != m->n || fr.bytes != n * HD_FRAME_BODY_BYTES) {
      fprintf(stderr, "haff movie: %s: run %lld: a frame of %ld bodies, the scene has %ld\n",
              m->dbpath, (long long)m->run, n, m->n);
      code = 1;
      break;
    }
    for (long i = 0; i < n; i++) {
      double d[3];
      float f[3];
      memcpy(d, data + (size_t)i * HD_FRAME_BODY_BYTES, sizeof d);
      memcpy(f, data + (size_t)i * HD_FRAME_BODY_BYTES + sizeof d, sizeof f);
      x[i] = d[0], y[i] = d[1], phi[i] = d[2];
      vx[i] = f[0], vy[i] = f[1];
    }
    if (m->color == COLOR_SPECIES)
      for (long i = 0; i < n; i++)
        val[i] = (double)strtol(okabe[body_species(m, i) % 8] + 1, NULL, 16);
    else
      colour(m->color == COLOR_DENSITY, n, x, y, vx, vy, m->lx, m->ly, reach, val);
    snprintf(path, sizeof path, "%s/f%06ld.dat", m->tmp, *frames);
    FILE *dat = fopen(path, "w");
    if (!dat) {
      fprintf(stderr, "haff movie: %s: %s\n", path, strerror(errno));
      code = 1;
      break;
    }
    for (long i = 0; i < n; i++) {
      hd_kin k = {x[i], y[i], vx[i], vy[i], phi[i], 0};
      const hd_shape *sh = body_shape(m, i);
      for (int j = 0; j < (sh ? sh->n : 1); j++) {
        double px = x[i], py = y[i], r = sh ? 0.5 * sh->dk[j] : 0.25;
        if (sh) hd_kin_disk_pos(&k, sh, j, &px, &py); /* the engine's disk positions */
        px -= m->lx * floor(px / m->lx);
        py -= m->ly * floor(py / m->ly);
        fprintf(dat, "%.9g %.9g %.6g %.8g\n", px / u, py / u, r / u, val[i]);
      }
    }
    fclose(dat);
    fprintf(gp,
            "set output '%s/f%06ld.png'\nset title sprintf('t = %%.6g   cpd = %%.4g   N = %ld', "
            "%.17g, %.17g)\nplot '%s/f%06ld.dat' using 1:2:3:4 with circles lc %s notitle%s\n",
            m->tmp, *frames, n, t, cpd, m->tmp, *frames,
            m->color == COLOR_SPECIES ? "rgb variable" : "palette",
            m->color == COLOR_SPECIES ? ", @keys NaN notitle" : "");
    (*frames)++;
  }
  if (!code && s < 0) {
    fprintf(stderr, "haff movie: %s: read frames: %s\n", m->dbpath, err.msg);
    code = 1;
  }
  if (!code && *frames == 0) {
    fprintf(stderr,
            "haff movie: %s: run %lld has no frames: run it with [log] frames_every or "
            "frames_every_time\n",
            m->dbpath, (long long)m->run);
    code = 2;
  }
  if (gp && fclose(gp) != 0 && !code) code = 1;
  hd_framedb_close(st);
  free(x), free(y), free(phi), free(val), free(vx), free(vy);
  return code;
}

/* The options of haff movie, into the movie. */
static const hd_optdef movie_opts[] = {
    HD_OPT_INT("run", 0, movie, run, 1, INT64_MAX, HD_OPTF_ONCE, "ID",
               "the run [the newest run in DB]"),
    HD_OPT_STR("output", 'o', movie, outpath, "FILE",
               "the movie; its extension chooses the format (.mp4 or .gif)",
               .flags = HD_OPTF_OUTPUT),
    HD_OPT_ENUM("color", 0, movie, color, "speed|density|species", "C",
                "speed, density or species [speed]"),
    HD_OPT_INT("fps", 0, movie, fps, 1, 120, 0, "N", "frames per second [10]"),
    HD_OPT_INT("size", 0, movie, size, 100, 4000, 0, "PX",
               "width of the longer side in pixels, even [720]"),
    {0}};

const hd_optspec hd_cmd_movie_spec = {
    HD_OPT_SPEC("movie", movie_opts, 0, 1, 1, "one DB"),
    .head = "usage: haff movie DB [--run ID] -o FILE.mp4|FILE.gif\n"
            "                  [--color speed|density|species] [--fps N] [--size PX]\n"
            "Draws the frames of a run ([log] frames_every or frames_every_time) as a movie: each\n"
            "disk as its disk, coloured by its body's speed over the frame's rms speed, or by the\n"
            "local density (bodies within 5 diameters over the frame's mean), on [0, 3], or by\n"
            "its species (a key names them); axes in units of the disk diameter d, each frame\n"
            "stamped with t, cpd and N.  gnuplot draws, ffmpeg encodes (H.264 for .mp4, GIF).\n"
            "2D runs only: a ring of rods is refused (rods-phase, rods-density show it).\n"};

int hd_cmd_movie(int argc, char **argv) {
  movie m = {.fps = 10, .size = 720};
  hd_optres res;
  int rc = hd_opt_parse(&hd_cmd_movie_spec, argc, argv, &m, &res);
  if (rc) return rc < 0 ? 0 : rc;
  if (m.size % 2) {
    fprintf(stderr, "haff movie: --size %d: must be an even number of pixels in [100, 4000]\n",
            m.size);
    return 2;
  }
  m.dbpath = res.pos[0];
  size_t len = m.outpath ? strlen(m.outpath) : 0;
  if (len > 4 && !strcmp(m.outpath + len - 4, ".gif"))
    m.gif = 1;
  else if (!(len > 4 && !strcmp(m.outpath + len - 4, ".mp4"))) {
    fprintf(stderr, "haff movie: -o %s: give the movie's file, ending in .mp4 or .gif\n",
            m.outpath ? m.outpath : "(missing)");
    return 2;
  }
  hd_error err;
  hd_error_clear(&err);
  static const char *const tables[] = {"runs", "states", NULL}; /* frames: not in older files */
  sqlite3 *h = NULL;
  int orc = hd_db_open_read(m.dbpath, SQLITE_OPEN_NOMUTEX, tables, &h, &err);
  if (orc) {
    fprintf(stderr, "haff movie: %s\n", err.msg);
    return orc == HD_EINPUT ? 2 : 1;
  }
  hd_scene_defaults(&m.sc);
  int code = read_run(h, &m);
  char tmpl[4200];
  const char *tmpdir = getenv("TMPDIR"); /* the temporary directory, as mkstemp(3) users take */
  snprintf(tmpl, sizeof tmpl, "%s/haff-movie-XXXXXX", tmpdir && *tmpdir ? tmpdir : "/tmp");
  long frames = 0;
  struct sigaction sa, old[3];
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = movie_signal;
  sigemptyset(&sa.sa_mask);
  static const int sigs[3] = {SIGINT, SIGTERM, SIGHUP};
  for (int k = 0; k < 3; k++) sigaction(sigs[k], &sa, &old[k]);
  if (!code && !mkdtemp(tmpl)) {
    fprintf(stderr, "haff movie: cannot make a temporary folder: %s\n", strerror(errno));
    code = 1;
  }
  if (!code) {
    m.tmp = tmpl;
    code = write_frames(h, &m, &frames);
  }
  hd_db_close_read(h);
  if (!code) {
    char gpfile[4200];
    snprintf(gpfile, sizeof gpfile, "%s/movie.gp", m.tmp);
    char *gpa[] = {"gnuplot", gpfile, NULL};
    int g = movie_stop ? -1 : run_prog(gpa);
    if (g != 0 && !movie_stop) {
      fprintf(stderr, "haff movie: gnuplot failed on %s (%s)\n", gpfile,
              g == 127 ? "is gnuplot-nox installed?" : "see its message above");
      code = 1;
    }
  }
  char outarg[4200]; /* a name that starts with '-' would be read by ffmpeg as an option */
  snprintf(outarg, sizeof outarg, "%s%s", m.outpath[0] == '-' ? "./" : "", m.outpath);
  if (!code && !movie_stop) {
    char in[4200], fps[16];
    snprintf(in, sizeof in, "%s/f%%06d.png", m.tmp);
    snprintf(fps, sizeof fps, "%d", m.fps);
    char *mp4[] = {"ffmpeg", "-nostdin", "-y",      "-loglevel", "error",   "-framerate", fps, "-i",
                   in,       "-c:v",     "libx264", "-pix_fmt",  "yuv420p", outarg,       NULL};
    char *gif[] = {"ffmpeg", "-nostdin", "-y", "-loglevel", "error", "-framerate",
                   fps,      "-i",       in,   outarg,      NULL};
    int f = run_prog(m.gif ? gif : mp4);
    if (f != 0) {
      if (!movie_stop)
        fprintf(stderr, "haff movie: ffmpeg could not write %s (%s)\n", m.outpath,
                f == 127 ? "is ffmpeg installed?" : "see its message above");
      unlink(outarg); /* nothing half-written */
      code = 1;
    }
  }
  if (movie_stop) {
    fprintf(stderr, "haff movie: interrupted (signal %d): no movie written\n", (int)movie_stop);
    code = 1;
  }
  if (m.tmp) { /* on every path: done, failed or interrupted */
    movie_stop = 0;
    char *rm[] = {"rm", "-rf", (char *)m.tmp, NULL};
    run_prog(rm);
  }
  for (int k = 0; k < 3; k++) sigaction(sigs[k], &old[k], NULL);
  if (!code)
    fprintf(stderr, "haff movie: %s: %ld frames of run %lld\n", m.outpath, frames,
            (long long)m.run);
  free(m.kinds);
  hd_scene_free(&m.sc);
  return code;
}
