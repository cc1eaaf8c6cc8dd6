#include "levelset/assembly_export.h"

#include "io/safe_write.h"
#include "levelset/assembly.h"
#include "levelset/layout_file.h"

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
    std::ofstream out(temporary);
    out.precision(17);
    write(out);
    out.close();
    if (!out) throw std::runtime_error("short write");
  });
}

template <class T>
void dataArray(std::ostream& out, const char* type, const char* name, int components, const std::vector<T>& values) {
  out << "<DataArray type=\"" << type << "\" Name=\"" << name << "\" NumberOfComponents=\"" << components
      << "\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < values.size(); ++i) out << +values[i] << ((i + 1) % 12 == 0 ? '\n' : ' ');
  out << "\n</DataArray>\n";
}

// An ASCII VTK XML UnstructuredGrid with one cell type.
void writeVtu(std::ostream& out, const std::vector<double>& points, const std::vector<std::int64_t>& connectivity,
              int cellType, int pointsPerCell, const std::function<void(std::ostream&)>& pointData,
              const std::function<void(std::ostream&)>& cellData) {
  const std::size_t cells = connectivity.size() / pointsPerCell;
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\""
      << points.size() / 3 << "\" NumberOfCells=\"" << cells << "\">\n<PointData>\n";
  pointData(out);
  out << "</PointData>\n<CellData>\n";
  cellData(out);
  out << "</CellData>\n<Points>\n";
  dataArray(out, "Float64", "Points", 3, points);
  out << "</Points>\n<Cells>\n";
  dataArray(out, "Int64", "connectivity", 1, connectivity);
  std::vector<std::int64_t> offsets(cells);
  for (std::size_t c = 0; c < cells; ++c) offsets[c] = static_cast<std::int64_t>((c + 1) * pointsPerCell);
  dataArray(out, "Int64", "offsets", 1, offsets);
  dataArray(out, "UInt8", "types", 1, std::vector<std::uint8_t>(cells, static_cast<std::uint8_t>(cellType)));
  out << "</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
}

}  // namespace

std::size_t writeBlocksVtu(const Bundle& bundle, const std::vector<Eigen::Vector3d>& position,
                           const std::vector<Eigen::Quaterniond>& orientation, const std::string& path) {
  std::vector<double> points;
  std::vector<std::int64_t> triangles;
  std::vector<std::int32_t> bodyOfCell, shapeOfCell;
  std::vector<std::uint8_t> fixedOfCell;
  for (int b = 0; b < static_cast<int>(bundle.bodies.size()); ++b) {
    const Body& body = bundle.bodies[b];
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
    }
  }
  writeAtomically(path, [&](std::ostream& out) {
    writeVtu(out, points, triangles, kVtkTriangle, 3, [](std::ostream&) {},
             [&](std::ostream& o) {
               dataArray(o, "Int32", "body_id", 1, bodyOfCell);
               dataArray(o, "Int32", "shape_id", 1, shapeOfCell);
               dataArray(o, "UInt8", "fixed", 1, fixedOfCell);
             });
  });
  return bodyOfCell.size();
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
  std::vector<double> flat;
  for (const auto& p : points) flat.insert(flat.end(), {p.x(), p.y(), p.z()});
  std::vector<std::int64_t> cells(points.size());
  for (std::size_t i = 0; i < cells.size(); ++i) cells[i] = static_cast<std::int64_t>(i);
  writeAtomically(path, [&](std::ostream& out) {
    writeVtu(out, flat, cells, kVtkVertex, 1,
             [&](std::ostream& o) {
               for (const auto& [name, values] : vectors) {
                 std::vector<double> v;
                 for (const auto& x : values) v.insert(v.end(), {x.x(), x.y(), x.z()});
                 dataArray(o, "Float64", name.c_str(), 3, v);
               }
               for (const auto& [name, values] : scalars) dataArray(o, "Float64", name.c_str(), 1, values);
             },
             [](std::ostream&) {});
  });
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
             [&](std::ostream& o) {
               dataArray(o, "Int32", "body_id", 1, bodyOfNode);
               dataArray(o, "Float64", "area", 1, areas);
               dataArray(o, "Float64", "normal", 3, normals);
               dataArray(o, "UInt8", "kind", 1, kinds);
             },
             [](std::ostream&) {});
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
