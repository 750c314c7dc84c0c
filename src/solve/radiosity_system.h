// The discrete radiosity system that every solver solves (see include/luxel/solve.h):
//   B_e = E_e + rho_e * (H0_e + sum_p F[e <- p] B_p),  B_p = sum_{e in p} A_e B_e / A_p.
#pragma once

#include <vector>

#include "luxel/solution.h"
#include "luxel/surface.h"

namespace luxel {

// Patches a progressive pass shoots together ("shooters-per-pass"): at most, and by default on
// the CPU and on a GPU.
inline constexpr int kMaxShootersPerPass = 32;
inline constexpr int kDefaultShootersPerPass = 8;

struct RadiositySystem {
  const SurfaceSet& surfaces;
  std::vector<Rgb> emission;     // E_e, exitance
  std::vector<Rgb> reflectance;  // rho_e
  std::vector<Rgb> analytic;     // H0_e, irradiance from analytic lights
  std::vector<float> area;       // A_e
  std::vector<float> patchArea;  // A_p, the sum of its elements' areas

  RadiositySystem(const SurfaceSet& surfaces, std::vector<Rgb> analyticIrradiance);
  // Reads the surfaces again (areas after a move) with new analytic irradiance.
  void refresh(std::vector<Rgb> analyticIrradiance);

  size_t elementCount() const { return area.size(); }
  size_t patchCount() const { return patchArea.size(); }
  // Area-weighted mean of a per-element quantity over each patch.
  std::vector<Rgb> patchMeans(const std::vector<Rgb>& perElement) const;
  // Power entering the system: sum A_e (E_e + rho_e H0_e), summed over channels.
  double sourcePower() const;
};

// Cohen et al. 1988's ambient term, for display: the unshot radiosity spread uniformly and
// multiplied by the interreflection factor 1 / (1 - mean reflectance), added to B and H.
void addAmbientTerm(const RadiositySystem& system, const std::vector<Rgb>& unshot, std::vector<Rgb>& radiosity,
                    std::vector<Rgb>& irradiance);

inline double channelSum(const Rgb& c) { return double(c.r) + double(c.g) + double(c.b); }

}  // namespace luxel
