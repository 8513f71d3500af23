/* The command line over several processes (cli_mpi.h). Compiled with BIREF_HAVE_MPI when CMake
 * found MPI (option BIREF_MPI); without it every process is alone. The state below is the command
 * line's (one per process), never the library's. */
#include "cli_mpi.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef BIREF_HAVE_MPI
#include <mpi.h>
#include <omp.h>
#include <time.h>
#include <unistd.h>
#endif

/* A bounded error line (cli_error's messages are one line well below this). */
enum { LINE_MAX_BYTES = 4096 };

static struct {
    int active, rank, size;
    int agreed_failure; /* cli_mpi_agree already ended the command with a failure */
    char line[LINE_MAX_BYTES];
} g = {0, 0, 1, 0, ""};

int cli_mpi_active(void) { return g.active; }
int cli_mpi_rank(void) { return g.rank; }
int cli_mpi_size(void) { return g.size; }

void cli_mpi_note_error(const char *line)
{
    snprintf(g.line, sizeof g.line, "%s", line);
}

#ifndef BIREF_HAVE_MPI

void cli_mpi_init(int *argc, char ***argv) { (void)argc, (void)argv; }
int cli_mpi_finish(int rc) { return rc; }
int cli_mpi_agree(int rc) { return rc; }
int cli_mpi_abort(int rc) { return rc; }
void cli_mpi_barrier(void) {}

#else

/* Started by an MPI launcher: Open MPI's mpirun, or a PMI/PMIx launcher (srun, hydra). A process
 * started any other way does not call MPI_Init (no singleton start-up, no daemon): it runs alone. */
static int launched_by_mpi(void)
{
    static const char *const VARS[] = {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"};
    for (size_t i = 0; i < sizeof VARS / sizeof VARS[0]; i++)
        if (getenv(VARS[i])) return 1;
    return 0;
}

/* The default thread count of each process (--threads and OMP_NUM_THREADS override it): the
 * machine's cores shared among its processes, within the cores the process is bound to. OpenMP's
 * own default, every core in each process, oversubscribes a machine that runs several: its idle
 * threads spin, and a frame of cheap tiles took 60x as long (docs/CLUSTER.md). */
static void share_cores(void)
{
    if (getenv("OMP_NUM_THREADS")) return;
    MPI_Comm node;
    int local = 1;
    if (MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node) == MPI_SUCCESS) {
        MPI_Comm_size(node, &local);
        MPI_Comm_free(&node);
    }
    const long cores = sysconf(_SC_NPROCESSORS_ONLN);
    const int bound = omp_get_num_procs(), share = cores > local ? (int)(cores / local) : 1;
    omp_set_num_threads(share < bound ? share : bound);
}

void cli_mpi_init(int *argc, char ***argv)
{
    if (!launched_by_mpi()) return;
    if (MPI_Init(argc, argv) != MPI_SUCCESS) return;
    MPI_Comm_rank(MPI_COMM_WORLD, &g.rank);
    MPI_Comm_size(MPI_COMM_WORLD, &g.size);
    g.active = g.size > 1;
    if (!g.active) {
        /* mpirun -n 1: one process, as without mpirun. */
        MPI_Finalize();
        g.rank = 0;
        g.size = 1;
        return;
    }
    share_cores();
    if (g.rank > 0) {
        /* Only rank 0 prints. The streams, not file descriptors 1 and 2, go to /dev/null (glibc's
         * stdout and stderr are variables one may set): a sanitizer's report, written to
         * descriptor 2, and cli_mpi_abort's line still reach mpirun. */
        FILE *null_out = fopen("/dev/null", "w"), *null_err = fopen("/dev/null", "w");
        if (null_out) stdout = null_out;
        if (null_err) stderr = null_err;
    }
}

/* Polls req until it completes, sleeping between tests: a rank that waits leaves its core to the
 * ranks and threads that compute (Open MPI's blocking calls spin). */
static void wait_quietly(MPI_Request *req, MPI_Status *st)
{
    const struct timespec pause = {0, 100 * 1000};
    int done = 0;
    for (;;) {
        MPI_Test(req, &done, st ? st : MPI_STATUS_IGNORE);
        if (done) return;
        nanosleep(&pause, NULL);
    }
}

void cli_mpi_barrier(void)
{
    if (!g.active) return;
    MPI_Request req;
    MPI_Ibarrier(MPI_COMM_WORLD, &req);
    wait_quietly(&req, NULL);
}

int cli_mpi_agree(int rc)
{
    if (!g.active) return rc;
    int key = rc ? g.rank : g.size, first = g.size;
    MPI_Request req;
    MPI_Iallreduce(&key, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD, &req);
    wait_quietly(&req, NULL);
    if (first == g.size) return 0;
    struct {
        int rc;
        char line[LINE_MAX_BYTES];
    } msg = {rc, ""};
    if (g.rank == first) memcpy(msg.line, g.line, sizeof msg.line);
    MPI_Ibcast(&msg, (int)sizeof msg, MPI_BYTE, first, MPI_COMM_WORLD, &req);
    wait_quietly(&req, NULL);
    msg.line[sizeof msg.line - 1] = '\0';
    if (g.rank == 0 && first != 0) fprintf(stderr, "%s\n", msg.line[0] ? msg.line : "biref: error on another process");
    g.agreed_failure = 1;
    return msg.rc;
}

int cli_mpi_finish(int rc)
{
    if (!g.active) return rc;
    if (!g.agreed_failure) rc = cli_mpi_agree(rc);
    fflush(stdout);
    fflush(stderr);
    MPI_Finalize();
    return rc;
}

int cli_mpi_abort(int rc)
{
    if (!g.active) return rc;
    /* Rank 0 printed its line already; another rank's stderr stream is /dev/null. */
    if (g.rank > 0 && g.line[0]) dprintf(STDERR_FILENO, "%s\n", g.line);
    fflush(stdout);
    MPI_Abort(MPI_COMM_WORLD, rc > 0 ? rc : 1);
    return rc; /* not reached */
}

/* Messages of cli_mpi_jobs: a job number to a rank (-1: no more), and a result to rank 0 (the
 * job number, then the result's bytes). */
enum { TAG_JOB = 17, TAG_RESULT = 18, DEPTH = 2 };

typedef struct {
    long n, next, stored;
    size_t msg_size;
    cli_mpi_compute_fn compute;
    cli_mpi_store_fn store;
    void *user;
    biref_progress_fn progress;
    void *progress_user;
} job_run;

static void send_job(job_run *j, int rank)
{
    long job = j->next < j->n ? j->next++ : -1;
    MPI_Send(&job, 1, MPI_LONG, rank, TAG_JOB, MPI_COMM_WORLD);
}

static void stored(job_run *j, const unsigned char *msg)
{
    long job;
    memcpy(&job, msg, sizeof job);
    j->store(j->user, job, msg + sizeof job);
    j->stored++;
    if (j->progress) j->progress(j->progress_user, (int)j->stored, (int)j->n);
}

/* Rank 0: hands out jobs as results announce themselves (a result's envelope arrives before its
 * data, so a rank gets its next job without waiting for the transfer), receives the results into
 * a pool of buffers, and computes a job itself whenever nothing came in. */
static int jobs_master(job_run *j)
{
    const int workers = g.size - 1, nbuf = workers * DEPTH + 1; /* the last one for rank 0's own jobs */
    unsigned char *buf = malloc((size_t)nbuf * j->msg_size);
    MPI_Request *req = malloc((size_t)nbuf * sizeof *req);
    char *busy = calloc((size_t)nbuf, 1);
    int *stopped = calloc((size_t)g.size, sizeof *stopped);
    if (!buf || !req || !busy || !stopped) {
        free(buf), free(req), free(busy), free(stopped);
        cli_mpi_note_error("biref: error: out of memory for the results of other processes");
        fprintf(stderr, "%s\n", g.line);
        return cli_mpi_abort(1);
    }
    for (int w = 1; w < g.size; w++)
        for (int d = 0; d < DEPTH; d++) {
            stopped[w] |= j->next >= j->n;
            send_job(j, w);
            if (stopped[w]) break;
        }
    unsigned char *own = buf + (size_t)(nbuf - 1) * j->msg_size;
    const struct timespec pause = {0, 100 * 1000};
    int rc = 0;
    while (j->stored < j->n && !rc) {
        int progressed = 0, flag = 0;
        MPI_Message m;
        MPI_Status st;
        for (;;) {
            /* A free buffer first: a result stays in the network until one is (a rank's results
             * can outrun the tests of their transfers). */
            int b = 0;
            while (b < nbuf - 1 && busy[b]) b++;
            if (b == nbuf - 1) break;
            MPI_Improbe(MPI_ANY_SOURCE, TAG_RESULT, MPI_COMM_WORLD, &flag, &m, &st);
            if (!flag) break;
            busy[b] = 1;
            MPI_Imrecv(buf + (size_t)b * j->msg_size, (int)j->msg_size, MPI_BYTE, &m, &req[b]);
            const int w = st.MPI_SOURCE;
            if (!stopped[w]) {
                stopped[w] = j->next >= j->n;
                send_job(j, w);
            }
            progressed = 1;
        }
        for (int b = 0; b < nbuf - 1; b++) {
            if (!busy[b]) continue;
            MPI_Test(&req[b], &flag, MPI_STATUS_IGNORE);
            if (!flag) continue;
            stored(j, buf + (size_t)b * j->msg_size);
            busy[b] = 0;
            progressed = 1;
        }
        if (progressed) continue;
        if (j->next < j->n) {
            const long job = j->next++;
            memcpy(own, &job, sizeof job);
            rc = j->compute(j->user, job, own + sizeof job);
            if (!rc) stored(j, own);
        } else {
            nanosleep(&pause, NULL);
        }
    }
    free(buf), free(req), free(busy), free(stopped);
    return rc ? cli_mpi_abort(rc) : 0;
}

/* Another rank: computes the jobs it is given until told there are no more; each result leaves
 * while the next job is computed (DEPTH buffers). */
static int jobs_worker(job_run *j)
{
    unsigned char *buf = malloc((size_t)DEPTH * j->msg_size);
    MPI_Request sent[DEPTH];
    for (int d = 0; d < DEPTH; d++) sent[d] = MPI_REQUEST_NULL;
    if (!buf) {
        cli_mpi_note_error("biref: error: out of memory for a job's result");
        return cli_mpi_abort(1);
    }
    for (long k = 0;; k++) {
        long job;
        MPI_Request req;
        MPI_Irecv(&job, 1, MPI_LONG, 0, TAG_JOB, MPI_COMM_WORLD, &req);
        wait_quietly(&req, NULL);
        if (job < 0) break;
        const int d = (int)(k % DEPTH);
        wait_quietly(&sent[d], NULL);
        unsigned char *msg = buf + (size_t)d * j->msg_size;
        memcpy(msg, &job, sizeof job);
        const int rc = j->compute(j->user, job, msg + sizeof job);
        if (rc) {
            free(buf);
            return cli_mpi_abort(rc);
        }
        MPI_Isend(msg, (int)j->msg_size, MPI_BYTE, 0, TAG_RESULT, MPI_COMM_WORLD, &sent[d]);
    }
    for (int d = 0; d < DEPTH; d++) wait_quietly(&sent[d], NULL);
    free(buf);
    return 0;
}

#endif /* BIREF_HAVE_MPI */

int cli_mpi_jobs(long n, size_t result_size, cli_mpi_compute_fn compute, cli_mpi_store_fn store, void *user,
                 biref_progress_fn progress, void *progress_user)
{
#ifdef BIREF_HAVE_MPI
    if (g.active) {
        job_run j = {n, 0, 0, sizeof(long) + result_size, compute, store, user, progress, progress_user};
        return g.rank == 0 ? jobs_master(&j) : jobs_worker(&j);
    }
#endif
    /* Alone: every job here, in order. */
    unsigned char *result = malloc(result_size ? result_size : 1);
    if (!result) return fprintf(stderr, "biref: error: out of memory\n"), 1;
    int rc = 0;
    for (long job = 0; job < n && !rc; job++) {
        rc = compute(user, job, result);
        if (!rc) store(user, job, result);
        if (!rc && progress) progress(progress_user, (int)(job + 1), (int)n);
    }
    free(result);
    return rc;
}
