#include "geometry/ply_reader.h"

#include "io/input_error.h"

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <vector>

namespace tessera {

namespace fs = std::filesystem;

namespace {

struct Property {
  std::string name, type, countType;  ///< countType: a list's count type ("" for a scalar)
};

struct Element {
  std::string name;
  std::uintmax_t count = 0;
  std::vector<Property> properties;
};

// Bytes of a PLY scalar type in a binary file; 0 for a type the format does not have.
std::size_t typeBytes(const std::string& type) {
  static const std::map<std::string, std::size_t> sizes{
      {"char", 1},   {"uchar", 1},  {"int8", 1},   {"uint8", 1},   {"short", 2},   {"ushort", 2}, {"int16", 2},
      {"uint16", 2}, {"int", 4},    {"uint", 4},   {"int32", 4},   {"uint32", 4},  {"float", 4},  {"float32", 4},
      {"double", 8}, {"float64", 8}};
  const auto found = sizes.find(type);
  return found == sizes.end() ? 0 : found->second;
}

bool integerType(const std::string& type) { return type != "float" && type != "float32" && type != "double" && type != "float64"; }

// The body's values one at a time, each read as its type: ASCII words, or binary in either byte order.
class Body {
public:
  Body(const std::string& bytes, std::size_t at, int format, std::string path)
      : bytes_(bytes), at_(at), format_(format), path_(std::move(path)) {}

  double next(const std::string& type) {
    return format_ == 0 ? nextWord(type) : nextBinary(type);
  }
  std::size_t left() const { return bytes_.size() - at_; }
  [[noreturn]] void fail(const std::string& why) const {
    throw InputError(path_ + ": " + why + "; the file is damaged, export the mesh again");
  }

private:
  double nextWord(const std::string& type) {
    while (at_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[at_]))) ++at_;
    std::size_t end = at_;
    while (end < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[end]))) ++end;
    if (end == at_) fail("it ends before its last element");
    const std::string word = bytes_.substr(at_, end - at_);
    at_ = end;
    char* stop = nullptr;
    const double v = std::strtod(word.c_str(), &stop);
    if (stop != word.c_str() + word.size() || !std::isfinite(v) || (integerType(type) && v != std::floor(v)))
      fail("'" + word.substr(0, 20) + "' is not a " + type);
    return v;
  }

  double nextBinary(const std::string& type) {
    const std::size_t n = typeBytes(type);
    if (left() < n) fail("it ends before its last element");
    unsigned char b[8];
    std::memcpy(b, bytes_.data() + at_, n);
    at_ += n;
    const std::uint16_t probe = 1;
    const bool hostLittle = *reinterpret_cast<const unsigned char*>(&probe) == 1;
    if ((format_ == 1) != hostLittle)
      for (std::size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
    const auto as = [&](auto value) {
      std::memcpy(&value, b, sizeof value);
      return static_cast<double>(value);
    };
    if (type == "char" || type == "int8") return as(std::int8_t{});
    if (type == "uchar" || type == "uint8") return as(std::uint8_t{});
    if (type == "short" || type == "int16") return as(std::int16_t{});
    if (type == "ushort" || type == "uint16") return as(std::uint16_t{});
    if (type == "int" || type == "int32") return as(std::int32_t{});
    if (type == "uint" || type == "uint32") return as(std::uint32_t{});
    if (type == "float" || type == "float32") return as(float{});
    return as(double{});
  }

  const std::string& bytes_;
  std::size_t at_;
  int format_;  // 0 ascii, 1 binary little-endian, 2 binary big-endian
  std::string path_;
};

}  // namespace

bool isPlyFile(const std::string& path) {
  std::string extension = fs::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  std::ifstream in(path, std::ios::binary);
  char first[3] = {};
  in.read(first, 3);
  const auto lower = [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); };
  return extension == ".ply" || (in.gcount() == 3 && lower(first[0]) == 'p' && lower(first[1]) == 'l' && lower(first[2]) == 'y');
}

TriangleMesh readPly(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto refuse = [&](const std::string& why) -> void {
    throw InputError(path + ": not a PLY mesh Tessera reads (" + why + "); export it again as PLY, STL or OBJ");
  };

  // Header: "ply", then format, comment, obj_info, element, property lines, to end_header.
  std::size_t at = 0, lines = 0;
  int format = -1;
  std::vector<Element> elements;
  for (bool ended = false; !ended;) {
    const std::size_t end = bytes.find('\n', at);
    if (end == std::string::npos || ++lines > 10000) refuse("no end_header line");
    std::string line = bytes.substr(at, end - at);
    at = end + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    for (char c : line)
      if (c < 0x20 || c > 0x7e) refuse("a control or non-ASCII character in the header");
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (lines == 1) {
      if (line != "ply") refuse("its first line is not 'ply'");
    } else if (word == "comment" || word == "obj_info") {
    } else if (word == "format") {
      words >> word;
      format = word == "ascii" ? 0 : word == "binary_little_endian" ? 1 : word == "binary_big_endian" ? 2 : -1;
      if (format < 0) refuse("format '" + word + "'");
    } else if (word == "element") {
      Element e;
      if (!(words >> e.name >> e.count)) refuse("an element without a name and a count");
      elements.push_back(e);
    } else if (word == "property") {
      Property p;
      words >> p.type;
      if (p.type == "list") words >> p.countType >> p.type;
      if (!(words >> p.name) || elements.empty() || typeBytes(p.type) == 0 || (!p.countType.empty() && typeBytes(p.countType) == 0))
        refuse("property '" + line.substr(0, 40) + "'");
      if (!p.countType.empty() && !integerType(p.countType)) refuse("a list counted by a " + p.countType);
      elements.back().properties.push_back(p);
    } else if (word == "end_header") {
      ended = true;
    } else {
      refuse("a line '" + line.substr(0, 40) + "' in the header");
    }
  }
  if (format < 0) refuse("no format line");

  // The counts against the bytes the file holds (each value at least a digit and a separator, or
  // its size; a list at least its count), before anything is stored.
  for (const Element& e : elements) {
    std::uintmax_t each = 0;
    for (const Property& p : e.properties) each += format == 0 ? 2 : typeBytes(p.countType.empty() ? p.type : p.countType);
    if (e.count > 0 && each > 0 && e.count > (bytes.size() - at) / each)
      throw InputError(path + ": its PLY header claims more elements than the file's " + std::to_string(bytes.size()) +
                       " bytes can hold (the file is truncated or its header damaged); export the mesh again");
  }

  Body body(bytes, at, format, path);
  TriangleMesh mesh;
  for (const Element& e : elements) {
    const bool vertex = e.name == "vertex", face = e.name == "face";
    int xyz[3] = {-1, -1, -1}, indices = -1;
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
      const Property& p = e.properties[k];
      for (int d = 0; d < 3 && vertex; ++d)
        if (p.name == std::string(1, static_cast<char>('x' + d)) && p.countType.empty()) xyz[d] = static_cast<int>(k);
      if (face && !p.countType.empty() && (p.name == "vertex_indices" || p.name == "vertex_index")) indices = static_cast<int>(k);
    }
    if (vertex && (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0)) refuse("vertices without x, y and z");
    if (face && indices < 0) refuse("faces without a vertex_indices list");
    std::vector<int> corners;
    for (std::uintmax_t i = 0; i < e.count; ++i) {
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        const Property& p = e.properties[k];
        if (p.countType.empty()) {
          const double v = body.next(p.type);
          for (int d = 0; d < 3; ++d)
            if (static_cast<int>(k) == xyz[d]) x[d] = v;
          continue;
        }
        const double n = body.next(p.countType);
        if (n < 0 || n > static_cast<double>(body.left())) body.fail("a list of " + std::to_string(n) + " values");
        corners.clear();
        for (long j = 0; j < static_cast<long>(n); ++j) {
          const double v = body.next(p.type);
          if (static_cast<int>(k) == indices) {
            if (v < 0 || v >= static_cast<double>(mesh.vertices.size()))
              body.fail("face " + std::to_string(i) + " names a vertex that is not there (or comes before the vertices)");
            corners.push_back(static_cast<int>(v));
          }
        }
      }
      if (vertex) mesh.vertices.push_back(x);
      for (std::size_t j = 2; face && j < corners.size(); ++j) mesh.triangles.push_back({corners[0], corners[j - 1], corners[j]});
    }
  }
  return mesh;
}

}  // namespace tessera
