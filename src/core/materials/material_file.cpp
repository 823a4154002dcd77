/* PERI-SISSM core: material parameter files (see material_file.h). */
#include "materials/material_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace PeriSISSM {

namespace {

  // a unit style as the sizes of its mass, length and time units in kg, m and s
  struct UnitStyle {
    const char *name;
    double mass, length, time;
  };

  constexpr UnitStyle kUnitStyles[] = {
      {"si", 1.0, 1.0, 1.0},
      {"cgs", 1.0e-3, 1.0e-2, 1.0},
      {"micro", 1.0e-15, 1.0e-6, 1.0e-6},
      {"nano", 1.0e-21, 1.0e-9, 1.0e-9},
  };

  const UnitStyle *unit_style(const std::string &name)
  {
    for (const auto &style : kUnitStyles)
      if (name == style.name) return &style;
    return nullptr;
  }

  // the size of one unit of a quantity of dimension mass^m length^l time^t in SI
  double unit_size(const UnitStyle &s, int m, int l, int t)
  {
    return std::pow(s.mass, m) * std::pow(s.length, l) * std::pow(s.time, t);
  }

  std::string trim(const std::string &s)
  {
    const auto first = s.find_first_not_of(" \t\r");
    if (first == std::string::npos) return "";
    const auto last = s.find_last_not_of(" \t\r");
    return s.substr(first, last - first + 1);
  }

  // the word after tag (e.g. "UNITS:") in a line, or ""
  std::string tag_value(const std::string &line, const std::string &tag)
  {
    std::istringstream words(line);
    std::string word;
    while (words >> word)
      if (word == tag) return (words >> word) ? word : "";
    return "";
  }

  [[noreturn]] void fail(const std::string &filename, int line, const std::string &what)
  {
    throw std::runtime_error("material file " + filename + " line " + std::to_string(line) + ": " +
                             what);
  }

  double parse_value(const std::string &word, const char *what, const std::string &filename,
                     int line, bool positive)
  {
    char *end = nullptr;
    const double value = std::strtod(word.c_str(), &end);
    if (end == word.c_str() || *end != '\0' || !std::isfinite(value))
      fail(filename, line, std::string(what) + " must be a number, got '" + word + "'");
    if (positive && !(value > 0.0))
      fail(filename, line, std::string(what) + " must be > 0, got '" + word + "'");
    return value;
  }

}    // namespace

const MaterialEntry *MaterialFile::find(const std::string &name) const
{
  for (const auto &entry : entries)
    if (entry.name == name) return &entry;
  return nullptr;
}

std::string MaterialFile::names() const
{
  std::string all;
  for (const auto &entry : entries) all += (all.empty() ? "" : ", ") + entry.name;
  return all;
}

MaterialFile parse_material_file(const std::string &text, const std::string &filename)
{
  MaterialFile file;
  std::istringstream in(text);
  std::string raw;
  int line = 0;
  while (std::getline(in, raw)) {
    ++line;
    const auto hash = raw.find('#');
    if (line == 1) {
      file.units = tag_value(raw, "UNITS:");
      file.date = tag_value(raw, "DATE:");
    }
    const std::string body = trim(raw.substr(0, hash));
    if (body.empty()) continue;
    std::istringstream words(body);
    std::vector<std::string> fields;
    for (std::string w; words >> w;) fields.push_back(w);
    if (fields.size() != 5)
      fail(filename, line,
           "an entry is 'name K G density G0' (G0 may be '-'), got " +
               std::to_string(fields.size()) + " words");
    MaterialEntry entry;
    entry.name = fields[0];
    entry.bulk = parse_value(fields[1], "bulk modulus K", filename, line, true);
    entry.shear = parse_value(fields[2], "shear modulus G", filename, line, true);
    entry.density = parse_value(fields[3], "density", filename, line, true);
    if (fields[4] != "-") entry.g0 = parse_value(fields[4], "G0", filename, line, true);
    entry.source = hash == std::string::npos ? "" : trim(raw.substr(hash + 1));
    entry.line = line;
    if (file.find(entry.name))
      fail(filename, line,
           "material '" + entry.name + "' is already defined on line " +
               std::to_string(file.find(entry.name)->line));
    file.entries.push_back(entry);
  }
  return file;
}

MaterialEntry convert_material(const MaterialEntry &entry, const std::string &from,
                               const std::string &to)
{
  std::string allowed;
  for (const auto &style : kUnitStyles)
    allowed += (allowed.empty() ? "" : ", ") + std::string(style.name);
  const UnitStyle *src = unit_style(from);
  const UnitStyle *dst = unit_style(to);
  if (!src)
    throw std::runtime_error(
        from.empty() ? "the file has no UNITS: tag on its first line (one of " + allowed + ")"
                     : "the file's units '" + from + "' are not one of " + allowed);
  if (!dst)
    throw std::runtime_error("material values cannot be converted to '" + to +
                             "' units (convertible unit styles: " + allowed + ")");
  MaterialEntry out = entry;
  // pressure: mass length^-1 time^-2; density: mass length^-3; energy per area: mass time^-2
  const double pressure = unit_size(*src, 1, -1, -2) / unit_size(*dst, 1, -1, -2);
  out.bulk *= pressure;
  out.shear *= pressure;
  out.density *= unit_size(*src, 1, -3, 0) / unit_size(*dst, 1, -3, 0);
  out.g0 *= unit_size(*src, 1, 0, -2) / unit_size(*dst, 1, 0, -2);
  return out;
}

std::string read_material_entry(const std::string &text, const std::string &file,
                                const std::string &path, const std::string &name,
                                const std::string &units, MaterialEntry &entry, std::string &log)
{
  try {
    const MaterialFile parsed = parse_material_file(text, file);
    if (!parsed.date.empty())
      log += "Reading material file " + path + " with DATE: " + parsed.date + "\n";
    const MaterialEntry *hit = parsed.find(name);
    if (!hit)
      return "pair_coeff peri/nosb material: no material '" + name + "' in " + file +
          " (it has: " + parsed.names() + ")";
    entry = convert_material(*hit, parsed.units, units);
    if (parsed.units != units)
      log += "Material " + name + " converted from " + parsed.units + " to " + units + " units\n";
  } catch (std::runtime_error &e) {
    return "pair_coeff peri/nosb material " + file + " " + name + ": " + e.what();
  }
  log += material_summary(entry, name, file);
  return "";
}

std::string material_summary(const MaterialEntry &entry, const std::string &name,
                             const std::string &file)
{
  char buf[256];
  std::snprintf(buf, sizeof(buf), ": K = %.6g, G = %.6g, density = %.6g", entry.bulk, entry.shear,
                entry.density);
  std::string text = "Material " + name + " from " + file + buf;
  if (entry.g0 > 0.0) {
    std::snprintf(buf, sizeof(buf), ", G0 = %.6g", entry.g0);
    text += buf;
  }
  if (!entry.source.empty()) text += "\n  source: " + entry.source;
  return text + "\n";
}

void density_ranges(int n, const double *rho, const int *type, int ntypes, std::vector<double> &lo,
                    std::vector<double> &hi)
{
  lo.assign(ntypes + 1, INFINITY);
  hi.assign(ntypes + 1, -INFINITY);
  for (int i = 0; i < n; i++) {
    lo[type[i]] = std::min(lo[type[i]], rho[i]);
    hi[type[i]] = std::max(hi[type[i]], rho[i]);
  }
}

std::vector<std::pair<int, std::string>> density_warnings(const std::vector<double> &density,
                                                          const std::vector<double> &lo,
                                                          const std::vector<double> &hi,
                                                          const std::vector<std::string> &name)
{
  std::vector<std::pair<int, std::string>> warnings;
  for (int t = 1; t < (int) density.size(); t++) {
    const double rho = density[t];
    if (!(rho > 0.0) || lo[t] > hi[t]) continue;    // no file, or no atoms of this type
    const double tol = 1.0e-6 * rho;
    if (std::fabs(lo[t] - rho) <= tol && std::fabs(hi[t] - rho) <= tol) continue;
    char buf[512];
    std::snprintf(buf, sizeof(buf),
                  "Pair peri/nosb: atoms of type %d have density (rmass) %.6g ... %.6g, but their "
                  "material %s has %.6g (set type %d density %.6g)",
                  t, lo[t], hi[t], name[t].c_str(), rho, t, rho);
    warnings.emplace_back(t, buf);
  }
  return warnings;
}

}    // namespace PeriSISSM
