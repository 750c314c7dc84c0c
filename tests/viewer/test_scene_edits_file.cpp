// The viewer saves an edited scene as a scene file over the scene it was loaded from ("base"),
// with moved objects' transforms and the lights replaced: loading that file gives the edited scene.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>

#include "error_message.h"
#include "luxel/import.h"
#include "scene_json_writer.h"

namespace {

namespace fs = std::filesystem;
using luxel::Scene;

template <class F>
void expectError(F f, const std::string& part) {
  const std::string message = luxel::test::errorOf(f);
  EXPECT_NE(message.find(part), std::string::npos) << "message: " << message << "\nexpected to contain: " << part;
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(LUXEL_TEST_TMP) / "scene-edits";
  fs::create_directories(dir);
  return dir / name;
}

TEST(SceneEditsFile, SavedEditsLoadBackAsTheEditedScene) {
  const Scene loaded = luxel::builtinScene("cornell-large");
  Scene edited = loaded;
  const int box = edited.findObject("box");
  ASSERT_GE(box, 0);
  const glm::mat4 to = glm::translate(glm::mat4(1.0f), luxel::Vec3(0.05f, 0.0f, -0.02f)) *
                       glm::rotate(glm::mat4(1.0f), glm::radians(25.0f), luxel::Vec3(0, 1, 0)) *
                       edited.objects[size_t(box)].transform;
  edited.placeObject(uint32_t(box), to);
  luxel::Light lamp;
  lamp.type = luxel::Light::Type::Spot;
  lamp.name = "lamp";
  lamp.position = luxel::Vec3(0.2f, 0.5f, 0.3f);
  lamp.direction = glm::normalize(luxel::Vec3(0.1f, -1.0f, 0.0f));
  lamp.innerConeAngle = 0.2f;
  lamp.outerConeAngle = 0.5f;
  lamp.intensity = 3.0f;
  lamp.color = luxel::Rgb(1.0f, 0.8f, 0.6f);
  edited.lights = {lamp};
  luxel::Camera cam;
  cam.eye = luxel::Vec3(0.27f, 0.27f, 1.2f);
  cam.target = luxel::Vec3(0.27f, 0.27f, 0.0f);

  const std::string text = luxel::viewer::sceneJson(edited, loaded, "cornell-large", cam);
  const Scene back = luxel::loadSceneJson(text, scratch(""), "saved.json");
  ASSERT_EQ(back.meshes.size(), edited.meshes.size());
  for (size_t m = 0; m < back.meshes.size(); ++m)
    for (size_t i = 0; i < back.meshes[m].positions.size(); ++i)
      EXPECT_LT(glm::length(back.meshes[m].positions[i] - edited.meshes[m].positions[i]), 1e-5f) << "mesh " << m;
  ASSERT_EQ(back.lights.size(), 1u);  // replaced, not added to the scene's own
  const luxel::Light& l = back.lights[0];
  EXPECT_EQ(l.type, luxel::Light::Type::Spot);
  EXPECT_LT(glm::length(l.position - lamp.position), 1e-6f);
  EXPECT_LT(glm::length(l.direction - lamp.direction), 1e-6f);
  EXPECT_NEAR(l.outerConeAngle, lamp.outerConeAngle, 1e-6f);
  EXPECT_NEAR(l.innerConeAngle, lamp.innerConeAngle, 1e-6f);
  EXPECT_LT(glm::length(l.power() - lamp.power()), 1e-6f);
  const luxel::Camera* c = back.findCamera("viewer");
  ASSERT_NE(c, nullptr);
  EXPECT_LT(glm::length(c->eye - cam.eye), 1e-6f);
  EXPECT_TRUE(back.objects[size_t(box)].dynamic);
}

TEST(SceneEditsFile, ObjectTransformsOnlyMoveDynamicObjects) {
  expectError([] {
    luxel::loadSceneJson(R"({"builtin": "cornell-large", "objects": {"box": {"dynamic": false, "transform": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}}})",
                         scratch(""), "s.json");
  }, "s.json: /objects/box/transform: object 'box' is not dynamic");
  expectError([] {
    luxel::loadSceneJson(R"({"builtin": "cornell-large", "objects": {"box": {"transform": [[2,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}}})",
                         scratch(""), "s.json");
  }, "s.json: /objects/box/transform:");
  expectError([] {
    luxel::loadSceneJson(R"({"builtin": "cornell-large", "objects": {"box": {"transform": [[1,0,0]]}}})", scratch(""), "s.json");
  }, "s.json: /objects/box/transform: expected 4 rows of 4 numbers");
}

TEST(SceneEditsFile, BasesAreCheckedAndCannotLoop) {
  expectError([] { luxel::loadSceneJson(R"({"builtin": "cornell", "base": "cornell"})", scratch(""), "s.json"); },
              "s.json: /base: give 'builtin' or 'base', not both");
  const fs::path self = scratch("self.json");
  std::ofstream(self) << R"({"base": "self.json"})";
  expectError([&] { luxel::loadSceneFile(self); }, "nest more than 8 deep");
  expectError([] { luxel::loadSceneJson(R"({"base": "missing.obj"})", scratch(""), "s.json"); }, "s.json: /base: ");
  // A base that is a scene file edits it: its lights stay unless replaced.
  const fs::path base = scratch("base.json");
  std::ofstream(base) << R"({"builtin": "cornell", "lights": [{"type": "point", "position": [0.2, 0.4, 0.2]}]})";
  const Scene s = luxel::loadSceneJson(R"({"base": "base.json", "lights": [{"type": "sky"}]})", scratch(""), "s.json");
  EXPECT_EQ(s.lights.size(), luxel::loadSceneFile(base).lights.size() + 1);
}

}  // namespace
