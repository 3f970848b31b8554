/* hd_build: the provenance of this build of haff, compiled in (build/gen/version.c, written by
 * the Makefile from git and the compiler; `make` rewrites it only when it changes).  hd_run
 * stores it with every run (runs.git_commit, git_dirty, compiler, cflags) and `haff -V` prints
 * it.  A build outside a git work tree of the source folder (a tarball) has commit "unknown". */
#ifndef HD_BUILD_H
#define HD_BUILD_H

/* The commit the sources were built from: `git rev-parse HEAD` (40 hex digits), or "unknown". */
extern const char hd_build_commit[];
/* `git describe --always --dirty` (the short commit, "-dirty" when modified), or "unknown". */
extern const char hd_build_describe[];
/* 1 when the tree differed from the commit (a tracked file modified, or an untracked file in a
 * source folder), 0 when it did not, -1 when unknown (no git). */
extern const int hd_build_dirty;
/* The compiler's first line of `CC --version`, e.g. "gcc (Debian 12.2.0-14) 12.2.0". */
extern const char hd_build_compiler[];
/* The flags every source was compiled with (CFLAGS, without the dependency-file flags). */
extern const char hd_build_cflags[];

#endif
