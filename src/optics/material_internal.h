/* The dispersive material object (material.h) and its evaluators, shared by the catalogue, the
 * formulas, the tables and the dispersive integration. */
#ifndef BIREF_OPTICS_MATERIAL_INTERNAL_H
#define BIREF_OPTICS_MATERIAL_INTERNAL_H

#include "biref/material.h"

typedef enum { MATERIAL_FORMULA = 0, MATERIAL_TABLE = 1 } material_kind;

/* One tabulated index: values and the Fritsch–Carlson slopes dn/dλ at the nodes. */
typedef struct {
    double *n, *slope;
} material_column;

struct biref_material {
    const char *name, *description, *source;
    material_kind kind;
    int isotropic;
    int has_range;        /* 0: valid everywhere (user formulas without a range) */
    double range_nm[2];
    int owned;            /* 1: made by a constructor (biref_material_destroy frees it) */
    biref_index_formula formula[2]; /* MATERIAL_FORMULA: o, e (e unused when isotropic) */
    size_t n_rows;                  /* MATERIAL_TABLE */
    double *lambda_nm;
    material_column column[2];
    char name_buf[64];
};

/* n and dn/dλ (per µm) of one formula at x µm. Returns 0 when n² <= 1 or a value is not finite. */
int biref_formula_eval(const biref_index_formula *f, double x_um, double *n, double *dn_dx);
/* BIREF_ERR_INVALID with a one-line reason for a formula outside its domain; which names it. */
biref_status biref_formula_check(const biref_index_formula *f, const char *which, char *msg, size_t msg_len);
/* The smallest pole (λ in nm) of the formula inside [lo_nm, hi_nm], or 0 if none. */
double biref_formula_pole_in(const biref_index_formula *f, double lo_nm, double hi_nm);

/* n and dn/dλ (per nm) of a table column at lambda_nm (linear beyond the ends). */
void biref_table_eval(const biref_material *m, int column, double lambda_nm, double *n, double *dn_dl);
/* Fills the slopes of a column (Fritsch–Carlson monotone cubic Hermite). */
void biref_table_slopes(size_t n, const double *x, const double *y, double *slope);

#endif
