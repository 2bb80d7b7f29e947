#include "scene/ply_check.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <vector>

#include "scene/load.h"

namespace tuneray {

namespace {

struct Property {
  std::string name;
  int size = 0;        // bytes of a scalar, or of each list item
  int count_size = 0;  // > 0 for lists: bytes of the item count
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> properties;
};

int type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32")
    return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

uint64_t read_unsigned(const char* p, int size, bool big_endian) {
  uint64_t v = 0;
  for (int i = 0; i < size; ++i) {
    int byte = big_endian ? i : size - 1 - i;
    v = (v << 8) | static_cast<unsigned char>(p[byte]);
  }
  return v;
}

// An ASCII body must hold, element by element, one number per scalar property and a count
// followed by that many numbers per list, with face indices in range: assimp leaks on short or
// mangled bodies (found by fuzz/fuzz_mesh).
template <class Fail>
void check_ascii_body(const std::string& body, const std::vector<Element>& elements,
                      const Fail& fail) {
  std::istringstream in(body);
  auto number = [&](const Element& e, uint64_t i) {
    std::string token;
    if (!(in >> token)) fail("file ends inside element '" + e.name + "' " + std::to_string(i));
    char* end = nullptr;
    const double v = std::strtod(token.c_str(), &end);
    if (end != token.c_str() + token.size() || !std::isfinite(v))
      fail("'" + token + "' is not a number (element '" + e.name + "' " + std::to_string(i) + ")");
    return v;
  };
  uint64_t vertex_count = 0;
  for (const Element& e : elements) {
    if (e.name == "vertex") vertex_count = e.count;
    for (uint64_t i = 0; i < e.count; ++i)
      for (const Property& p : e.properties) {
        if (p.count_size == 0) {
          number(e, i);
          continue;
        }
        const double items = number(e, i);
        if (items < 0 || items > 1e6 || items != std::floor(items))
          fail("bad list length in element '" + e.name + "' " + std::to_string(i));
        for (int k = 0; k < static_cast<int>(items); ++k) {
          const double index = number(e, i);
          if (e.name == "face" && (index < 0 || index >= static_cast<double>(vertex_count)))
            fail("face " + std::to_string(i) + " has a vertex index out of range");
        }
      }
  }
}

}  // namespace

void check_ply_file(const std::string& path) {
  auto fail = [&](const std::string& what) { throw SceneError(path + ": malformed PLY: " + what); };
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open file");
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t header_end = data.find("\nend_header");
  if (data.rfind("ply", 0) != 0 || header_end == std::string::npos || header_end > (1 << 20))
    fail("header missing 'ply' or 'end_header'");
  // The end_header line holds nothing else: assimp looped forever on "end_headersss..." (found
  // by fuzz/fuzz_mesh).
  const size_t line_end = data.find('\n', header_end + 1);
  const std::string end_line = data.substr(
      header_end + 1, (line_end == std::string::npos ? data.size() : line_end) - header_end - 1);
  if (end_line.find_first_not_of(" \t\r", std::string("end_header").size()) != std::string::npos)
    fail("bad end_header line '" + end_line.substr(0, 80) + "'");

  // Every header line is one of the PLY keywords with exactly its words: assimp accepts
  // mangled headers and then leaks or misreads (found by fuzz/fuzz_mesh).
  std::istringstream header(data.substr(0, header_end));
  std::string line, format;
  std::vector<Element> elements;
  while (std::getline(header, line)) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "ply") {
    } else if (keyword == "format") {
      std::string version;
      if (!(words >> format >> version)) fail("bad format line '" + line + "'");
    } else if (keyword == "element") {
      Element e;
      if (!(words >> e.name >> e.count)) fail("bad element line '" + line + "'");
      elements.push_back(e);
    } else if (keyword == "property") {
      if (elements.empty()) fail("property before any element");
      std::string type;
      Property p;
      words >> type;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type;
        p.count_size = type_size(count_type);
        p.size = type_size(item_type);
        if (p.count_size == 0 || p.size == 0) fail("bad list property '" + line + "'");
      } else {
        p.size = type_size(type);
        if (p.size == 0) fail("unknown property type '" + type + "'");
      }
      if (!(words >> p.name)) fail("property without a name: '" + line + "'");
      elements.back().properties.push_back(p);
    } else {
      fail("unknown header line '" + line + "'");
    }
    std::string extra;
    if (words >> extra) fail("unexpected '" + extra + "' in header line '" + line + "'");
  }
  size_t pos = line_end;
  if (pos == std::string::npos) fail("no data after the header");
  ++pos;
  if (format == "ascii") return check_ascii_body(data.substr(pos), elements, fail);
  if (format != "binary_little_endian" && format != "binary_big_endian")
    fail("unknown format '" + format + "'");
  const bool big = format == "binary_big_endian";

  uint64_t vertex_count = 0;
  for (const Element& e : elements) {
    if (e.name == "vertex") vertex_count = e.count;
    for (uint64_t i = 0; i < e.count; ++i)
      for (const Property& p : e.properties) {
        uint64_t items = 1;
        if (p.count_size > 0) {
          if (pos + p.count_size > data.size()) fail("file ends inside element '" + e.name + "'");
          items = read_unsigned(&data[pos], p.count_size, big);
          pos += p.count_size;
        }
        if (items * p.size > data.size() - pos) fail("file ends inside element '" + e.name + "'");
        if (e.name == "face" && p.count_size > 0)
          for (uint64_t k = 0; k < items; ++k)
            if (read_unsigned(&data[pos + k * p.size], p.size, big) >= vertex_count)
              fail("face " + std::to_string(i) + " has a vertex index out of range");
        pos += items * p.size;
      }
  }
}

}  // namespace tuneray
