/* Finite-element results in VTK files (.vtu XML with inline, binary, appended or compressed data;
 * legacy .vtk; .vtp), read by VTK's own readers (cli/fea_vtk.cpp, C++, built when CMake finds
 * VTK) into a biref_pe_mesh: the plane cells with their connectivity and the nodal stresses. */
#ifndef BIREF_CLI_FEA_VTK_H
#define BIREF_CLI_FEA_VTK_H

#include <stddef.h>

#include "biref/photoelastic.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What to read: tensor (a point-data array of 3 = xx,yy,xy, 6 = VTK's xx,yy,zz,xy,yz,xz or 9
 * components) or three scalar arrays comp[0..2] (sxx, syy, txy); both NULL: the first of the
 * usual names (tensors stress, S, sigma; scalars stress_xx/_yy/_xy as Elmer writes them, sxx/syy/
 * sxy, S11/S22/S12). Units: metres and pascals per file unit. */
typedef struct {
    const char *tensor;
    const char *comp[3];
    double length_m, stress_pa;
} pe_vtk_request;

/* 1 when the command was built with VTK. */
int pe_vtk_available(void);
/* Reads path (legacy != 0: the legacy .vtk format); BIREF_OK or a status with one line in msg.
 * The array found is named in used (at least 96 bytes). */
biref_status pe_vtk_load(const char *path, int legacy, const pe_vtk_request *req, biref_pe_mesh **out, char *used,
                         char *msg, size_t msg_len);

#ifdef __cplusplus
}
#endif

#endif
