// Material files (potentials/*.nosb): parsing, lookup, errors with line numbers, and the
// conversion between unit styles.
#include "materials/material_file.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace PeriSISSM;

namespace {

const char *kFile = "# DATE: 2026-11-24 UNITS: si CONTRIBUTOR: test\n"
                    "# name K G density G0\n"
                    "\n"
                    "steel  1.75e11 8.0769e10 7850 -   # EN 1993-1-1\n"
                    "glass  3.8889e10 2.9167e10 2500 7.714 # soda-lime\n"
                    "   # an indented comment\n"
                    "bare   1 2 3 4\n";

// the message of the runtime_error that f throws ("" if it throws none)
template <class F> std::string error_of(F f)
{
  try {
    f();
  } catch (std::runtime_error &e) {
    return e.what();
  }
  return "";
}

}    // namespace

TEST(MaterialFile, ReadsTagsEntriesAndSources)
{
  const auto file = parse_material_file(kFile, "test.nosb");
  EXPECT_EQ(file.units, "si");
  EXPECT_EQ(file.date, "2026-11-24");
  ASSERT_EQ(file.entries.size(), 3u);
  const auto *steel = file.find("steel");
  ASSERT_NE(steel, nullptr);
  EXPECT_EQ(steel->bulk, 1.75e11);
  EXPECT_EQ(steel->shear, 8.0769e10);
  EXPECT_EQ(steel->density, 7850.0);
  EXPECT_EQ(steel->g0, 0.0);    // '-': none
  EXPECT_EQ(steel->source, "EN 1993-1-1");
  EXPECT_EQ(steel->line, 4);
  EXPECT_EQ(file.find("glass")->g0, 7.714);
  EXPECT_EQ(file.find("bare")->source, "");
  EXPECT_EQ(file.find("Steel"), nullptr);    // names are case sensitive, as LAMMPS's
  EXPECT_EQ(file.names(), "steel, glass, bare");
}

TEST(MaterialFile, ErrorsNameTheLineAndTheValue)
{
  const std::string head = "# UNITS: si\n";
  auto parse = [&](const std::string &body) {
    return error_of([&] {
      parse_material_file(head + body, "bad.nosb");
    });
  };
  EXPECT_NE(parse("steel 1e11 8e10 7850\n").find("bad.nosb line 2"), std::string::npos);
  EXPECT_NE(parse("steel 1e11 8e10 7850\n").find("got 4 words"), std::string::npos);
  EXPECT_NE(parse("steel 1e11 8e1x 7850 -\n").find("shear modulus G must be a number, got '8e1x'"),
            std::string::npos);
  EXPECT_NE(parse("steel 1e11 8e10 -7850 -\n").find("density must be > 0"), std::string::npos);
  EXPECT_NE(parse("steel 1e11 8e10 7850 0\n").find("G0 must be > 0"), std::string::npos);
  EXPECT_NE(parse("steel inf 8e10 7850 -\n").find("must be a number"), std::string::npos);
  EXPECT_NE(parse("a 1 1 1 -\n\na 2 2 2 -\n")
                .find("line 4: material 'a' is already defined "
                      "on line 2"),
            std::string::npos);
  EXPECT_EQ(parse("a 1 1 1 -\n"), "");
}

TEST(MaterialFile, ConvertsBetweenMechanicalUnitStyles)
{
  MaterialEntry si;
  si.bulk = 2.0e9;        // Pa
  si.shear = 1.0e9;       // Pa
  si.density = 1000.0;    // kg/m^3
  si.g0 = 10.0;           // J/m^2
  // cgs: 1 Pa = 10 dyne/cm^2, 1 kg/m^3 = 1e-3 g/cm^3, 1 J/m^2 = 1e3 erg/cm^2
  const auto cgs = convert_material(si, "si", "cgs");
  EXPECT_DOUBLE_EQ(cgs.bulk, 2.0e10);
  EXPECT_DOUBLE_EQ(cgs.shear, 1.0e10);
  EXPECT_DOUBLE_EQ(cgs.density, 1.0);
  EXPECT_DOUBLE_EQ(cgs.g0, 1.0e4);
  // micro (picogram, micrometer, microsecond): pressure unit 1e3 Pa, density unit 1e3 kg/m^3,
  // energy per area unit 1e-3 J/m^2
  const auto micro = convert_material(si, "si", "micro");
  EXPECT_DOUBLE_EQ(micro.bulk, 2.0e6);
  EXPECT_DOUBLE_EQ(micro.density, 1.0);
  EXPECT_DOUBLE_EQ(micro.g0, 1.0e4);
  // nano (attogram, nanometer, nanosecond): pressure unit 1e6 Pa, density unit 1e6 kg/m^3
  const auto nano = convert_material(si, "si", "nano");
  EXPECT_DOUBLE_EQ(nano.bulk, 2.0e3);
  EXPECT_DOUBLE_EQ(nano.density, 1.0e-3);
  // there and back, and the identity
  const auto back = convert_material(convert_material(si, "si", "nano"), "nano", "cgs");
  EXPECT_DOUBLE_EQ(back.bulk, cgs.bulk);
  EXPECT_DOUBLE_EQ(back.g0, cgs.g0);
  EXPECT_EQ(convert_material(si, "si", "si").shear, si.shear);
}

TEST(MaterialFile, RefusesUnitStylesWithoutAMechanicalConversion)
{
  MaterialEntry entry;
  for (const char *style : {"metal", "real", "lj", "electron"}) {
    const auto what = error_of([&] {
      convert_material(entry, "si", style);
    });
    EXPECT_NE(what.find(std::string("cannot be converted to '") + style + "'"), std::string::npos)
        << what;
    EXPECT_NE(what.find("si, cgs, micro, nano"), std::string::npos) << what;
  }
  EXPECT_NE(error_of([&] {
              convert_material(entry, "", "si");
            }).find("no UNITS: tag"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              convert_material(entry, "metal", "si");
            }).find("units 'metal' are not one of"),
            std::string::npos);
}

#ifdef PERISISSM_POTENTIALS_DIR
// the shipped file parses, names every class of material the docs promise, and each entry is
// an admissible isotropic material with a source
TEST(MaterialFile, ShippedFileIsComplete)
{
  std::ifstream in(std::string(PERISISSM_POTENTIALS_DIR) + "/materials.nosb");
  ASSERT_TRUE(in.good());
  std::stringstream text;
  text << in.rdbuf();
  const auto file = parse_material_file(text.str(), "materials.nosb");
  EXPECT_EQ(file.units, "si");
  for (const char *name : {"steel", "aluminium", "glass", "pmma", "rubber", "cloth"})
    EXPECT_NE(file.find(name), nullptr) << name;
  for (const auto &e : file.entries) {
    const double nu = (3.0 * e.bulk - 2.0 * e.shear) / (2.0 * (3.0 * e.bulk + e.shear));
    EXPECT_GT(nu, -1.0) << e.name;
    EXPECT_LT(nu, 0.5) << e.name;
    EXPECT_FALSE(e.source.empty()) << e.name;
  }
}
#endif

TEST(MaterialFile, SummaryForTheLog)
{
  const MaterialFile f = parse_material_file(kFile, "test.nosb");
  EXPECT_EQ(material_summary(*f.find("steel"), "steel", "test.nosb"),
            "Material steel from test.nosb: K = 1.75e+11, G = 8.0769e+10, density = 7850\n"
            "  source: EN 1993-1-1\n");
  EXPECT_EQ(material_summary(*f.find("bare"), "bare", "x"),
            "Material bare from x: K = 1, G = 2, density = 3, G0 = 4\n");
}

TEST(MaterialFile, DensityWarningsOutsideOneInAMillion)
{
  // types 1..4: no file; within 1e-6 rho; one atom off; no atoms
  const std::vector<double> rho = {0.0, 0.0, 1000.0, 1000.0, 1000.0};
  const std::vector<double> lo = {0.0, 5.0, 1000.0 - 9.0e-4, 1000.0, 1.0 / 0.0};
  const std::vector<double> hi = {0.0, 7.0, 1000.0 + 9.0e-4, 1000.0 + 2.0e-3, -1.0 / 0.0};
  const std::vector<std::string> names = {"", "", "glass", "steel", "foam"};
  const auto w = density_warnings(rho, lo, hi, names);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].first, 3);
  EXPECT_EQ(w[0].second,
            "Pair peri/nosb: atoms of type 3 have density (rmass) 1000 ... 1000, but their "
            "material steel has 1000 (set type 3 density 1000)");
  const std::vector<double> at = {0.0, 6.0, 1000.0009, 1000.002, 1.0 / 0.0};
  const auto again = density_warnings(rho, at, hi, names);    // type 3 alone: 1000.002 again
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].first, 3);
  const std::vector<double> low = {0.0, 0.0, 999.0, 1000.0, 1.0 / 0.0};
  EXPECT_EQ(density_warnings(rho, low, low, names)[0].second.substr(0, 75),
            "Pair peri/nosb: atoms of type 2 have density (rmass) 999 ... 999, but their");
}

TEST(MaterialFile, EntryForPairCoeffWithLogAndErrors)
{
  MaterialEntry e;
  std::string log;
  EXPECT_EQ(read_material_entry(kFile, "t.nosb", "/p/t.nosb", "glass", "si", e, log), "");
  EXPECT_EQ(e.bulk, 3.8889e10);
  EXPECT_EQ(log,
            "Reading material file /p/t.nosb with DATE: 2026-11-24\n" +
                material_summary(e, "glass", "t.nosb"));
  log.clear();
  EXPECT_EQ(read_material_entry(kFile, "t.nosb", "/p/t.nosb", "glass", "cgs", e, log), "");
  EXPECT_DOUBLE_EQ(e.bulk, 3.8889e11);    // Pa to barye
  EXPECT_NE(log.find("\nMaterial glass converted from si to cgs units\nMaterial glass from"),
            std::string::npos)
      << log;
  log.clear();
  EXPECT_EQ(read_material_entry(kFile, "t.nosb", "/p/t.nosb", "iron", "si", e, log),
            "pair_coeff peri/nosb material: no material 'iron' in t.nosb (it has: steel, glass, "
            "bare)");
  EXPECT_EQ(log, "Reading material file /p/t.nosb with DATE: 2026-11-24\n");
  const std::string units = read_material_entry(kFile, "t.nosb", "", "steel", "metal", e, log);
  EXPECT_EQ(units.rfind("pair_coeff peri/nosb material t.nosb steel: ", 0), 0u) << units;
  const std::string bad = read_material_entry("x 1 2\n", "b.nosb", "", "x", "si", e, log);
  EXPECT_EQ(bad.rfind("pair_coeff peri/nosb material b.nosb x: ", 0), 0u) << bad;
}

TEST(MaterialFile, DensityRangesPerType)
{
  const double rho[5] = {3.0, 1.0, 2.0, 5.0, 4.0};
  const int type[5] = {1, 1, 3, 1, 3};
  std::vector<double> lo, hi;
  density_ranges(5, rho, type, 3, lo, hi);
  ASSERT_EQ(lo.size(), 4u);
  EXPECT_EQ(lo[1], 1.0);
  EXPECT_EQ(hi[1], 5.0);
  EXPECT_GT(lo[2], hi[2]);    // no particles of type 2
  EXPECT_EQ(lo[3], 2.0);
  EXPECT_EQ(hi[3], 4.0);
  density_ranges(0, rho, type, 3, lo, hi);
  EXPECT_GT(lo[1], hi[1]);
}
