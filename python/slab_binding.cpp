// tessera.prep, tessera.tile, tessera.tile_layout, tessera.read_bundle: shapes and slabs from Python
// (lengths in m).
#include "python/bindings.h"

#include "io/input_error.h"
#include "io/output_directory.h"
#include "levelset/assembly_checks.h"
#include "levelset/bundle.h"
#include "levelset/bundle_edit.h"
#include "levelset/shape.h"
#include "levelset/slab_plan.h"
#include "levelset/tiler.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>

namespace tessera::python {

namespace py = pybind11;

namespace {

ShapeResolution resolution(std::optional<double> voxel, std::optional<double> spacing, double edgeSpacing) {
  ShapeResolution r;
  for (const auto& [name, value] : {std::pair{"voxel", voxel}, std::pair{"spacing", spacing}})
    if (value && !(*value > 0 && std::isfinite(*value)))
      throw InputError(std::string(name) + " must be a positive length in m, got " + std::to_string(*value));
  if (!validEdgeSpacingFraction(edgeSpacing))
    throw InputError("edge_spacing must be between 0.05 and 1, a fraction of the node spacing (1: uniform nodes), got " +
                     std::to_string(edgeSpacing));
  if (voxel) r.voxelSize = *voxel;
  if (spacing) r.nodeSpacing = *spacing;
  r.edgeSpacingFraction = edgeSpacing;
  return r;
}

// The plan tiled, checked like tile's (overlaps refused) and written to `output`.
py::dict tileAndWrite(const SlabPlan& plan, const std::string& output, const ShapeResolution& r, double gap, bool replace) {
  checkBundleOutput(output, replace);
  PrepLog log;
  const Bundle bundle = tileSlab(plan, r, log);
  const AssemblySummary summary =
      checkAssemblyBeforeWriting(bundle, std::nullopt, gap, "check the pitch or the layout positions, or add a gap",
                                 "check the pitch or positions (in m) and that the blocks' thickness is along z (up='y' for y-up meshes)",
                                 true);
  writeBundle(output, bundle);
  std::vector<std::string> notes = plan.notes, warnings = log.warnings;
  notes.insert(notes.end(), log.notes.begin(), log.notes.end());
  notes.insert(notes.end(), summary.notes.begin(), summary.notes.end());
  warnings.insert(warnings.end(), summary.warnings.begin(), summary.warnings.end());
  for (const std::string& w : warnings) py::print("tessera: tile: warning:", w, py::arg("file") = py::module_::import("sys").attr("stderr"));
  py::dict d;
  d["bundle"] = output;
  d["bodies"] = bundle.bodies.size();
  d["free"] = summary.free;
  d["interlocked"] = summary.locked;
  d["span_length"] = bundle.spanLength;
  d["span_interfaces"] = bundle.spanInterfaces;
  d["notes"] = notes;
  d["warnings"] = warnings;
  return d;
}

py::dict bundleOf(const std::string& path) {
  const Bundle bundle = readBundle(path);
  std::vector<std::string> names, shapes, shapeNames;
  py::array_t<double> position({static_cast<py::ssize_t>(bundle.bodies.size()), py::ssize_t{3}});
  py::array_t<double> orientation({static_cast<py::ssize_t>(bundle.bodies.size()), py::ssize_t{4}});
  py::array_t<bool> fixed(static_cast<py::ssize_t>(bundle.bodies.size()));
  auto p = position.mutable_unchecked<2>();
  auto q = orientation.mutable_unchecked<2>();
  auto f = fixed.mutable_unchecked<1>();
  for (std::size_t i = 0; i < bundle.bodies.size(); ++i) {
    const Body& b = bundle.bodies[i];
    names.push_back(b.name);
    shapes.push_back(bundle.shapes[b.shape].name);
    for (int k = 0; k < 3; ++k) p(i, k) = b.position[k];
    q(i, 0) = b.orientation.w();
    q(i, 1) = b.orientation.x();
    q(i, 2) = b.orientation.y();
    q(i, 3) = b.orientation.z();
    f(i) = b.fixed;
  }
  for (const Shape& s : bundle.shapes) shapeNames.push_back(s.name);
  py::dict d;
  d["names"] = names;
  d["shape"] = shapes;
  d["position"] = position;
  d["orientation"] = orientation;
  d["fixed"] = fixed;
  d["shapes"] = shapeNames;
  d["span_length"] = bundle.spanLength;
  d["span_interfaces"] = bundle.spanInterfaces;
  return d;
}

}  // namespace

void bindSlabs(py::module_& m) {
  m.def(
      "prep",
      [](const std::string& mesh, const std::string& unit, const std::string& output, const std::string& name,
         std::optional<double> voxel, std::optional<double> spacing, double edgeSpacing, bool replace, const std::string& up) {
        PrepLog log;
        const Shape s = prepareIntoBundle({mesh, unit, name, resolution(voxel, spacing, edgeSpacing), ShapeLimits{}, up},
                                          output, replace, log);
        py::dict d;
        d["name"] = s.name;
        d["volume"] = s.mass.volume;
        d["surface_area"] = s.mass.surfaceArea;
        d["nodes"] = s.nodes.size();
        d["node_spacing"] = s.resolution.nodeSpacing;
        d["edge_node_spacing"] = s.resolution.edgeSpacingFraction * s.resolution.nodeSpacing;
        d["voxel"] = s.sdf.voxelSize;
        d["level_set"] = levelSetPath(s);
        d["notes"] = log.notes;
        d["warnings"] = log.warnings;
        return d;
      },
      py::arg("mesh"), py::arg("unit"), py::arg("output"), py::arg("name") = "", py::arg("voxel") = py::none(),
      py::arg("spacing") = py::none(), py::arg("edge_spacing") = ShapeResolution{}.edgeSpacingFraction,
      py::arg("replace") = false, py::arg("up") = "z",
      "A block mesh (STL/OBJ, its length unit given) validated and prepared as a shape, added to the bundle "
      "in `output` (as `tessera prep`); voxel and node spacing in m, edge_spacing the node spacing along sharp edges "
      "as a fraction of it (1: uniform). Returns its volume (m^3), area (m^2), nodes.");
  m.def(
      "tile",
      [](const std::string& block, const std::string& unit, const std::string& output, std::pair<int, int> grid,
         double pitch, double gap, bool alternate, bool fixPerimeter, std::optional<double> voxel,
         std::optional<double> spacing, double edgeSpacing, bool replace, const std::string& up) {
        if (grid.first < 1 || grid.second < 1 || static_cast<long>(grid.first) * grid.second > 10000)
          throw InputError("grid must be (columns, rows), each at least 1 and at most 10000 blocks in all");
        if (!(pitch > 0)) throw InputError("pitch must be a positive length in m (the centre-to-centre distance)");
        SquareGridOptions options;
        options.columns = grid.first;
        options.rows = grid.second;
        options.pitch = pitch;
        options.gap = gap;
        options.alternate = alternate;
        options.fixPerimeter = fixPerimeter;
        return tileAndWrite(gridSlabPlan(block, unit, options, up), output, resolution(voxel, spacing, edgeSpacing), gap,
                            replace);
      },
      py::arg("block"), py::arg("unit"), py::arg("output"), py::arg("grid") = std::pair<int, int>{7, 7},
      py::arg("pitch"), py::arg("gap") = 0.0, py::arg("alternate") = true, py::arg("fix_perimeter") = true,
      py::arg("voxel") = py::none(), py::arg("spacing") = py::none(),
      py::arg("edge_spacing") = ShapeResolution{}.edgeSpacingFraction, py::arg("replace") = false, py::arg("up") = "z",
      "A slab bundle (as `tessera tile --block`): a square grid of one block mesh (its length unit given), "
      "pitch and gap in m; voxel and node spacing in m (default: relative to the block). Returns a summary.");
  m.def(
      "tile_layout",
      [](const std::string& layout, const std::string& output, std::optional<double> voxel, std::optional<double> spacing,
         double edgeSpacing, bool replace, const std::string& up) {
        SlabPlan plan = layoutSlabPlan(layout, 10000);
        plan.up = up;
        return tileAndWrite(plan, output, resolution(voxel, spacing, edgeSpacing), 0.0, replace);
      },
      py::arg("layout"), py::arg("output"), py::arg("voxel") = py::none(), py::arg("spacing") = py::none(),
      py::arg("edge_spacing") = ShapeResolution{}.edgeSpacingFraction, py::arg("replace") = false, py::arg("up") = "z", "A slab bundle from a layout file (docs/tiling.md), as `tessera tile --layout`.");
  m.def("read_bundle", &bundleOf, py::arg("path"),
        "A bundle's bodies: names, shape, position (n, 3) m, orientation (n, 4) (w, x, y, z), fixed; its span.");
}

}  // namespace tessera::python
