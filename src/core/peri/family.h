// Bond families: the storage view, reference bonds across periodic images, bond weights and the
// shape tensor of one family (doc/theory.rst, "Bond families").
//
// The per-particle arrays are owned by the caller (in LAMMPS, fix nosb/family grows, migrates
// and restarts them); Families is a view of them. Row i holds the bond slots of local particle
// i; a broken bond keeps its slot with partner index -1.

#ifndef PERISISSM_PERI_FAMILY_H
#define PERISISSM_PERI_FAMILY_H

#include <algorithm>
#include <utility>
#include <vector>

namespace PeriSISSM {

// The box the families were built in: periodic images of reference bonds. A reference bond is
// x0_j - x0_i with the minimum image convention in this box (so that a later change of the box
// does not change the reference bonds; the x0 of a periodic ghost image is not shifted).
struct ReferenceBox {
  int periodic[3] = {0, 0, 0};
  double box[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};    // xprd yprd zprd yz xz xy
  bool any() const { return periodic[0] || periodic[1] || periodic[2]; }

  // distances between the box's opposite faces: width[0] between the two faces normal to x
  // (the yz faces), width[1], width[2] likewise
  void face_distances(double width[3]) const;

  // minimum image of a difference of reference positions (restricted triclinic box)
  inline void image(double &dx, double &dy, double &dz) const
  {
    if (periodic[2]) {
      if (dz > 0.5 * box[2]) {
        dz -= box[2];
        dy -= box[3];
        dx -= box[4];
      } else if (dz < -0.5 * box[2]) {
        dz += box[2];
        dy += box[3];
        dx += box[4];
      }
    }
    if (periodic[1]) {
      if (dy > 0.5 * box[1]) {
        dy -= box[1];
        dx -= box[5];
      } else if (dy < -0.5 * box[1]) {
        dy += box[1];
        dx += box[5];
      }
    }
    if (periodic[0]) {
      if (dx > 0.5 * box[0])
        dx -= box[0];
      else if (dx < -0.5 * box[0])
        dx += box[0];
    }
  }
};

// The families of the local particles (arrays of at least nlocal rows).
struct Families {
  int *npartner = nullptr;      // bond slots of each particle
  int **jlocal = nullptr;       // local index of each partner (its closest image), -1 = broken
  double **omega = nullptr;     // weight of each bond, omega = w beta V_j
  double **kinv = nullptr;      // K^-1 (row-major 3x3) of each particle; zeros when singular
  int *kregular = nullptr;      // 1 if K is regular (F defined), 0 otherwise
  double *lamref = nullptr;     // largest eigenvalue of the particle's initial K
  double **normal = nullptr;    // reference unit normal of each membrane particle (rows of the
                                //   others unused); null when no particle is a membrane
};

// Whether an unbroken bond joins an owned particle of a group (mask & groupbit, masks of owned
// and ghost rows) with a particle outside it.
bool bonds_leave_group(const Families &fam, int nlocal, const int *mask, int groupbit);

// Smallest accepted ratio lambda_min(K) / lambda_ref for a shape tensor K, where lambda_ref is
// the larger of lambda_max(K) and a reference value (the largest eigenvalue of the particle's
// initial, intact K). Below it K counts as singular: the family spans fewer than three
// directions (no partners, one or two partners, all partners coplanar or collinear), or
// fracture has left it so flat or so small that F would amplify noise in its weakest
// direction by more than 1/kMinShapeConditioning, and the particle's correspondence stiffness
// (which grows like 1/lambda_min(K)) would exceed that of its intact state by as much, which
// breaks the explicit time step chosen for the intact body. Intact bodies at least two
// particles thick stay well above it (on a simple cubic lattice with horizon 3a: interior 1,
// face 0.77, edge 0.36, corner 0.28, corner of a two-layer plate 0.11).
constexpr double kMinShapeConditioning = 0.05;

// Inverse of a shape tensor, with the singularity test above.
//
// Inputs:  K (row-major 3x3, symmetric positive semi-definite, units volume * length^2);
//          lambda_ref >= 0 reference eigenvalue (same units; 0 = none).
// Outputs: Kinv (row-major 3x3, symmetric) = K^-1 when K is regular, else all zeros;
//          lambda_max (if not null) the largest eigenvalue of K.
//          Returns true when K is regular: everything finite, lambda_max > 0 and
//          lambda_min >= kMinShapeConditioning * max(lambda_max, lambda_ref).
bool invert_shape_tensor(const double K[9], double lambda_ref, double Kinv[9],
                         double *lambda_max = nullptr);

// Partial-volume factor beta of a bond of reference length r in a horizon delta, for particles
// of size h (edge of a cube of the particle's volume). The partner's cube is taken as cut by the
// sphere of radius delta along the bond direction only (the rule of LAMMPS's PERI styles):
//   beta = 1                         for r <= delta - h/2,
//   beta = (delta + h/2 - r) / h     for delta - h/2 < r <= delta + h/2,
//   beta = 0                         beyond.
// Inputs:  r >= 0, delta > 0, h > 0 (all length). Outputs: beta in [0, 1].
double partial_volume_factor(double r, double delta, double h);

// Weight of a bond: influence function w = 1 times the partial-volume factor (h the mean of the
// two particles' sizes, so the weight is symmetric up to the factor V_j) times V_j.
// Inputs: r reference length, delta horizon, vi, vj volumes; ti, tj thicknesses of membrane
//         particles (0 for volume particles). Outputs: omega (volume).
// A volume particle's size is V^(1/3); a membrane particle's, its spacing in the plane,
// (V / t)^(1/2) (V = area times thickness t).
double bond_weight(double r, double delta, double vi, double vj, double ti = 0.0, double tj = 0.0);

// Reference bond xi = x0_j - x0_i of particles i and j (x0 three doubles per particle).
inline void reference_bond(const double *x0, const ReferenceBox &box, int i, int j, double xi[3])
{
  xi[0] = x0[3 * j] - x0[3 * i];
  xi[1] = x0[3 * j + 1] - x0[3 * i + 1];
  xi[2] = x0[3 * j + 2] - x0[3 * i + 2];
  if (box.any()) box.image(xi[0], xi[1], xi[2]);
}

// K_i = sum over the unbroken bonds of omega xi (x) xi, its inverse, the regular flag, and the
// largest eigenvalue seen so far (lamref, the reference of the singularity test). For a
// membrane particle (n0 given) the bonds are projected on its tangent plane, xi - (xi . n0) n0,
// and kinv is the in-plane pseudo-inverse (membrane/membrane.h).
// Inputs: families (npartner, jlocal, omega of row i), x0, box; n0 the particle's reference
//         unit normal if it is a membrane, else null. Outputs: kinv[i], kregular[i], lamref[i].
void update_shape(const Families &fam, const double *x0, const ReferenceBox &box, int i,
                  const double *n0 = nullptr);

// A family in the order in which every per-particle sum runs: its partners sorted by ID (then
// by local index), so that the sums agree whatever the number of MPI ranks. Id is the integer
// type of particle IDs.
// Inputs/Outputs: partners as (ID, local index of the image found). Returns the smallest ID that
// appears twice (two images of one particle within the horizon: a periodic box shorter than
// two horizons), 0 if none.
template <class Id> Id order_family(std::vector<std::pair<Id, int>> &partners)
{
  std::sort(partners.begin(), partners.end());
  for (size_t k = 1; k < partners.size(); k++)
    if (partners[k].first == partners[k - 1].first) return partners[k].first;
  return 0;
}

// Damage of a particle: 1 - (sum of omega over its unbroken bonds) / vinit, 0 when vinit <= 0.
// Inputs: n bond slots, partner IDs (0 = broken), omega per slot, vinit (sum of omega over the
// initial family). Outputs: damage in [0, 1].
template <class Id> double damage(int n, const Id *partner, const double *omega, double vinit)
{
  if (vinit <= 0.0) return 0.0;
  double vnow = 0.0;
  for (int b = 0; b < n; b++)
    if (partner[b]) vnow += omega[b];
  return 1.0 - vnow / vinit;
}

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_FAMILY_H
