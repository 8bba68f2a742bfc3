// OpenMesh drives its format parsers through the BaseImporter interface; our importer only records
// what the parser reports (positions, polygons, texture coordinates) into a PolygonSoup.
#include "common/mesh/mesh_file_reader.hpp"

#include "common/base/errors.hpp"

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <string_view>
#include <filesystem>
#include <fstream>
#include <map>
#include <new>
#include <optional>
#include <regex>
#include <sstream>

namespace physarum {

namespace {

using OpenMesh::EdgeHandle;
using OpenMesh::FaceHandle;
using OpenMesh::HalfedgeHandle;
using OpenMesh::VertexHandle;

// Records the soup. Everything a parser may report that we do not need (normals, colors, status,
// halfedge connectivity) is accepted and ignored.
class SoupImporter final : public OpenMesh::IO::BaseImporter {
 public:
  PolygonSoup soup;
  std::vector<std::optional<Eigen::Vector2d>> vertex_uv;          // PLY/OFF style: one per vertex
  std::vector<std::vector<Eigen::Vector2d>> polygon_corner_uvs;  // OBJ style: per face corner

  VertexHandle add_vertex(const OpenMesh::Vec3f& p) override { return add_vertex(OpenMesh::Vec3d(p)); }
  VertexHandle add_vertex(const OpenMesh::Vec3d& p) override {
    soup.positions.emplace_back(p[0], p[1], p[2]);
    vertex_uv.emplace_back();
    return VertexHandle(static_cast<int>(soup.positions.size()) - 1);
  }
  VertexHandle add_vertex() override { return add_vertex(OpenMesh::Vec3d(0, 0, 0)); }
  HalfedgeHandle add_edge(VertexHandle, VertexHandle) override { return HalfedgeHandle(); }

  FaceHandle add_face(const VHandles& corners) override {
    std::vector<int> ids(corners.size());
    std::transform(corners.begin(), corners.end(), ids.begin(), [](VertexHandle v) { return v.idx(); });
    soup.add_polygon(ids);
    polygon_corner_uvs.emplace_back();
    return FaceHandle(soup.polygon_count() - 1);
  }
  FaceHandle add_face(HalfedgeHandle) override { return FaceHandle(); }

  void add_face_texcoords(FaceHandle f, VertexHandle, const std::vector<OpenMesh::Vec2f>& uv) override {
    if (!f.is_valid() || f.idx() >= soup.polygon_count()) return;
    auto& corners = polygon_corner_uvs[f.idx()];
    corners.clear();
    for (const auto& t : uv) corners.emplace_back(t[0], t[1]);
  }
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec3f>&) override {}
  void set_texcoord(VertexHandle v, const OpenMesh::Vec2f& t) override {
    if (v.is_valid() && v.idx() < static_cast<int>(vertex_uv.size())) vertex_uv[v.idx()] = Eigen::Vector2d(t[0], t[1]);
  }
  void set_texcoord(HalfedgeHandle, const OpenMesh::Vec2f&) override {}
  void set_texcoord(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_texcoord(HalfedgeHandle, const OpenMesh::Vec3f&) override {}
  void set_point(VertexHandle v, const OpenMesh::Vec3f& p) override {
    if (v.is_valid() && v.idx() < static_cast<int>(soup.positions.size())) soup.positions[v.idx()] = Eigen::Vector3d(p[0], p[1], p[2]);
  }

  void set_face_texindex(FaceHandle, int) override {}
  void set_halfedge(VertexHandle, HalfedgeHandle) override {}
  void set_normal(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_normal(VertexHandle, const OpenMesh::Vec3d&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec4f&) override {}
  void set_status(VertexHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_next(HalfedgeHandle, HalfedgeHandle) override {}
  void set_face(HalfedgeHandle, FaceHandle) override {}
  void request_face_texcoords2D() override {}
  void set_status(HalfedgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec3f&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec4f&) override {}
  void set_status(EdgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3f&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3d&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec3f&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec4f&) override {}
  void set_status(FaceHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void add_texture_information(int, std::string) override {}

  void reserve(unsigned int vertices, unsigned int, unsigned int faces) override {
    soup.positions.reserve(vertices);
    vertex_uv.reserve(vertices);
    soup.polygon_start.reserve(size_t{faces} + 1);
    polygon_corner_uvs.reserve(faces);
  }
  size_t n_vertices() const override { return soup.positions.size(); }
  size_t n_faces() const override { return static_cast<size_t>(soup.polygon_count()); }
  size_t n_edges() const override { return 0; }

  // Chooses the texture coordinates: per-corner ones (OBJ "vt" indices, which may differ between
  // the faces around a vertex along a seam) when every polygon has them, else per-vertex ones when
  // every used vertex has one, else none. Partial texture coordinates cannot be baked onto.
  void finish_texcoords() {
    const int polygons = soup.polygon_count();
    if (polygons == 0) return;
    const bool per_corner = std::all_of(polygon_corner_uvs.begin(), polygon_corner_uvs.end(), [&](const auto& c) { return !c.empty(); }) &&
                            [&] {
                              for (int p = 0; p < polygons; ++p)
                                if (static_cast<int>(polygon_corner_uvs[p].size()) != soup.polygon_size(p)) return false;
                              return true;
                            }();
    if (per_corner) {
      // Identical coordinates share one entry, so a UV island keeps its connectivity.
      std::map<std::pair<double, double>, int> index_of;
      soup.corner_uv.reserve(soup.corner_vertex.size());
      for (const auto& corners : polygon_corner_uvs)
        for (const Eigen::Vector2d& t : corners) {
          auto [it, inserted] = index_of.try_emplace({t.x(), t.y()}, static_cast<int>(soup.uvs.size()));
          if (inserted) soup.uvs.push_back(t);
          soup.corner_uv.push_back(it->second);
        }
      return;
    }
    const int n = static_cast<int>(soup.positions.size());
    for (int v : soup.corner_vertex)
      if (v < 0 || v >= n || !vertex_uv[v]) return;
    soup.uvs.resize(n, Eigen::Vector2d::Zero());
    for (int v = 0; v < n; ++v)
      if (vertex_uv[v]) soup.uvs[v] = *vertex_uv[v];
    soup.corner_uv = soup.corner_vertex;
  }
};

// OpenMesh reports parse problems on its own streams (omerr goes to std::cerr, omout to
// std::cout); we report them ourselves as InputError, and standard output must stay clean for
// --json, so its streams are muted while a reader runs.
class MutedOpenMeshStreams {
 public:
  MutedOpenMeshStreams() : log_(::omlog().is_enabled()), out_(::omout().is_enabled()), err_(::omerr().is_enabled()) {
    ::omlog().disable();
    ::omout().disable();
    ::omerr().disable();
  }
  ~MutedOpenMeshStreams() {
    if (log_) ::omlog().enable();
    if (out_) ::omout().enable();
    if (err_) ::omerr().enable();
  }
  MutedOpenMeshStreams(const MutedOpenMeshStreams&) = delete;
  MutedOpenMeshStreams& operator=(const MutedOpenMeshStreams&) = delete;

 private:
  bool log_, out_, err_;
};

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// The first word of a line that parses completely as a non-finite number ("nan", "inf", "1e999"),
// or "".
std::string find_non_finite_number_in(const std::string& line) {
  std::istringstream words(line);
  std::string word;
  while (words >> word) {
    char* end = nullptr;
    const double x = std::strtod(word.c_str(), &end);
    if (end == word.c_str() + word.size() && !std::isfinite(x)) return word;
  }
  return "";
}

std::string read_whole_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Calls visit(line_number, line) for every line of `text`.
template <class Visit>
void for_each_line(const std::string& text, Visit visit) {
  size_t begin = 0;
  for (int number = 1; begin < text.size(); ++number) {
    size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    visit(number, std::string_view(text).substr(begin, end - begin));
    begin = end + 1;
  }
}

std::string_view trim_left(std::string_view line) {
  while (!line.empty() && std::isspace(static_cast<unsigned char>(line.front()))) line.remove_prefix(1);
  return line;
}

bool starts_with_keyword(std::string_view line, std::string_view keyword) {
  return line.size() > keyword.size() && line.starts_with(keyword) && std::isspace(static_cast<unsigned char>(line[keyword.size()]));
}

// OpenMesh's OBJ reader silently skips a "v" line whose numbers it cannot parse (which shifts every
// later vertex index) and silently removes repeated corners from "f" lines (dropping the face when
// fewer than three remain). Scanning the lines ourselves turns the first into a clear error and the
// second into a warning.
void check_obj_lines(const std::string& path, PolygonSoup& soup) {
  const std::string text = read_whole_file(path);
  int vertex_lines = 0, faces_with_repeats = 0, first_face_with_repeats = -1, face_lines = 0;
  std::vector<long> corners;
  for_each_line(text, [&](int, std::string_view raw) {
    const std::string_view line = trim_left(raw);
    if (starts_with_keyword(line, "v")) {
      ++vertex_lines;
    } else if (starts_with_keyword(line, "f")) {
      corners.clear();
      std::istringstream words{std::string(line.substr(1))};
      std::string word;
      while (words >> word) corners.push_back(std::strtol(word.c_str(), nullptr, 10));
      std::sort(corners.begin(), corners.end());
      if (std::adjacent_find(corners.begin(), corners.end()) != corners.end() && faces_with_repeats++ == 0)
        first_face_with_repeats = face_lines;
      ++face_lines;
    }
  });
  if (vertex_lines != static_cast<int>(soup.positions.size())) {
    int vertex = 0;
    std::string message;
    for_each_line(text, [&](int number, std::string_view raw) {
      const std::string_view line = trim_left(raw);
      if (!message.empty() || !starts_with_keyword(line, "v")) return;
      std::istringstream words{std::string(line.substr(1))};
      float x, y, z;
      if (!(words >> x >> y >> z)) {
        const bool non_finite = !find_non_finite_number_in(std::string(line.substr(1))).empty();
        message = path + ": line " + std::to_string(number) + ": vertex " + std::to_string(vertex) + " has " +
                  (non_finite ? "a non-finite coordinate" : "coordinates that cannot be read") + ": '" + std::string(line) + "'";
      }
      ++vertex;
    });
    throw InputError(message.empty() ? path + ": the obj reader skipped some vertex lines" : message);
  }
  if (faces_with_repeats > 0)
    soup.warnings.push_back(std::to_string(faces_with_repeats) + (faces_with_repeats == 1 ? " face lists" : " faces list") +
                            " a vertex more than once (the first is face " + std::to_string(first_face_with_repeats) +
                            "); the repeats were removed, and faces left with fewer than three corners dropped");
}

// OpenMesh's OBJ reader aborts (an assert in the library) on a face corner without a vertex index
// ("f /1 2/2 3/3") or a face line without corners: refuse such a line before the reader sees it.
void check_obj_face_corners(const std::string& path) {
  const std::string text = read_whole_file(path);
  std::string message;
  for_each_line(text, [&](int number, std::string_view raw) {
    const std::string_view line = trim_left(raw);
    if (!message.empty() || !starts_with_keyword(line, "f")) return;
    int corners = 0;
    for (size_t i = 1; i < line.size();) {
      while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      if (i == line.size()) break;
      const size_t word = i;
      while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      ++corners;
      size_t digit = word;
      while (digit < i && line[digit] == '-') ++digit;
      if (digit < i && std::isdigit(static_cast<unsigned char>(line[digit]))) continue;
      message = path + ": line " + std::to_string(number) + ": face corner '" + std::string(line.substr(word, i - word)) +
                "' does not start with a vertex index: '" + std::string(line) + "'";
      return;
    }
    if (corners == 0) message = path + ": line " + std::to_string(number) + ": face without corners: '" + std::string(line) + "'";
  });
  if (!message.empty()) throw InputError(message);
}

// OpenMesh's PLY reader, given a header it does not understand (an unknown keyword or type) or an
// element count far beyond the file, reads for minutes and then runs out of memory. Check the
// header first: known keywords and types only, and no element with more entries than bytes follow.
void check_ply_header(const std::string& path) {
  const std::string text = read_whole_file(path);
  static const std::vector<std::string> types{"char",  "uchar",  "short",  "ushort", "int",   "uint",
                                              "float", "double", "int8",   "uint8",  "int16", "uint16",
                                              "int32", "uint32", "float32", "float64"};
  const auto is_type = [](const std::string& t) { return std::find(types.begin(), types.end(), t) != types.end(); };
  size_t begin = 0;
  std::vector<std::pair<std::string, long long>> elements;
  std::vector<double> properties;  // per element
  bool ascii = false;
  for (int number = 1; begin < text.size(); ++number) {
    size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(begin, end - begin);
    begin = end + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto bad = [&](const std::string& why) {
      throw InputError(path + ": line " + std::to_string(number) + " of the PLY header: " + why + ": '" + line + "'");
    };
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (number == 1) {
      if (keyword != "ply") return;  // not a PLY file at all: OpenMesh's reader says so
      continue;
    }
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "end_header") {
      const double follow = static_cast<double>(text.size() - std::min(begin, text.size()));
      double least_numbers = 0.0;  // every property one number at least (a list its length)
      for (size_t e = 0; e < elements.size(); ++e) {
        const auto& [name, count] = elements[e];
        if (static_cast<double>(count) > follow)
          throw InputError(path + ": PLY element '" + name + "' claims " + std::to_string(count) + " entries but only " +
                           std::to_string(static_cast<long long>(follow)) + " bytes follow the header");
        least_numbers += static_cast<double>(count) * properties[e];
      }
      if (ascii) {
        // Every word of an ASCII body is a number; OpenMesh's reader spins on one that is not.
        std::istringstream body(text.substr(std::min(begin, text.size())));
        std::string word;
        double numbers = 0.0;
        while (body >> word) {
          char* stop = nullptr;
          std::strtod(word.c_str(), &stop);
          if (stop == word.c_str() || *stop != '\0')
            throw InputError(path + ": the PLY body holds '" + word + "', which is not a number");
          ++numbers;
        }
        if (numbers < least_numbers)
          throw InputError(path + ": the PLY body ends early: " + std::to_string(static_cast<long long>(numbers)) +
                           " numbers where the header needs at least " +
                           std::to_string(static_cast<long long>(least_numbers)));
      }
      return;
    }
    if (keyword == "format") {
      std::string format, version;
      if (!(words >> format >> version) || version != "1.0" ||
          (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian"))
        bad("unknown format (ascii, binary_little_endian or binary_big_endian, version 1.0)");
      ascii = format == "ascii";
    } else if (keyword == "element") {
      std::string name, count;
      if (!(words >> name >> count) || count.find_first_not_of("0123456789") != std::string::npos || count.size() > 18)
        bad("an element needs a name and a count");
      elements.emplace_back(name, std::stoll(count));
      properties.push_back(0.0);
    } else if (keyword == "property") {
      std::string type, a, b;
      if (!(words >> type >> a)) bad("a property needs a type and a name");
      if (type == "list" ? !(is_type(a) && (words >> b) && is_type(b) && (words >> b)) : !is_type(type))
        bad("unknown property type");
      if (elements.empty()) bad("a property before any element");
      properties.back() += 1.0;
    } else {
      bad("unknown header keyword");
    }
  }
  throw InputError(path + ": the PLY header has no end_header line");
}

// OpenMesh's OFF reader takes a negative corner count as a huge one and allocates until the machine
// runs out of memory. Check an ASCII OFF's structure first: counts no larger than the file, then
// each face line a corner count k >= 1 followed by k vertex indices. (Binary OFF: not checked.)
void check_off_structure(const std::string& path) {
  const std::string text = read_whole_file(path);
  std::vector<std::pair<int, std::string>> lines;  // (number, content) without comments and blank lines
  for_each_line(text, [&](int number, std::string_view raw) {
    std::string line(raw.substr(0, raw.find('#')));
    if (line.find_first_not_of(" \t\r") != std::string::npos) lines.emplace_back(number, std::move(line));
  });
  if (lines.empty()) return;  // OpenMesh's own message
  for (size_t i = 0; i < std::min<size_t>(lines.size(), 2); ++i)
    for (const char c : lines[i].second)
      if (std::iscntrl(static_cast<unsigned char>(c)) && c != '\t' && c != '\r')
        throw InputError(path + ": line " + std::to_string(lines[i].first) +
                         ": the OFF header holds a control character (byte " +
                         std::to_string(static_cast<unsigned char>(c)) + ")");
  std::istringstream header(lines[0].second);
  std::string keyword;
  header >> keyword;
  // The header keywords OFF files use ([ST][C][N][4][n]OFF); OpenMesh's reader hangs on some others
  // that start like one ("OFFX" followed by one count).
  static const std::regex off_keyword("(ST)?C?N?4?n?OFF");
  if (!std::regex_match(keyword, off_keyword))
    throw InputError(path + ": line " + std::to_string(lines[0].first) + ": '" + keyword +
                     "' is not an OFF header (OFF, COFF, NOFF, STOFF, 4OFF, ...)");
  std::string word;
  const bool binary = (header >> word) && word == "BINARY";
  if (binary) return;  // binary data follows: no lines to check
  size_t next = 1;
  std::vector<std::string> counts;
  if (!word.empty()) counts.push_back(word);
  while (header >> word) counts.push_back(word);
  if (counts.empty() && next < lines.size()) {
    std::istringstream second(lines[next++].second);
    while (second >> word) counts.push_back(word);
  }
  const auto count_of = [&](size_t i, const char* what) -> long long {
    if (i >= counts.size() || counts[i].empty() || counts[i].size() > 18 ||
        counts[i].find_first_not_of("0123456789") != std::string::npos)
      throw InputError(path + ": the OFF header needs non-negative vertex and face counts (" + what + ")");
    const long long n = std::stoll(counts[i]);
    if (static_cast<double>(n) > static_cast<double>(text.size()))
      throw InputError(path + ": the OFF header claims " + std::to_string(n) + " " + what + " in a file of " +
                       std::to_string(text.size()) + " bytes");
    return n;
  };
  const long long vertices = count_of(0, "vertices"), faces = count_of(1, "faces");
  next += static_cast<size_t>(vertices);
  for (long long f = 0; f < faces; ++f, ++next) {
    if (next >= lines.size())
      throw InputError(path + ": the OFF file ends after " + std::to_string(f) + " of its " + std::to_string(faces) +
                       " faces");
    std::istringstream in(lines[next].second);
    long long k = -1;
    std::vector<long long> corners;
    long long index = 0;
    const bool counted = static_cast<bool>(in >> k);
    for (long long c = 0; counted && c < k && in >> index; ++c) corners.push_back(index);
    // (Indices out of range are the mesh checks' to name, after reading.)
    if (!counted || k < 1 || static_cast<long long>(corners.size()) != k)
      throw InputError(path + ": line " + std::to_string(lines[next].first) +
                       ": a face needs a corner count k >= 1 followed by k vertex indices: '" + lines[next].second + "'");
  }
}

}  // namespace

std::string find_non_finite_number(const std::string& path) {
  const std::string text = read_whole_file(path);
  std::string found;
  for_each_line(text, [&](int number, std::string_view line) {
    if (!found.empty() || line.find('\0') != std::string_view::npos) return;  // binary data from here on
    if (const std::string word = find_non_finite_number_in(std::string(line)); !word.empty())
      found = "line " + std::to_string(number) + ": non-finite number '" + word + "'";
  });
  return found;
}

const std::vector<std::string>& supported_mesh_extensions() {
  static const std::vector<std::string> extensions{".obj", ".off", ".ply", ".stl"};
  return extensions;
}

PolygonSoup read_polygon_soup(const std::string& path) {
  const std::string ext = lower_extension(path);
  const auto& supported = supported_mesh_extensions();
  if (std::find(supported.begin(), supported.end(), ext) == supported.end())
    throw InputError(path + ": unsupported mesh file extension '" + ext + "' (supported: .obj, .off, .ply, .stl, or shape:NAME)");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path + ": no such file");
  if (!std::ifstream(path).good()) throw InputError(path + ": cannot open the file for reading");
  // Said plainly: each reader would otherwise report an empty file its own way ("no faces", "could
  // not parse"), which hides the likelier cause (an interrupted download or copy).
  if (std::filesystem::file_size(path, ec) == 0 && !ec) throw InputError(path + ": the file is empty (0 bytes)");

  if (ext == ".obj") check_obj_face_corners(path);
  if (ext == ".ply") check_ply_header(path);
  if (ext == ".off") check_off_structure(path);

  SoupImporter importer;
  OpenMesh::IO::Options options;
  options += OpenMesh::IO::Options::VertexTexCoord;
  options += OpenMesh::IO::Options::FaceTexCoord;
  bool ok = false;
  try {
    MutedOpenMeshStreams muted;
    ok = OpenMesh::IO::IOManager().read(path, importer, options);
  } catch (const std::bad_alloc&) {
    // The last line of defence against a corrupted count the checks above let through.
    throw InputError(path + ": the " + ext.substr(1) + " reader ran out of memory (a corrupted element count?)");
  }
  if (!ok) {
    const std::string non_finite = find_non_finite_number(path);
    throw InputError(path + ": " + (non_finite.empty() ? "the " + ext.substr(1) + " reader could not parse the file" : non_finite));
  }
  if (ext == ".obj") check_obj_lines(path, importer.soup);
  importer.finish_texcoords();
  return std::move(importer.soup);
}

}  // namespace physarum
