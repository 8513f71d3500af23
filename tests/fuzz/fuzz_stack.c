/* libFuzzer target: the stack-file parser (JSON text -> checked biref_stack), then the optics. */
#include <stddef.h>
#include <stdint.h>

#include "biref/stack.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    biref_stack stack;
    char msg[320];
    if (biref_stack_parse((const char *)data, size, &stack, msg, sizeof msg) != BIREF_OK) return 0;
    /* A parsed stack passes its own check (parse and check agree), and prepares. */
    if (biref_stack_check(&stack, msg, sizeof msg) != BIREF_OK) __builtin_trap();
    biref_stack_state st;
    if (biref_stack_prepare(&stack, 0.5, &st) == BIREF_OK) {
        biref_jones T, R;
        biref_stack_jones_at(&st, 550.0, &T, &R);
    }
    return 0;
}
