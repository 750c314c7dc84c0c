// Spherical-harmonic transfer lightmaps (seed 004's CaSHL, section 4; Sloan, Kautz and Snyder,
// "Precomputed Radiance Transfer for Real-Time Rendering in Dynamic, Low-Frequency Lighting
// Environments", SIGGRAPH 2002): for light from far away (suns and skies), each texel keeps how the
// irradiance it receives depends on where that light comes from, shadows and interreflection
// included, so that the sun can turn and the sky change without a new bake. Colour per channel
// (004's was monochrome). docs/baking.md, "Transfer lightmaps", has the definitions.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "luxel/bake.h"
#include "luxel/lightmap.h"

namespace luxel {

// Distant light as incident radiance in real spherical harmonics: c_i = integral of L(w) Y_i(w) over
// the sphere, bands^2 coefficients per channel (core/spherical_harmonics.h's functions).
struct DistantLightSh {
  int bands = 0;
  std::vector<Rgb> coefficients;
  std::vector<std::string> warnings;  // light that is not distant (point, spot, emitting surfaces), left out
};
// The scene's suns (each its irradiance along its direction: its disc is far smaller than what
// four bands resolve) and skies (uniform and CIE overcast, projected by quadrature over 20,000
// directions). bands: 2, 3 or 4.
DistantLightSh distantLightSh(const Scene& scene, int bands);

struct TransferBakeOptions {
  // The texels, their validity, seams, gutters (its solve and directional fields are not read).
  LightmapBakeOptions texels;
  int bands = 4;           // 2, 3 or 4: 4, 9 or 16 coefficients per channel (004's default: 4 bands)
  int directRays = 256;    // visibility rays per texel for the self-shadowed transfer (a square: 16 x 16)
  double unshot = 1e-3;    // shooting stops when the unshot transfer falls below this share of the first
};

// T per texel and channel: the irradiance a texel receives from a distant light of radiance SH L is
// sum_i T_i L_i. Direct: T_i = integral over the texel's hemisphere of V(w) cos(theta) Y_i(w)
// (stratified cosine-weighted rays); interreflected: T = T_direct + F rho T, shot patch by patch
// like radiosity (the form factors of the CPU transport), each coefficient a separate "colour".
struct TransferBake {
  LightmapBake texels;  // the texel layout, state, validity, seam statistics (of band 0); no pages
  int bands = 0;
  std::vector<std::vector<std::vector<Rgb>>> planes;  // [coefficient][page][texel]
  uint64_t shots = 0;
  double unshotFraction = 0.0;
  double secondsDirect = 0.0, secondsShoot = 0.0;
};

// Throws Error on absurd options, a scene of no texels, or bands outside [2, 4].
TransferBake bakeTransfer(const Scene& scene, const LightmapAtlas& atlas, const TransferBakeOptions& options = {},
                          const ProgressCallback& progress = {});

// The recipe `luxel render --mode lightmap --transfer` and `luxel bake --lightmaps --transfer`
// share: the lightmap recipe's atlas (its density and pages; its solve is not read), then a
// transfer bake of `bands` bands whose dilation fills the atlas's gutter.
struct BakedTransfer {
  LightmapAtlas atlas;
  TransferBake transfer;
};
BakedTransfer bakeTransfer(const Scene& scene, const LightmapRecipe& recipe, int bands,
                           const ProgressCallback& progress = {});

// The irradiance pages of a transfer bake under `light` (H = sum_i T_i L_i per texel and channel),
// in LightmapBake::pages' layout. Throws Error when the band counts differ.
std::vector<std::vector<Rgb>> relightTransfer(const TransferBake& transfer, const DistantLightSh& light);

// A lightmap bake of the transfer relit by `light`, for renderLightmapped and the glb export.
LightmapBake relitLightmaps(const TransferBake& transfer, const DistantLightSh& light);

// The glb of a transfer bake (docs/baking.md, "Transfer lightmaps in the glb"): the lightmaps of
// `relit` (addLightmaps: the fallback for engines that ignore the extension), and per page the
// transfer's band 0 as an RGBM page and its other coefficients relative to band 0, per channel,
// q = T_i / T_0 stored as 0.5 + 0.5 q / s_i with s_i the largest |q_i| on the page, four numbers a
// texel in RGBA PNGs, coefficient 1 channel r first; with the scene's sky (SH) and suns.
void addTransferLightmaps(GlbOptions& o, const Scene& scene, const LightmapAtlas& atlas, const TransferBake& transfer,
                          const LightmapBake& relit);

}  // namespace luxel
