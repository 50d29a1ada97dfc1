/* moraine: the processes of a distributed run (MPI), and what they say to
 * each other.
 *
 * A thin layer over MPI so that the rest of the engine neither includes
 * <mpi.h> nor cares whether it was built with MPI: without MPI
 * (-DMORAINE_MPI=OFF), or in a program that was not started by an MPI
 * launcher, there is one process, rank 0 of 1, and every call below is a
 * copy or nothing. MPI is initialised only when the program was started by
 * a launcher (mpirun sets OMPI_COMM_WORLD_SIZE, PMI_SIZE or PMIX_RANK), so a
 * plain `moraine deck.lua` never pays for MPI's start-up. */
#ifndef MRN_CORE_COMM_H
#define MRN_CORE_COMM_H

#include <stddef.h>

typedef enum { MRN_COMM_SUM, MRN_COMM_MIN, MRN_COMM_MAX } mrn_comm_op;

/* start MPI when launched by mpirun (and with MPI_THREAD_FUNNELED: only the
 * main thread calls MPI); 0, or an error code with the message set */
int mrn_comm_init(int *argc, char ***argv);
void mrn_comm_finalize(void);
int mrn_comm_rank(void);
int mrn_comm_size(void);
/* stop every process of the run (after a message was printed) */
void mrn_comm_abort(int code);

/* v[0 .. n) combined over every process, in place, the same on each */
void mrn_comm_allreduce(double *v, int n, mrn_comm_op op);
void mrn_comm_allreduce_long(long *v, int n, mrn_comm_op op);
/* v[0 .. n) summed over every process into v on `root` (in place) */
void mrn_comm_reduce_sum(double *v, size_t n, int root);
/* `bytes` at buf sent from `root` to every process */
void mrn_comm_bcast(void *buf, size_t bytes, int root);
/* exchange with one process: send `sbytes` to `peer`, receive `rbytes` from it */
void mrn_comm_exchange(int peer, const void *sbuf, size_t sbytes, void *rbuf, size_t rbytes);
/* every process sends scount[r] bytes (from sbuf at sdispl[r]) to process
 * r and receives rcount[r] bytes (into rbuf at rdispl[r]) from it */
void mrn_comm_alltoallv(const void *sbuf, const size_t *scount, const size_t *sdispl, void *rbuf,
                        const size_t *rcount, const size_t *rdispl);
/* every process's `bytes` gathered on `root` at rbuf in rank order (counts
 * and displacements in bytes, needed on root only) */
void mrn_comm_gatherv(const void *sbuf, size_t bytes, void *rbuf, const size_t *rcount, const size_t *rdispl, int root);
/* one size_t from every process, into all[size] on each */
void mrn_comm_allgather_size(size_t mine, size_t *all);
/* An error every process holds (agreed, solver/dist.h): process 0 alone
 * reports it. Otherwise the process that failed reports it and stops the
 * others (mrn_comm_abort). */
void mrn_comm_set_shared_error(int shared);
int mrn_comm_shared_error(void);
/* 1 on the process that writes files and prints (process 0) */
static inline int mrn_comm_writes(void) { return mrn_comm_rank() == 0; }

#endif
