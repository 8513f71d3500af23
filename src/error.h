/* The library's one error convention. Every fallible entry point returns a biref_status
 * (biref_status_string names it); the ones that can say more take a caller-owned buffer
 * (char *msg, size_t msg_len; NULL or 0 = not wanted) and write one line saying why into it.
 * The message belongs to the call, so there is no global or thread-local state to race on.
 * These helpers are the only writers of such messages. */
#ifndef BIREF_ERROR_H
#define BIREF_ERROR_H

#include <stddef.h>

#include "biref/common.h"

/* Writes the formatted reason into msg and returns BIREF_ERR_INVALID. */
biref_status biref_fail(char *msg, size_t msg_len, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* The same with any status. */
biref_status biref_fail_status(biref_status s, char *msg, size_t msg_len, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
/* "field: reason" (a JSON path, an option), BIREF_ERR_INVALID. */
biref_status biref_fail_field(char *msg, size_t msg_len, const char *field, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

#endif
