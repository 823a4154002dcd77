/* PERI-SISSM core: Wavefront OBJ files (see obj_file.h). */
#include "mesh/obj_file.h"

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace PeriSISSM {

namespace {

  [[noreturn]] void fail(const std::string &filename, int line, const std::string &what)
  {
    throw std::runtime_error("mesh file " + filename + " line " + std::to_string(line) + ": " +
                             what);
  }

  // the words of a line (blanks separate them; '#' starts a comment)
  std::vector<std::string> words_of(const std::string &line)
  {
    std::vector<std::string> words;
    size_t k = 0;
    const size_t end = line.find('#');
    const size_t n = (end == std::string::npos) ? line.size() : end;
    while (k < n) {
      while (k < n && (line[k] == ' ' || line[k] == '\t' || line[k] == '\r')) k++;
      const size_t first = k;
      while (k < n && line[k] != ' ' && line[k] != '\t' && line[k] != '\r') k++;
      if (k > first) words.push_back(line.substr(first, k - first));
    }
    return words;
  }

  bool is_number(const std::string &word, double &value)
  {
    char *end = nullptr;
    value = std::strtod(word.c_str(), &end);
    return end != word.c_str() && *end == '\0' && std::isfinite(value);
  }

  bool is_integer(const std::string &word, long &value)
  {
    if (word.empty()) return false;
    char *end = nullptr;
    errno = 0;
    value = std::strtol(word.c_str(), &end, 10);
    return *end == '\0' && errno == 0 && value >= INT_MIN && value <= INT_MAX;
  }

  // the vertex index of a face word (a, a/t, a//n, a/t/n); 0 if malformed
  long vertex_index(const std::string &word)
  {
    std::vector<std::string> parts;
    size_t first = 0;
    while (true) {
      const size_t slash = word.find('/', first);
      parts.push_back(word.substr(first, slash - first));
      if (slash == std::string::npos) break;
      first = slash + 1;
    }
    long index = 0, other = 0;
    if (parts.size() > 3 || !is_integer(parts[0], index)) return 0;
    if (parts.size() == 2 && !is_integer(parts[1], other)) return 0;    // a/t
    if (parts.size() == 3) {                                            // a/t/n or a//n
      if (!parts[1].empty() && !is_integer(parts[1], other)) return 0;
      if (!is_integer(parts[2], other)) return 0;
    }
    return index;
  }

}    // namespace

TriangleMesh parse_obj(const std::string &text, const std::string &filename)
{
  TriangleMesh mesh;
  std::vector<std::array<long, 3>> raw;    // file indices (1-based), resolved at the end
  int lineno = 0;
  size_t pos = 0;
  while (pos < text.size()) {
    size_t eol = text.find('\n', pos);
    if (eol == std::string::npos) eol = text.size();
    const std::string line = text.substr(pos, eol - pos);
    pos = eol + 1;
    lineno++;

    const auto words = words_of(line);
    if (words.empty()) continue;

    if (words[0] == "v") {
      std::array<double, 3> x{};
      if (words.size() < 4)
        fail(filename, lineno, "a vertex needs three coordinates (v x y z), got '" + line + "'");
      for (size_t k = 1; k < words.size(); k++) {
        double value = 0.0;
        if (!is_number(words[k], value))
          fail(filename, lineno,
               "vertex coordinate '" + words[k] + "' is not a finite number in '" + line + "'");
        if (k <= 3) x[k - 1] = value;    // w or a colour after them: checked, not kept
      }
      mesh.vertices.push_back(x);
      mesh.vertex_line.push_back(lineno);

    } else if (words[0] == "f") {
      if (words.size() < 4)
        fail(filename, lineno,
             "a face needs at least three vertex indices (f a b c), got '" + line + "'");
      std::vector<long> face;
      for (size_t k = 1; k < words.size(); k++) {
        long index = vertex_index(words[k]);
        if (index == 0)
          fail(filename, lineno,
               "face vertex '" + words[k] +
                   "' is not a vertex index (a nonzero integer, as a, a/t, a//n or a/t/n)");
        if (index < 0) {    // relative to the vertices read so far
          const long absolute = (long) mesh.vertices.size() + 1 + index;
          if (absolute < 1)
            fail(filename, lineno,
                 "face vertex index " + std::to_string(index) + " is out of range: only " +
                     std::to_string(mesh.vertices.size()) + " vertices are defined before it");
          index = absolute;
        }
        face.push_back(index);
      }
      for (size_t k = 1; k + 1 < face.size(); k++) {
        raw.push_back({face[0], face[k], face[k + 1]});
        mesh.triangle_line.push_back(lineno);
      }
    }
  }

  const long nvertex = (long) mesh.vertices.size();
  mesh.triangles.resize(raw.size());
  for (size_t t = 0; t < raw.size(); t++) {
    for (int c = 0; c < 3; c++) {
      if (raw[t][c] > nvertex)
        fail(filename, mesh.triangle_line[t],
             "face vertex index " + std::to_string(raw[t][c]) + " is out of range: the file has " +
                 std::to_string(nvertex) + " vertices");
      mesh.triangles[t][c] = (int) (raw[t][c] - 1);
    }
  }
  return mesh;
}

TriangleMesh read_obj_file(const std::string &filename)
{
  FILE *fp = fopen(filename.c_str(), "rb");
  if (!fp)
    throw std::runtime_error("cannot open mesh file " + filename + ": " + std::strerror(errno));
  std::string text;
  char chunk[65536];
  size_t n;
  while ((n = fread(chunk, 1, sizeof(chunk), fp)) > 0) text.append(chunk, n);
  fclose(fp);
  return parse_obj(text, filename);
}

}    // namespace PeriSISSM
