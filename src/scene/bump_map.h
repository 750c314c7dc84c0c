// Bump (height) maps, read as tangent-space normal maps, so that the rest of luxel sees one kind
// of map (Material::normalTexture, render/normal_map.h).
//
// A height map gives no unit for its heights (OBJ's `-bm` is a bare multiplier), so luxel reads
// them in texels, as image tools' height-to-normal filters do: a height of 1 (white) stands one
// texel width above 0 (black), times the multiplier. The surface's slopes are then central
// differences of the height, and its normal is normalize(-dh/du, -dh/dv, 1) in the tangent frame.
// That keeps a map's relief the same whatever the mesh's size; on the bump maps of Sibenik
// (kamen-bump.png) it tilts 90% of the texels by under 5 degrees and 99% by under 14.
#pragma once

#include "luxel/scene.h"

namespace luxel {

// OBJ's default `-bm`, used as well when a format gives no multiplier.
inline constexpr float kDefaultBumpMultiplier = 1.0f;

// The tangent-space normal map of `height` (texels undecoded, in [0,1]; the height is the mean of
// the three channels, the grey of a grey image), encoded as glTF's normalTexture (2 t - 1 is the
// unit normal), same size and path. Central differences wrap around, as lookups do.
Texture normalMapFromHeight(const Texture& height, float multiplier);

// Whether an image in a bump slot is a tangent-space normal map instead (Blender's OBJ exporter
// writes its normal maps as `map_Bump`): coloured, not grey (mean spread between its channels
// over 0.1), and bluish (mean blue over 0.6, where a normal map's z, mostly near 1, is stored).
bool looksLikeNormalMap(const Texture& texture);

}  // namespace luxel
