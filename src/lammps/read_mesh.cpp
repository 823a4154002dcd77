/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   read_mesh FILE type T thickness t density rho [offset dx dy dz] [scale s]
             [rotate theta Rx Ry Rz] [group G]

   Rank 0 reads and checks the OBJ file (core: mesh/obj_file.h, mesh/triangle_mesh.h) and
   broadcasts the mesh; every rank places all vertices (mesh/mesh_geometry.h) and creates the
   atoms of the vertices in its sub-domain, as create_atoms does: vertex k of the file becomes
   atom maxtag + 1 + k of type T, with vfrac = t x (one third of the areas of its triangles),
   rmass = rho (the density, as atom_style peri stores it), x0 = x, v = 0, image flags 0, in the
   groups all and G. A vertex outside a fixed boundary of the box is an error (create_atoms
   would drop it); across a periodic boundary it is wrapped into the box; beyond a
   shrink-wrapped one the box grows. The triangles go to fix nosb/mesh (created by the first
   read_mesh as NOSB_MESH), each mesh with the next mesh id.
------------------------------------------------------------------------- */

#include "read_mesh.h"

#include "fix_nosb_mesh.h"

#include "mesh/mesh_geometry.h"
#include "mesh/obj_file.h"
#include "mesh/read_mesh_options.h"
#include "mesh/triangle_mesh.h"

#include "atom.h"
#include "atom_vec.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "group.h"
#include "irregular.h"
#include "modify.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

using namespace LAMMPS_NS;

namespace {

// a finite number for read_mesh (utils::numeric), naming the keyword on error
double number(const char *what, const char *str, LAMMPS *lmp)
{
  if (!utils::is_double(str))
    lmp->error->all(FLERR, "Illegal read_mesh command: {} must be a finite number, got '{}'", what,
                    str);
  const double value = utils::numeric(FLERR, str, false, lmp);
  if (!std::isfinite(value))
    lmp->error->all(FLERR, "Illegal read_mesh command: {} must be a finite number, got '{}'", what,
                    str);
  return value;
}

// an atom type: a number or a type label (labelmap atom), from 1 to ntypes
int atom_type(const char *str, LAMMPS *lmp)
{
  char *expanded = utils::expand_type(FLERR, str, Atom::ATOM, lmp);
  const std::string type = expanded ? expanded : str;
  delete[] expanded;
  const int ntypes = lmp->atom->ntypes;
  const int value = utils::is_integer(type) ? utils::inumeric(FLERR, type, false, lmp) : 0;
  if (value < 1 || value > ntypes)
    lmp->error->all(FLERR,
                    "Illegal read_mesh command: type must be an atom type from 1 to {} "
                    "or a type label, got '{}'",
                    ntypes, str);
  return value;
}

// the arguments (core mesh/read_mesh_options.h), numbers and types parsed as LAMMPS does
PeriSISSM::ReadMeshOptions parse(int narg, char **arg, LAMMPS *lmp)
{
  auto num = [lmp](const char *what, const std::string &text) {
    return number(what, text.c_str(), lmp);
  };
  auto type = [lmp](const std::string &text) {
    return atom_type(text.c_str(), lmp);
  };
  try {
    return PeriSISSM::parse_read_mesh({arg, arg + narg}, num, type);
  } catch (std::invalid_argument &e) {
    lmp->error->all(FLERR, e.what());
  }
}

// rank 0 reads and checks the file, all ranks get the mesh (or the same error)
PeriSISSM::TriangleMesh read_mesh_file(const std::string &file, LAMMPS *lmp)
{
  PeriSISSM::TriangleMesh mesh;
  std::string message;
  if (lmp->comm->me == 0) {
    FILE *fp = fopen(file.c_str(), "rb");
    if (!fp) {
      message = "Read_mesh: cannot open mesh file " + file + ": " + utils::getsyserror();
    } else {
      std::string text;
      char chunk[65536];
      size_t n;
      while ((n = fread(chunk, 1, sizeof(chunk), fp)) > 0) text.append(chunk, n);
      fclose(fp);
      try {
        mesh = PeriSISSM::parse_obj(text, file);
        PeriSISSM::check_mesh(mesh, file, FixNosbMesh::MAXTRI);
      } catch (std::exception &e) {
        message = std::string("Read_mesh: ") + e.what();
      }
    }
  }

  int len = (int) message.size();
  MPI_Bcast(&len, 1, MPI_INT, 0, lmp->world);
  if (len) {
    message.resize(len);
    MPI_Bcast(&message[0], len, MPI_CHAR, 0, lmp->world);
    lmp->error->all(FLERR, message);
  }

  int sizes[2] = {(int) mesh.vertices.size(), (int) mesh.triangles.size()};
  MPI_Bcast(sizes, 2, MPI_INT, 0, lmp->world);
  mesh.vertices.resize(sizes[0]);
  mesh.vertex_line.resize(sizes[0]);
  mesh.triangles.resize(sizes[1]);
  mesh.triangle_line.resize(sizes[1]);
  MPI_Bcast(mesh.vertices.data(), 3 * sizes[0], MPI_DOUBLE, 0, lmp->world);
  MPI_Bcast(mesh.vertex_line.data(), sizes[0], MPI_INT, 0, lmp->world);
  MPI_Bcast(mesh.triangles.data(), 3 * sizes[1], MPI_INT, 0, lmp->world);
  MPI_Bcast(mesh.triangle_line.data(), sizes[1], MPI_INT, 0, lmp->world);
  return mesh;
}

}    // namespace

/* ---------------------------------------------------------------------- */

void ReadMesh::command(int narg, char **arg)
{
  if (!domain->box_exist)
    error->all(FLERR,
               "Read_mesh command before the simulation box is defined: create the box "
               "first (region and create_box)");
  if (!atom->peri_flag || !atom->vfrac_flag || !atom->rmass_flag || !atom->x0)
    error->all(FLERR,
               "Read_mesh requires atom_style peri (per-atom volume, density and "
               "reference position): write atom_style peri before the box is created");
  if (atom->map_style == Atom::MAP_NONE)
    error->all(FLERR,
               "Read_mesh requires an atom map (triangles are stored by atom ID): write "
               "atom_modify map array (or hash) before the box is created");
  if (domain->dimension != 3) error->all(FLERR, "Read_mesh requires a 3d simulation");

  const PeriSISSM::ReadMeshOptions opt = parse(narg, arg, lmp);

  // new atoms would get the per-atom restart data of fixes defined later wrong (as for
  // create_atoms)

  if (modify->nfix_restart_peratom) {
    // (the advice names the mesh fix the file holds)
    const FixNosbMesh *restored = FixNosbMesh::restore(lmp);
    error->all(FLERR,
               "Read_mesh after read_restart: the restart file holds per-atom data of fixes, "
               "which they take from it when defined or at the first run; put 'run 0' before "
               "read_mesh (as for create_atoms){}",
               restored ? fmt::format(", and re-specify 'fix {} all nosb/mesh' right after "
                                      "read_restart so that the meshes of the restart file are "
                                      "kept",
                                      restored->id)
                        : "");
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

  // place the vertices (all ranks the same), areas

  std::vector<std::array<double, 3>> x(nvertex);
  for (int k = 0; k < nvertex; k++)
    PeriSISSM::place(opt.place, mesh.vertices[k].data(), x[k].data());
  const std::vector<double> area = PeriSISSM::vertex_areas(x, mesh.triangles);
  double total_area = 0.0;
  for (const auto &t : mesh.triangles)
    total_area += PeriSISSM::triangle_area(x[t[0]].data(), x[t[1]].data(), x[t[2]].data());

  // where each vertex goes: wrapped across periodic boundaries, an error outside a fixed one;
  // beyond a shrink-wrapped boundary it belongs to the sub-domain at that face until the box
  // has grown

  const int triclinic = domain->triclinic;
  const double *sublo = triclinic ? domain->sublo_lamda : domain->sublo;
  const double *subhi = triclinic ? domain->subhi_lamda : domain->subhi;
  std::vector<int> mine;
  int grows = 0;
  for (int k = 0; k < nvertex; k++) {
    domain->remap(x[k].data());
    double c[3];
    if (triclinic)
      domain->x2lamda(x[k].data(), c);
    else
      for (int d = 0; d < 3; d++) c[d] = x[k][d];
    for (int d = 0; d < 3; d++) {
      const double lo = triclinic ? 0.0 : domain->boxlo[d];
      const double hi = triclinic ? 1.0 : domain->boxhi[d];
      const bool fixed[2] = {domain->boundary[d][0] == 1, domain->boundary[d][1] == 1};
      int side = 0;
      const auto fit = PeriSISSM::fit_to_box(c[d], lo, hi, domain->periodicity[d], fixed, side);
      if (fit == PeriSISSM::BoxFit::kOutside)
        error->all(FLERR,
                   "Read_mesh: vertex {} of {} (line {}) is placed at ({:.8g}, {:.8g}, {:.8g}), "
                   "outside the box in {}{} (boundary f: the box is {} to {}{}): enlarge the "
                   "box, or move the mesh with offset, scale or rotate",
                   k + 1, opt.file, mesh.vertex_line[k], x[k][0], x[k][1], x[k][2], "xyz"[d],
                   triclinic ? " (fractional coordinate of the triclinic box)" : "", lo, hi,
                   side ? ", its upper face excluded" : "");
      if (fit == PeriSISSM::BoxFit::kGrows) grows = 1;
    }
    if (c[0] >= sublo[0] && c[0] < subhi[0] && c[1] >= sublo[1] && c[1] < subhi[1] &&
        c[2] >= sublo[2] && c[2] < subhi[2])
      mine.push_back(k);
  }

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

  // create the atoms (as create_atoms: ghosts and the map are cleared first, since new atoms
  // overwrite ghost rows)

  if (atom->map_style != Atom::MAP_NONE) atom->map_clear();
  atom->nghost = 0;
  atom->avec->clear_bonus();

  const bigint natoms_previous = atom->natoms;
  const int nlocal_previous = atom->nlocal;
  for (int k : mine) {
    atom->avec->create_atom(opt.type, x[k].data());
    const int i = atom->nlocal - 1;
    atom->tag[i] = maxtag_all + 1 + k;
    atom->mask[i] |= groupbit;
    atom->vfrac[i] = opt.thickness * area[k];
    atom->rmass[i] = opt.density;
    for (int d = 0; d < 3; d++) atom->x0[i][d] = atom->x[i][d];
  }
  atom->data_fix_compute_variable(nlocal_previous, atom->nlocal);

  const auto at = PeriSISSM::vertex_triangles(nvertex, mesh.triangles);
  tagint others[FixNosbMesh::MAXTRI][2];
  for (int n = 0; n < (int) mine.size(); n++) {
    const int k = mine[n];
    int ntri = 0;
    for (const auto &corner : at[k]) {
      const auto &t = mesh.triangles[corner[0]];
      others[ntri][0] = maxtag_all + 1 + t[(corner[1] + 1) % 3];
      others[ntri][1] = maxtag_all + 1 + t[(corner[1] + 2) % 3];
      ntri++;
    }
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
  if (atom->map_style != Atom::MAP_NONE) {
    atom->map_init();
    atom->map_set();
  }

  // a shrink-wrapped box grows around vertices beyond it, and the atoms move to their
  // sub-domains (as read_data does)

  if (grows) {
    if (triclinic) domain->x2lamda(atom->nlocal);
    domain->reset_box();
    Irregular irregular(lmp);
    irregular.migrate_atoms(1);
    if (triclinic) domain->lamda2x(atom->nlocal);
    if (atom->map_style != Atom::MAP_NONE) {
      atom->map_init();
      atom->map_set();
    }
  }

  if (comm->me == 0)
    utils::logmesg(lmp,
                   "Read mesh {}: {} vertices, {} triangles, area {:.8g}, thickness {:.8g}, mesh "
                   "id {}\n  atom IDs {} to {}, type {}{}\n",
                   opt.file, nvertex, ntriangle, total_area, opt.thickness, meshid, maxtag_all + 1,
                   maxtag_all + nvertex, opt.type, opt.group.empty() ? "" : ", group " + opt.group);
}
