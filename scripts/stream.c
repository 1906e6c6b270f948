/* STREAM triad, a[i] = b[i] + s c[i], on every MPI rank at once: the memory bandwidth the ranks get
 * together. `make bench` runs it on 1 and 2 processes first; the ratio of the two is the ceiling of
 * the 2-rank speed-up of a memory-bound solve (a sparse matrix product, CG, a triangular solve), and
 * each bench row's speed-up is printed next to it (scripts/bench.py). The arrays (3 x 80 MB per
 * rank) are far larger than any cache; the best of 10 repetitions counts, as in McCalpin's STREAM.
 * Prints one line: "stream ranks P triad_mbs B" with B summed over the ranks. */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
  const long n = 10 * 1000 * 1000;
  const int  reps = 10;
  double    *a, *b, *c, best = 1e30, s = 3.0;
  int        rank, size;

  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  a = malloc(n * sizeof(double));
  b = malloc(n * sizeof(double));
  c = malloc(n * sizeof(double));
  if (!a || !b || !c) MPI_Abort(MPI_COMM_WORLD, 1);
  for (long i = 0; i < n; ++i) {
    a[i] = 1.0;
    b[i] = 2.0;
    c[i] = 0.5;
  }
  for (int r = 0; r < reps; ++r) {
    double t0, t;
    MPI_Barrier(MPI_COMM_WORLD);
    t0 = MPI_Wtime();
    for (long i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
    t = MPI_Wtime() - t0;
    /* the slowest rank sets the pace of the repetition */
    MPI_Allreduce(MPI_IN_PLACE, &t, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    if (t < best) best = t;
    s = a[n / 2] > 1e300 ? 1.0 : s; /* a use of a, so the loop is not optimized away */
  }
  if (!rank) printf("stream ranks %d triad_mbs %.1f\n", size, 3.0 * sizeof(double) * n * size / best / 1e6);
  free(a);
  free(b);
  free(c);
  MPI_Finalize();
  return 0;
}
