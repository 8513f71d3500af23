/* Strict JSON for input files (scenes, material lists): the whole text must be one JSON value
 * (nothing but whitespace after it), strings may hold no raw control character (RFC 8259: they
 * are escaped, "\t", "\u0001"), and objects may hold only known keys, each once.
 * Not part of the public API: compiled into the library (scene files) and the tools. */
#ifndef BIREF_IO_JSON_STRICT_H
#define BIREF_IO_JSON_STRICT_H

#include <stddef.h>

#include <cjson/cJSON.h>

/* Parses text[0..len); NULL with a reason such as "malformed JSON at line 3, column 7" or
 * "malformed JSON: extra text at line 9, column 1" in msg. Free the result with cJSON_Delete. */
cJSON *biref_json_parse_strict(const char *text, size_t len, char *msg, size_t msg_len);

/* The first key of obj that is not in allowed (a NULL-terminated list) or that appears twice;
 * NULL if there is none. *twice tells which. "comment" and keys starting with '_' are free-form
 * annotations and always allowed. cJSON keeps duplicate keys and its look-ups silently use the
 * first, so they must be refused here. */
const char *biref_json_bad_key(const cJSON *obj, const char *const *allowed, int *twice);

#endif
