#include "common/mesh/ply_reader.hpp"

#include "common/base/errors.hpp"

#include <bit>
#include <cctype>
#include <cstdlib>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <sstream>

namespace physarum {
namespace {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

PlyType parse_type(const std::string& name, const std::string& path) {
  if (name == "char" || name == "int8") return PlyType::Int8;
  if (name == "uchar" || name == "uint8") return PlyType::UInt8;
  if (name == "short" || name == "int16") return PlyType::Int16;
  if (name == "ushort" || name == "uint16") return PlyType::UInt16;
  if (name == "int" || name == "int32") return PlyType::Int32;
  if (name == "uint" || name == "uint32") return PlyType::UInt32;
  if (name == "float" || name == "float32") return PlyType::Float32;
  if (name == "double" || name == "float64") return PlyType::Float64;
  throw InputError(path + ": unknown PLY property type '" + name + "'");
}

size_t type_size(PlyType t) {
  switch (t) {
    case PlyType::Int8:
    case PlyType::UInt8: return 1;
    case PlyType::Int16:
    case PlyType::UInt16: return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
  }
  return 0;
}

enum class PlyFormat { BinaryLittleEndian, BinaryBigEndian, Ascii };

// Binary bytes in the file's byte order to a value, whatever the host's byte order.
double decode(const unsigned char* p, PlyType t, bool big_endian) {
  const size_t size = type_size(t);
  std::uint64_t bits = 0;
  for (size_t b = 0; b < size; ++b) bits |= static_cast<std::uint64_t>(p[big_endian ? size - 1 - b : b]) << (8 * b);
  switch (t) {
    case PlyType::Int8: return static_cast<std::int8_t>(bits);
    case PlyType::UInt8: return static_cast<std::uint8_t>(bits);
    case PlyType::Int16: return static_cast<std::int16_t>(bits);
    case PlyType::UInt16: return static_cast<std::uint16_t>(bits);
    case PlyType::Int32: return static_cast<std::int32_t>(bits);
    case PlyType::UInt32: return static_cast<std::uint32_t>(bits);
    case PlyType::Float32: return std::bit_cast<float>(static_cast<std::uint32_t>(bits));
    case PlyType::Float64: return std::bit_cast<double>(bits);
  }
  return 0.0;
}

struct ScalarProperty {
  std::string name;
  PlyType type;
};

struct Element {
  std::string name;
  long long count = 0;
  std::vector<ScalarProperty> scalars;
  bool has_list = false;
  size_t scalars_before_list = 0;  // scalar properties declared before the list
  PlyType list_count_type = PlyType::UInt8, list_item_type = PlyType::Int32;
};

const std::vector<double>& named_column(const std::map<std::string, std::vector<double>>& columns,
                                        const std::vector<std::string>& names, const std::string& name,
                                        const std::string& source, const char* element) {
  const auto it = columns.find(name);
  if (it != columns.end()) return it->second;
  std::string known;
  for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
  throw InputError(source + ": no " + element + " property '" + name + "' (it has: " + (known.empty() ? "none" : known) +
                   ")");
}

// One "property" line of the header, added to the element it follows.
void parse_property(std::stringstream& words, Element& e, const std::string& path) {
  std::string type;
  words >> type;
  if (type == "list") {
    std::string count_type, item_type, name;
    words >> count_type >> item_type >> name;
    if (e.has_list) throw InputError(path + ": element '" + e.name + "' has more than one list property");
    e.has_list = true;
    e.scalars_before_list = e.scalars.size();
    e.list_count_type = parse_type(count_type, path);
    e.list_item_type = parse_type(item_type, path);
  } else {
    std::string name;
    words >> name;
    e.scalars.push_back({name, parse_type(type, path)});
  }
}

struct Header {
  PlyFormat format = PlyFormat::BinaryLittleEndian;
  std::vector<Element> elements;
};

// The format and the elements the header (everything before "end_header") declares, with their properties.
Header parse_header(const std::string& header_text, const std::string& path) {
  Header parsed;
  std::vector<Element>& elements = parsed.elements;
  std::stringstream header(header_text);
  for (std::string line; std::getline(header, line);) {
    std::stringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "format") {
      std::string format;
      words >> format;
      if (format == "binary_little_endian") parsed.format = PlyFormat::BinaryLittleEndian;
      else if (format == "binary_big_endian") parsed.format = PlyFormat::BinaryBigEndian;
      else if (format == "ascii") parsed.format = PlyFormat::Ascii;
      else throw InputError(path + ": PLY format '" + format + "' is not one of ascii, binary_little_endian, binary_big_endian");
    } else if (keyword == "element") {
      Element e;
      words >> e.name >> e.count;
      if (e.count < 0) throw InputError(path + ": negative count for element '" + e.name + "'");
      elements.push_back(e);
    } else if (keyword == "property") {
      if (elements.empty()) throw InputError(path + ": property before any element");
      parse_property(words, elements.back(), path);
    }
  }
  return parsed;
}

// The body being read: the file's bytes, its format and the read position. next() reads one value
// of a type: its bytes in a binary body, one whitespace-separated number in an ASCII one.
struct Body {
  const std::string& path;
  const std::string& bytes;
  PlyFormat format;
  size_t at;

  double next(PlyType t) {
    // A value declared float is a float whichever way it is written: an ASCII number is rounded to
    // float as a binary file would have stored it.
    if (format == PlyFormat::Ascii) return t == PlyType::Float32 ? static_cast<float>(next_word()) : next_word();
    const size_t size = type_size(t);
    if (at + size > bytes.size()) throw InputError(path + ": file ends early (truncated body)");
    const double value = decode(reinterpret_cast<const unsigned char*>(bytes.data()) + at, t, format == PlyFormat::BinaryBigEndian);
    at += size;
    return value;
  }

  // Past the last element: nothing but (in ASCII) white space.
  bool at_end() {
    if (format == PlyFormat::Ascii) skip_space();
    return at == bytes.size();
  }

 private:
  void skip_space() {
    while (at < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[at]))) ++at;
  }

  double next_word() {
    skip_space();
    const size_t start = at;
    while (at < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[at]))) ++at;
    if (start == at) throw InputError(path + ": file ends early (truncated body)");
    const std::string word = bytes.substr(start, at - start);
    char* end = nullptr;
    const double value = std::strtod(word.c_str(), &end);
    if (end != word.c_str() + word.size())
      throw InputError(path + ": '" + word + "' at byte " + std::to_string(start) + " is not a number");
    return value;
  }
};

void read_vertices(const Element& e, Body& body, PlyFields& result) {
  const std::string& path = body.path;
  if (e.has_list) throw InputError(path + ": list properties on vertices are not read");
  int xyz[3] = {-1, -1, -1};
  std::vector<std::vector<double>*> columns;
  for (size_t p = 0; p < e.scalars.size(); ++p) {
    const std::string& n = e.scalars[p].name;
    if (n == "x" || n == "y" || n == "z") {
      xyz[n[0] - 'x'] = static_cast<int>(p);
      columns.push_back(nullptr);
    } else {
      result.property_names.push_back(n);
      columns.push_back(&result.properties[n]);
    }
  }
  if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0) throw InputError(path + ": vertices lack x, y or z");
  result.mesh.positions.resize(static_cast<size_t>(e.count));
  for (auto* c : columns)
    if (c) c->reserve(static_cast<size_t>(e.count));
  for (long long v = 0; v < e.count; ++v) {
    for (size_t p = 0; p < e.scalars.size(); ++p) {
      const double value = body.next(e.scalars[p].type);
      if (columns[p])
        columns[p]->push_back(value);
      else
        result.mesh.positions[static_cast<size_t>(v)][e.scalars[p].name[0] - 'x'] = value;
    }
  }
}

// One face's vertex-index list, which must be a triangle of existing vertices.
std::array<int, 3> read_triangle(const Element& e, Body& body, long long f, size_t vertex_count) {
  const std::string& path = body.path;
  const double corners = body.next(e.list_count_type);
  if (corners != 3) throw InputError(path + ": face " + std::to_string(f) + " is not a triangle");
  std::array<int, 3> t{};
  for (int c = 0; c < 3; ++c) {
    const double index = body.next(e.list_item_type);
    if (index < 0 || index >= static_cast<double>(vertex_count))
      throw InputError(path + ": face " + std::to_string(f) + " has vertex index " +
                       std::to_string(static_cast<long long>(index)) + " out of range");
    t[c] = static_cast<int>(index);
  }
  return t;
}

void read_faces(const Element& e, Body& body, PlyFields& result) {
  const std::string& path = body.path;
  if (!e.has_list) throw InputError(path + ": faces must have a list property (vertex indices)");
  // Where the list sits among the scalars: the header lists it in order, but this reader keeps
  // scalars and the list apart, so they are read in the order the header gave them.
  std::vector<std::vector<double>*> columns;
  for (const ScalarProperty& p : e.scalars) {
    if (result.face_properties.count(p.name) > 0) throw InputError(path + ": face property '" + p.name + "' appears twice");
    result.face_property_names.push_back(p.name);
    columns.push_back(&result.face_properties[p.name]);
    columns.back()->reserve(static_cast<size_t>(e.count));
  }
  result.mesh.triangles.reserve(static_cast<size_t>(e.count));
  auto read_scalars = [&](size_t from, size_t to) {
    for (size_t p = from; p < to; ++p) columns[p]->push_back(body.next(e.scalars[p].type));
  };
  for (long long f = 0; f < e.count; ++f) {
    read_scalars(0, e.scalars_before_list);
    result.mesh.triangles.push_back(read_triangle(e, body, f, result.mesh.positions.size()));
    read_scalars(e.scalars_before_list, e.scalars.size());
  }
}

}  // namespace

const std::vector<double>& PlyFields::property(const std::string& name) const {
  return named_column(properties, property_names, name, mesh.source, "vertex");
}

const std::vector<double>& PlyFields::face_property(const std::string& name) const {
  return named_column(face_properties, face_property_names, name, mesh.source, "face");
}

PlyFields read_ply_fields(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // Lines end in LF or CR LF (files written on Windows).
  const size_t end = bytes.find("end_header");
  const size_t body_start = end == std::string::npos ? end : bytes.find('\n', end);
  if ((bytes.rfind("ply\n", 0) != 0 && bytes.rfind("ply\r\n", 0) != 0) || body_start == std::string::npos)
    throw InputError(path + ": not a PLY file");
  const Header header = parse_header(bytes.substr(0, end), path);

  PlyFields result;
  result.mesh.source = path;
  Body body{path, bytes, header.format, body_start + 1};
  for (const Element& e : header.elements) {
    if (e.name == "vertex") {
      read_vertices(e, body, result);
    } else if (e.name == "face") {
      read_faces(e, body, result);
    } else {
      throw InputError(path + ": element '" + e.name + "' is not read (only vertex and face)");
    }
  }
  if (!body.at_end()) throw InputError(path + ": unexpected bytes after the last element");
  result.mesh.file_vertex.resize(result.mesh.positions.size());
  for (size_t v = 0; v < result.mesh.file_vertex.size(); ++v) result.mesh.file_vertex[v] = static_cast<int>(v);
  return result;
}

}  // namespace physarum
