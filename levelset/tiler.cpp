#include "levelset/tiler.h"

#include "io/input_error.h"
#include "levelset/assembly.h"

#include <map>

namespace tessera {

Bundle tileAssembly(const std::vector<LayoutShape>& shapes, const std::vector<Placement>& placements,
                    const std::string& meshUnit, const ShapeResolution& resolution, PrepLog& log,
                    const ShapeLimits& limits, const std::string& meshUp) {
  Bundle bundle;
  bundle.generator = generatorVersion();
  bundle.sourceUp = meshUp;
  std::map<std::string, int> index;
  std::map<std::string, Bundle> sourceBundles;  // each source bundle read once
  for (const LayoutShape& s : shapes) {
    if (index.count(s.key)) throw InputError("shape '" + s.key + "' is defined twice");
    Shape shape;
    if (!s.bundle.empty()) {
      auto it = sourceBundles.find(s.bundle);
      if (it == sourceBundles.end()) it = sourceBundles.emplace(s.bundle, readBundle(s.bundle)).first;
      const int found = it->second.findShape(s.bundleShape);
      if (found < 0) throw InputError(s.bundle + ": holds no shape named '" + s.bundleShape + "'");
      shape = it->second.shapes[found];
      shape.name = s.key;
    } else {
      ShapeResolution r = resolution;
      if (s.voxel) r.voxelSize = *s.voxel;
      if (s.spacing) r.nodeSpacing = *s.spacing;
      shape = prepareShapeFromFile(s.mesh, meshUnit, s.key, r, log, limits, meshUp);
    }
    index[s.key] = static_cast<int>(bundle.shapes.size());
    bundle.shapes.push_back(std::move(shape));
  }
  for (const Placement& p : placements) {
    const auto it = index.find(p.shape);
    if (it == index.end()) throw InputError("body '" + p.name + "' uses unknown shape '" + p.shape + "'");
    bundle.bodies.push_back(placeBody(bundle.shapes[it->second], it->second, p));
  }
  return bundle;
}

}  // namespace tessera
