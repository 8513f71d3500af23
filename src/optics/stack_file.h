/* The stack files' layer reader, shared with scene files (a scene slab may be a stack). */
#ifndef BIREF_STACK_FILE_H
#define BIREF_STACK_FILE_H

#include <cjson/cJSON.h>

#include "biref/stack.h"

/* The "layers" array (NULL: missing) into out->layers and out->n_layers (eta_i untouched), with the
 * stack files' syntax and strictness; errors name the JSON path below prefix ("" for a stack file,
 * "slabs[2]" in a scene: "slabs[2].layers[1].eta_o: must be positive"). */
biref_status biref_stack_parse_layers(const cJSON *layers, const char *prefix, biref_stack *out, char *msg,
                                      size_t msg_len);

#endif
