// The arguments of read_mesh: every keyword, any order, the numbers and the type converted in
// the order of the arguments, and the message of each kind of error.
#include "mesh/read_mesh_options.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

using namespace PeriSISSM;

namespace {

// the caller's converters: numbers by strtod (noting what they were), types by atoi
struct Converters {
  std::vector<std::string> seen;    // "what=text" of each number, "type=text" of each type
  std::function<double(const char *, const std::string &)> number =
      [this](const char *what, const std::string &text) {
        seen.push_back(std::string(what) + "=" + text);
        return std::strtod(text.c_str(), nullptr);
      };
  std::function<int(const std::string &)> type = [this](const std::string &text) {
    seen.push_back("type=" + text);
    return std::atoi(text.c_str());
  };
};

std::string error_of(const std::vector<std::string> &args)
{
  Converters c;
  try {
    parse_read_mesh(args, c.number, c.type);
  } catch (std::invalid_argument &e) {
    return e.what();
  }
  return "";
}

}    // namespace

TEST(ReadMeshOptions, ReadsEveryKeywordInAnyOrder)
{
  Converters c;
  const auto opt =
      parse_read_mesh({"cloth.obj", "scale", "2",  "group", "cloth",     "density", "1000",
                       "rotate",    "90",    "1",  "0",     "0",         "type",    "3",
                       "offset",    "0.5",   "-1", "2",     "thickness", "0.001"},
                      c.number, c.type);
  EXPECT_EQ(opt.file, "cloth.obj");
  EXPECT_EQ(opt.type, 3);
  EXPECT_EQ(opt.thickness, 0.001);
  EXPECT_EQ(opt.density, 1000.0);
  EXPECT_EQ(opt.group, "cloth");
  EXPECT_EQ(opt.place.scale, 2.0);
  EXPECT_EQ(opt.place.theta, 90.0);
  for (int d = 0; d < 3; d++) EXPECT_EQ(opt.place.axis[d], d == 0 ? 1.0 : 0.0);
  EXPECT_EQ(opt.place.offset[0], 0.5);
  EXPECT_EQ(opt.place.offset[1], -1.0);
  EXPECT_EQ(opt.place.offset[2], 2.0);
  const std::vector<std::string> order = {
      "scale=2",       "density=1000",   "rotate angle theta=90",
      "rotate axis=1", "rotate axis=0",  "rotate axis=0",
      "type=3",        "offset=0.5",     "offset=-1",
      "offset=2",      "thickness=0.001"};
  EXPECT_EQ(c.seen, order);
}

TEST(ReadMeshOptions, DefaultsPlaceTheFileAsItIs)
{
  Converters c;
  const auto opt =
      parse_read_mesh({"a.obj", "type", "1", "thickness", "1", "density", "2"}, c.number, c.type);
  EXPECT_EQ(opt.place.scale, 1.0);
  EXPECT_EQ(opt.place.theta, 0.0);
  EXPECT_EQ(opt.place.axis[2], 1.0);
  for (int d = 0; d < 3; d++) EXPECT_EQ(opt.place.offset[d], 0.0);
  EXPECT_TRUE(opt.group.empty());
}

TEST(ReadMeshOptions, ErrorsNameTheKeywordAndTheValue)
{
  const std::string usage = " (read_mesh FILE type T thickness t density rho [offset dx dy dz] "
                            "[scale s] [rotate theta Rx Ry Rz] [group G])";
  const std::vector<std::string> ok = {"a.obj", "type", "1", "thickness", "1", "density", "2"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = ok;
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  };
  EXPECT_EQ(error_of({}), "Illegal read_mesh command: no mesh file" + usage);
  EXPECT_EQ(error_of({"a.obj", "type", "1", "density", "2"}),
            "Illegal read_mesh command: keyword thickness is required" + usage);
  EXPECT_EQ(error_of({"a.obj", "thickness", "1", "density", "2"}),
            "Illegal read_mesh command: keyword type is required" + usage);
  EXPECT_EQ(error_of({"a.obj", "type", "1", "thickness", "1"}),
            "Illegal read_mesh command: keyword density is required" + usage);
  EXPECT_EQ(error_of(with({"offset", "1", "2"})),
            "Illegal read_mesh command: keyword offset needs 3 values" + usage);
  EXPECT_EQ(error_of(with({"scale"})),
            "Illegal read_mesh command: keyword scale needs 1 value" + usage);
  EXPECT_EQ(error_of(with({"scale", "0"})),
            "Illegal read_mesh command: scale must be > 0, got '0'");
  EXPECT_EQ(error_of({"a.obj", "type", "1", "thickness", "-1", "density", "2"}),
            "Illegal read_mesh command: thickness must be > 0, got '-1'");
  EXPECT_EQ(error_of({"a.obj", "type", "1", "thickness", "1", "density", "0"}),
            "Illegal read_mesh command: density must be > 0, got '0'");
  EXPECT_EQ(error_of(with({"rotate", "30", "0", "0.0", "0"})),
            "Illegal read_mesh command: the rotate axis must not be zero, got 0 0.0 0");
  EXPECT_EQ(error_of(with({"shift", "1"})),
            "Illegal read_mesh command: unknown keyword 'shift'" + usage);
  EXPECT_EQ(error_of(ok), "");
}
