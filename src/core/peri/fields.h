// The per-particle data one force evaluation reads and writes, as plain arrays (rows over the
// owned particles first, then their ghost copies; 3-vectors three doubles per particle), and
// the callbacks through which an evaluation communicates. LAMMPS-free: the glue fills these
// with pointers into its own per-atom arrays.

#ifndef PERISISSM_PERI_FIELDS_H
#define PERISISSM_PERI_FIELDS_H

namespace PeriSISSM {

// What the particles are.
struct Particles {
  int nlocal = 0;                    // owned particles (rows 0 .. nlocal-1)
  int nall = 0;                      // owned and ghost rows (membrane decks, ParticleFields::cols)
  const double *x = nullptr;         // current positions
  const double *x0 = nullptr;        // reference positions
  const double *volume = nullptr;    // V_i
  const int *type = nullptr;         // type of each particle (1 .. ntypes)
  double *smin = nullptr;            // smallest bond stretch of the last evaluation (breaking)
  double *f = nullptr;               // force density, accumulated into for the owned rows
};

// Per-particle state of the correspondence model, written for the owned rows and sent to the
// ghosts by the halo between passes.
struct ParticleFields {
  // g: F (row-major 3x3), C (stabilization modulus), regular flag (1 or 0)
  enum { G_C = 9, G_REG = 10, NG = 11 };
  // k: implicit stiffness H (xx yy zz xy xz yz), C, and 1 (K_ONE: the weighted sum of a
  // family's k rows then carries the family's weight sum too; eight doubles, one cache line),
  // for the SISSM blocks
  enum { K_C = 6, K_ONE = 7, NK = 8 };
  double *g = nullptr;    // NG per particle
  double *h = nullptr;    // 9 per particle: H = (P + Q) K^-1
  double *k = nullptr;    // NK per particle (only when blocks are asked for)
  double *w = nullptr;    // energy density of each owned particle (complete only with energy)
  bool energy = true;     // false: w lacks the stabilization energy (not summed: faster)
  double *smin_new = nullptr;    // scratch, one per owned particle
  double *normal = nullptr;      // scratch, 3 per particle (owned and ghost): current normals of
                                 // membrane particles; needed only when the model has membranes
  double *cols = nullptr;        // scratch, NCOLS per particle (owned and ghost), optional: the
                                 // fused passes' copy of F, then of H, by columns (peri/columns.h);
                                 // without it they run their scalar code
  enum { NCOLS = 12 };
};

// One per-particle field: width doubles per particle, contiguous rows.
struct HaloField {
  double *rows;
  int width;
};

// Forward communication of per-particle fields from the owners to their ghost copies.
class Halo {
 public:
  virtual ~Halo() = default;
  // n fields in one exchange (one message per neighbor rank, not n); after the call the ghost
  // rows of every field hold their owners' values
  virtual void forward(const HaloField *fields, int n) = 0;
  void forward(double *rows, int width)
  {
    const HaloField one{rows, width};
    forward(&one, 1);
  }
};

// A halo's message: the rows of nfields fields of the particles list[0 .. n-1], field after
// field for each particle, into buf (as many doubles as the return value).
inline int pack_halo_rows(const HaloField *fields, int nfields, int n, const int *list, double *buf)
{
  int m = 0;
  for (int ii = 0; ii < n; ii++)
    for (int q = 0; q < nfields; q++) {
      const int width = fields[q].width;
      const double *row = fields[q].rows + (long long) width * list[ii];
      for (int k = 0; k < width; k++) buf[m++] = row[k];
    }
  return m;
}

// The message of pack_halo_rows() into the rows of the particles first .. first + n - 1.
inline void unpack_halo_rows(const HaloField *fields, int nfields, int n, int first,
                             const double *buf)
{
  int m = 0;
  for (int i = first; i < first + n; i++)
    for (int q = 0; q < nfields; q++) {
      const int width = fields[q].width;
      double *row = fields[q].rows + (long long) width * i;
      for (int k = 0; k < width; k++) row[k] = buf[m++];
    }
}

// The reverse message of one field (width doubles per particle, rows): the rows of the ghost
// particles first .. first + n - 1 into buf (as many doubles as the return value), ...
inline int pack_reverse_rows(const double *rows, int width, int n, int first, double *buf)
{
  int m = 0;
  for (int i = first; i < first + n; i++)
    for (int k = 0; k < width; k++) buf[m++] = rows[(long long) width * i + k];
  return m;
}

// ... added to the rows of their owners list[0 .. n-1].
inline void add_reverse_rows(double *rows, int width, int n, const int *list, const double *buf)
{
  int m = 0;
  for (int ii = 0; ii < n; ii++)
    for (int k = 0; k < width; k++) rows[(long long) width * list[ii] + k] += buf[m++];
}

// Where virial contributions go (either may be null).
struct Virial {
  double *global = nullptr;      // 6 doubles: xx yy zz xy xz yz
  double **peratom = nullptr;    // 6 per owned particle
  bool any() const { return global || peratom; }
};

// Virial of the bonds of one particle: the sums of eta (x) t over its bonds (t the bond's
// force density on the particle), tallied as s (sums) with s = -V_i / 2 (half of each bond to
// each end, x_i - x_j = -eta), as pair peri/lps tallies.
struct BondVirial {
  double v0 = 0.0, v1 = 0.0, v2 = 0.0, v3 = 0.0, v4 = 0.0, v5 = 0.0;
  inline void add(double e0, double e1, double e2, double t0, double t1, double t2)
  {
    v0 += e0 * t0;
    v1 += e1 * t1;
    v2 += e2 * t2;
    v3 += e0 * t1;
    v4 += e0 * t2;
    v5 += e1 * t2;
  }
  inline void tally(const Virial &virial, int i, double s) const
  {
    const double v[6] = {s * v0, s * v1, s * v2, s * v3, s * v4, s * v5};
    if (virial.global)
      for (int k = 0; k < 6; k++) virial.global[k] += v[k];
    if (virial.peratom)
      for (int k = 0; k < 6; k++) virial.peratom[i][k] += v[k];
  }
};

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_FIELDS_H
