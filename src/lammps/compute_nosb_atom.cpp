/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   compute ID group nosb/atom: per-atom damage, W, J, von Mises and Cauchy stress and stable
   time step estimate (columns: core peri/particle.h nosb_atom_row(); doc/compute_nosb_atom.rst)
   from the state of pair peri/nosb at its last force evaluation and the current bond families.
   Atoms outside the group get zeros.
------------------------------------------------------------------------- */

#include "compute_nosb_atom.h"

#include "fix_nosb_family.h"
#include "pair_peri_nosb.h"

#include "peri/model.h"
#include "peri/particle.h"

#include "atom.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "update.h"

using namespace LAMMPS_NS;
using namespace PeriSISSM::NosbAtom;    // the columns

/* ---------------------------------------------------------------------- */

ComputeNosbAtom::ComputeNosbAtom(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), nmax(0), values(nullptr), dtstable(nullptr), pair(nullptr)
{
  if (narg != 3)
    error->all(FLERR, "Illegal compute nosb/atom command: no arguments expected after the style");
  peratom_flag = 1;
  size_peratom_cols = NCOLUMNS;
}

/* ---------------------------------------------------------------------- */

ComputeNosbAtom::~ComputeNosbAtom()
{
  memory->destroy(values);
  memory->destroy(dtstable);
}

/* ---------------------------------------------------------------------- */

void ComputeNosbAtom::init()
{
  pair = dynamic_cast<PairPeriNosb *>(force->pair_match("peri/nosb", 1));
  if (!pair) error->all(FLERR, "Compute nosb/atom requires pair_style peri/nosb");
}

/* ---------------------------------------------------------------------- */

void ComputeNosbAtom::compute_peratom()
{
  invoked_peratom = update->ntimestep;

  if (atom->nmax > nmax) {
    nmax = atom->nmax;
    memory->grow(values, nmax, NCOLUMNS, "nosb/atom:values");
    memory->grow(dtstable, nmax, "nosb/atom:dtstable");
    array_atom = values;
  }

  const int nlocal = atom->nlocal;
  int *mask = atom->mask;
  int *type = atom->type;
  FixNosbFamily *family = pair->family;
  const bool ready = family && family->built;
  // after read_restart, or after atoms were added or removed, the pair has no state for the
  // current atoms until it has evaluated its forces
  if (ready && !pair->state_current())
    error->all(FLERR,
               "Compute nosb/atom: pair peri/nosb has not evaluated the current atoms yet (the "
               "compute reports the state of the last force evaluation; use 'run 0' first)");
  if (ready) pair->stable_time_steps(dtstable);

  for (int i = 0; i < nlocal; i++) {
    double *v = values[i];
    for (int k = 0; k < NCOLUMNS; k++) v[k] = 0.0;
    if (!(mask[i] & groupbit)) continue;
    v[JACOBIAN] = 1.0;
    if (ready)
      PeriSISSM::nosb_atom_row(pair->model().material(type[i]), family->kregular[i] != 0,
                               pair->deformation_gradient(i), pair->energy_density(i),
                               family->damage(i), dtstable[i], v);
  }
}

/* ---------------------------------------------------------------------- */

double ComputeNosbAtom::memory_usage()
{
  return (double) nmax * (NCOLUMNS + 1) * sizeof(double);
}
