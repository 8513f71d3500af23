#include <stdarg.h>
#include <stdio.h>

#include "biref/common.h"
#include "error.h"

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

static void write_msg(char *msg, size_t msg_len, const char *field, const char *fmt, va_list ap)
{
    if (!msg || !msg_len) return;
    if (!field) {
        vsnprintf(msg, msg_len, fmt, ap);
        return;
    }
    char reason[200];
    vsnprintf(reason, sizeof reason, fmt, ap);
    snprintf(msg, msg_len, "%s: %s", field, reason);
}

biref_status biref_fail(char *msg, size_t msg_len, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    write_msg(msg, msg_len, NULL, fmt, ap);
    va_end(ap);
    return BIREF_ERR_INVALID;
}

biref_status biref_fail_status(biref_status s, char *msg, size_t msg_len, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    write_msg(msg, msg_len, NULL, fmt, ap);
    va_end(ap);
    return s;
}

biref_status biref_fail_field(char *msg, size_t msg_len, const char *field, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    write_msg(msg, msg_len, field, fmt, ap);
    va_end(ap);
    return BIREF_ERR_INVALID;
}
