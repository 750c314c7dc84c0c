// The emitting surfaces' direct light per element (solve/emitter_direct.h), which the face-cluster
// solver starts from: against the exact area-to-area form factor where nothing is in the way, and
// against path-traced direct light (transport/path_traced_irradiance.h) under a shadow's edge.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "scene/builtin/builtin_scenes.h"
#include "solve/emitter_direct.h"
#include "transport/form_factor.h"
#include "transport/path_traced_irradiance.h"

namespace luxel {
namespace {

// A 1 x 1 lamp (Le 1) 1 m over a 4 x 4 floor in 0.25 m elements; with `blocked`, a thin roof at
// 0.5 m over x < 0.1, whose edge crosses a column of elements.
struct LampScene {
  Scene scene;
  SurfaceSet set;
  Polygon lamp;
};
LampScene lampScene(bool blocked) {
  LampScene l;
  l.scene.name = "lamp";
  l.scene.materials = {Material{.name = "lamp", .reflectance = Rgb(0.0f), .emission = Rgb(1.0f)},
                       Material{.name = "grey", .reflectance = Rgb(0.5f)}};
  Mesh lamp{.name = "lamp", .material = 0};
  builtin::addQuad(lamp, {-0.5f, 1, -0.5f}, {0.5f, 1, -0.5f}, {0.5f, 1, 0.5f}, {-0.5f, 1, 0.5f});  // normal -y
  Mesh floor{.name = "floor", .material = 1};
  builtin::addQuad(floor, {-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2});  // normal +y
  l.scene.meshes = {lamp, floor};
  if (blocked) {
    Mesh roof{.name = "roof", .material = 1};
    builtin::addQuad(roof, {-3, 0.5f, -3}, {0.1f, 0.5f, -3}, {0.1f, 0.5f, 3}, {-3, 0.5f, 3});  // normal -y
    l.scene.meshes.push_back(roof);
  }
  l.set = discretise(l.scene, DiscretiseOptions{.elementSize = 0.25f, .orientByLight = false});
  for (const Element& e : l.set.elements)
    if (e.material == 0) l.lamp = Polygon{l.set.faces[e.face].corners, 4};
  return l;
}

std::vector<Polygon> facePolygons(const SurfaceSet& set) {
  std::vector<Polygon> out;
  for (const SurfaceFace& f : set.faces) out.push_back(Polygon{f.corners, f.triangle ? 3 : 4});
  return out;
}

TEST(EmitterDirect, UnoccludedLightIsTheExactFormFactor) {
  const LampScene l = lampScene(false);
  const std::vector<Polygon> faces = facePolygons(l.set);
  const RayTracer tracer(faces);
  const EmitterDirectLight d = emitterDirectLight(l.set, tracer, 0, 7);
  double worst = 0.0;
  int floorElements = 0;
  for (size_t e = 0; e < l.set.elements.size(); ++e) {
    const Element& el = l.set.elements[e];
    if (el.material != 1 || el.normal.y < 0.5f) continue;
    const double exact = std::numbers::pi * polygonToPolygonFormFactor(el.polygon, l.lamp, 32);
    worst = std::max(worst, std::abs(d.irradiance[e].g / exact - 1.0));
    ++floorElements;
  }
  ASSERT_EQ(floorElements, 256);
  // Four jittered points of a 0.25 m element where the factor varies over a metre: the
  // quadrature's error, measured 0.3% at worst.
  EXPECT_LT(worst, 0.01);
  EXPECT_EQ(d.rays, 256u * 16u) << "every ray of an unoccluded element agrees: none is refined";
}

TEST(EmitterDirect, AShadowsEdgeAgreesWithPathTracing) {
  const LampScene l = lampScene(true);
  const std::vector<Polygon> faces = facePolygons(l.set);
  const RayTracer tracer(faces);
  const EmitterDirectLight d = emitterDirectLight(l.set, tracer, 0, 7);
  // The floor elements under the lamp, all in the roof's penumbra.
  std::vector<uint32_t> edge;
  for (uint32_t e = 0; e < l.set.elements.size(); ++e) {
    const Element& el = l.set.elements[e];
    if (el.material == 1 && el.normal.y > 0.5f && el.centroid.y < 0.1f && std::abs(el.centroid.x - 0.1f) < 0.5f &&
        std::abs(el.centroid.z) < 0.75f)
      edge.push_back(e);
  }
  ASSERT_EQ(edge.size(), 24u);
  const auto traced = pathTraceElementIrradiance(
      l.scene, l.set, edge, PathTracingOptions{.minPaths = 1u << 14, .maxPaths = 1u << 14, .maxBounces = 0});
  double squares = 0.0, norm = 0.0, difference = 0.0, sum = 0.0;
  for (size_t i = 0; i < edge.size(); ++i) {
    const double x = d.irradiance[edge[i]].g, t = traced[i].mean.g, se = traced[i].standardError.g;
    squares += (x - t) * (x - t) - se * se, norm += t * t, difference += x - t, sum += t;
  }
  // Each element's visible share is a ratio over 80 kernel-weighted rays (16, then 64 more where
  // they disagree): at a visible share V its relative standard deviation is about
  // sqrt((1 - V) / (80 V)) unstratified, 8% at half and 26% at 0.15, and these elements run from
  // 0.15 to 0.8. Measured: RMS 7.7%, bias +0.3%. With 4 first rays it was 12.6% and -1.7%: an
  // element whose 4 rays happened to agree kept all or none of the lamp (docs/algorithms.md,
  // "Direct light first"). The bounds hold what is measured, and catch 4 first rays again, a lost
  // refinement or a wrong factor.
  std::printf("RMS %.4f, bias %+.4f\n", std::sqrt(std::max(0.0, squares) / norm), difference / sum);
  EXPECT_LT(std::sqrt(std::max(0.0, squares) / norm), 0.11);
  EXPECT_LT(std::abs(difference / sum), 0.03);
}

TEST(EmitterDirect, NoEmittersNoLight) {
  Scene s = builtin::furnace(0.5f, 0.0f);
  const SurfaceSet set = discretise(s, DiscretiseOptions{.elementBudget = 100});
  const std::vector<Polygon> faces = facePolygons(set);
  const RayTracer tracer(faces);
  const EmitterDirectLight d = emitterDirectLight(set, tracer, 4, 1);
  ASSERT_EQ(d.irradiance.size(), set.elements.size());
  for (const Rgb& c : d.irradiance) EXPECT_EQ(c, Rgb(0.0f));
  EXPECT_EQ(d.rays, 0u);
  EXPECT_EQ(emittingPolygonCount(set), 0u);
}

}  // namespace
}  // namespace luxel
