// Built-in scenes with known answers, for tests, demos and benchmarks.
#pragma once

#include "luxel/scene.h"

namespace luxel::builtin {

// The original Cornell box from the Cornell Program of Computer Graphics measured data
// (https://www.graphics.cornell.edu/online/box/data.html), converted from millimetres to metres.
// RGB reduction of the spectral data: white (0.725, 0.71, 0.68), red (0.63, 0.065, 0.05),
// green (0.14, 0.45, 0.091); light radiance (17, 12, 4). The ceiling has a hole where the light is.
// Camera "default": eye (0.278, 0.273, -0.8) looking down +z, vertical fov 39.3077 degrees.
Scene cornellBox();

// A closed unit cube seen from inside: every wall has reflectance `rho` and emits radiance `le`
// from its inner face. The exact radiance everywhere is le / (1 - rho).
Scene furnace(float rho = 0.5f, float le = 1.0f);

// CIE 171:2006 test case 5.8: a closed 4 m cube (S = 96 m^2) whose walls all have reflectance
// `rho`, lit by an isotropic point source of `flux` (lm) at its centre. The exact mean
// illuminance over the walls is flux / (S (1 - rho)).
Scene cieCube(float rho = 0.5f, float flux = 10000.0f);

// Adds a planar quad (a, b, c, d counter-clockwise seen from the front) to `mesh`.
void addQuad(Mesh& mesh, Vec3 a, Vec3 b, Vec3 c, Vec3 d);
// Adds the six inward-facing walls of the axis-aligned box [lo, hi] to `mesh`.
void addInwardBox(Mesh& mesh, Vec3 lo, Vec3 hi);

}  // namespace luxel::builtin
