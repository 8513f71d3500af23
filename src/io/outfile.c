/* Output files: atomic replace for regular files, write-through for everything else (outfile.h). */
#define _GNU_SOURCE /* O_TMPFILE, linkat's AT_SYMLINK_FOLLOW, getrandom */
#include "io/outfile.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

enum outfile_kind {
    OUT_STDOUT,   /* "-" */
    OUT_DIRECT,   /* FIFO, device, dangling symlink: written where it is */
    OUT_UNNAMED,  /* O_TMPFILE in the target's directory, linked and renamed on commit */
    OUT_NAMED     /* ".biref-XXXXXX" in the target's directory, renamed on commit */
};

struct biref_outfile {
    enum outfile_kind kind;
    FILE *f;
    char *target; /* the file to replace (a symlink resolved) */
    char *tmp;    /* OUT_NAMED: the temporary's name */
    char *dir;    /* OUT_UNNAMED, OUT_NAMED: the target's directory */
};

static void fail(char *msg, size_t msg_len, const char *path, const char *why)
{
    if (msg && msg_len) snprintf(msg, msg_len, "%s: cannot write: %s", path, why);
}

/* The directory part of path ("." for a bare name); malloc'ed. */
static char *dir_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    if (!slash) return strdup(".");
    if (slash == path) return strdup("/");
    return strndup(path, (size_t)(slash - path));
}

/* "DIR/.biref-XXXXXX" with six random name characters: short whatever the target's name is,
 * so that a target name of NAME_MAX characters still works. */
static char *temp_name(const char *dir)
{
    static const char alphabet[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
    unsigned char r[6];
    if (getrandom(r, sizeof r, GRND_NONBLOCK) != (ssize_t)sizeof r) {
        /* No entropy yet (early boot): the clock and pid still differ between runs; O_EXCL or
         * linkat's EEXIST catches a collision and the caller retries. */
        struct timespec ts;
        clock_gettime(CLOCK_REALTIME, &ts);
        unsigned long x = (unsigned long)ts.tv_nsec ^ ((unsigned long)getpid() << 16) ^ (unsigned long)rand();
        for (int i = 0; i < 6; i++, x /= 61) r[i] = (unsigned char)x;
    }
    size_t n = strlen(dir);
    char *name = malloc(n + 16);
    if (!name) return NULL;
    memcpy(name, dir, n);
    memcpy(name + n, "/.biref-", 8);
    for (int i = 0; i < 6; i++) name[n + 8 + i] = alphabet[r[i] % (sizeof alphabet - 1)];
    name[n + 14] = '\0';
    return name;
}

static void outfile_free(biref_outfile *o)
{
    free(o->target);
    free(o->tmp);
    free(o->dir);
    free(o);
}

/* Where PATH's data really goes: a symlink's final target, or PATH itself. *dangling is set for
 * a symlink whose target does not exist (it is then created through the link). */
static char *resolve(const char *path, int *dangling)
{
    struct stat lst;
    *dangling = 0;
    if (lstat(path, &lst) == 0 && S_ISLNK(lst.st_mode)) {
        char *real = realpath(path, NULL);
        if (real) return real;
        *dangling = 1;
    }
    return strdup(path);
}

/* Fills o->f for a regular target: an unnamed file where supported, else a named one. */
static int open_atomic(biref_outfile *o, const struct stat *existing, char *msg, size_t msg_len)
{
    o->dir = dir_of(o->target);
    if (!o->dir) return fail(msg, msg_len, o->target, "out of memory"), -1;
    /* 0666 less the umask for a new file, as open(2) does. */
    int fd = -1, tried = 0;
    /* The unnamed file gets its name on commit through /proc/self/fd (linkat). */
    if (access("/proc/self/fd", X_OK) == 0) {
        tried = 1;
        fd = open(o->dir, O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
    }
    if (fd >= 0) {
        o->kind = OUT_UNNAMED;
    } else if (tried && (errno == ENOENT || errno == ENOTDIR || errno == EACCES || errno == EPERM ||
                         errno == EROFS || errno == ENOSPC || errno == EDQUOT)) {
        if (errno == ENOENT || errno == ENOTDIR) {
            char why[300];
            snprintf(why, sizeof why, "directory '%s' does not exist", o->dir);
            return fail(msg, msg_len, o->target, why), -1;
        }
        return fail(msg, msg_len, o->target, strerror(errno)), -1;
    } else {
        /* The file system has no O_TMPFILE (EOPNOTSUPP, EISDIR on old kernels, ...). */
        for (int tries = 0; fd < 0 && tries < 100; tries++) {
            free(o->tmp);
            o->tmp = temp_name(o->dir);
            if (!o->tmp) return fail(msg, msg_len, o->target, "out of memory"), -1;
            fd = open(o->tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
            if (fd < 0 && errno != EEXIST) return fail(msg, msg_len, o->target, strerror(errno)), -1;
        }
        if (fd < 0) return fail(msg, msg_len, o->target, "no free temporary name"), -1;
        o->kind = OUT_NAMED;
    }
    if (existing) {
        /* Owner first: chown clears set-id bits that the chmod then restores. Both are best
         * effort, as for cp -p run by an ordinary user. */
        if (fchown(fd, existing->st_uid, existing->st_gid) != 0) { /* not permitted: keep ours */ }
        if (fchmod(fd, existing->st_mode & 07777) != 0) { /* e.g. a foreign file system */ }
    }
    o->f = fdopen(fd, "wb");
    if (!o->f) {
        int e = errno;
        close(fd);
        if (o->tmp) unlink(o->tmp);
        return fail(msg, msg_len, o->target, strerror(e)), -1;
    }
    return 0;
}

biref_outfile *biref_outfile_open(const char *path, char *msg, size_t msg_len)
{
    if (!path) path = "";
    size_t n = strlen(path);
    if (n == 0 || path[n - 1] == '/') return fail(msg, msg_len, path, "not a file name"), NULL;
    biref_outfile *o = calloc(1, sizeof *o);
    if (!o) return fail(msg, msg_len, path, "out of memory"), NULL;
    if (strcmp(path, "-") == 0) {
        o->kind = OUT_STDOUT;
        o->f = stdout;
        return o;
    }
    int dangling;
    o->target = resolve(path, &dangling);
    if (!o->target) return outfile_free(o), fail(msg, msg_len, path, "out of memory"), NULL;
    struct stat st;
    int exists = stat(o->target, &st) == 0;
    if (!exists && errno != ENOENT) {
        fail(msg, msg_len, path, strerror(errno));
        return outfile_free(o), NULL;
    }
    if (exists && S_ISDIR(st.st_mode)) return outfile_free(o), fail(msg, msg_len, path, "is a directory"), NULL;
    if (dangling || (exists && !S_ISREG(st.st_mode))) {
        /* Written in place: a FIFO or device has no contents to protect, and a dangling link's
         * target is created through the link. */
        int fd = open(o->target, O_WRONLY | O_CLOEXEC | (dangling ? O_CREAT | O_TRUNC : 0), 0666);
        o->f = fd >= 0 ? fdopen(fd, "wb") : NULL;
        if (!o->f) {
            int e = errno;
            if (fd >= 0) close(fd);
            fail(msg, msg_len, path, strerror(e));
            return outfile_free(o), NULL;
        }
        o->kind = OUT_DIRECT;
        return o;
    }
    /* A file the user may not write stays protected, as with cp or a shell redirection,
     * although replacing it would only need a writable directory. */
    if (exists && access(o->target, W_OK) != 0) {
        fail(msg, msg_len, path, strerror(errno));
        return outfile_free(o), NULL;
    }
    if (open_atomic(o, exists ? &st : NULL, msg, msg_len)) {
        if (msg && msg_len && strcmp(o->target, path) != 0) {
            /* Name the file the user typed, not the resolved one, at the start of the message. */
            char why[512];
            const char *p = strstr(msg, ": cannot write: ");
            snprintf(why, sizeof why, "%s", p ? p + 16 : msg);
            fail(msg, msg_len, path, why);
        }
        return outfile_free(o), NULL;
    }
    return o;
}

FILE *biref_outfile_stream(biref_outfile *o) { return o->f; }

FILE *biref_outfile_dup_stream(biref_outfile *o)
{
    if (fflush(o->f) != 0) return NULL;
    int fd = fcntl(fileno(o->f), F_DUPFD_CLOEXEC, 0);
    if (fd < 0) return NULL;
    FILE *f = fdopen(fd, "wb");
    if (!f) close(fd);
    return f;
}

/* Gives the unnamed file a temporary name beside the target and renames it over the target. */
static int link_unnamed(biref_outfile *o)
{
    char proc[64];
    snprintf(proc, sizeof proc, "/proc/self/fd/%d", fileno(o->f));
    for (int tries = 0; tries < 100; tries++) {
        char *name = temp_name(o->dir);
        if (!name) return errno = ENOMEM, -1;
        if (linkat(AT_FDCWD, proc, AT_FDCWD, name, AT_SYMLINK_FOLLOW) == 0) {
            /* A SIGKILL between these two calls is the one moment a named temporary exists. */
            int rc = rename(name, o->target);
            int e = errno;
            if (rc != 0) unlink(name);
            free(name);
            return rc == 0 ? 0 : (errno = e, -1);
        }
        int e = errno;
        free(name);
        if (e != EEXIST) return errno = e, -1;
    }
    return errno = EEXIST, -1;
}

biref_status biref_outfile_close(biref_outfile *o, int ok, char *msg, size_t msg_len)
{
    if (!o) return BIREF_ERR_IO;
    const char *why = ok ? NULL : "write failed";
    int err = 0;
    if (ok && (fflush(o->f) != 0 || ferror(o->f))) {
        ok = 0;
        err = errno ? errno : EIO;
    }
    switch (o->kind) {
    case OUT_STDOUT: break;
    case OUT_DIRECT:
        if (fclose(o->f) != 0 && ok) ok = 0, err = errno;
        break;
    case OUT_UNNAMED:
        if (ok && link_unnamed(o) != 0) ok = 0, err = errno;
        /* Nothing to undo otherwise: the unnamed file disappears with its last descriptor. */
        fclose(o->f);
        break;
    case OUT_NAMED:
        if (fclose(o->f) != 0 && ok) ok = 0, err = errno;
        if (ok && rename(o->tmp, o->target) != 0) ok = 0, err = errno;
        if (!ok) unlink(o->tmp);
        break;
    }
    if (!ok) {
        if (err) why = strerror(err);
        fail(msg, msg_len, o->kind == OUT_STDOUT ? "standard output" : o->target, why);
    }
    outfile_free(o);
    return ok ? BIREF_OK : BIREF_ERR_IO;
}

biref_status biref_outfile_check(const char *path, char *msg, size_t msg_len)
{
    if (!path) path = "";
    size_t n = strlen(path);
    if (n == 0 || path[n - 1] == '/') return fail(msg, msg_len, path, "not a file name"), BIREF_ERR_IO;
    if (strcmp(path, "-") == 0) return BIREF_OK;
    int dangling;
    char *target = resolve(path, &dangling);
    if (!target) return fail(msg, msg_len, path, "out of memory"), BIREF_ERR_IO;
    biref_status s = BIREF_OK;
    struct stat st;
    char why[300];
    if (stat(target, &st) == 0) {
        if (S_ISDIR(st.st_mode))
            s = BIREF_ERR_IO, fail(msg, msg_len, path, "is a directory");
        else if (access(target, W_OK) != 0)
            s = BIREF_ERR_IO, fail(msg, msg_len, path, strerror(errno));
    }
    if (s == BIREF_OK && (dangling || stat(target, &st) != 0 || S_ISREG(st.st_mode))) {
        /* Created or replaced in its directory: that must exist and be writable. */
        char *dir = dir_of(target);
        if (!dir) {
            s = BIREF_ERR_IO, fail(msg, msg_len, path, "out of memory");
        } else if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
            snprintf(why, sizeof why, "directory '%s' does not exist", dir);
            s = BIREF_ERR_IO, fail(msg, msg_len, path, why);
        } else if (access(dir, W_OK | X_OK) != 0) {
            s = BIREF_ERR_IO, fail(msg, msg_len, path, strerror(errno));
        }
        free(dir);
    }
    free(target);
    return s;
}

int biref_outfile_is_file(const char *out, const char *in)
{
    if (!out || !in || strcmp(out, "-") == 0) return 0;
    struct stat a, b;
    if (stat(out, &a) != 0 || stat(in, &b) != 0) return 0;
    return a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}
