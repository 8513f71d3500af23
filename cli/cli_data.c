#include "cli_data.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Relative path from the installed executable's directory to the data directory, set by the build
 * from the install layout (bin -> share/biref by default). */
#ifndef BIREF_CLI_DATA_RELDIR
#define BIREF_CLI_DATA_RELDIR "../share/biref"
#endif

static const char *copy(const char *s, char *buf, size_t len)
{
    snprintf(buf, len, "%s", s);
    return buf;
}

/* The directory of the running executable (Linux /proc), without a trailing slash. */
static int exe_dir(char *buf, size_t len)
{
    ssize_t n = readlink("/proc/self/exe", buf, len - 1);
    if (n <= 0 || (size_t)n >= len - 1) return -1;
    buf[n] = '\0';
    char *slash = strrchr(buf, '/');
    if (!slash) return -1;
    *slash = '\0';
    return 0;
}

const char *cli_data_path(const char *rel, char *buf, size_t len)
{
    const char *env = getenv("BIREF_DATA_DIR");
    if (env && *env) {
        snprintf(buf, len, "%s/%s", env, rel);
        return buf;
    }
    if (access(rel, F_OK) == 0) return copy(rel, buf, len);
    char dir[PATH_MAX];
    if (exe_dir(dir, sizeof dir) == 0) {
        int n = snprintf(buf, len, "%s/%s/%s", dir, BIREF_CLI_DATA_RELDIR, rel);
        if (n > 0 && (size_t)n < len && access(buf, F_OK) == 0) return buf;
    }
    return copy(rel, buf, len);
}
