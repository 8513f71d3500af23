/* Where the CLI finds the files shipped with biref (example scenes), wherever it is run from. */
#ifndef BIREF_CLI_DATA_H
#define BIREF_CLI_DATA_H

#include <stddef.h>

/* Resolves rel (e.g. "examples/fig9a.json") to, in this order: $BIREF_DATA_DIR/rel when that
 * variable is set; rel itself when it exists (run from a source tree); the installed copy
 * <prefix>/share/biref/rel, found from the executable's own path. Falls back to rel, so a
 * missing file is reported under the name the user knows. Returns buf. */
const char *cli_data_path(const char *rel, char *buf, size_t len);

#endif
