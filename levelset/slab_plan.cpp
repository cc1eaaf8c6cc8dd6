#include "levelset/slab_plan.h"

#include "geometry/length_unit.h"
#include "geometry/mesh_import.h"
#include "io/input_error.h"
#include "levelset/shape_builder.h"

#include <sstream>

namespace tessera {

SlabPlan gridSlabPlan(const std::string& block, const std::string& unit, const SquareGridOptions& grid,
                      const std::string& up) {
  SlabPlan plan;
  plan.unit = unit;
  plan.up = up;
  const double m = parseLengthUnit(unit).metres;
  LayoutShape shape;
  shape.key = shapeNameFromPath(block);
  shape.mesh = block;
  plan.shapes.push_back(shape);
  plan.placements = squareGrid(grid, shape.key);
  MeshImportOptions import;
  import.metresPerUnit = m;
  import.up = up;
  const Eigen::AlignedBox3d box = boundingBox(importMesh(block, import).mesh.vertices);
  const Eigen::Vector3d centre(box.center().x(), box.center().y(), 0.0);
  if (centre.norm() > 1e-9 * box.diagonal().norm()) {
    for (Placement& p : plan.placements) p.translation -= p.rotation * centre;
    std::ostringstream note;
    note << "the block mesh is centred at (" << centre.x() / m << ", " << centre.y() / m << ") " << unit
         << " in plan, not at its origin; blocks are placed by that centre";
    plan.notes.push_back(note.str());
  }
  const InterlockingSpan span = squareGridSpan(grid);
  plan.spanLength = span.length;
  plan.spanInterfaces = span.interfaces;
  return plan;
}

SlabPlan layoutSlabPlan(const std::string& layoutFile, long maxBodies) {
  Layout layout = readLayout(layoutFile);
  if (static_cast<long>(layout.bodies.size()) > maxBodies)
    throw InputError(layoutFile + ": " + std::to_string(layout.bodies.size()) + " bodies, more than --max-bodies " +
                     std::to_string(maxBodies) + "; raise --max-bodies if you mean it (tiling time grows as the square of the count)");
  SlabPlan plan;
  plan.unit = layout.unit;
  plan.shapes = layout.shapes;
  plan.placements = layout.bodies;
  plan.spanLength = layout.spanLength;
  plan.spanInterfaces = layout.spanInterfaces;
  return plan;
}

Bundle tileSlab(const SlabPlan& plan, const ShapeResolution& resolution, PrepLog& log, const ShapeLimits& limits) {
  Bundle bundle = tileAssembly(plan.shapes, plan.placements, plan.unit, resolution, log, limits, plan.up);
  bundle.spanLength = plan.spanLength;
  bundle.spanInterfaces = plan.spanInterfaces;
  return bundle;
}

}  // namespace tessera
