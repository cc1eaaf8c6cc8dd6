// tessera.prep, tile, tile_layout, tile_tiling, check, read_bundle: shapes and slabs from Python
// (lengths in m).
#include "python/bindings.h"

#include "io/input_error.h"
#include "io/output_directory.h"
#include "levelset/assembly_checks.h"
#include "levelset/bundle.h"
#include "levelset/bundle_edit.h"
#include "levelset/generated_slab.h"
#include "levelset/rigid_block_analysis.h"
#include "levelset/shape.h"
#include "levelset/slab_plan.h"
#include "levelset/tiler.h"
#include "solver/contact_parameters.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
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

// The bundle checked like tile's (overlaps refused) and written to `output`.
py::dict checkAndWrite(const Bundle& bundle, const std::vector<std::string>& planNotes, const PrepLog& log, const std::string& output,
                       double gap) {
  const AssemblySummary summary =
      checkAssemblyBeforeWriting(bundle, std::nullopt, gap, "check the pitch or the layout positions, or add a gap",
                                 "check the pitch or positions (in m) and that the blocks' thickness is along z (up='y' for y-up meshes)",
                                 true);
  writeBundle(output, bundle);
  std::vector<std::string> notes = planNotes, warnings = log.warnings;
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

// The plan tiled, checked and written.
py::dict tileAndWrite(const SlabPlan& plan, const std::string& output, const ShapeResolution& r, double gap, bool replace) {
  checkBundleOutput(output, replace);
  PrepLog log;
  return checkAndWrite(tileSlab(plan, r, log), plan.notes, log, output, gap);
}

py::list motionList(const Bundle& bundle, const std::vector<BodyMotion>& motion) {
  py::list list;
  for (const BodyMotion& m : motion) {
    py::dict d;
    d["body"] = bundle.bodies[m.body].name;
    d["translation"] = std::vector<double>{m.translation.x(), m.translation.y(), m.translation.z()};
    d["rotation"] = std::vector<double>{m.rotation.x(), m.rotation.y(), m.rotation.z()};
    list.append(d);
  }
  return list;
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

// prep: one block mesh into a bundle.
void bindPrep(py::module_& m) {
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
}

// tile, tile_layout, tile_tiling: the three ways `tessera tile` makes a slab.
void bindTiles(py::module_& m) {
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
  m.def(
      "tile_tiling",
      [](const std::string& tiling, const std::string& output, double thickness, double angle, std::pair<int, int> grid,
         std::optional<double> pitch, const std::string& surface, double radius, unsigned seed, bool fixPerimeter,
         std::optional<double> voxel, std::optional<double> spacing, double edgeSpacing, bool replace, const std::string& up) {
        GeneratedSlabOptions options;
        options.up = up;
        if (isTilingKind(tiling)) {
          if (!pitch) throw InputError("tiling '" + tiling + "' needs pitch, the distance between neighbouring tile centres in m");
          if (grid.first < 1 || grid.second < 1 || static_cast<long>(grid.first) * grid.second > 10000)
            throw InputError("grid must be (columns, rows), each at least 1 and at most 10000 tiles in all");
          options.tiling = {tiling, *pitch, grid.first, grid.second, seed};
        } else {
          options.tilingFile = tiling;  // a polygon mesh, in m
        }
        options.thickness = thickness;
        if (!(angle >= 0 && angle < 90)) throw InputError("angle must be the faces' tilt in degrees, in [0, 90)");
        options.angle = angle * M_PI / 180;
        options.surface = baseSurface(surface, radius, 1.0, up);
        options.fixPerimeter = fixPerimeter;
        checkBundleOutput(output, replace);
        PrepLog log;
        AssembleReport report;
        const Bundle bundle = generatedSlab(options, "m", resolution(voxel, spacing, edgeSpacing), ShapeLimits{}, log, report);
        return checkAndWrite(bundle, {"span " + report.spanRule}, log, output, 0.0);
      },
      py::arg("tiling"), py::arg("output"), py::arg("thickness"), py::arg("angle") = 5.0, py::arg("grid") = std::pair<int, int>{7, 7},
      py::arg("pitch") = py::none(), py::arg("surface") = "plane", py::arg("radius") = 0.0, py::arg("seed") = 1u,
      py::arg("fix_perimeter") = true, py::arg("voxel") = py::none(), py::arg("spacing") = py::none(),
      py::arg("edge_spacing") = ShapeResolution{}.edgeSpacingFraction, py::arg("replace") = false, py::arg("up") = "z",
      "A slab bundle generated from a tiling (as `tessera tile --tiling`, docs/tiling.md): 'square', 'hex', 'triangle', "
      "'rhombille', 'voronoi' or a polygon mesh file (in m; edges drawn as lines in a group named angle_<degrees> take that angle); pitch, thickness and radius in m, angle in degrees; "
      "surface 'plane', 'sphere', 'cylinder' or a mesh file of a height field (in m). Returns a summary.");
}

// check and read_bundle: what a bundle holds and whether it stands.
void bindBundleQueries(py::module_& m) {
  m.def(
      "check",
      [](const std::string& path, double friction) {
        const Bundle bundle = readBundle(path);
        if (!(friction >= 0)) throw InputError("friction must be a Coulomb coefficient >= 0");
        const AssemblyStatics s = analyseAssembly(bundle, AssemblyLevelSets(bundle), friction);
        py::dict d;
        d["bundle"] = path;
        d["interlocked"] = s.interlocking.interlocked;
        d["stable"] = s.stability.stable;
        d["friction"] = friction;
        d["least_friction"] = s.stability.leastFriction ? py::object(py::float_(*s.stability.leastFriction)) : py::object(py::none());
        d["free_motion"] = motionList(bundle, s.interlocking.motion);
        d["rigid_least_friction"] = s.stability.rigidLeastFriction ? py::object(py::float_(*s.stability.rigidLeastFriction)) : py::object(py::none());
        d["falling_motion"] = motionList(bundle, s.stability.falling);
        d["sliding_modes"] = s.interlocking.slidingModes;
        d["sliding_motion"] = motionList(bundle, s.interlocking.sliding);
        d["contact_pairs"] = s.pairs;
        d["contact_polygons"] = s.polygons;
        d["contact_corners"] = s.corners;
        d["settled"] = s.stability.settled;
        d["contact_nodes"] = s.stability.nodes;
        d["seconds"] = s.seconds;
        return d;
      },
      py::arg("bundle"), py::arg("friction") = ContactParameters{}.friction,
      "Is the assembly interlocked, and does it stand under its own weight (as `tessera check`, docs/check.md)? "
      "The same keys as `tessera check --json`.");
  m.def("read_bundle", &bundleOf, py::arg("path"),
        "A bundle's bodies: names, shape, position (n, 3) m, orientation (n, 4) (w, x, y, z), fixed; its span.");
}

}  // namespace

void bindSlabs(py::module_& m) {
  bindPrep(m);
  bindTiles(m);
  bindBundleQueries(m);
}

}  // namespace tessera::python
