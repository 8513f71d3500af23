/* The command built without VTK: .vtu/.vtk files are refused with one line saying so. */
#include <stdio.h>

#include "fea_vtk.h"

int pe_vtk_available(void)
{
    return 0;
}

biref_status pe_vtk_load(const char *path, int legacy, const pe_vtk_request *req, biref_pe_mesh **out, char *used,
                         char *msg, size_t msg_len)
{
    (void)path, (void)legacy, (void)req, (void)used;
    *out = NULL;
    snprintf(msg, msg_len, "this biref was built without VTK (install libvtk9-dev and rebuild) and cannot read VTK files");
    return BIREF_ERR_INVALID;
}
