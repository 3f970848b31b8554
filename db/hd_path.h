/* hd_path: whether writing one file would destroy another (the same file by any link, or the
 * log SQLite keeps beside a database): the check of every output against the inputs, by the
 * option parser (hd_opt_check_outputs), haff export and haff merge. */
#ifndef HD_PATH_H
#define HD_PATH_H

/* Whether writing the file out would destroy the file in: 1 when they are the same file (by
 * device and inode when both exist, whatever symbolic or hard link leads there; else the same
 * path once the folder is resolved by realpath), or when out is one of the files SQLite keeps
 * beside a database in (in-wal, in-shm, in-journal), which hold its newest rows; else 0. */
int hd_path_overwrites(const char *out, const char *in);

#endif
