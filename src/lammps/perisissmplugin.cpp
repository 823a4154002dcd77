/* ----------------------------------------------------------------------
   PERI-SISSM plugin: registers the package's styles with LAMMPS
   (plugin load perisissmplugin.so, or automatically from LAMMPS_PLUGIN_PATH).
------------------------------------------------------------------------- */

#include "lammpsplugin.h"

#include "output.h"
#include "version.h"

#include "compute_nosb_atom.h"
#include "dump_nosb_mesh.h"
#include "fix_nosb_contact.h"
#include "fix_nosb_family.h"
#include "fix_nosb_mesh.h"
#include "fix_sissm.h"
#include "pair_peri_nosb.h"
#include "read_mesh.h"

using namespace LAMMPS_NS;

namespace {

// the creators LAMMPS calls (as its own plugins' creators: the new style as its base class)
template <class Base, class T> void *create(void *lmp)
{
  return static_cast<Base *>(new T((LAMMPS *) lmp));
}

template <class Base, class T> void *create_with_args(void *lmp, int argc, char **argv)
{
  return static_cast<Base *>(new T((LAMMPS *) lmp, argc, argv));
}

Dump *create_dump_nosb_mesh(LAMMPS *lmp, int argc, char **argv)
{
  return new DumpNosbMesh(lmp, argc, argv);
}

// one style: kind, name, description, and its creator (v1: lmp only; v2: lmp and arguments)
struct Style {
  const char *style, *name, *info;
  lammpsplugin_factory1 *v1;
  lammpsplugin_factory2 *v2;
};

}    // namespace

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  const Style styles[] = {
      {"pair", "peri/nosb",
       "PERI-SISSM correspondence peridynamics (SVD-split hyperelastic stresses)",
       &create<Pair, PairPeriNosb>, nullptr},
      {"fix", "nosb/family", "PERI-SISSM bond families of pair_style peri/nosb", nullptr,
       &create_with_args<Fix, FixNosbFamily>},
      {"fix", "sissm", "PERI-SISSM semi-implicit successive substitution integrator", nullptr,
       &create_with_args<Fix, FixSissm>},
      {"fix", "nosb/mesh", "PERI-SISSM triangles of the meshes read by read_mesh", nullptr,
       &create_with_args<Fix, FixNosbMesh>},
      {"fix", "nosb/contact", "PERI-SISSM barrier contact between mesh primitives", nullptr,
       &create_with_args<Fix, FixNosbContact>},
      {"command", "read_mesh",
       "PERI-SISSM one peri particle per vertex of a triangle mesh (Wavefront OBJ)",
       &create<Command, ReadMesh>, nullptr},
      {"compute", "nosb/atom", "PERI-SISSM per-atom damage, energy density, J and Cauchy stress",
       nullptr, &create_with_args<Compute, ComputeNosbAtom>},
  };
  auto register_plugin = (lammpsplugin_regfunc) regfunc;
  for (const Style &s : styles) {
    lammpsplugin_t plugin;
    plugin.version = LAMMPS_VERSION;
    plugin.author = "PERI-SISSM developers";
    plugin.handle = handle;
    plugin.style = s.style;
    plugin.name = s.name;
    plugin.info = s.info;
    if (s.v1)
      plugin.creator.v1 = s.v1;
    else
      plugin.creator.v2 = s.v2;
    (*register_plugin)(&plugin, lmp);
  }
  // dump nosb/mesh: this LAMMPS's plugin loader registers no dump styles (PLUGIN/plugin.cpp
  // takes pair, bond, angle, dihedral, improper, kspace, compute, fix, region and command), so
  // the creator goes into the table the dump command reads; "plugin list" does not show it
  (*((LAMMPS *) lmp)->output->dump_map)["nosb/mesh"] = &create_dump_nosb_mesh;
}
