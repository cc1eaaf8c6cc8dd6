#pragma once
#include "levelset/bundle.h"
#include "levelset/shape_builder.h"

#include <string>

namespace tessera {

/// What prepareIntoBundle is given: a block mesh file in a length unit, the shape's name in the
/// bundle ("" for the file's name) and its resolution.
struct ShapeRequest {
  std::string mesh;
  std::string unit;
  std::string name;
  ShapeResolution resolution;
  ShapeLimits limits;
  std::string up = "z";  ///< the mesh's up axis, turned into +z
};

/// Prepares the shape of a block mesh (shape_builder.h) and adds it to the bundle in `directory`,
/// created if absent; a shape of the same name is replaced only with `replace` (else InputError
/// naming the fix). Returns the shape as written.
Shape prepareIntoBundle(const ShapeRequest& request, const std::string& directory, bool replace, PrepLog& log);

}  // namespace tessera
