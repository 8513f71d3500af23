/* The CIE 1931 2-degree colour matching functions at 1 nm (columns nm, x, y, z),
 * embedded at build time from data/cie1931_2deg_xyz_1nm.csv. */
#ifndef BIREF_COLOR_CIE1931_TABLE_H
#define BIREF_COLOR_CIE1931_TABLE_H
extern const int biref_cie1931_rows;
extern const double biref_cie1931_table[][4];
#endif
