/* Pinhole camera: its frame and image-plane extent (the tiles make the rays, render_tile_lanes.inc). */
#include <math.h>

#include "render/render_internal.h"
#include "shading/vec3.h"

void biref_render_camera_init(render_camera *c, const biref_camera *cam)
{
    double f[3], r[3], u[3];
    v3_sub(cam->look_at, cam->position, f);
    v3_normalize(f, f);
    /* The scene validator rejects up parallel to the view, so the cross product is non-zero. */
    v3_cross(f, cam->up, r);
    v3_normalize(r, r);
    v3_cross(r, f, u);
    for (int i = 0; i < 3; i++) {
        c->origin[i] = cam->position[i];
        c->forward[i] = f[i];
        c->right[i] = r[i];
        c->up[i] = u[i];
    }
    c->width = cam->width;
    c->height = cam->height;
    /* fov_deg is vertical; square pixels fix the horizontal extent. */
    c->tan_half_v = tan(0.5 * cam->fov_deg * M_PI / 180.0);
    c->tan_half_h = c->tan_half_v * (double)cam->width / (double)cam->height;
}

void biref_render_camera_columns(const render_camera *c, double *sx)
{
    for (int x = 0; x < c->width; x++) sx[x] = render_camera_sx(c, x + 0.5);
}
