// The settings of GPU cross-redistribution (cross_redistribution_gl.h), apart from its GL
// objects so that the solver's settings can name them without OpenGL.
#pragma once

#include "gl/hemicube_layering.h"

namespace luxel::gl {

struct CrossRedistributionSettings {
  int gatherResolution = 64;  // the moved elements' gather hemicubes, pixels a side
  int backResolution = 32;    // the back hemicubes (001: "as low as 16 x 16 per face")
  int grid = 4;               // g x g rays from a receiver point through a moved patch
  HemicubeLayering layering = HemicubeLayering::Auto;  // the gather and back hemicubes'
  // What a static receiver sees behind a moved patch (the rays through it into its back
  // hemicube): from each receiver patch's centre, shared by its elements, or from each element's
  // 2 x 2 points (four times the element count in rays per receiver and mover: most of a frame).
  bool behindPerPatch = true;
  // Keep the moved elements' gather hemicubes where they went, to be the next move's gather where
  // they were (the same pixels), within a memory budget.
  bool keepGathers = true;
};

}  // namespace luxel::gl
