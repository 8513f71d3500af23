/* Two path names, one file? (same_file.h) */
#define _GNU_SOURCE /* realpath, strndup */
#include "io/same_file.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Symbolic links followed per name before giving up, as the kernel does (ELOOP). */
enum { MAX_LINKS = 40 };

static char *join(const char *dir, const char *name)
{
    size_t nd = strlen(dir), nn = strlen(name);
    char *s = malloc(nd + nn + 2);
    if (!s) return NULL;
    memcpy(s, dir, nd);
    size_t k = nd;
    if (k == 0 || s[k - 1] != '/') s[k++] = '/';
    memcpy(s + k, name, nn + 1);
    return s;
}

/* The parent of an absolute, normalised name ("/a/b" -> "/a", "/a" -> "/"), in place. */
static void up(char *abs)
{
    char *slash = strrchr(abs, '/');
    if (!slash) return;
    if (slash == abs)
        abs[1] = '\0';
    else
        *slash = '\0';
}

static char *resolve(const char *path, int depth)
{
    if (depth > MAX_LINKS) return strdup(path); /* a loop of links: its own name is all it has */
    char *real = realpath(path, NULL);
    if (real) return real;
    struct stat lst;
    if (lstat(path, &lst) == 0 && S_ISLNK(lst.st_mode)) { /* a dangling link: where it points */
        char target[PATH_MAX];
        ssize_t n = readlink(path, target, sizeof target - 1);
        if (n > 0) {
            target[n] = '\0';
            if (target[0] == '/') return resolve(target, depth + 1);
            const char *slash = strrchr(path, '/');
            char *dir = slash ? strndup(path, (size_t)(slash - path) + 1) : strdup("./");
            char *joined = dir ? join(dir, target) : NULL;
            free(dir);
            char *r = joined ? resolve(joined, depth + 1) : NULL;
            free(joined);
            return r;
        }
    }
    /* Does not exist (yet): the directory's name resolved, then the last component. */
    size_t n = strlen(path);
    while (n > 1 && path[n - 1] == '/') n--;
    const char *last = path + n;
    while (last > path && last[-1] != '/') last--;
    char *base = strndup(last, (size_t)(path + n - last));
    if (base && last == path && (!strcmp(base, ".") || !strcmp(base, ".."))) return base; /* no working directory */
    char *dir = last == path ? strdup(".") : strndup(path, (size_t)(last - path));
    char *r = NULL;
    if (base && dir) {
        char *rdir = resolve(dir, depth);
        if (rdir && (!strcmp(base, ".") || !base[0]))
            r = rdir, rdir = NULL;
        else if (rdir && !strcmp(base, ".."))
            up(rdir), r = rdir, rdir = NULL;
        else if (rdir)
            r = join(rdir, base);
        free(rdir);
    }
    free(base);
    free(dir);
    return r;
}

char *biref_file_name_resolved(const char *path)
{
    return resolve(path && path[0] ? path : ".", 0);
}

int biref_same_file(const char *a, const char *b)
{
    if (!a || !b) return 0;
    if (!strcmp(a, "-") || !strcmp(b, "-")) return !strcmp(a, b);
    struct stat sa, sb;
    if (stat(a, &sa) == 0 && stat(b, &sb) == 0) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    char *ra = biref_file_name_resolved(a), *rb = biref_file_name_resolved(b);
    int same = ra && rb ? !strcmp(ra, rb) : !strcmp(a, b);
    free(ra);
    free(rb);
    return same;
}
