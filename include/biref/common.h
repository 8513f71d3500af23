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

BIREF_API const char *biref_status_string(biref_status s);

#ifdef __cplusplus
}
#endif

#endif /* BIREF_COMMON_H */
