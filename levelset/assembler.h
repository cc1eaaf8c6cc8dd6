#pragma once
#include "levelset/bundle.h"
#include "levelset/shape_builder.h"

#include <string>
#include <vector>

namespace tessera {

/// How `tessera assemble` reads an assembly exported by a design tool: part meshes already placed
/// in world coordinates (docs/tiling.md, "Assemblies").
struct AssembleOptions {
  std::string unit;                      ///< length unit of every file (required)
  std::string up = "z";                  ///< the files' up axis; turned into +z (rotationToZUp)
  std::vector<std::string> fixPatterns;  ///< bodies whose name matches a glob pattern are fixed
  /// Bodies whose name ends in one of these numbers are fixed (a design tool's list of support
  /// parts: TopoLite's Boundary_PartIDs 43,44,... name Part_43.obj, Part_44.obj, ...).
  std::vector<long> fixIds;
  std::vector<std::string> frameFiles;   ///< every piece of these files is a fixed body
  bool fixOuterRing = false;             ///< fix the bodies on the outer ring (outerRingBodies)
  double spanLength = 0;                 ///< m, L of k_n = E M / L; 0: estimated (estimateSpan)
  int spanInterfaces = 0;                ///< M; 0: estimated
  ShapeResolution resolution;            ///< zero lengths relative to each shape
  ShapeLimits limits;
  /// Parts equal up to a rigid motion share a shape: same triangles, vertices in the same order,
  /// and every vertex within this x the part's size of the rigidly moved other (Kabsch fit).
  double sameShapeTolerance = 1e-4;  // as ConvexFitOptions: covers 6-decimal metre exports
};

/// What was read, for the report.
struct AssembleReport {
  std::size_t files = 0, pieces = 0;
  std::string spanRule;  ///< how L and M were chosen
};

/// One part of an assembly: its mesh in place (world, m, z up).
struct AssemblyPart {
  std::string name;   ///< body name
  std::string label;  ///< where it came from, for messages (file, piece)
  TriangleMesh mesh;
  bool fixed = false;
};

/// Reads every file (multi-object and multi-piece OBJ, STL, PLY: each connected piece one body,
/// named after its file, "<stem>_<k>" when a file holds several), turns the up axis to +z, shares
/// one shape among identical parts, fixes bodies by the rules of `options` and sets the span.
/// Throws InputError naming the file for a part it cannot use, for no fixed body, or for no free one.
Bundle assembleParts(const std::vector<std::string>& files, const AssembleOptions& options, PrepLog& log,
                     AssembleReport& report);

/// The bundle of parts already in place (a generated tiling's blocks): the fixing rules of
/// `options` applied on top of each part's own `fixed`, one shape shared among parts equal up to a
/// rigid motion, the span set (report.spanRule). Throws InputError for a repeated name, for no
/// fixed body, or for no free one.
Bundle assembleParts(std::vector<AssemblyPart> parts, const AssembleOptions& options, PrepLog& log, AssembleReport& report);

/// The bodies on the assembly's outer ring: those whose centroid lies, in plan (x, y), within half
/// the distance to its nearest neighbour's centroid of the boundary of the convex hull of all
/// centroids. On a square grid, exactly the perimeter.
std::vector<int> outerRingBodies(const Bundle& bundle);

/// The span of k_n = E M / L for any assembly (Feldfogel et al. define it on square slabs:
/// L = (n - 2) pitch, M = n - 1): with s the median distance between neighbouring centroids (the
/// pitch), L is the free bodies' centroid extent in plan along the shorter of x and y plus s, and
/// M = round(L / s) + 1. A square grid gets exactly the paper's values. `rule` says so in words.
void estimateSpan(const Bundle& bundle, double& length, int& interfaces, std::string& rule);

}  // namespace tessera
