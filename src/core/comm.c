/* moraine: the processes of a distributed run (see comm.h). */
#include "core/comm.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"

static int shared_error;
void mrn_comm_set_shared_error(int shared) { shared_error = shared; }
int mrn_comm_shared_error(void) { return shared_error; }

#ifdef MRN_HAVE_MPI
#include <mpi.h>

static int started; /* MPI_Init was called here */
static int rank, size = 1;

/* launched by an MPI launcher: Open MPI's, or one speaking PMI / PMIx */
static int launched(void) {
  return getenv("OMPI_COMM_WORLD_SIZE") || getenv("PMI_SIZE") || getenv("PMIX_RANK");
}

int mrn_comm_init(int *argc, char ***argv) {
  if (started || !launched()) return MRN_OK;
  int provided = 0;
  if (MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
    return mrn_error("MPI: MPI_Init_thread failed");
  started = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return MRN_OK;
}

void mrn_comm_finalize(void) {
  if (started) MPI_Finalize();
  started = 0;
  rank = 0;
  size = 1;
}

int mrn_comm_rank(void) { return rank; }
int mrn_comm_size(void) { return size; }

void mrn_comm_abort(int code) {
  fflush(stdout);
  fflush(stderr);
  if (size > 1) MPI_Abort(MPI_COMM_WORLD, code ? code : 1);
}

/* MPI counts are ints: a message beyond 2 GiB stops the run */
static int count_of(size_t bytes) {
  if (bytes > (size_t)INT_MAX) {
    fprintf(stderr, "moraine: MPI message of %zu bytes is above the 2 GiB limit of one message\n", bytes);
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  return (int)bytes;
}

static MPI_Op op_of(mrn_comm_op op) { return op == MRN_COMM_SUM ? MPI_SUM : op == MRN_COMM_MIN ? MPI_MIN : MPI_MAX; }

void mrn_comm_allreduce(double *v, int n, mrn_comm_op op) {
  if (size > 1) MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_DOUBLE, op_of(op), MPI_COMM_WORLD);
}

void mrn_comm_allreduce_long(long *v, int n, mrn_comm_op op) {
  if (size > 1) MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_LONG, op_of(op), MPI_COMM_WORLD);
}

void mrn_comm_reduce_sum(double *v, size_t n, int root) {
  if (size > 1)
    MPI_Reduce(rank == root ? MPI_IN_PLACE : v, v, count_of(n), MPI_DOUBLE, MPI_SUM, root, MPI_COMM_WORLD);
}

void mrn_comm_bcast(void *buf, size_t bytes, int root) {
  if (size > 1) MPI_Bcast(buf, count_of(bytes), MPI_BYTE, root, MPI_COMM_WORLD);
}

void mrn_comm_exchange(int peer, const void *sbuf, size_t sbytes, void *rbuf, size_t rbytes) {
  MPI_Sendrecv(sbuf, count_of(sbytes), MPI_BYTE, peer, 0, rbuf, count_of(rbytes), MPI_BYTE, peer, 0, MPI_COMM_WORLD,
               MPI_STATUS_IGNORE);
}

/* size_t counts and displacements as the ints MPI takes */
static int *ints_of(const size_t *v) {
  int *out = malloc((size_t)size * sizeof *out);
  if (!out) {
    fprintf(stderr, "moraine: out of memory in an MPI exchange\n");
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  for (int r = 0; r < size; r++) out[r] = count_of(v[r]);
  return out;
}

void mrn_comm_alltoallv(const void *sbuf, const size_t *scount, const size_t *sdispl, void *rbuf,
                        const size_t *rcount, const size_t *rdispl) {
  int *sc = ints_of(scount), *sd = ints_of(sdispl), *rc = ints_of(rcount), *rd = ints_of(rdispl);
  MPI_Alltoallv(sbuf, sc, sd, MPI_BYTE, rbuf, rc, rd, MPI_BYTE, MPI_COMM_WORLD);
  free(sc);
  free(sd);
  free(rc);
  free(rd);
}

void mrn_comm_gatherv(const void *sbuf, size_t bytes, void *rbuf, const size_t *rcount, const size_t *rdispl,
                      int root) {
  int *rc = NULL, *rd = NULL;
  if (rank == root) {
    rc = ints_of(rcount);
    rd = ints_of(rdispl);
  }
  MPI_Gatherv(sbuf, count_of(bytes), MPI_BYTE, rbuf, rc, rd, MPI_BYTE, root, MPI_COMM_WORLD);
  free(rc);
  free(rd);
}

void mrn_comm_allgather_size(size_t mine, size_t *all) {
  unsigned long long m = mine, *a = malloc((size_t)size * sizeof *a);
  if (!a) {
    fprintf(stderr, "moraine: out of memory in an MPI exchange\n");
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  MPI_Allgather(&m, 1, MPI_UNSIGNED_LONG_LONG, a, 1, MPI_UNSIGNED_LONG_LONG, MPI_COMM_WORLD);
  for (int r = 0; r < size; r++) all[r] = (size_t)a[r];
  free(a);
}

#else /* one process */

int mrn_comm_init(int *argc, char ***argv) { return MRN_OK; }
void mrn_comm_finalize(void) {}
int mrn_comm_rank(void) { return 0; }
int mrn_comm_size(void) { return 1; }
void mrn_comm_abort(int code) {}
void mrn_comm_allreduce(double *v, int n, mrn_comm_op op) {}
void mrn_comm_allreduce_long(long *v, int n, mrn_comm_op op) {}
void mrn_comm_bcast(void *buf, size_t bytes, int root) {}
void mrn_comm_reduce_sum(double *v, size_t n, int root) {}
void mrn_comm_exchange(int peer, const void *sbuf, size_t sbytes, void *rbuf, size_t rbytes) {
  memcpy(rbuf, sbuf, sbytes < rbytes ? sbytes : rbytes);
}
void mrn_comm_alltoallv(const void *sbuf, const size_t *scount, const size_t *sdispl, void *rbuf,
                        const size_t *rcount, const size_t *rdispl) {
  memcpy((char *)rbuf + rdispl[0], (const char *)sbuf + sdispl[0], scount[0]);
}
void mrn_comm_gatherv(const void *sbuf, size_t bytes, void *rbuf, const size_t *rcount, const size_t *rdispl,
                      int root) {
  memcpy((char *)rbuf + rdispl[0], sbuf, bytes);
}
void mrn_comm_allgather_size(size_t mine, size_t *all) { all[0] = mine; }

#endif
