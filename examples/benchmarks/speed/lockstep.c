/* The machine's own ceiling for a 2-rank parallel efficiency (bench_impact.py's "lockstep"
   configuration; nothing of LAMMPS or the plugin).

     mpirun -np R lockstep CHUNKS EVERY

   does CHUNKS equal chunks of arithmetic in all, CHUNKS / R on each rank, and every EVERY
   chunks of its own the ranks meet in an MPI_Allreduce of one double, as a force evaluation
   meets its neighbours in a halo exchange. The work of a chunk is the same on every rank and
   in every run (a fixed number of fused multiply-add sweeps over two arrays of 256 KiB each,
   L2-resident like a rank's gathered partner data), and there is nothing to communicate but the
   one double. So with R = 1 and R = 2 run in turn, t1 / (2 t2) is the 2-rank efficiency that
   perfectly balanced work with free communication gets from the machine at that moment: 1 on
   two idle cores of their own, less where the two cores run at unequal speeds between two
   meetings (a virtual CPU shares its physical core or cache with other guests, or is taken
   away for a while), since every meeting waits for the slower rank.

   Rank 0 prints one line,

     LOCKSTEP ranks R chunks N every E seconds T mpi M checksum C

   T the wall time between the barriers around the loop, M the mean over the ranks of the time
   spent in the meetings (waiting for the other rank), C the mean over the ranks of the sum of
   a (so the compiler keeps the work; the same for every E with the same N and R). Build:
   mpicc -O2 -o lockstep lockstep.c */

#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

enum { N = 32768, SWEEPS = 12 };

static double a[N], b[N];

/* one chunk: SWEEPS multiply-add sweeps over a and b; the values stay bounded (a -> b / 0.001) */
static void chunk(void)
{
  for (int s = 0; s < SWEEPS; s++)
    for (int i = 0; i < N; i++) a[i] = 0.999 * a[i] + b[i];
}

int main(int argc, char **argv)
{
  MPI_Init(&argc, &argv);
  int rank, ranks;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  const long chunks = argc > 1 ? atol(argv[1]) : 0;
  const long every = argc > 2 ? atol(argv[2]) : 0;
  if (argc != 3 || chunks <= 0 || every <= 0 || chunks % ranks != 0) {
    if (rank == 0)
      fprintf(stderr, "usage: mpirun -np R lockstep CHUNKS EVERY (CHUNKS > 0 a multiple of R, "
                      "EVERY > 0)\n");
    MPI_Finalize();
    return 2;
  }
  for (int i = 0; i < N; i++) {
    a[i] = 0.0;
    b[i] = 1e-6 * (i % 97);
  }
  const long mine = chunks / ranks;
  double in_mpi = 0.0;

  MPI_Barrier(MPI_COMM_WORLD);
  const double start = MPI_Wtime();
  for (long c = 0; c < mine; c++) {
    chunk();
    if ((c + 1) % every == 0 || c + 1 == mine) {
      const double t0 = MPI_Wtime();
      double one = a[c % N], sum;
      MPI_Allreduce(&one, &sum, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
      in_mpi += MPI_Wtime() - t0;
    }
  }
  const double t0 = MPI_Wtime();
  MPI_Barrier(MPI_COMM_WORLD);
  const double end = MPI_Wtime();
  in_mpi += end - t0;

  double mine_sum = 0.0, checksum = 0.0, mpi_sum = 0.0;
  for (int i = 0; i < N; i++) mine_sum += a[i];
  MPI_Reduce(&mine_sum, &checksum, 1, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
  MPI_Reduce(&in_mpi, &mpi_sum, 1, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
  if (rank == 0)
    printf("LOCKSTEP ranks %d chunks %ld every %ld seconds %.6f mpi %.6f checksum %.10g\n", ranks,
           chunks, every, end - start, mpi_sum / ranks, checksum / ranks);
  MPI_Finalize();
  return 0;
}
