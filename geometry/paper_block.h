#pragma once

namespace tessera {

/// The thickness of the paper's block (Feldfogel et al.: planar TIS blocks, a = 10 mm,
/// h = 3.18 mm). Defaults that are lengths are written as the paper's absolute value divided by
/// it: the paper's block keeps them exactly, every other block gets them in proportion to its size
/// (docs/scene.md, "Scale").
constexpr double kPaperThickness = 3.18e-3;  // m

}  // namespace tessera
