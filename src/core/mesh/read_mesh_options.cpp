/* PERI-SISSM core: the arguments of the read_mesh command (see read_mesh_options.h). */
#include "mesh/read_mesh_options.h"

#include <stdexcept>

namespace PeriSISSM {

namespace {

  const char *const kUsage = "read_mesh FILE type T thickness t density rho [offset dx dy dz] "
                             "[scale s] [rotate theta Rx Ry Rz] [group G]";

  [[noreturn]] void illegal(const std::string &what)
  {
    throw std::invalid_argument("Illegal read_mesh command: " + what);
  }

}    // namespace

ReadMeshOptions
parse_read_mesh(const std::vector<std::string> &args,
                const std::function<double(const char *, const std::string &)> &number,
                const std::function<int(const std::string &)> &type)
{
  const int narg = (int) args.size();
  if (narg < 1) illegal(std::string("no mesh file (") + kUsage + ")");
  ReadMeshOptions opt;
  opt.file = args[0];
  bool have_type = false, have_thickness = false, have_density = false;
  int iarg = 1;
  auto need = [&](const std::string &keyword, int n) {
    if (iarg + n >= narg)
      illegal("keyword " + keyword + " needs " + std::to_string(n) + " value" + (n > 1 ? "s" : "") +
              " (" + kUsage + ")");
  };
  auto positive = [&](const char *what, const std::string &text) {
    const double value = number(what, text);
    if (!(value > 0.0)) illegal(std::string(what) + " must be > 0, got '" + text + "'");
    return value;
  };
  while (iarg < narg) {
    const std::string &keyword = args[iarg];
    if (keyword == "type") {
      need(keyword, 1);
      opt.type = type(args[iarg + 1]);
      have_type = true;
      iarg += 2;
    } else if (keyword == "thickness") {
      need(keyword, 1);
      opt.thickness = positive("thickness", args[iarg + 1]);
      have_thickness = true;
      iarg += 2;
    } else if (keyword == "density") {
      need(keyword, 1);
      opt.density = positive("density", args[iarg + 1]);
      have_density = true;
      iarg += 2;
    } else if (keyword == "offset") {
      need(keyword, 3);
      for (int d = 0; d < 3; d++) opt.place.offset[d] = number("offset", args[iarg + 1 + d]);
      iarg += 4;
    } else if (keyword == "scale") {
      need(keyword, 1);
      opt.place.scale = positive("scale", args[iarg + 1]);
      iarg += 2;
    } else if (keyword == "rotate") {
      need(keyword, 4);
      opt.place.theta = number("rotate angle theta", args[iarg + 1]);
      for (int d = 0; d < 3; d++) opt.place.axis[d] = number("rotate axis", args[iarg + 2 + d]);
      const double *r = opt.place.axis;
      if (r[0] == 0.0 && r[1] == 0.0 && r[2] == 0.0)
        illegal("the rotate axis must not be zero, got " + args[iarg + 2] + " " + args[iarg + 3] +
                " " + args[iarg + 4]);
      iarg += 5;
    } else if (keyword == "group") {
      need(keyword, 1);
      opt.group = args[iarg + 1];
      iarg += 2;
    } else {
      illegal("unknown keyword '" + keyword + "' (" + kUsage + ")");
    }
  }
  const char *missing = !have_type ? "type"
      : !have_thickness            ? "thickness"
      : !have_density              ? "density"
                                   : nullptr;
  if (missing) illegal(std::string("keyword ") + missing + " is required (" + kUsage + ")");
  return opt;
}

}    // namespace PeriSISSM
