/*
 * CIELAB and CIEDE2000 through Little CMS 2.
 *
 *  - CIE 1976 L*a*b*: CIE 015:2018 §8.2.1; lcms2's cmsXYZ2Lab / cmsLab2XYZ
 *    with an explicit white point (lcms2 would use D50 for a NULL white; we
 *    never pass NULL to it). Below (24/116)³ lcms2 uses the linear segment
 *    of the CIE definition, so tiny or negative components stay finite.
 *  - CIEDE2000: G. Sharma, W. Wu, E. N. Dalal, "The CIEDE2000 color-difference
 *    formula: implementation notes, supplementary test data, and mathematical
 *    observations", Color Res. Appl. 30(1), 2005, 21–30. lcms2's
 *    cmsCIE2000DeltaE(k_L = k_C = k_H = 1) reproduces all 34 pairs of their
 *    table 1 (data/ciede2000_sharma2005.csv) with max |error| 4.95e-5 (the
 *    table is rounded to 4 decimals) and agrees with an independent
 *    implementation of the paper's equations (tests/test_color.c) to ~1e-12,
 *    so we use it rather than a second implementation. Measured with lcms2
 *    2.14; tests/test_color.c re-checks whichever lcms2 is linked.
 *
 * The lcms2 functions used are pure (no context, no global state), so these
 * wrappers are thread-safe.
 */
#include <lcms2.h>

#include "biref/color.h"

void biref_xyz_to_lab(const double xyz[3], const double white[3], double lab[3])
{
    const cmsCIEXYZ w = white ? (cmsCIEXYZ){white[0], white[1], white[2]} : (cmsCIEXYZ){1.0, 1.0, 1.0};
    const cmsCIEXYZ c = {xyz[0], xyz[1], xyz[2]};
    cmsCIELab out;
    cmsXYZ2Lab(&w, &out, &c);
    lab[0] = out.L;
    lab[1] = out.a;
    lab[2] = out.b;
}

void biref_lab_to_xyz(const double lab[3], const double white[3], double xyz[3])
{
    const cmsCIEXYZ w = white ? (cmsCIEXYZ){white[0], white[1], white[2]} : (cmsCIEXYZ){1.0, 1.0, 1.0};
    const cmsCIELab c = {lab[0], lab[1], lab[2]};
    cmsCIEXYZ out;
    cmsLab2XYZ(&w, &out, &c);
    xyz[0] = out.X;
    xyz[1] = out.Y;
    xyz[2] = out.Z;
}

double biref_ciede2000(const double lab1[3], const double lab2[3])
{
    const cmsCIELab a = {lab1[0], lab1[1], lab1[2]};
    const cmsCIELab b = {lab2[0], lab2[1], lab2[2]};
    return cmsCIE2000DeltaE(&a, &b, 1.0, 1.0, 1.0);
}

double biref_delta_e00_xyz(const double xyz1[3], const double xyz2[3])
{
    double l1[3], l2[3];
    biref_xyz_to_lab(xyz1, NULL, l1);
    biref_xyz_to_lab(xyz2, NULL, l2);
    return biref_ciede2000(l1, l2);
}
