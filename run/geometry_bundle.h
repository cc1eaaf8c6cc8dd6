#pragma once
#include "run/scene.h"

#include <functional>
#include <string>

namespace tessera {

/// The bundle of a scene's [geometry] (docs/scene.md): generated once per distinct recipe into
/// `cache`/geometry_<digest of the recipe> and found there again (by later runs, by a resumed run,
/// by the other cases of a sweep: they share the sweep folder's bundles/). Runs that want the same
/// bundle at once take turns on its lock file; the one that builds it writes it with the checks
/// of `tessera tile` (an overlap refuses it). Returns the bundle's folder. `log` hears what is built.
std::string geometryBundle(const GeometryRecipe& recipe, const std::string& cache, const std::function<void(const std::string&)>& log);

/// Where a run writing to `output` keeps the bundles of [geometry]: the sweep folder's bundles/
/// for a case of a sweep (sweep.json in the folder's parent or grandparent), else `output` itself.
std::string geometryCache(const std::string& output);

}  // namespace tessera
