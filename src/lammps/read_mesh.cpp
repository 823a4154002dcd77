/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   read_mesh FILE type T thickness t density rho [offset dx dy dz] [scale s]
             [rotate theta Rx Ry Rz] [group G]

   Rank 0 reads and checks the OBJ file and broadcasts the mesh; every rank places all vertices
   and creates the atoms of the vertices in its sub-domain, as create_atoms does (what each atom
   gets: doc/read_mesh.rst; the file, the placement and the checks: core mesh/). The triangles
   go to fix nosb/mesh (created by the first read_mesh as NOSB_MESH), each mesh with the next
   mesh id.
------------------------------------------------------------------------- */

#include "read_mesh.h"

#include "fix_nosb_mesh.h"

#include "mesh/mesh_geometry.h"
#include "mesh/mesh_requirements.h"
#include "mesh/obj_file.h"
#include "mesh/place_mesh.h"
#include "mesh/read_mesh_options.h"

#include "atom.h"
#include "atom_vec.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "group.h"
#include "irregular.h"
#include "modify.h"

#include <array>
#include <cmath>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

using namespace LAMMPS_NS;

namespace {

// the arguments (core mesh/read_mesh_options.h), numbers and types parsed as LAMMPS does
PeriSISSM::ReadMeshOptions parse(int narg, char **arg, LAMMPS *lmp)
{
  // a finite number (utils::numeric), naming the keyword on error
  auto number = [lmp](const char *what, const std::string &str) {
    const double value = utils::is_double(str) ? utils::numeric(FLERR, str, false, lmp)
                                               : std::nan("");
    if (!std::isfinite(value))
      lmp->error->all(FLERR, "Illegal read_mesh command: {} must be a finite number, got '{}'",
                      what, str);
    return value;
  };
  // an atom type: a number or a type label (labelmap atom), from 1 to ntypes
  auto type = [lmp](const std::string &str) {
    char *expanded = utils::expand_type(FLERR, str, Atom::ATOM, lmp);
    const std::string word = expanded ? expanded : str;
    delete[] expanded;
    const int ntypes = lmp->atom->ntypes;
    const int value = utils::is_integer(word) ? utils::inumeric(FLERR, word, false, lmp) : 0;
    if (value < 1 || value > ntypes)
      lmp->error->all(FLERR,
                      "Illegal read_mesh command: type must be an atom type from 1 to {} "
                      "or a type label, got '{}'",
                      ntypes, str);
    return value;
  };
  try {
    return PeriSISSM::parse_read_mesh({arg, arg + narg}, number, type);
  } catch (std::invalid_argument &e) {
    lmp->error->all(FLERR, e.what());
  }
}

// rank 0 reads and checks the file, all ranks get the mesh (or the same error)
PeriSISSM::TriangleMesh read_mesh_file(const std::string &file, LAMMPS *lmp)
{
  std::vector<double> buf;
  std::string message;
  if (lmp->comm->me == 0) {
    try {
      const PeriSISSM::TriangleMesh mesh = PeriSISSM::read_obj_file(file);
      PeriSISSM::check_mesh(mesh, file, FixNosbMesh::MAXTRI);
      buf = PeriSISSM::pack_mesh(mesh);
    } catch (std::exception &e) {
      message = std::string("Read_mesh: ") + e.what();
    }
  }

  int len = (int) message.size();
  MPI_Bcast(&len, 1, MPI_INT, 0, lmp->world);
  if (len) {
    message.resize(len);
    MPI_Bcast(&message[0], len, MPI_CHAR, 0, lmp->world);
    lmp->error->all(FLERR, message);
  }

  int n = (int) buf.size();
  MPI_Bcast(&n, 1, MPI_INT, 0, lmp->world);
  buf.resize(n);
  MPI_Bcast(buf.data(), n, MPI_DOUBLE, 0, lmp->world);
  return PeriSISSM::unpack_mesh(buf);
}

}    // namespace

/* ---------------------------------------------------------------------- */

void ReadMesh::command(int narg, char **arg)
{
  const PeriSISSM::ReadMeshDeck deck = {
      domain->box_exist != 0, atom->peri_flag && atom->vfrac_flag && atom->rmass_flag && atom->x0,
      atom->map_style != Atom::MAP_NONE, domain->dimension};
  const std::string unmet = PeriSISSM::read_mesh_unmet(deck);
  if (!unmet.empty()) error->all(FLERR, unmet);

  const PeriSISSM::ReadMeshOptions opt = parse(narg, arg, lmp);

  // new atoms would get the per-atom restart data of fixes defined later wrong (as for
  // create_atoms)

  if (modify->nfix_restart_peratom) {
    const FixNosbMesh *restored = FixNosbMesh::restore(lmp);
    error->all(FLERR, PeriSISSM::read_mesh_after_restart(restored ? restored->id : ""));
  }

  int igroup = 0;
  if (!opt.group.empty()) {
    igroup = group->find_or_create(opt.group.c_str());
    if (group->dynamic[igroup])
      error->all(FLERR, "Read_mesh: group {} is dynamic; give a static group", opt.group);
  }
  const int groupbit = group->bitmask[igroup];

  const PeriSISSM::TriangleMesh mesh = read_mesh_file(opt.file, lmp);
  const int nvertex = (int) mesh.vertices.size();
  const int ntriangle = (int) mesh.triangles.size();

  // place the vertices (all ranks the same); where each vertex goes: wrapped across periodic
  // boundaries, an error outside a fixed one; beyond a shrink-wrapped boundary it belongs to
  // the sub-domain at that face until the box has grown

  const PeriSISSM::PlacedMesh placed = PeriSISSM::place_mesh(mesh, opt.place);
  std::vector<std::array<double, 3>> x = placed.x, c(nvertex);
  const int triclinic = domain->triclinic;
  PeriSISSM::MeshBox box;
  for (int d = 0; d < 3; d++) {
    box.lo[d] = triclinic ? 0.0 : domain->boxlo[d];
    box.hi[d] = triclinic ? 1.0 : domain->boxhi[d];
    box.sublo[d] = triclinic ? domain->sublo_lamda[d] : domain->sublo[d];
    box.subhi[d] = triclinic ? domain->subhi_lamda[d] : domain->subhi[d];
    box.periodic[d] = domain->periodicity[d];
    for (int side = 0; side < 2; side++) box.fixed[d][side] = domain->boundary[d][side] == 1;
  }
  for (int k = 0; k < nvertex; k++) {
    domain->remap(x[k].data());
    c[k] = x[k];
    if (triclinic) domain->x2lamda(x[k].data(), c[k].data());
  }
  const PeriSISSM::SubdomainVertices own = PeriSISSM::subdomain_vertices(box, c);
  if (own.outside >= 0) {
    const int k = own.outside, d = own.dim;
    error->all(FLERR,
               "Read_mesh: vertex {} of {} (line {}) is placed at ({:.8g}, {:.8g}, {:.8g}), "
               "outside the box in {}{} (boundary f: the box is {} to {}{}): enlarge the "
               "box, or move the mesh with offset, scale or rotate",
               k + 1, opt.file, mesh.vertex_line[k], x[k][0], x[k][1], x[k][2], "xyz"[d],
               triclinic ? " (fractional coordinate of the triclinic box)" : "", box.lo[d],
               box.hi[d], own.side ? ", its upper face excluded" : "");
  }
  const std::vector<int> &mine = own.mine;

  // atom IDs after the largest one

  tagint maxtag = 0, maxtag_all;
  for (int i = 0; i < atom->nlocal; i++) maxtag = MAX(maxtag, atom->tag[i]);
  MPI_Allreduce(&maxtag, &maxtag_all, 1, MPI_LMP_TAGINT, MPI_MAX, world);
  if ((double) maxtag_all + nvertex >= (double) MAXTAGINT)
    error->all(FLERR, "Read_mesh: too many atom IDs ({} + {} vertices)", maxtag_all, nvertex);

  // the first read_mesh of a deck defines the mesh fix
  FixNosbMesh *fix = FixNosbMesh::find(lmp);
  if (!fix)
    fix = dynamic_cast<FixNosbMesh *>(
        modify->add_fix(std::string(FixNosbMesh::DEFAULT_ID) + " all nosb/mesh"));
  const int meshid = fix->add_mesh(ntriangle);

  // create the atoms (as create_atoms: ghosts and the map (which read_mesh requires) are
  // cleared first, since new atoms overwrite ghost rows)

  atom->map_clear();
  atom->nghost = 0;
  atom->avec->clear_bonus();

  const bigint natoms_previous = atom->natoms;
  const int nlocal_previous = atom->nlocal;
  for (int k : mine) {
    atom->avec->create_atom(opt.type, x[k].data());
    const int i = atom->nlocal - 1;
    atom->tag[i] = maxtag_all + 1 + k;
    atom->mask[i] |= groupbit;
    atom->vfrac[i] = opt.thickness * placed.area[k];
    atom->rmass[i] = opt.density;
    for (int d = 0; d < 3; d++) atom->x0[i][d] = atom->x[i][d];
  }
  atom->data_fix_compute_variable(nlocal_previous, atom->nlocal);

  const auto at = PeriSISSM::vertex_triangles(nvertex, mesh.triangles);
  tagint others[FixNosbMesh::MAXTRI][2];
  for (int n = 0; n < (int) mine.size(); n++) {
    const int ntri = PeriSISSM::corner_ids(at[mine[n]], mesh.triangles, maxtag_all + 1, others);
    fix->set_vertex(nlocal_previous + n, meshid, opt.thickness, ntri, others);
  }

  // bookkeeping as create_atoms

  bigint nblocal = atom->nlocal;
  MPI_Allreduce(&nblocal, &atom->natoms, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (atom->natoms != natoms_previous + nvertex)
    error->all(FLERR,
               "Read_mesh: {} of the {} vertices were created (a vertex on no or on two "
               "sub-domains)",
               atom->natoms - natoms_previous, nvertex);
  atom->tag_check();
  atom->map_init();
  atom->map_set();

  // a shrink-wrapped box grows around vertices beyond it, and the atoms move to their
  // sub-domains (as read_data does)

  if (own.grows) {
    if (triclinic) domain->x2lamda(atom->nlocal);
    domain->reset_box();
    Irregular irregular(lmp);
    irregular.migrate_atoms(1);
    if (triclinic) domain->lamda2x(atom->nlocal);
    atom->map_init();
    atom->map_set();
  }

  if (comm->me == 0)
    utils::logmesg(lmp,
                   "Read mesh {}: {} vertices, {} triangles, area {:.8g}, thickness {:.8g}, mesh "
                   "id {}\n  atom IDs {} to {}, type {}{}\n",
                   opt.file, nvertex, ntriangle, placed.total_area, opt.thickness, meshid,
                   maxtag_all + 1, maxtag_all + nvertex, opt.type,
                   opt.group.empty() ? "" : ", group " + opt.group);
}
