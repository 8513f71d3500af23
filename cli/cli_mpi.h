/* The command line over several processes (MPI; docs/CLUSTER.md). The library knows nothing of
 * MPI: this module is the command line's, and the only one that includes <mpi.h>.
 *
 * A process started by mpirun (or another MPI launcher, seen in its environment) with more than one
 * process in the job joins MPI at start-up; any other process, and every process of a build
 * without MPI (BIREF_MPI=OFF, or no Open MPI found), runs alone exactly as without this module.
 *
 * In a job of several processes, rank 0 alone prints and writes: the other ranks' stdout and
 * stderr streams go to /dev/null, and their error lines are kept for cli_mpi_agree. render,
 * accuracy and figure share their work out through cli_mpi_jobs; every other command refuses to
 * run in more than one process. */
#ifndef BIREF_CLI_MPI_H
#define BIREF_CLI_MPI_H

#include <stddef.h>

#include "biref/common.h"

/* Joins MPI when the launcher started this process (see above). Call first in main. */
void cli_mpi_init(int *argc, char ***argv);
/* The exit code every process of the job leaves with: the command's, agreed between the ranks
 * (cli_mpi_agree) unless that was already done with a failure; leaves MPI. Call last in main. */
int cli_mpi_finish(int rc);

/* 1 in a job of several processes, else 0; this process's rank (0 when alone) and their number. */
int cli_mpi_active(void);
int cli_mpi_rank(void);
int cli_mpi_size(void);

/* Collective (every rank calls it at the same step): the exit code of the lowest rank that
 * failed (rc != 0), or 0. Rank 0 prints that rank's error line when it is not its own, so the
 * job says one line whichever process met the bad input. Alone: rc. */
int cli_mpi_agree(int rc);

/* The last error line of this process (cli_error), for cli_mpi_agree and cli_mpi_abort. */
void cli_mpi_note_error(const char *line);

/* An unexpected failure in the middle of shared work: the last error line on this process's
 * original standard error, then the whole job ends with rc (MPI_Abort). Alone: returns rc. */
int cli_mpi_abort(int rc);

/* One job's result into result (result_size bytes): 0, or a CLI exit code after one error line. */
typedef int (*cli_mpi_compute_fn)(void *user, long job, void *result);
/* Rank 0 keeps a job's result (each job once, in any order). */
typedef void (*cli_mpi_store_fn)(void *user, long job, const void *result);

/* Jobs 0 .. n - 1 over every process of the job, dynamically: rank 0 hands out job numbers to
 * the other ranks (each holds two, so it never waits for the next) as their results come back,
 * computes jobs itself between their messages, and stores every result; the other ranks compute
 * and send. Collective: every rank calls it with the same n and result_size. The results do not
 * depend on which process computed them, so neither does anything built from them. progress
 * (rank 0; may be NULL) gets the jobs stored so far. A failed job ends the whole job
 * (cli_mpi_abort). Returns 0, or a failed job's code when alone. */
int cli_mpi_jobs(long n, size_t result_size, cli_mpi_compute_fn compute, cli_mpi_store_fn store, void *user,
                 biref_progress_fn progress, void *progress_user);

/* Waits, without spinning on a core, until every rank has called it (a barrier for ranks that
 * have nothing to do while rank 0 works alone). */
void cli_mpi_barrier(void);

#endif
