/* Whether two path names are one file: the test behind "every path a command writes is checked
 * against every path it reads and against each other" (docs/CLI.md, "Files").
 *
 * Not part of the public API: shared by the command line and the tools (biref_io). Re-entrant. */
#ifndef BIREF_IO_SAME_FILE_H
#define BIREF_IO_SAME_FILE_H

#include <stddef.h>

/* 1 if A and B name the same file: the same device and inode when both exist (hard links,
 * symbolic links and "dir/../name" spellings included), otherwise the same absolute name once
 * the symbolic links that exist are followed and "." and ".." are resolved (so a file that a
 * command is about to create is recognised under any spelling). 0 otherwise. "-" (standard
 * input or output) is only the same as "-". */
int biref_same_file(const char *a, const char *b);

/* The absolute name PATH's data would have (as above), malloc'ed; NULL when out of memory. */
char *biref_file_name_resolved(const char *path);

#endif
