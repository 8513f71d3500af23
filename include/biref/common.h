/* biref — status codes shared by every part of the library. */
#ifndef BIREF_COMMON_H
#define BIREF_COMMON_H

#include <stddef.h>

/* Complex amplitudes in public structs: C99 double _Complex in C, std::complex<double> in C++.
 * Both are laid out as double[2] {re, im} (C17 6.2.5p13, C++ [complex.numbers]), so one struct
 * definition serves both languages and the library's <complex.h> arithmetic. */
#ifdef __cplusplus
#include <complex>
typedef std::complex<double> biref_complex;
#else
#include <complex.h>
typedef double _Complex biref_complex;
#endif

/* Marks the public API. The library is built with hidden visibility, so only declarations
 * carrying BIREF_API are exported from the shared library. */
#if defined(BIREF_API)
/* defined by the user (e.g. empty, for tools that parse the declarations) */
#elif defined(_WIN32) && defined(BIREF_SHARED_LIBRARY)
#  if defined(BIREF_BUILDING_LIBRARY)
#    define BIREF_API __declspec(dllexport)
#  else
#    define BIREF_API __declspec(dllimport)
#  endif
#elif defined(__GNUC__) || defined(__clang__)
#  define BIREF_API __attribute__((visibility("default")))
#else
#  define BIREF_API
#endif

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

/* The one error convention.
 *
 * Every function that can fail returns a biref_status; biref_status_string names the code.
 *
 * A function whose failure can have more than one cause (a parser, a constructor checking a
 * configuration, a slab or material check) also takes, as its last two parameters, a buffer the
 * caller owns: (char *msg, size_t msg_len). On failure it writes one line there saying why (no
 * trailing newline, always NUL-terminated, truncated if the buffer is short); NULL or 0 means the
 * reason is not wanted. On success the buffer is left alone. BIREF_MSG_SIZE bytes hold every
 * message the library writes, except for file paths beyond a few hundred bytes.
 *
 * The functions called per sample (per pixel or per wavelength: biref_slab_prepare,
 * biref_slab_jones*, biref_medium_modes, biref_interface_solve, biref_integrate*,
 * biref_shade_hit, biref_hit_frames_make, the light constructors) take no buffer: each of their
 * codes has one documented meaning, and BIREF_ERR_INVALID there means that the arguments fail
 * the named check function (biref_slab_check, biref_theta_check, biref_medium_check), which
 * says why.
 *
 * The message belongs to the call: there is no global or thread-local error state, and any
 * number of threads may call the library at once. */
#define BIREF_MSG_SIZE 512

BIREF_API const char *biref_status_string(biref_status s);

/* Progress of a long call (a rendered picture): called after each finished row, from inside the
 * parallel loop but serialised (never concurrently); rows_done counts the rows finished so far. */
typedef void (*biref_progress_fn)(void *user, int rows_done, int rows_total);

#ifdef __cplusplus
}
#endif

#endif /* BIREF_COMMON_H */
