#include "levelset/bundle_edit.h"

#include "io/input_error.h"

#include <filesystem>

namespace tessera {

namespace fs = std::filesystem;

Shape prepareIntoBundle(const ShapeRequest& request, const std::string& directory, bool replace, PrepLog& log) {
  const std::string name = request.name.empty() ? shapeNameFromPath(request.mesh) : request.name;
  Bundle bundle;
  if (fs::exists(fs::path(directory) / kBundleFileName)) bundle = readBundle(directory);
  else if (fs::exists(directory) && !fs::is_directory(directory))
    throw InputError(directory + ": exists and is not a directory; give a bundle directory with -o");
  const int existing = bundle.findShape(name);
  if (existing >= 0 && !replace)
    throw InputError(directory + ": already holds a shape named '" + name + "'; choose another --name or pass --replace");
  Shape shape = prepareShapeFromFile(request.mesh, request.unit, name, request.resolution, log, request.limits, request.up);
  if (existing >= 0) bundle.shapes[existing] = shape;
  else bundle.shapes.push_back(shape);
  bundle.generator = generatorVersion();
  writeBundle(directory, bundle);
  return shape;
}

}  // namespace tessera
