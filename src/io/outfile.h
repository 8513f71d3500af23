/* Output files written the way careful Unix tools write them.
 *
 * A regular file (new or existing) is written under a temporary, unnamed file in the target's
 * directory (O_TMPFILE; a short hidden ".biref-XXXXXX" name where the file system lacks it) and
 * renamed over the target only once everything is written: readers see the old file or the new
 * one, never a partial one, and a failed or interrupted write leaves the old file untouched. The
 * new file keeps an existing file's mode (and, where permitted, owner); a new file gets 0666
 * minus the umask. A symbolic link is written through (its target is replaced, the link stays);
 * a FIFO, a character or block device, and "-" (standard output) are written directly.
 *
 * On a signal the process dies with the unnamed file, which the kernel frees: nothing is left
 * behind. Only on file systems without O_TMPFILE can a process killed mid-write leave a
 * ".biref-XXXXXX" file beside the target.
 *
 * Not part of the public API: compiled into the library (image writers) and the command-line
 * tool (CSV, Markdown, plots). Re-entrant, no global state. */
#ifndef BIREF_IO_OUTFILE_H
#define BIREF_IO_OUTFILE_H

#include <stddef.h>
#include <stdio.h>

#include "biref/common.h"

typedef struct biref_outfile biref_outfile;

/* Opens PATH for writing; NULL with "PATH: cannot write: reason" in msg on failure. */
biref_outfile *biref_outfile_open(const char *path, char *msg, size_t msg_len);
/* The stream to write to (owned by o). */
FILE *biref_outfile_stream(biref_outfile *o);
/* A second stream on the same file for a writer that closes its stream itself (PLplot); the
 * caller's writer owns it. NULL on failure. */
FILE *biref_outfile_dup_stream(biref_outfile *o);
/* ok != 0: flushes and puts the file in place; ok == 0: discards it (the target is untouched
 * unless it is written directly). Frees o. BIREF_ERR_IO with a one-line msg if the commit fails. */
biref_status biref_outfile_close(biref_outfile *o, int ok, char *msg, size_t msg_len);

/* Checks without writing that PATH could be opened (its directory exists and is writable, it
 * is not a directory), so that a long computation is not wasted on a typo. */
biref_status biref_outfile_check(const char *path, char *msg, size_t msg_len);

/* 1 if writing OUT would overwrite the existing file IN (same device and inode, through any
 * links); 0 otherwise, including when either does not exist. "-" is never a file. */
int biref_outfile_is_file(const char *out, const char *in);

#endif
