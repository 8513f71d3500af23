/* biref photoelastic: colour key and scale bar drawn on the picture with cairo. */
#include <stdio.h>

#include "photoelastic_ext.h"

static const char *const CMD = "photoelastic";

int pe_ext_write_png(const pe_ext *e, const pe_ext_ctx *c, const unsigned char *rgb)
{
    char msg[512];
    if (biref_png_write_rgb8(c->out, c->io->width, c->io->height, rgb, msg, sizeof msg) != BIREF_OK) {
        cli_error(CMD, "%s", msg);
        return CLI_EXIT_FAIL;
    }
    return CLI_EXIT_OK;
}
