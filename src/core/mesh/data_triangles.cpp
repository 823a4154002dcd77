/* PERI-SISSM core: the Mesh Triangles section of data files (see data_triangles.h). */
#include "mesh/data_triangles.h"

#include <cstring>
#include <stdexcept>

namespace PeriSISSM {

namespace {

  const char *const kBlanks = " \t\r\n\f\v";

  std::string trim(const std::string &s)
  {
    const size_t first = s.find_first_not_of(kBlanks);
    if (first == std::string::npos) return "";
    return s.substr(first, s.find_last_not_of(kBlanks) + 1 - first);
  }

  // the words of a line without its '#' comment (ValueTokenizer's separators)
  std::vector<std::string> words_of(const std::string &line)
  {
    const std::string text = line.substr(0, line.find('#'));
    std::vector<std::string> words;
    size_t start = text.find_first_not_of(" \t\r\n\f");
    while (start != std::string::npos) {
      const size_t end = text.find_first_of(" \t\r\n\f", start);
      words.push_back(text.substr(start, end == std::string::npos ? end : end - start));
      start = end == std::string::npos ? end : text.find_first_not_of(" \t\r\n\f", end);
    }
    return words;
  }

  // a conversion of the whole word, else ValueTokenizer's message
  template <class T, class Convert> T convert(const std::string &word, const char *kind, Convert f)
  {
    const std::string message = std::string("Not a valid ") + kind + ": '" + word + "'";
    size_t end = 0;
    T value;
    try {
      value = f(word, &end);
    } catch (std::logic_error &) {    // std::invalid_argument, std::out_of_range
      throw std::invalid_argument(message);
    }
    if (end != word.size()) throw std::invalid_argument(message);
    return value;
  }

  long long id_of(const std::string &word, long long max_id)
  {
    const long long id = convert<long long>(word, "integer number", [](auto &w, size_t *end) {
      return std::stoll(w, end, 10);
    });
    if (id < -max_id - 1 || id > max_id)
      throw std::invalid_argument("Not a valid integer number: '" + word + "'");
    return id;
  }

  DataTriangle parse_line(const std::string &text, const std::string &keyword, long long id_offset,
                          int mesh_offset, long long max_id)
  {
    DataTriangle t;
    t.line = trim(text);
    const std::string where = "line '" + t.line + "' of the " + keyword + " section";
    const std::vector<std::string> words = words_of(text);
    if (words.size() != 6)
      throw std::invalid_argument("Fix nosb/mesh: " + where + " of the data file has " +
                                  std::to_string(words.size()) +
                                  " values instead of 6 (ID mesh thickness v1 v2 v3)");
    try {
      id_of(words[0], max_id);
      t.mesh = convert<int>(words[1], "integer number", [](auto &w, size_t *end) {
        return std::stoi(w, end);
      });
      t.thickness = convert<double>(words[2], "floating-point number", [](auto &w, size_t *end) {
        return std::stod(w, end);
      });
      for (int c = 0; c < 3; c++) t.v[c] = id_of(words[3 + c], max_id) + id_offset;
    } catch (std::invalid_argument &e) {
      throw std::invalid_argument("Fix nosb/mesh: invalid line '" + t.line + "' in the " + keyword +
                                  " section of the data file: " + e.what());
    }
    if (t.mesh < 1 || !(t.thickness > 0.0) || t.v[0] == t.v[1] || t.v[1] == t.v[2] ||
        t.v[0] == t.v[2])
      throw std::invalid_argument("Fix nosb/mesh: invalid line '" + t.line + "' in the " + keyword +
                                  " section of the data file: the mesh id must be >= 1, the "
                                  "thickness > 0 and the three vertex IDs distinct");
    t.mesh += mesh_offset;
    return t;
  }

}    // namespace

std::vector<DataTriangle> parse_data_triangles(const char *buf, int n, const std::string &keyword,
                                               long long id_offset, int mesh_offset,
                                               long long max_id)
{
  std::vector<DataTriangle> triangles;
  for (int l = 0; l < n; l++) {
    const char *next = std::strchr(buf, '\n');
    if (!next)
      throw std::invalid_argument("Unexpected end of file while reading data section " + keyword);
    triangles.push_back(
        parse_line(std::string(buf, next), keyword, id_offset, mesh_offset, max_id));
    buf = next + 1;
  }
  return triangles;
}

void DataSectionRead::start(const std::string &line, int nmesh, int nlocal)
{
  const std::vector<std::string> words = words_of(line);
  try {
    if (words.empty()) throw std::invalid_argument("no words");
    announced = convert<long long>(words[0], "integer number", [](auto &w, size_t *end) {
      return std::stoll(w, end, 10);
    });
  } catch (std::invalid_argument &) {
    throw std::invalid_argument(
        "Fix nosb/mesh: invalid mesh triangles line in the data file header: '" + trim(line) + "'");
  }
  if (announced < 0)
    throw std::invalid_argument(
        "Fix nosb/mesh: negative number of mesh triangles in the data file: '" + trim(line) + "'");
  open = true;
  nread = 0;
  mesh_offset = nmesh;
  first_row = nlocal;
  rows.clear();
}

void DataSectionRead::read(long long n)
{
  nread += n;
  if (nread == announced) open = false;
}

}    // namespace PeriSISSM
