#include "levelset/assembly_export.h"

#include "io/safe_write.h"
#include "levelset/assembly.h"
#include "levelset/layout_file.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>

namespace tessera {

namespace fs = std::filesystem;

namespace {

// VTK cell types (VTK file formats, "Cell types").
constexpr int kVtkVertex = 1;
constexpr int kVtkTriangle = 5;

void writeAtomically(const fs::path& target, const std::function<void(std::ostream&)>& write) {
  writeFileSafely(target, [&](const fs::path& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out.precision(17);
    write(out);
    out.close();
    if (!out) throw std::runtime_error("short write");
  });
}

// One data array of a VTU file, its values kept as raw bytes for the appended block.
struct VtuArray {
  std::string type;  // VTK's name: Float64, Int64, Int32, UInt8
  std::string name;
  int components = 1;
  std::string bytes;
};

template <class T>
VtuArray vtuArray(const char* type, const std::string& name, int components, const std::vector<T>& values) {
  return {type, name, components, std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T))};
}

// A VTK XML UnstructuredGrid with one cell type, every array in one appended block of raw
// little-endian bytes, each preceded by its byte count as UInt64 (VTK file formats, "Appended
// data"): 5-7 times faster to read than ASCII and a third of its size. Field data (the body
// names) is ASCII: VTK reads string arrays only so.
void writeVtu(std::ostream& out, const std::vector<double>& points, const std::vector<std::int64_t>& connectivity,
              int cellType, int pointsPerCell, const std::vector<VtuArray>& pointData,
              const std::vector<VtuArray>& cellData, const std::vector<std::string>& names = {}) {
  const std::size_t cells = connectivity.size() / pointsPerCell;
  std::vector<std::int64_t> offsets(cells);
  for (std::size_t c = 0; c < cells; ++c) offsets[c] = static_cast<std::int64_t>((c + 1) * pointsPerCell);
  const VtuArray pointArray = vtuArray("Float64", "Points", 3, points);
  const std::vector<VtuArray> cellArrays{vtuArray("Int64", "connectivity", 1, connectivity),
                                         vtuArray("Int64", "offsets", 1, offsets),
                                         vtuArray("UInt8", "types", 1, std::vector<std::uint8_t>(cells, static_cast<std::uint8_t>(cellType)))};
  std::uint64_t offset = 0;
  std::string appended;
  const auto declare = [&](const VtuArray& a) {
    out << "<DataArray type=\"" << a.type << "\" Name=\"" << a.name << "\" NumberOfComponents=\"" << a.components
        << "\" format=\"appended\" offset=\"" << offset << "\"/>\n";
    const std::uint64_t size = a.bytes.size();
    appended.append(reinterpret_cast<const char*>(&size), sizeof size);
    appended += a.bytes;
    offset += sizeof size + size;
  };
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n<UnstructuredGrid>\n";
  if (!names.empty()) {
    out << "<FieldData>\n<DataArray type=\"String\" Name=\"body_names\" NumberOfTuples=\"" << names.size()
        << "\" format=\"ascii\">\n";
    for (const std::string& n : names) {
      for (unsigned char c : n) out << +c << ' ';
      out << "0\n";
    }
    out << "</DataArray>\n</FieldData>\n";
  }
  out << "<Piece NumberOfPoints=\"" << points.size() / 3 << "\" NumberOfCells=\"" << cells << "\">\n<PointData>\n";
  for (const VtuArray& a : pointData) declare(a);
  out << "</PointData>\n<CellData>\n";
  for (const VtuArray& a : cellData) declare(a);
  out << "</CellData>\n<Points>\n";
  declare(pointArray);
  out << "</Points>\n<Cells>\n";
  for (const VtuArray& a : cellArrays) declare(a);
  out << "</Cells>\n</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_";
  out.write(appended.data(), static_cast<std::streamsize>(appended.size()));
  out << "\n</AppendedData>\n</VTKFile>\n";
}

std::vector<double> flatten(const std::vector<Eigen::Vector3d>& v) {
  std::vector<double> flat;
  flat.reserve(3 * v.size());
  for (const auto& x : v) flat.insert(flat.end(), {x.x(), x.y(), x.z()});
  return flat;
}

}  // namespace

std::size_t writeBlocksVtu(const Bundle& bundle, const std::vector<Eigen::Vector3d>& position,
                           const std::vector<Eigen::Quaterniond>& orientation, const std::string& path,
                           const std::vector<std::pair<std::string, std::vector<Eigen::Vector3d>>>& bodyVectors) {
  std::vector<double> points;
  std::vector<std::int64_t> triangles;
  std::vector<std::int32_t> bodyOfCell, shapeOfCell;
  std::vector<std::uint8_t> fixedOfCell;
  std::vector<std::vector<double>> vectorsOfCell(bodyVectors.size());
  std::vector<std::string> names;
  for (int b = 0; b < static_cast<int>(bundle.bodies.size()); ++b) {
    const Body& body = bundle.bodies[b];
    names.push_back(body.name);
    const Shape& shape = bundle.shapes[body.shape];
    const auto base = static_cast<std::int64_t>(points.size() / 3);
    for (const auto& v : shape.mesh.vertices) {
      const Eigen::Vector3d x = orientation[b] * v + position[b];
      points.insert(points.end(), {x.x(), x.y(), x.z()});
    }
    for (const auto& t : shape.mesh.triangles) {
      triangles.insert(triangles.end(), {base + t[0], base + t[1], base + t[2]});
      bodyOfCell.push_back(b);
      shapeOfCell.push_back(body.shape);
      fixedOfCell.push_back(body.fixed ? 1 : 0);
      for (std::size_t k = 0; k < bodyVectors.size(); ++k) {
        const Eigen::Vector3d& v = bodyVectors[k].second[b];
        vectorsOfCell[k].insert(vectorsOfCell[k].end(), {v.x(), v.y(), v.z()});
      }
    }
  }
  std::vector<VtuArray> cellData{vtuArray("Int32", "body_id", 1, bodyOfCell), vtuArray("Int32", "shape_id", 1, shapeOfCell),
                                 vtuArray("UInt8", "fixed", 1, fixedOfCell)};
  for (std::size_t k = 0; k < bodyVectors.size(); ++k)
    cellData.push_back(vtuArray("Float64", bodyVectors[k].first, 3, vectorsOfCell[k]));
  writeAtomically(path, [&](std::ostream& out) { writeVtu(out, points, triangles, kVtkTriangle, 3, {}, cellData, names); });
  return bodyOfCell.size();
}

void writeSphereVtu(const Eigen::Vector3d& centre, double radius, const std::string& path) {
  // A UV sphere: 24 meridians, 12 parallels (poles included), triangles outward.
  const int meridians = 24, parallels = 12;
  std::vector<double> points;
  for (int i = 0; i <= parallels; ++i) {
    const double theta = M_PI * i / parallels;
    for (int j = 0; j < meridians; ++j) {
      const double phi = 2 * M_PI * j / meridians;
      const Eigen::Vector3d x = centre + radius * Eigen::Vector3d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                                                 std::cos(theta));
      points.insert(points.end(), {x.x(), x.y(), x.z()});
    }
  }
  std::vector<std::int64_t> triangles;
  const auto at = [&](int i, int j) { return static_cast<std::int64_t>(i * meridians + (j % meridians)); };
  for (int i = 0; i < parallels; ++i)
    for (int j = 0; j < meridians; ++j) {
      if (i > 0) triangles.insert(triangles.end(), {at(i, j), at(i + 1, j), at(i, j + 1)});
      if (i + 1 < parallels) triangles.insert(triangles.end(), {at(i, j + 1), at(i + 1, j), at(i + 1, j + 1)});
    }
  writeAtomically(path, [&](std::ostream& out) { writeVtu(out, points, triangles, kVtkTriangle, 3, {}, {}); });
}

void writePvd(const std::string& path, const std::vector<std::string>& files, const std::vector<double>& times) {
  writeAtomically(path, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\">\n<Collection>\n";
    int part = 0;
    for (std::size_t i = 0; i < files.size(); ++i) {
      part = i > 0 && times[i] == times[i - 1] ? part + 1 : 0;
      out << "<DataSet timestep=\"" << times[i] << "\" part=\"" << part << "\" file=\"" << files[i] << "\"/>\n";
    }
    out << "</Collection>\n</VTKFile>\n";
  });
}

void writePointsVtu(const std::string& path, const std::vector<Eigen::Vector3d>& points,
                    const std::vector<std::pair<std::string, std::vector<Eigen::Vector3d>>>& vectors,
                    const std::vector<std::pair<std::string, std::vector<double>>>& scalars) {
  std::vector<std::int64_t> cells(points.size());
  for (std::size_t i = 0; i < cells.size(); ++i) cells[i] = static_cast<std::int64_t>(i);
  std::vector<VtuArray> pointData;
  for (const auto& [name, values] : vectors) pointData.push_back(vtuArray("Float64", name, 3, flatten(values)));
  for (const auto& [name, values] : scalars) pointData.push_back(vtuArray("Float64", name, 1, values));
  writeAtomically(path, [&](std::ostream& out) { writeVtu(out, flatten(points), cells, kVtkVertex, 1, pointData, {}); });
}

ExportSummary exportAssembly(const Bundle& bundle, const std::string& bundlePath, const std::string& directory) {
  const fs::path dir(directory);
  fs::create_directories(dir);
  ExportSummary summary;

  std::vector<Eigen::Vector3d> position;
  std::vector<Eigen::Quaterniond> orientation;
  for (const Body& body : bundle.bodies) {
    position.push_back(body.position);
    orientation.push_back(body.orientation);
  }
  summary.triangles = writeBlocksVtu(bundle, position, orientation, (dir / "blocks.vtu").string());

  // Surface nodes, in world coordinates.
  std::vector<double> nodePoints, normals, areas;
  std::vector<std::int32_t> bodyOfNode;
  std::vector<std::uint8_t> kinds;
  for (int b = 0; b < static_cast<int>(bundle.bodies.size()); ++b) {
    const Body& body = bundle.bodies[b];
    const SurfaceNodes& nodes = bundle.shapes[body.shape].nodes;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const Eigen::Vector3d x = body.orientation * nodes.positions[i] + body.position;
      const Eigen::Vector3d n = body.orientation * nodes.normals[i];
      nodePoints.insert(nodePoints.end(), {x.x(), x.y(), x.z()});
      normals.insert(normals.end(), {n.x(), n.y(), n.z()});
      areas.push_back(nodes.areas[i]);
      bodyOfNode.push_back(b);
      kinds.push_back(static_cast<std::uint8_t>(nodes.kinds[i]));
    }
  }
  summary.nodes = bodyOfNode.size();
  std::vector<std::int64_t> vertexCells(summary.nodes);
  for (std::size_t i = 0; i < vertexCells.size(); ++i) vertexCells[i] = static_cast<std::int64_t>(i);
  writeAtomically(dir / "nodes.vtu", [&](std::ostream& out) {
    writeVtu(out, nodePoints, vertexCells, kVtkVertex, 1,
             {vtuArray("Int32", "body_id", 1, bodyOfNode), vtuArray("Float64", "area", 1, areas),
              vtuArray("Float64", "normal", 3, normals), vtuArray("UInt8", "kind", 1, kinds)},
             {});
  });

  writeAtomically(dir / "assembly.pvd", [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\">\n<Collection>\n"
           "<DataSet timestep=\"0\" part=\"0\" name=\"blocks\" file=\"blocks.vtu\"/>\n"
           "<DataSet timestep=\"0\" part=\"1\" name=\"nodes\" file=\"nodes.vtu\"/>\n"
           "</Collection>\n</VTKFile>\n";
  });

  // Layout: mesh-frame placements of shapes taken from the bundle itself.
  Layout layout;
  layout.unit = "m";
  for (const Shape& s : bundle.shapes) {
    LayoutShape shape;
    shape.key = s.name;
    shape.bundle = fs::absolute(bundlePath).string();
    shape.bundleShape = s.name;
    layout.shapes.push_back(shape);
  }
  for (const Body& b : bundle.bodies) layout.bodies.push_back(placementOf(b, bundle.shapes[b.shape]));
  layout.spanLength = bundle.spanLength;
  layout.spanInterfaces = bundle.spanInterfaces;
  writeLayout((dir / "layout.json").string(), layout);
  return summary;
}

}  // namespace tessera
