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

// The test scenes of the seed papers, with their element counts exactly (docs/seed-scenes.md;
// Mesh::elementGrids fixes them, whatever the element budget). In every scene seed 001's moving
// box is the one dynamic object (Object::dynamic), its origin at the box's centre, and it spins
// about the vertical through that centre at kSeedBoxDegreesPerSecond (Scene::animation; `luxel
// animate`).
//
// Seed 001 (van de Hoef 2013, Sec. 5.1): a closed Cornell box 0.55 m a side, the light 1 mm below
// the ceiling facing down, a white 0.165 x 0.385 x 0.165 m box floating at the centre.
// cornell-large: 10,254 static elements, 918 on the box; light 0.161 x 0.188 m, radiance
// (8.5, 6, 2). cornell-small: the same counts, the light a third as long and wide, 9 times the
// radiance. cornell-low: cornell-large's geometry with 2,734 static elements and 270 on the box.
// The thesis gives no rate for its "rotating box"; 30 degrees a second is one degree a frame at
// 30 frames a second, a full turn in 12 s.
inline constexpr double kSeedBoxDegreesPerSecond = 30.0;
Scene cornellLarge();
Scene cornellSmall();
Scene cornellLow();
// Seed 001's indirect-light scene: a 5 x 2.5 x 4 m room of albedo 0.9, a window in its right wall
// facing away from a directional sun, which lights the ground and a facade outside; 10,296 static
// elements, a 0.6 x 0.9 x 0.7 m box of 318 elements at the left side.
Scene indirectLight();
// Seed 000's closed 2 m box, six inward k x k grids of one-element quads (12 k^2 triangles),
// red left and green right walls, the ceiling's central fifth emitting (100.4, 96.8, 90.0).
// k = 10, 20, 40, 50 are the scenes shader-box-774, -2734, -10254, -15814 (the thesis's vertex
// counts); k must be a multiple of 5.
Scene shaderBox(int k);
// Seed 000's Plate C.10: shaderBox(10) with a sphere above the floor and a torus above the sphere.
Scene shaderSphereTorus();

// Seed 002's room (Gobbetti, Spano and Agus 2003, Sec. 4): a closed 6 x 5 x 4 m room (x, y, z
// in metres from the origin corner, y up) with a red left and a green right wall, a 1 x 1 m
// ceiling light of 10,925 W, and three Stanford bunnies 1 m tall on rounded-column pedestals;
// the area-weighted average reflectance is 0.67. The bunnies are subdivided and simplified by
// quadric error metrics so that the whole scene has `faces` faces (Scene::faceCount; the walls'
// and pedestals' quads count as one) to within 0.01%: room-160k, -500k, -1m, -1.5m and -10m are
// 160,000 to 10,000,000. Reads the bunny from the build tree (LUXEL_BUNNY_OBJ) once per process;
// throws Error naming that path when it is missing, or when `faces` leaves the statues fewer than
// 1,000 each.
Scene faceClusterRoom(size_t faces);

// The room's built-in ladder, by name: the one list the scene registry and the room's own name read.
struct RoomRung {
  const char* name;
  size_t faces;
};
inline constexpr RoomRung kRoomLadder[] = {{"room-20k", 20'000},       {"room-160k", 160'000}, {"room-500k", 500'000},
                                           {"room-1m", 1'000'000},     {"room-1.5m", 1'500'000},
                                           {"room-10m", 10'000'000}};

// Adds a planar quad (a, b, c, d counter-clockwise seen from the front) to `mesh`.
void addQuad(Mesh& mesh, Vec3 a, Vec3 b, Vec3 c, Vec3 d);
// Adds the six inward-facing walls of the axis-aligned box [lo, hi] to `mesh`.
void addInwardBox(Mesh& mesh, Vec3 lo, Vec3 hi);

}  // namespace luxel::builtin
