/* ----------------------------------------------------------------------
   PERI-SISSM plugin: registers the package's styles with LAMMPS
   (plugin load perisissmplugin.so, or automatically from LAMMPS_PLUGIN_PATH).
------------------------------------------------------------------------- */

#include "lammpsplugin.h"

#include "version.h"

#include "compute_nosb_atom.h"
#include "fix_nosb_contact.h"
#include "fix_nosb_family.h"
#include "fix_nosb_mesh.h"
#include "fix_sissm.h"
#include "pair_peri_nosb.h"
#include "read_mesh.h"

using namespace LAMMPS_NS;

static Pair *peri_nosb_creator(LAMMPS *lmp)
{
  return new PairPeriNosb(lmp);
}

static Fix *nosb_family_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new FixNosbFamily(lmp, argc, argv);
}

static Fix *sissm_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new FixSissm(lmp, argc, argv);
}

static Fix *nosb_mesh_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new FixNosbMesh(lmp, argc, argv);
}

static Fix *nosb_contact_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new FixNosbContact(lmp, argc, argv);
}

static Command *read_mesh_creator(LAMMPS *lmp)
{
  return new ReadMesh(lmp);
}

static Compute *nosb_atom_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new ComputeNosbAtom(lmp, argc, argv);
}

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  lammpsplugin_t plugin;
  auto register_plugin = (lammpsplugin_regfunc) regfunc;

  plugin.version = LAMMPS_VERSION;
  plugin.author = "PERI-SISSM developers";
  plugin.handle = handle;

  plugin.style = "pair";
  plugin.name = "peri/nosb";
  plugin.info = "PERI-SISSM correspondence peridynamics (SVD-split hyperelastic stresses)";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &peri_nosb_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.style = "fix";
  plugin.name = "nosb/family";
  plugin.info = "PERI-SISSM bond families of pair_style peri/nosb";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &nosb_family_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.style = "fix";
  plugin.name = "sissm";
  plugin.info = "PERI-SISSM semi-implicit successive substitution integrator";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &sissm_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.style = "fix";
  plugin.name = "nosb/mesh";
  plugin.info = "PERI-SISSM triangles of the meshes read by read_mesh";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &nosb_mesh_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.style = "fix";
  plugin.name = "nosb/contact";
  plugin.info = "PERI-SISSM barrier contact between mesh primitives";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &nosb_contact_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.style = "command";
  plugin.name = "read_mesh";
  plugin.info = "PERI-SISSM one peri particle per vertex of a triangle mesh (Wavefront OBJ)";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &read_mesh_creator;
  (*register_plugin)(&plugin, lmp);

  plugin.style = "compute";
  plugin.name = "nosb/atom";
  plugin.info = "PERI-SISSM per-atom damage, energy density, J and Cauchy stress";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &nosb_atom_creator;
  (*register_plugin)(&plugin, lmp);
}
