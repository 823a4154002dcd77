// A line of pair_coeff peri/nosb read by the core: the coefficients of valid lines (numbers,
// material file entries, keywords, the file's G0), the first problem of invalid ones as the
// LAMMPS error message names it.
#include "peri/coefficient_line.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace PeriSISSM;

namespace {

// readers that throw where LAMMPS stops with an error
CoefficientReaders readers()
{
  CoefficientReaders read;
  read.number = [](const std::string &what, const std::string &text) {
    char *end = nullptr;
    const double x = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0') throw std::invalid_argument(what + " not a number");
    return x;
  };
  read.logical = [](const std::string &text) {
    if (text == "yes") return true;
    if (text == "no") return false;
    throw std::invalid_argument("not yes/no: " + text);
  };
  read.material = [](const std::string &file, const std::string &name) {
    if (file != "test.nosb") throw std::invalid_argument("no file " + file);
    MaterialEntry e;
    e.name = name;
    e.bulk = 1.0e10;
    e.shear = 5.0e9;
    e.density = 2500.0;
    e.g0 = name == "tough" ? 40.0 : 0.0;
    return e;
  };
  return read;
}

std::vector<std::string> words(const std::string &text)
{
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

// the problem of a line ("" if none) and what it read
std::string read_line(const std::string &text, CoefficientLine &line)
{
  return read_coefficient_line(words(text), readers(), line);
}

}    // namespace

TEST(CoefficientLine, NumbersAndKeywords)
{
  CoefficientLine line;
  ASSERT_EQ(read_line("1 2 stvk 2e9 1e9 0.003 0.01 0.25 stabilize 0.5 break yes contact no "
                      "membrane yes bend 3.5",
                      line),
            "");
  const PairCoefficients &c = line.c;
  EXPECT_EQ(c.moduli.model, "stvk");
  EXPECT_EQ(c.moduli.k, 2e9);
  EXPECT_EQ(c.moduli.g, 1e9);
  EXPECT_EQ(c.horizon, 0.003);
  EXPECT_EQ(c.s00, 0.01);
  EXPECT_EQ(c.alpha, 0.25);
  EXPECT_EQ(c.cs, 0.5);
  EXPECT_TRUE(c.breaks);
  EXPECT_FALSE(c.contact);
  EXPECT_TRUE(c.membrane);
  EXPECT_EQ(line.bend, 3.5);
  EXPECT_EQ(c.g0, 0.0);
  EXPECT_EQ(line.material, "");
  EXPECT_EQ(line.density, 0.0);
}

TEST(CoefficientLine, DefaultsWithoutKeywords)
{
  CoefficientLine line;
  ASSERT_EQ(read_line("* * linear 1 0.6 0.003 0.5 0.25", line), "");
  EXPECT_EQ(line.c.cs, kDefaultCs);
  EXPECT_TRUE(line.c.breaks);
  EXPECT_TRUE(line.c.contact);
  EXPECT_FALSE(line.c.membrane);
  EXPECT_EQ(line.bend, 0.0);
  CoefficientLine autobend;
  ASSERT_EQ(read_line("1 1 linear 1 0.6 0.003 0.5 0.25 membrane yes bend auto", autobend), "");
  EXPECT_EQ(autobend.bend, -1.0);
}

TEST(CoefficientLine, MaterialFileEntryAndItsG0)
{
  CoefficientLine line;
  ASSERT_EQ(read_line("1 1 neohookean material test.nosb glass 0.003 0.01 0.25", line), "");
  EXPECT_EQ(line.c.moduli.k, 1.0e10);
  EXPECT_EQ(line.c.moduli.g, 5.0e9);
  EXPECT_EQ(line.material, "glass");
  EXPECT_EQ(line.density, 2500.0);
  EXPECT_EQ(line.c.g0, 0.0);    // s00 given: the file's G0 is not asked for
  // s00 NULL: the file's G0, unless the G0 keyword gives one
  CoefficientLine tough;
  ASSERT_EQ(read_line("1 1 linear material test.nosb tough 0.003 NULL 0.25", tough), "");
  EXPECT_EQ(tough.c.g0, 40.0);
  EXPECT_EQ(tough.c.s00, 0.0);
  CoefficientLine keyword;
  ASSERT_EQ(read_line("1 1 linear material test.nosb tough 0.003 NULL 0.25 G0 7", keyword), "");
  EXPECT_EQ(keyword.c.g0, 7.0);
  CoefficientLine numbers;
  ASSERT_EQ(read_line("1 1 linear 1 0.6 0.003 NULL 0.25 G0 7", numbers), "");
  EXPECT_EQ(numbers.c.g0, 7.0);
}

// (line, the whole error message or the start of it); each line has one problem
struct BadLine {
  const char *line;
  const char *message;
};

TEST(CoefficientLine, FirstProblemAsTheLammpsError)
{
  const std::string illegal = "Illegal pair_coeff peri/nosb command: ";
  const std::vector<BadLine> bad = {
      {"1 1 linear 1 0.6 0.003 0.5",
       "Incorrect number of args for pair_coeff peri/nosb command: expected I J MODEL K G "
       "horizon s00 alpha"},
      {"1 1 linear material test.nosb glass 0.003 0.5",
       "Incorrect number of args for pair_coeff peri/nosb command: expected I J MODEL material "
       "FILE NAME horizon s00 alpha [keywords], got 8 arguments"},
      {"1 1 hookean 1 0.6 0.003 0.5 0.25", "unknown model 'hookean' (allowed: "},
      {"1 1 xu -1 0 0.003 0.5 0.25", "xu modulus s0 must be > 0, got -1"},
      {"1 1 linear 0 0.6 0.003 0.5 0.25", "bulk modulus K must be > 0, got 0"},
      {"1 1 stvk 1 -5e8 0.003 0.5 0.25", "shear modulus G must be > 0, got -5e8"},
      {"1 1 linear 1e-300 1 0.003 0.5 0.25",
       "K = 1e-300 and G = 1 give Poisson's ratio -1 outside (-1, 0.5)"},
      {"1 1 linear 1 0.6 -0.003 0.5 0.25", "horizon must be > 0, got -0.003"},
      {"1 1 linear 1 0.6 0.003 0.5 0.25 damping 0.3",
       "unknown keyword 'damping' (allowed: stabilize, deviation, break, contact, membrane, bend, "
       "bending, G0)"},
      {"1 1 linear 1 0.6 0.003 0.5 0.25 membrane yes bend auto bending flat",
       "bending must be plate or hinge, got flat"},
      {"1 1 linear 1 0.6 0.003 0.5 0.25 membrane yes bending plate",
       "bending chooses the energy of bend (add 'bend D' or 'bend auto' to the line of type 1)"},
      {"1 1 linear 1 0.6 0.003 0.5 0.25 stabilize",
       "Illegal pair_coeff peri/nosb stabilize command: missing argument(s)"},
      {"1 1 linear 1 0.6 0.003 0.5 0.25 stabilize -0.1", "stabilize Cs must be >= 0, got -0.1"},
      {"1 1 linear 1 0.6 0.003 0.5 0.25 membrane yes bend 0",
       "bend D must be > 0 (or auto, or no), got 0"},
      {"2*3 2*3 linear 1 0.6 0.003 0.5 0.25 bend auto",
       "bend is a term of membranes (add 'membrane yes' to the line of type 2*3)"},
      {"1 1 linear 1 0.6 0.003 NULL 0.25 G0 -2.5", "G0 must be > 0, got -2.5"},
      {"1 1 linear 1 0.6 0.003 0.001 0.25 G0 3.0",
       "s00 = 0.001 and G0 = 3.0 both set the critical stretch (give s00 as NULL with G0)"},
      {"1 1 linear 1 0.6 0.003 NULL 0.25 G0 3.5 break no",
       "G0 = 3.5 sets the critical stretch, but bonds cannot break with 'break no'"},
      {"1 1 linear 1 0.6 0.003 NULL 0.25",
       "s00 = NULL needs the G0 keyword (the critical energy release rate that sets the "
       "critical stretch)"},
      {"1 1 linear material test.nosb glass 0.003 NULL 0.25",
       "s00 = NULL needs the G0 keyword (the critical energy release rate that sets the "
       "critical stretch); material glass gives no G0"},
      {"1 1 linear material test.nosb tough 0.003 NULL 0.25 break no",
       "s00 = NULL needs the G0 keyword"},    // the file's G0 is not taken with 'break no'
      {"1 1 linear 1 0.6 0.003 0 0.25",
       "s00 must be > 0 when bonds can break, got 0 (use 'break no' to turn bond breaking off)"},
      {"1 1 linear 1 0.6 0.003 0.5 -0.25", "alpha must be >= 0, got -0.25"},
  };
  for (const BadLine &b : bad) {
    CoefficientLine line;
    const std::string problem = read_line(b.line, line);
    std::string expected = b.message;
    if (expected.rfind("Incorrect", 0) != 0 && expected.rfind("Illegal", 0) != 0)
      expected = illegal + expected;
    EXPECT_EQ(problem.substr(0, expected.size()), expected) << b.line;
  }
  // valid lines the checks above must not refuse
  for (const char *good :
       {"1 1 linear 1 0.6 0.003 0 0.25 break no", "1 1 linear 1 0.6 0.003 0.5 -0.25 break no",
        "1 1 linear 1 0.6 0.003 0.5 0.25 stabilize 0 membrane yes bend no"}) {
    CoefficientLine line;
    EXPECT_EQ(read_line(good, line), "") << good;
  }
}

// values are read in the order of the line: the first unreadable one stops it
TEST(CoefficientLine, ReadersSeeTheValuesInOrder)
{
  CoefficientLine line;
  EXPECT_THROW(read_line("1 1 linear stiff 0.6 0.003 0.5 0.25", line), std::invalid_argument);
  EXPECT_THROW(read_line("1 1 linear 1 0.6 0.003 0.5 0.25 break maybe", line),
               std::invalid_argument);
  EXPECT_THROW(read_line("1 1 linear material other.nosb glass 0.003 0.5 0.25", line),
               std::invalid_argument);
}
