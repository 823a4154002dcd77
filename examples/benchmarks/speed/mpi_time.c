/* Time spent inside MPI calls during a LAMMPS run loop, per rank (the MPI profiling interface,
   loaded with LD_PRELOAD by bench_impact.py into its multi-rank runs; nothing of the plugin).

   LAMMPS's run command calls MPI_Barrier right before the loop and right after it
   (Timer::barrier_start/barrier_stop) and reads the clock after each. The wrapper keeps, for
   every interval between the returns of two barriers (the last 1024 of them), the wall time and
   the time inside the MPI calls below (point-to-point sends, receives and waits of the halo
   exchanges, and collectives, the closing barrier included); at MPI_Finalize each rank prints
   them on stderr, one line per interval k:

     MPITIME rank R interval k loop L mpi M

   The run loop is the interval whose L, averaged over the ranks, is LAMMPS's loop time (which
   is that average); bench_impact.py picks it so, within 1 %, and uses no MPI time where none
   matches. (Taking the longest interval was wrong for short runs, whose set-up between two
   barriers can outlast the loop.) M is what the rank spent waiting for the other ranks and
   moving data; L - M is its own work.
   Build: mpicc -shared -fPIC -O2 -o libmpi_time.so mpi_time.c */

#include <mpi.h>
#include <stdio.h>

enum { KEPT = 1024 };
static double interval_start, in_mpi, kept_loop[KEPT], kept_mpi[KEPT];
static long intervals;

#define TIMED(call)                       \
  do {                                    \
    const double t0_ = PMPI_Wtime();      \
    const int rc_ = call;                 \
    in_mpi += PMPI_Wtime() - t0_;         \
    return rc_;                           \
  } while (0)

int MPI_Barrier(MPI_Comm comm)
{
  const double enter = PMPI_Wtime();
  const int rc = PMPI_Barrier(comm);
  const double now = PMPI_Wtime();
  // the interval ends when the barrier returns, as LAMMPS's loop time does (it reads the clock
  // after Timer::barrier_stop's barrier): a rank's wait in it is MPI time of the interval
  kept_loop[intervals % KEPT] = now - interval_start;
  kept_mpi[intervals % KEPT] = in_mpi + (now - enter);
  intervals++;
  interval_start = now;
  in_mpi = 0.0;
  return rc;
}

int MPI_Send(const void *buf, int count, MPI_Datatype type, int dest, int tag, MPI_Comm comm)
{
  TIMED(PMPI_Send(buf, count, type, dest, tag, comm));
}

int MPI_Recv(void *buf, int count, MPI_Datatype type, int source, int tag, MPI_Comm comm,
             MPI_Status *status)
{
  TIMED(PMPI_Recv(buf, count, type, source, tag, comm, status));
}

int MPI_Sendrecv(const void *sbuf, int scount, MPI_Datatype stype, int dest, int stag, void *rbuf,
                 int rcount, MPI_Datatype rtype, int source, int rtag, MPI_Comm comm,
                 MPI_Status *status)
{
  TIMED(PMPI_Sendrecv(sbuf, scount, stype, dest, stag, rbuf, rcount, rtype, source, rtag, comm,
                      status));
}

int MPI_Wait(MPI_Request *request, MPI_Status *status)
{
  TIMED(PMPI_Wait(request, status));
}

int MPI_Waitall(int n, MPI_Request requests[], MPI_Status statuses[])
{
  TIMED(PMPI_Waitall(n, requests, statuses));
}

int MPI_Waitany(int n, MPI_Request requests[], int *index, MPI_Status *status)
{
  TIMED(PMPI_Waitany(n, requests, index, status));
}

int MPI_Allreduce(const void *sbuf, void *rbuf, int count, MPI_Datatype type, MPI_Op op,
                  MPI_Comm comm)
{
  TIMED(PMPI_Allreduce(sbuf, rbuf, count, type, op, comm));
}

int MPI_Reduce(const void *sbuf, void *rbuf, int count, MPI_Datatype type, MPI_Op op, int root,
               MPI_Comm comm)
{
  TIMED(PMPI_Reduce(sbuf, rbuf, count, type, op, root, comm));
}

int MPI_Bcast(void *buf, int count, MPI_Datatype type, int root, MPI_Comm comm)
{
  TIMED(PMPI_Bcast(buf, count, type, root, comm));
}

int MPI_Allgather(const void *sbuf, int scount, MPI_Datatype stype, void *rbuf, int rcount,
                  MPI_Datatype rtype, MPI_Comm comm)
{
  TIMED(PMPI_Allgather(sbuf, scount, stype, rbuf, rcount, rtype, comm));
}

int MPI_Allgatherv(const void *sbuf, int scount, MPI_Datatype stype, void *rbuf,
                   const int rcounts[], const int displs[], MPI_Datatype rtype, MPI_Comm comm)
{
  TIMED(PMPI_Allgatherv(sbuf, scount, stype, rbuf, rcounts, displs, rtype, comm));
}

int MPI_Scan(const void *sbuf, void *rbuf, int count, MPI_Datatype type, MPI_Op op, MPI_Comm comm)
{
  TIMED(PMPI_Scan(sbuf, rbuf, count, type, op, comm));
}

int MPI_Init(int *argc, char ***argv)
{
  const int rc = PMPI_Init(argc, argv);
  interval_start = PMPI_Wtime();
  return rc;
}

int MPI_Init_thread(int *argc, char ***argv, int required, int *provided)
{
  const int rc = PMPI_Init_thread(argc, argv, required, provided);
  interval_start = PMPI_Wtime();
  return rc;
}

int MPI_Finalize(void)
{
  int rank;
  PMPI_Comm_rank(MPI_COMM_WORLD, &rank);
  for (long k = intervals > KEPT ? intervals - KEPT : 0; k < intervals; k++)
    fprintf(stderr, "MPITIME rank %d interval %ld loop %.6f mpi %.6f\n", rank, k,
            kept_loop[k % KEPT], kept_mpi[k % KEPT]);
  fflush(stderr);
  return PMPI_Finalize();
}
