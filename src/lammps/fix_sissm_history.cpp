/* ----------------------------------------------------------------------
   PERI-SISSM: fix sissm, the per-atom history of the time scheme (solvers/time_scheme.h, its
   columns and global state): it moves with its atom between processes and restart files keep
   it, so that a run split by a restart continues as if it had not been split. precond amg's
   node numbers (fix_sissm_amg.cpp) move with their atoms too (restart files do not keep them). A restart file
   written with another scheme (or none) gives no history: the atoms start again as at the
   first step, and the log says so.
------------------------------------------------------------------------- */

#include "fix_sissm.h"
#include "restart_records.h"

#include "atom.h"
#include "comm.h"
#include "memory.h"

#include <vector>

using namespace LAMMPS_NS;

namespace {
// restart layout version of fix sissm's global record (2: the forcing term after the state)
constexpr double kRestartVersion = 2.0;

// a code for the scheme that wrote a history (its name and its parameters' effect on the
// columns: all generalized-alpha variants share the layout)
double scheme_code(const std::string &name)
{
  if (name == "bdf2") return 2.0;
  if (name == "genalpha") return 3.0;
  return 1.0;
}
}    // namespace

/* ---------------------------------------------------------------------- */

void FixSissm::grow_arrays(int n)
{
  if (ncols > 0) memory->grow(hist, n, ncols, "sissm:hist");
  if (travels) memory->grow(gnode, n, "sissm:gnode");
}

void FixSissm::copy_arrays(int i, int j, int /*delflag*/)
{
  for (int k = 0; k < ncols; k++) hist[j][k] = hist[i][k];
  if (travels) gnode[j] = gnode[i];
}

// a new atom has no history and no node number
void FixSissm::set_arrays(int i)
{
  for (int k = 0; k < ncols; k++) hist[i][k] = 0.0;
  if (travels) gnode[i] = -1.0;
}

int FixSissm::pack_exchange(int i, double *buf)
{
  for (int k = 0; k < ncols; k++) buf[k] = hist[i][k];
  if (travels) buf[ncols] = gnode[i];
  return maxexchange;
}

int FixSissm::unpack_exchange(int nlocal, double *buf)
{
  for (int k = 0; k < ncols; k++) hist[nlocal][k] = buf[k];
  if (travels) gnode[nlocal] = buf[ncols];
  return maxexchange;
}

/* ----------------------------------------------------------------------
   global record: version, scheme code, state size, state, the Newton forcing term carried to
   the next solve (version 1 has no forcing term: the run then starts from its default)
------------------------------------------------------------------------- */

void FixSissm::write_restart(FILE *fp)
{
  std::vector<double> list = {kRestartVersion, scheme_code(scheme->name()),
                              (double) scheme->state_size()};
  list.resize(3 + scheme->state_size());
  scheme->get_state(list.data() + 3);
  list.push_back(forcing.first);
  write_global_record(fp, comm->me, list.data(), (int) list.size());
}

void FixSissm::restart(char *buf)
{
  auto list = (double *) buf;
  if (list[0] == kRestartVersion) forcing.first = list[3 + (int) list[2]];
  hist_from_restart = (list[0] == kRestartVersion || list[0] == 1.0) &&
      list[1] == scheme_code(scheme->name()) && (int) list[2] == scheme->state_size();
  if (hist_from_restart) {
    scheme->set_state(list + 3);
  } else if (comm->me == 0 && ncols > 0) {
    utils::logmesg(lmp,
                   "Fix sissm {}: the restart file holds no history of scheme {} (written with "
                   "another scheme): the atoms start it anew, as at a first step\n",
                   id, scheme->name());
  }
}

/* ----------------------------------------------------------------------
   per-atom record: count, scheme code, the history columns
------------------------------------------------------------------------- */

int FixSissm::pack_restart(int i, double *buf)
{
  buf[0] = ncols + 2;
  buf[1] = scheme_code(scheme->name());
  for (int k = 0; k < ncols; k++) buf[2 + k] = hist[i][k];
  return ncols + 2;
}

void FixSissm::unpack_restart(int nlocal, int nth)
{
  const double *rec = fix_record(atom->extra, nlocal, nth);
  const bool same = hist_from_restart && static_cast<int>(rec[0]) == ncols + 2 &&
      rec[1] == scheme_code(scheme->name());
  for (int k = 0; k < ncols; k++) hist[nlocal][k] = same ? rec[2 + k] : 0.0;
}

int FixSissm::size_restart(int /*i*/)
{
  return ncols + 2;
}

int FixSissm::maxsize_restart()
{
  return ncols + 2;
}
