/* Values of the shared command-line grammar (docs/CLI.md) that are more than a number: a linear
 * polarizer "linear:DEG", a window given by two opposite corners "x0,y0,x1,y1" and the
 * anti-aliasing choice "prefilter|none". */
#ifndef BIREF_CLI_VALUES_H
#define BIREF_CLI_VALUES_H

/* "linear:DEG" -> DEG. Prints one error and returns -1 otherwise. */
int cli_parse_linear_polarizer(const char *cmd, const char *opt, const char *text, double *deg);
/* "x0,y0,x1,y1", two opposite corners in any order, -> {xmin, xmax, ymin, ymax} with a non-empty
 * area. Prints one error and returns -1 otherwise. */
int cli_parse_window(const char *cmd, const char *opt, const char *text, double frame[4]);

/* Plate coordinates in mm are at most CLI_MAX_COORDINATE_MM in magnitude (a kilometre, as the
 * stress grids' coordinates): lengths and steps between them stay finite. Prints one error and
 * returns -1 otherwise. */
#define CLI_MAX_COORDINATE_MM 1e6
int cli_check_coordinates_mm(const char *cmd, const char *opt, const char *text, const double *v, int n);

/* "prefilter" -> 1, "none" -> 0 (--antialias of render and photoelastic). Prints one error and
 * returns -1 otherwise. */
int cli_parse_antialias(const char *cmd, const char *text, int *prefilter);

#endif
