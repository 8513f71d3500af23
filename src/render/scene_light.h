/* A scene file's two light objects ("light.polarization", "filter") as written, and the one
 * biref_light they make (scene.c parses them; docs/SCENES.md "Polarisation"). */
#ifndef BIREF_RENDER_SCENE_LIGHT_H
#define BIREF_RENDER_SCENE_LIGHT_H

#include "biref/render.h"

typedef enum { POL_UNPOLARIZED, POL_SP, POL_LINEAR } pol_type;
typedef struct {
    pol_type type;
    double s, p;         /* POL_SP: fractions, normalised to s + p = 1 */
    double direction[3]; /* POL_LINEAR: world-fixed polarizer axis */
} scene_pol;
typedef enum { FILTER_NONE, FILTER_S, FILTER_P, FILTER_LINEAR } filter_type;
typedef struct {
    filter_type type;
    double direction[3]; /* FILTER_LINEAR: world-fixed analyzer axis */
} scene_filter;

/* The paper's s/p light and mask, with the world-fixed polarizer and analyzer put in. */
void biref_scene_light(const scene_pol *pol, const scene_filter *f, biref_light *out);

/* A scene's light is what a scene file can say, which every back-end (CPU, GLSL) takes: s/p
 * fractions or a world-fixed polarizer, seen through no filter, an s or p filter or a world-fixed
 * analyzer. BIREF_ERR_INVALID with "FIELD: reason" otherwise. */
biref_status biref_scene_light_check(const biref_light *l, char *msg, size_t msg_len);

#endif
