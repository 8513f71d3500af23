/* biref — status codes shared by every part of the library. */
#ifndef BIREF_COMMON_H
#define BIREF_COMMON_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    BIREF_OK = 0,
    BIREF_ERR_INVALID = 1,  /* a parameter is out of its domain */
    BIREF_ERR_NOMEM = 2,
    BIREF_ERR_SINGULAR = 3, /* a linear system is numerically singular */
    BIREF_ERR_IO = 4,
    BIREF_ERR_ILLCOND = 5   /* method cannot give a trustworthy answer here */
} biref_status;

const char *biref_status_string(biref_status s);

#ifdef __cplusplus
}
#endif

#endif /* BIREF_COMMON_H */
