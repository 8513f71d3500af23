/* CalculiX result files (.frd, ASCII), the part biref needs: the nodes block (2C), the elements
 * block (3C) and the nodal result blocks (100C), in the fixed columns ccx writes them (CalculiX
 * GraphiX manual, "Result Format"):
 *
 *     2C  ... NUMNOD ... FORMAT        FORMAT 0: node numbers I5, 1: I10, 2: binary (refused)
 *     -1  node x y z                   (1X,'-1',I5|I10,3E12.5)
 *     3C  ... NUMELEM ... FORMAT
 *     -1  elem type group material     type 7 tr3, 8 tr6, 9 qu4, 10 qu8 (1-6: 3-D solids)
 *     -2  node node ...                I5|I10 each, as many lines as needed
 *     100C ... FORMAT                  one result block per quantity and increment
 *     -4  NAME ncomp                   e.g. STRESS 6
 *     -5  COMPONENT ...                SXX SYY SZZ SXY SYZ SZX
 *     -1  node v v v v v v             (1X,'-1',I5|I10,6E12.5), -2 lines continue beyond six
 *     -3                               end of a block
 *
 * Values are fixed 12-character fields that may touch ("-3.00000E+01-3.00000E+01"). Plane
 * elements keep CalculiX's node order, which is VTK's. The last block holding the three named
 * components is taken: the last increment's stresses, extrapolated to the nodes and averaged by
 * ccx. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "optics/validate.h"
#include "photoelastic/mesh_internal.h"
#include "photoelastic/textfile.h"

void biref_pe_frd_format_default(biref_pe_frd_format *f)
{
    f->sxx = "SXX";
    f->syy = "SYY";
    f->txy = "SXY";
    f->length_m = 1e-3;
    f->stress_pa = 1e6;
}

typedef struct {
    pe_line_reader rd;
    long max_id;
    /* nodes by number: index + 1 (0: none) */
    size_t *index;
    size_t nn, ncap;
    double *xyz; /* [nn][3] */
    size_t nel, ecap, ccap, nconn;
    int *type;
    size_t *conn;
    int solid; /* a 3-D element seen: its frd type */
    double *stress; /* [nn][3], NAN where no value */
    int have_stress;
    char *msg;
    size_t msg_len;
} frd_reader;

/* An integer of the fixed field [b, b + w) of the line [lb, le). */
static int field_long(const char *lb, const char *le, size_t off, size_t w, long *out)
{
    if (lb + off >= le) return 0;
    char buf[24];
    size_t n = (size_t)(le - lb - (long)off) < w ? (size_t)(le - lb - (long)off) : w;
    memcpy(buf, lb + off, n);
    buf[n] = '\0';
    char *end;
    long v = strtol(buf, &end, 10);
    while (*end == ' ') end++;
    if (end == buf || *end) return 0;
    *out = v;
    return 1;
}

static int field_double(const char *lb, const char *le, size_t off, double *out)
{
    if (lb + off + 12 > le) return 0;
    char show[48];
    const char *b = lb + off, *e = b + 12;
    while (b < e && *b == ' ') b++;
    return pe_parse_number(b, e, out, show) == PE_NUM_OK;
}

static biref_status fail_line(frd_reader *r, const char *what)
{
    return biref_fail(r->msg, r->msg_len, "line %ld: %s", r->rd.line, what);
}

/* The last integer of a block's header line: its FORMAT (0 short, 1 long, 2 binary). */
static biref_status block_format(frd_reader *r, const char *b, const char *e, int *w)
{
    const char *p = e;
    while (p > b && p[-1] == ' ') p--;
    const char *q = p;
    while (q > b && p - q < 3 && q[-1] >= '0' && q[-1] <= '9') q--;
    const int f = q < p ? atoi(q) : -1;
    if (f == 2) return fail_line(r, "binary .frd results: let ccx write ASCII (the default; no *NODE FILE OUTPUT=BINARY)");
    if (f != 0 && f != 1) return fail_line(r, "not a CalculiX .frd block header (no format 0 or 1 at its end)");
    *w = f ? 10 : 5;
    return BIREF_OK;
}

static biref_status read_nodes(frd_reader *r, int w)
{
    const char *b, *e;
    while (pe_next_raw_line(&r->rd, &b, &e)) {
        if (e - b >= 3 && !strncmp(b, " -3", 3)) return BIREF_OK;
        long id;
        double v[3];
        if (e - b < 3 || strncmp(b, " -1", 3) || !field_long(b, e, 3, (size_t)w, &id))
            return fail_line(r, "expected a node record ' -1 number x y z'");
        for (int c = 0; c < 3; c++)
            if (!field_double(b, e, 3 + (size_t)w + 12 * (size_t)c, &v[c]))
                return fail_line(r, "a node's coordinate is not a number in its 12-character field");
        if (id < 1 || id > r->max_id) return fail_line(r, "node number out of range");
        if (r->index[id]) return fail_line(r, "node number repeated");
        if (r->nn == r->ncap) {
            r->ncap = r->ncap ? 2 * r->ncap : 1024;
            double *nx = realloc(r->xyz, r->ncap * 3 * sizeof *nx);
            if (!nx) return biref_fail_status(BIREF_ERR_NOMEM, r->msg, r->msg_len, "out of memory");
            r->xyz = nx;
        }
        memcpy(r->xyz + 3 * r->nn, v, sizeof v);
        r->index[id] = ++r->nn;
    }
    return fail_line(r, "the file ends inside the nodes block");
}

/* frd element type -> biref type (-1: skipped 1-D element, -2: 3-D solid, -3: unknown). */
static int map_type(long t, int *nn)
{
    static const int nodes[13] = {0, 8, 6, 4, 20, 15, 10, 3, 6, 4, 8, 2, 3};
    *nn = t >= 1 && t <= 12 ? nodes[t] : 0;
    if (t >= 1 && t <= 6) return -2;
    if (t == 11 || t == 12) return -1;
    return t == 7 ? BIREF_PE_TRI3 : t == 8 ? BIREF_PE_TRI6 : t == 9 ? BIREF_PE_QUAD4 : t == 10 ? BIREF_PE_QUAD8 : -3;
}

static biref_status add_element(frd_reader *r, int type, const long *ids, int nn)
{
    if (r->nel == r->ecap) {
        r->ecap = r->ecap ? 2 * r->ecap : 1024;
        int *nt = realloc(r->type, r->ecap * sizeof *nt);
        if (nt) r->type = nt;
        if (!nt) return biref_fail_status(BIREF_ERR_NOMEM, r->msg, r->msg_len, "out of memory");
    }
    if (r->nconn + (size_t)nn > r->ccap) {
        r->ccap = 2 * (r->ccap + (size_t)nn);
        size_t *nc = realloc(r->conn, r->ccap * sizeof *nc);
        if (!nc) return biref_fail_status(BIREF_ERR_NOMEM, r->msg, r->msg_len, "out of memory");
        r->conn = nc;
    }
    for (int k = 0; k < nn; k++) {
        if (ids[k] < 1 || ids[k] > r->max_id || !r->index[ids[k]])
            return fail_line(r, "an element refers to a node that is not in the nodes block");
        r->conn[r->nconn++] = r->index[ids[k]] - 1;
    }
    r->type[r->nel++] = type;
    return BIREF_OK;
}

static biref_status read_elements(frd_reader *r, int w)
{
    const char *b, *e;
    while (pe_next_raw_line(&r->rd, &b, &e)) {
        if (e - b >= 3 && !strncmp(b, " -3", 3)) return BIREF_OK;
        long id, t;
        if (e - b < 3 || strncmp(b, " -1", 3) || !field_long(b, e, 3, (size_t)w, &id) ||
            !field_long(b, e, 3 + (size_t)w, 5, &t))
            return fail_line(r, "expected an element record ' -1 number type group material'");
        int nn, type = map_type(t, &nn);
        if (type == -3) return fail_line(r, "unknown element type");
        if (type == -2 && !r->solid) r->solid = (int)t;
        long ids[20];
        int k = 0;
        while (k < nn) {
            if (!pe_next_raw_line(&r->rd, &b, &e) || e - b < 3 || strncmp(b, " -2", 3))
                return fail_line(r, "expected the element's node numbers on ' -2' lines");
            for (size_t off = 3; k < nn && field_long(b, e, off, (size_t)w, &ids[k]); off += (size_t)w) k++;
        }
        if (type >= 0) {
            biref_status st = add_element(r, type, ids, nn);
            if (st != BIREF_OK) return st;
        }
    }
    return fail_line(r, "the file ends inside the elements block");
}

/* A result block: if its components include the three names, their values replace the stresses
 * read so far (a later increment wins). */
static biref_status read_results(frd_reader *r, int w, const biref_pe_frd_format *f)
{
    const char *b, *e;
    int ncomp = 0, col[3] = {-1, -1, -1}, icomp = 0;
    while (pe_next_raw_line(&r->rd, &b, &e)) {
        if (e - b < 3) continue;
        if (!strncmp(b, " -3", 3)) break;
        if (!strncmp(b, " -4", 3)) {
            long nc;
            if (!field_long(b, e, 13, 5, &nc) || nc < 1 || nc > 64) return fail_line(r, "a result block without a component count");
            ncomp = (int)nc;
            continue;
        }
        if (!strncmp(b, " -5", 3)) {
            char name[16] = "";
            sscanf(b + 3, "%15s", name);
            const char *want[3] = {f->sxx, f->syy, f->txy};
            for (int c = 0; c < 3; c++)
                if (!strcasecmp(name, want[c])) col[c] = icomp;
            icomp++;
            continue;
        }
        if (strncmp(b, " -1", 3)) continue;
        if (col[0] < 0 || col[1] < 0 || col[2] < 0 || !ncomp) {
            /* not the block asked for: skip its records */
            continue;
        }
        long id;
        if (!field_long(b, e, 3, (size_t)w, &id) || id < 1 || id > r->max_id || !r->index[id])
            return fail_line(r, "a result for a node that is not in the nodes block");
        double v[64];
        int k = 0;
        size_t off = 3 + (size_t)w;
        for (;;) {
            while (k < ncomp && field_double(b, e, off, &v[k])) off += 12, k++;
            if (k >= ncomp) break;
            if (!pe_next_raw_line(&r->rd, &b, &e) || e - b < 3 || strncmp(b, " -2", 3))
                return fail_line(r, "a result record has fewer values than its block's components");
            off = 3 + (size_t)w;
        }
        if (!r->have_stress) {
            for (size_t i = 0; i < 3 * r->nn; i++) r->stress[i] = NAN;
            r->have_stress = 1;
        }
        double *s = r->stress + 3 * (r->index[id] - 1);
        for (int c = 0; c < 3; c++) s[c] = v[col[c]] * f->stress_pa;
    }
    return BIREF_OK;
}

/* Largest node number (fixed columns of ' -1' lines in the nodes block) to size the index. */
static long max_node_number(const char *text, size_t len)
{
    return (long)(len / 40) + 100000; /* a node record is at least 40 bytes: ids beyond are refused */
}

static biref_status scan(frd_reader *r, const biref_pe_frd_format *f)
{
    const char *b, *e;
    biref_status st = BIREF_OK;
    while (st == BIREF_OK && pe_next_raw_line(&r->rd, &b, &e)) {
        int w;
        if (e - b >= 6 && !strncmp(b, "    2C", 6)) {
            if ((st = block_format(r, b, e, &w)) == BIREF_OK) st = read_nodes(r, w);
            if (st == BIREF_OK && r->nn > 0) {
                r->stress = malloc(r->nn * 3 * sizeof *r->stress);
                if (!r->stress) st = biref_fail_status(BIREF_ERR_NOMEM, r->msg, r->msg_len, "out of memory");
            }
        } else if (e - b >= 6 && !strncmp(b, "    3C", 6)) {
            if ((st = block_format(r, b, e, &w)) == BIREF_OK) st = read_elements(r, w);
        } else if (e - b >= 6 && !strncmp(b, "  100C", 6)) {
            if (!r->stress) return fail_line(r, "a result block before the nodes block");
            if ((st = block_format(r, b, e, &w)) == BIREF_OK) st = read_results(r, w, f);
        } else if (e - b >= 4 && !strncmp(b, "9999", 4)) {
            break;
        }
    }
    return st;
}

/* Plane results only: one z for all nodes, no solid elements, every node of an element with a
 * stress. Then the mesh. */
static biref_status finish(frd_reader *r, const biref_pe_frd_format *f, biref_pe_mesh **out)
{
    char *msg = r->msg;
    size_t ml = r->msg_len;
    if (r->solid)
        return biref_fail(msg, ml, "3-D solid elements (frd type %d): biref pictures plane stress; export a plane-stress "
                          "model (CPS3/CPS4/CPS6/CPS8 elements), or a section of the part as .vtu (ParaView: Slice)",
                          r->solid);
    if (!r->nn) return biref_fail(msg, ml, "no nodes block (2C): not a CalculiX .frd result file?");
    if (!r->nel) return biref_fail(msg, ml, "no plane elements (tr3, tr6, qu4, qu8) in the elements block");
    if (!r->have_stress)
        return biref_fail(msg, ml, "no result block with components %s, %s, %s (ccx writes them with *EL FILE: S; other "
                          "names with --columns sxx=...,syy=...,txy=...)", f->sxx, f->syy, f->txy);
    double zlo = INFINITY, zhi = -INFINITY, ext = 0;
    for (size_t i = 0; i < r->nn; i++) {
        zlo = fmin(zlo, r->xyz[3 * i + 2]), zhi = fmax(zhi, r->xyz[3 * i + 2]);
        ext = fmax(ext, fmax(fabs(r->xyz[3 * i]), fabs(r->xyz[3 * i + 1])));
    }
    if (zhi - zlo > 1e-9 * ext)
        return biref_fail(msg, ml, "the nodes are not in one plane z = const (z %g..%g): a shell or a 3-D part; export "
                          "a plane-stress model, or a section in the x-y plane as .vtu", zlo, zhi);
    for (size_t k = 0; k < r->nconn; k++)
        if (isnan(r->stress[3 * r->conn[k]]))
            return biref_fail(msg, ml, "an element's node has no %s value in the result block", f->sxx);
    double *xy = malloc(r->nn * 2 * sizeof *xy);
    if (!xy) return biref_fail_status(BIREF_ERR_NOMEM, msg, ml, "out of memory");
    for (size_t i = 0; i < r->nn; i++) {
        xy[2 * i] = r->xyz[3 * i] * f->length_m;
        xy[2 * i + 1] = r->xyz[3 * i + 1] * f->length_m;
    }
    biref_pe_elements el = {r->nn, xy, r->stress, r->nel, r->type, r->conn};
    biref_status st = biref_pe_mesh_from_elements(&el, out, msg, ml);
    free(xy);
    return st;
}

biref_status biref_pe_frd_parse(const char *text, size_t len, const biref_pe_frd_format *fmt, biref_pe_mesh **out,
                                char *msg, size_t msg_len)
{
    if (!out) return biref_fail(msg, msg_len, "no output");
    *out = NULL;
    if (!text || !fmt || !fmt->sxx || !fmt->syy || !fmt->txy) return biref_fail(msg, msg_len, "no text or format");
    if (!(isfinite(fmt->length_m) && fmt->length_m > 0 && isfinite(fmt->stress_pa) && fmt->stress_pa > 0))
        return biref_fail(msg, msg_len, "length and stress units must be positive");
    long nul = pe_nul_line(text, len);
    if (nul) return biref_fail(msg, msg_len, "line %ld: contains a NUL byte (a binary .frd? let ccx write ASCII)", nul);
    frd_reader r;
    memset(&r, 0, sizeof r);
    r.rd = (pe_line_reader){text, text + len, 0, 0};
    r.msg = msg;
    r.msg_len = msg_len;
    r.max_id = max_node_number(text, len);
    r.index = calloc((size_t)r.max_id + 1, sizeof *r.index);
    biref_status st = r.index ? scan(&r, fmt) : biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    if (st == BIREF_OK) st = finish(&r, fmt, out);
    free(r.index);
    free(r.xyz);
    free(r.type);
    free(r.conn);
    free(r.stress);
    return st;
}

biref_status biref_pe_frd_load(const char *path, const biref_pe_frd_format *fmt, biref_pe_mesh **out, char *msg,
                               size_t msg_len)
{
    if (out) *out = NULL;
    char *text;
    size_t len;
    biref_status st = biref_pe_read_text(path, PE_MAX_FILE_BYTES, &text, &len, msg, msg_len);
    if (st != BIREF_OK) return st;
    st = biref_pe_frd_parse(text, len, fmt, out, msg, msg_len);
    free(text);
    return st;
}
