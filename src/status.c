#include "biref/common.h"

const char *biref_status_string(biref_status s)
{
    switch (s) {
    case BIREF_OK: return "ok";
    case BIREF_ERR_INVALID: return "invalid parameter";
    case BIREF_ERR_NOMEM: return "out of memory";
    case BIREF_ERR_SINGULAR: return "numerically singular system";
    case BIREF_ERR_IO: return "input/output error";
    case BIREF_ERR_ILLCOND: return "ill-conditioned: method cannot give a trustworthy answer";
    }
    return "unknown status";
}
