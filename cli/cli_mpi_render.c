/* A frame over the processes of an MPI job (cli_mpi_render.h): tiles of the image as jobs. */
#define BIREF_EXPERIMENTAL_API /* biref_renderer_render_rect */
#include "cli_mpi_render.h"

#include <string.h>

#include "biref/experimental.h"
#include "cli_mpi.h"

typedef struct {
    biref_render_stats stats;
    int status;
    float xyz[CLI_MPI_TILE * CLI_MPI_TILE * 3]; /* the tile's rows, CLI_MPI_TILE pixels apart */
} tile_result;

typedef struct {
    const biref_renderer *r;
    int W, H, tiles_x;
    float *xyz; /* rank 0 */
    biref_render_stats stats;
    biref_status status;
} frame_job;

static void tile_rect(const frame_job *f, long job, int *x, int *y, int *w, int *h)
{
    *x = (int)(job % f->tiles_x) * CLI_MPI_TILE;
    *y = (int)(job / f->tiles_x) * CLI_MPI_TILE;
    *w = f->W - *x < CLI_MPI_TILE ? f->W - *x : CLI_MPI_TILE;
    *h = f->H - *y < CLI_MPI_TILE ? f->H - *y : CLI_MPI_TILE;
}

static int compute_tile(void *user, long job, void *result)
{
    const frame_job *f = user;
    tile_result *t = result;
    int x, y, w, h;
    tile_rect(f, job, &x, &y, &w, &h);
    memset(&t->stats, 0, sizeof t->stats);
    t->status = biref_renderer_render_rect(f->r, x, y, w, h, t->xyz, 3 * CLI_MPI_TILE, &t->stats);
    return 0; /* a non-finite pixel is stored as 0 and reported once the frame is whole */
}

static void store_tile(void *user, long job, const void *result)
{
    frame_job *f = user;
    const tile_result *t = result;
    int x, y, w, h;
    tile_rect(f, job, &x, &y, &w, &h);
    for (int j = 0; j < h; j++)
        memcpy(f->xyz + ((size_t)(y + j) * f->W + x) * 3, t->xyz + (size_t)j * 3 * CLI_MPI_TILE,
               3 * (size_t)w * sizeof *t->xyz);
    f->stats.pixels += t->stats.pixels;
    f->stats.slab_pixels += t->stats.slab_pixels;
    f->stats.fallback_evals += t->stats.fallback_evals;
    if (t->status != BIREF_OK && f->status == BIREF_OK) f->status = (biref_status)t->status;
}

biref_status cli_mpi_render(const biref_renderer *r, float *xyz, biref_progress_fn progress, void *progress_user,
                            biref_render_stats *stats)
{
    frame_job f = {r, biref_renderer_width(r), biref_renderer_height(r), 0, xyz, {0, 0, 0}, BIREF_OK};
    f.tiles_x = (f.W + CLI_MPI_TILE - 1) / CLI_MPI_TILE;
    const long tiles = (long)f.tiles_x * ((f.H + CLI_MPI_TILE - 1) / CLI_MPI_TILE);
    cli_mpi_jobs(tiles, sizeof(tile_result), compute_tile, store_tile, &f, progress, progress_user);
    if (stats) *stats = f.stats;
    return f.status;
}
