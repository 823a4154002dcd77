// One line of pair_coeff peri/nosb (see coefficient_line.h).

#include "peri/coefficient_line.h"

#include "materials/material.h"
#include "materials/moduli.h"

#include <algorithm>
#include <charconv>
#include <cstdio>

namespace PeriSISSM {

namespace {

  const std::string kIllegal = "Illegal pair_coeff peri/nosb command: ";

  // the shortest text that reads back as x
  std::string shortest(double x)
  {
    char buf[32];
    const auto end = std::to_chars(buf, buf + sizeof(buf), x).ptr;
    return std::string(buf, end);
  }

  std::string full_precision(double x)
  {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.17g", x);
    return buf;
  }

  // what is wrong with moduli m given as k_text and g_text, "" if nothing
  std::string moduli_problem(const Moduli &m, const std::string &k_text, const std::string &g_text)
  {
    switch (check_moduli(m)) {
      case ModuliProblem::NONE:
        return "";
      case ModuliProblem::MODULUS_NOT_POSITIVE:
        return kIllegal + m.model + " modulus s0 must be > 0, got " + k_text;
      case ModuliProblem::BULK_NOT_POSITIVE:
        return kIllegal + "bulk modulus K must be > 0, got " + k_text;
      case ModuliProblem::SHEAR_NOT_POSITIVE:
        return kIllegal + "shear modulus G must be > 0, got " + g_text;
      case ModuliProblem::POISSON_OUT_OF_RANGE:
        return kIllegal + "K = " + k_text + " and G = " + g_text + " give Poisson's ratio " +
            shortest(poisson_from_bulk_shear(m.k, m.g)) + " outside (-1, 0.5)";
    }
    return "";
  }

  // reads keyword key with its value into line (g0_text: the G0 value as given); "" or the problem
  std::string read_keyword(const std::string &key, const std::string &value,
                           const CoefficientReaders &read, CoefficientLine &line,
                           std::string &g0_text)
  {
    PairCoefficients &c = line.c;
    if (key == "stabilize") {
      c.cs = read.number("stabilize Cs", value);
      if (c.cs < 0.0) return kIllegal + "stabilize Cs must be >= 0, got " + value;
    } else if (key == "break") {
      c.breaks = read.logical(value);
    } else if (key == "contact") {
      c.contact = read.logical(value);
    } else if (key == "membrane") {
      c.membrane = read.logical(value);
    } else if (key == "deviation") {
      if (value != "length" && value != "vector")
        return kIllegal + "deviation must be length or vector, got " + value;
      c.length = value == "length";
      line.length_given = c.length;
    } else if (key == "bending") {
      if (value != "plate" && value != "hinge")
        return kIllegal + "bending must be plate or hinge, got " + value;
      c.plate = value == "plate";
      line.bending_given = true;
    } else if (key == "bend") {
      if (value == "auto") {
        line.bend = -1.0;
      } else if (value == "no") {
        line.bend = 0.0;
      } else {
        line.bend = read.number("bend D", value);
        if (line.bend <= 0.0) return kIllegal + "bend D must be > 0 (or auto, or no), got " + value;
      }
    } else {    // G0
      c.g0 = read.number("G0", value);
      g0_text = value;
      if (c.g0 <= 0.0) return kIllegal + "G0 must be > 0, got " + value;
    }
    return "";
  }

}    // namespace

const std::vector<std::string> &coefficient_keywords()
{
  static const std::vector<std::string> keys = {"stabilize", "deviation", "break",   "contact",
                                                "membrane",  "bend",      "bending", "G0"};
  return keys;
}

std::string read_coefficient_line(const std::vector<std::string> &args,
                                  const CoefficientReaders &read, CoefficientLine &line)
{
  const int narg = (int) args.size();
  const bool from_file = narg > 3 && args[3] == "material";
  const int ih = from_file ? 6 : 5;    // index of the horizon
  if (from_file && narg < 9)
    return "Incorrect number of args for pair_coeff peri/nosb command: expected I J MODEL "
           "material FILE NAME horizon s00 alpha [keywords], got " +
        std::to_string(narg) + " arguments";
  if (narg < 8)
    return "Incorrect number of args for pair_coeff peri/nosb command: expected I J MODEL K G "
           "horizon s00 alpha [stabilize Cs] [break yes/no] [contact yes/no] [G0 value] (or "
           "MODEL material FILE NAME in place of MODEL K G), got " +
        std::to_string(narg) + " arguments";

  const auto &names = material_names();
  if (std::find(names.begin(), names.end(), args[2]) == names.end())
    return kIllegal + "unknown model '" + args[2] + "' (allowed: " + material_names_joined() + ")";

  // the moduli: two numbers, or a material file's entry (with its density and G0)
  PairCoefficients &c = line.c;
  c.moduli.model = args[2];
  std::string k_text = args[3], g_text = args[4];
  double file_g0 = 0.0;
  if (from_file) {
    const MaterialEntry entry = read.material(args[4], args[5]);
    c.moduli.k = entry.bulk;
    c.moduli.g = entry.shear;
    k_text = full_precision(entry.bulk);
    g_text = full_precision(entry.shear);
    line.material = args[5];
    line.density = entry.density;
    file_g0 = entry.g0;
  } else {
    c.moduli.k = read.number("bulk modulus K", args[3]);
    c.moduli.g = read.number("shear modulus G", args[4]);
  }
  c.horizon = read.number("horizon", args[ih]);
  // s00 = NULL: the critical stretch comes from the G0 keyword (at init)
  const bool s00_null = args[ih + 1] == "NULL";
  c.s00 = s00_null ? 0.0 : read.number("s00", args[ih + 1]);
  c.alpha = read.number("alpha", args[ih + 2]);

  std::string problem = moduli_problem(c.moduli, k_text, g_text);
  if (!problem.empty()) return problem;
  if (c.horizon <= 0.0) return kIllegal + "horizon must be > 0, got " + args[ih];

  std::string g0_text;
  const auto &keys = coefficient_keywords();
  for (int iarg = ih + 3; iarg < narg; iarg += 2) {
    const std::string &key = args[iarg];
    if (std::find(keys.begin(), keys.end(), key) == keys.end())
      return kIllegal + "unknown keyword '" + key +
          "' (allowed: stabilize, deviation, break, contact, membrane, bend, bending, G0)";
    if (iarg + 2 > narg)
      return "Illegal pair_coeff peri/nosb " + key + " command: missing argument(s)";
    problem = read_keyword(key, args[iarg + 1], read, line, g0_text);
    if (!problem.empty()) return problem;
  }

  if (line.length_given && c.membrane)
    return kIllegal + "deviation length is a form of volume particles; the membranes of type " +
        args[0] + " keep the vector form in their tangent planes (drop the keyword)";
  // membranes: the tangent-plane vector form whatever the default
  if (c.membrane) c.length = false;
  if (line.bend != 0.0 && !c.membrane)
    return kIllegal + "bend is a term of membranes (add 'membrane yes' to the line of type " +
        args[0] + ")";
  if (line.bending_given && line.bend == 0.0)
    return kIllegal + "bending chooses the energy of bend (add 'bend D' or 'bend auto' to the "
        "line of type " + args[0] + ")";

  // s00 = NULL without the G0 keyword: the material file's G0, if it gives one
  if (s00_null && c.g0 == 0.0 && file_g0 > 0.0 && c.breaks) c.g0 = file_g0;
  if (c.g0 > 0.0 && !s00_null)
    return kIllegal + "s00 = " + args[ih + 1] + " and G0 = " + g0_text +
        " both set the critical stretch (give s00 as NULL with G0)";
  if (c.g0 > 0.0 && !c.breaks)
    return kIllegal + "G0 = " + g0_text +
        " sets the critical stretch, but bonds cannot break with 'break no'";
  if (s00_null && c.g0 == 0.0)
    return kIllegal +
        "s00 = NULL needs the G0 keyword (the critical energy release rate that sets the "
        "critical stretch)" +
        (line.material.empty() ? "" : "; material " + line.material + " gives no G0");
  if (c.breaks && !s00_null && c.s00 <= 0.0)
    return kIllegal + "s00 must be > 0 when bonds can break, got " + args[ih + 1] +
        " (use 'break no' to turn bond breaking off)";
  if (c.breaks && c.alpha < 0.0) return kIllegal + "alpha must be >= 0, got " + args[ih + 2];
  return "";
}

}    // namespace PeriSISSM
