/* libFuzzer target: the scene loader (JSON text -> validated biref_scene). */
#include <stddef.h>
#include <stdint.h>

#include "biref/render.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    biref_scene scene;
    char msg[320];
    if (biref_scene_parse((const char *)data, size, &scene, msg, sizeof msg) == BIREF_OK) {
        /* A parsed scene must pass its own validation again (parse and validate agree). */
        if (biref_scene_validate(&scene, msg, sizeof msg) != BIREF_OK) __builtin_trap();
    }
    return 0;
}
