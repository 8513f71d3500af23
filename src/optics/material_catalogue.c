/* The named materials (docs/MATERIALS.md): each index's formula as published, λ in µm. The
 * standard Sellmeier form n² − 1 = Σ B λ²/(λ² − C²) with C in µm appears here as a = 1 and
 * c = C² (squared in the initialiser, so the printed coefficients stay recognisable). */
#include <string.h>

#include "optics/material_internal.h"

#define SELL2(A, B1, C1, B2, C2) \
    {.kind = BIREF_FORMULA_SELLMEIER, .a = (A), .n_terms = 2, .b = {(B1), (B2)}, .c = {(C1), (C2)}}
#define SELL3(A, B1, C1, B2, C2, B3, C3) \
    {.kind = BIREF_FORMULA_SELLMEIER, .a = (A), .n_terms = 3, .b = {(B1), (B2), (B3)}, .c = {(C1), (C2), (C3)}}
/* n² = A + D/(λ² − E) + F λ² */
#define POLE1(A, D, E, F) {.kind = BIREF_FORMULA_SELLMEIER, .a = (A), .n_poles = 1, .d = {(D)}, .e = {(E)}, .f = (F)}
#define SELL1(A, B1, C1) {.kind = BIREF_FORMULA_SELLMEIER, .a = (A), .n_terms = 1, .b = {(B1)}, .c = {(C1)}}

#define UNIAXIAL(NAME, DESC, SRC, LO, HI, O, E)                                                              \
    {.name = NAME, .description = DESC, .source = SRC, .kind = MATERIAL_FORMULA, .has_range = 1,            \
     .range_nm = {LO, HI}, .formula = {O, E}}
#define ISOTROPIC(NAME, DESC, SRC, LO, HI, O)                                                                \
    {.name = NAME, .description = DESC, .source = SRC, .kind = MATERIAL_FORMULA, .isotropic = 1,            \
     .has_range = 1, .range_nm = {LO, HI}, .formula = {O, O}}

static const char GHOSH[] = "G. Ghosh, Dispersion-equation coefficients for the refractive index and birefringence "
                            "of calcite and quartz crystals, Opt. Commun. 163, 95-102 (1999)";
static const char SULTANOVA[] =
    "N. Sultanova, S. Kasarova, I. Nikolov, Dispersion properties of optical polymers, Acta Phys. Pol. A 116, "
    "585-587 (2009)";

static const struct biref_material CATALOGUE[] = {
    UNIAXIAL("calcite", "calcite (CaCO3), negative uniaxial, room temperature", GHOSH, 204.0, 2172.0,
             SELL2(1.73358749, 0.96464345, 1.94325203e-2, 1.82831454, 120.0),
             SELL2(1.35859695, 0.82427830, 1.06689543e-2, 0.14429128, 120.0)),
    UNIAXIAL("quartz", "crystalline quartz (alpha-SiO2), positive uniaxial, room temperature", GHOSH, 198.0,
             2053.1, SELL2(1.28604141, 1.07044083, 1.00585997e-2, 1.10202242, 100.0),
             SELL2(1.28851804, 1.09509924, 1.02101864e-2, 1.15662475, 100.0)),
    UNIAXIAL("sapphire", "synthetic sapphire (Al2O3), negative uniaxial, 20 C",
             "I. H. Malitson, M. J. Dodge, Refractive index and birefringence of synthetic sapphire, J. Opt. Soc. "
             "Am. 62, 1405 (1972); Sellmeier coefficients in M. J. Dodge, Handbook of Laser Science and "
             "Technology IV, CRC Press (1986)",
             200.0, 5000.0,
             SELL3(1.0, 1.4313493, 0.0726631 * 0.0726631, 0.65054713, 0.1193242 * 0.1193242, 5.3414021,
                   18.028251 * 18.028251),
             SELL3(1.0, 1.5039759, 0.0740288 * 0.0740288, 0.55069141, 0.1216529 * 0.1216529, 6.5927379,
                   20.072248 * 20.072248)),
    UNIAXIAL("rutile", "rutile (TiO2), positive uniaxial, room temperature",
             "J. R. DeVore, Refractive indices of rutile and sphalerite, J. Opt. Soc. Am. 41, 416-419 (1951)", 430.0,
             1530.0, POLE1(5.913, 0.2441, 0.0803, 0.0), POLE1(7.197, 0.3322, 0.0843, 0.0)),
    UNIAXIAL("mgf2", "magnesium fluoride (MgF2), positive uniaxial, 19 C",
             "M. J. Dodge, Refractive properties of magnesium fluoride, Appl. Opt. 23, 1980-1985 (1984)", 200.0,
             7000.0,
             SELL3(1.0, 0.48755108, 0.04338408 * 0.04338408, 0.39875031, 0.09461442 * 0.09461442, 2.3120353,
                   23.793604 * 23.793604),
             SELL3(1.0, 0.41344023, 0.03684262 * 0.03684262, 0.50497499, 0.09076162 * 0.09076162, 2.4904862,
                   23.771995 * 23.771995)),
    UNIAXIAL("yvo4", "yttrium orthovanadate (YVO4), positive uniaxial, 20 C",
             "H. S. Shi, G. Zhang, H. Y. Shen, Measurement of principal refractive indices and the thermal "
             "refractive index coefficients of yttrium vanadate, J. Synthetic Cryst. 30, 85-88 (2001)",
             480.0, 1340.0, POLE1(3.778790, 0.070479, 0.045731, -0.009701),
             POLE1(4.607200, 0.108087, 0.052495, -0.014305)),
    UNIAXIAL("linbo3", "lithium niobate (LiNbO3), congruent, negative uniaxial, 21 C",
             "D. E. Zelmon, D. L. Small, D. Jundt, Infrared corrected Sellmeier coefficients for congruently "
             "grown lithium niobate and 5 mol.% magnesium oxide-doped lithium niobate, J. Opt. Soc. Am. B 14, "
             "3319-3322 (1997)",
             400.0, 5000.0, SELL3(1.0, 2.6734, 0.01764, 1.2290, 0.05914, 12.614, 474.60),
             SELL3(1.0, 2.9804, 0.02047, 0.5981, 0.0666, 8.9543, 416.08)),
    UNIAXIAL("bbo", "beta barium borate (beta-BaB2O4), negative uniaxial, room temperature",
             "D. Eimerl, L. Davis, S. Velsko, E. K. Graham, A. Zalkin, Optical, mechanical, and thermal "
             "properties of barium borate, J. Appl. Phys. 62, 1968-1983 (1987)",
             220.0, 1060.0, POLE1(2.7405, 0.0184, 0.0179, -0.0155), POLE1(2.3730, 0.0128, 0.0156, -0.0044)),
    ISOTROPIC("polycarbonate", "polycarbonate (PC), isotropic, room temperature", SULTANOVA, 436.8, 1052.0,
              SELL1(1.0, 1.4182, 0.021304)),
    ISOTROPIC("pmma", "poly(methyl methacrylate) (PMMA), isotropic, room temperature", SULTANOVA, 436.8, 1052.0,
              SELL1(1.0, 1.1819, 0.011313)),
};

enum { N_CATALOGUE = sizeof CATALOGUE / sizeof CATALOGUE[0] };

size_t biref_material_catalogue_size(void) { return N_CATALOGUE; }

const biref_material *biref_material_catalogue(size_t i) { return i < N_CATALOGUE ? &CATALOGUE[i] : NULL; }

const biref_material *biref_material_find(const char *name)
{
    if (!name) return NULL;
    for (size_t i = 0; i < N_CATALOGUE; i++)
        if (!strcmp(CATALOGUE[i].name, name)) return &CATALOGUE[i];
    return NULL;
}
