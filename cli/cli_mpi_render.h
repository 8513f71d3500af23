/* A rendered frame shared out over the processes of an MPI job (cli_mpi.h, docs/CLUSTER.md). */
#ifndef BIREF_CLI_MPI_RENDER_H
#define BIREF_CLI_MPI_RENDER_H

#include "biref/render.h"

/* The side of the square tiles a frame is cut into (the last column and row narrower). A tile
 * over the sky costs ~100x less than one over a slab with ground truth: rank 0 hands them out
 * one by one (cli_mpi_jobs), so fast and slow tiles even out. */
#define CLI_MPI_TILE 32

/* Collective: renders r's whole frame over every process, tiles as jobs; rank 0 gets the image in
 * xyz (width x height x 3 floats; the other ranks pass NULL) and the stats summed over the tiles.
 * The image is the one biref_render_image gives, bit for bit. Status as biref_render_image's
 * (rank 0; the others return BIREF_OK). progress (rank 0): tiles done of all. */
biref_status cli_mpi_render(const biref_renderer *r, float *xyz, biref_progress_fn progress, void *progress_user,
                            biref_render_stats *stats);

#endif
