// Scene loading: the paper's Figure 1, every constructor, poses, transforms, defines, collection.
// Errors and the sandbox are tested in test_scene_errors.cpp.
#include <doctest/doctest.h>

#include <clocale>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <string>

#include "core/warning.h"
#include "scene/scene.h"
#include "scene_test_util.h"

using namespace dicsynth;
using dicsynth::test::kCameraLine;
using dicsynth::test::loadError;
using dicsynth::test::TempFolder;

namespace {

void checkMatrix(const dmat4& actual, const dmat4& expected, double tolerance = 1e-15) {
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row) {
      INFO("col " << col << " row " << row);
      CHECK(std::fabs(actual[col][row] - expected[col][row]) <= tolerance);
    }
}

void checkVec(const dvec3& actual, const dvec3& expected, double tolerance = 1e-15) {
  INFO("actual (" << actual.x << ", " << actual.y << ", " << actual.z << ") expected ("
                  << expected.x << ", " << expected.y << ", " << expected.z << ")");
  CHECK(glm::length(actual - expected) <= tolerance);
}

dvec3 apply(const dmat4& m, const dvec3& p) {
  const dvec4 q = m * dvec4(p, 1.0);
  return dvec3(q) / q.w;
}

// Loads a scene whose body follows kCameraLine.
Scene loadBody(const TempFolder& dir, const std::string& body, const SceneParams& params = {}) {
  return loadScene(dir.write("scene.lua", std::string(kCameraLine) + body), params);
}

}  // namespace

TEST_CASE("scene: Figure 1 of the paper loads verbatim") {
  TempFolder dir;
  dir.write("speckle.tif", "not really a TIFF; decoded elsewhere");
  const std::string path = dir.write(
      "figure1.lua",
      R"(camera1 = Camera.Pinhole { resolution = {1600, 1200}; principalPoint = {800, 600}; focalLength = 0.012;
  pixelSize = {4.4e-6, 4.4e-6}; fillFactor = 0.9; bitsPerPixel = 10;
  distortion = Distortion.Brown { radial = {-0.13, -0.39, 1.20}; tangential = {1.1e-6, -1.2e-6}; }; };
object = Object.Simple { shape = Shape.Sphere { radius = 0.1; location = {0, 0, 0.5}; };
  shader = Shader.Constant { color = {.2, .8, 1}; }; texture = Texture.File { fileName = "speckle.tif"; };
  transform = rotate_y(degrees(35)); };
)");
  const Scene scene = loadScene(path, {});
  CHECK(scene.file == path);
  REQUIRE(scene.cameras.size() == 1);
  REQUIRE(scene.objects.size() == 1);
  CHECK(scene.lights.empty());

  const Camera& camera = scene.cameras[0];
  CHECK(camera.name == "camera1");
  CHECK(camera.where.file == path);
  CHECK(camera.where.line == 1);
  CHECK(camera.kind() == CameraKind::Pinhole);
  CHECK(camera.width_px == 1600);
  CHECK(camera.height_px == 1200);
  CHECK(camera.principalPoint_px == dvec2(800, 600));
  CHECK(std::get<cameras::Pinhole>(camera.model).focalLength_m == 0.012);
  CHECK(camera.pixelSize_m == dvec2(4.4e-6, 4.4e-6));
  CHECK(camera.fillFactor == 0.9);
  CHECK(camera.bitsPerPixel == 10);
  CHECK(camera.exposure == 1.0);
  CHECK(camera.distortion.kind == DistortionKind::Brown);
  CHECK(camera.distortion.k1 == -0.13);
  CHECK(camera.distortion.k2 == -0.39);
  CHECK(camera.distortion.k3 == 1.20);
  CHECK(camera.distortion.p1 == 1.1e-6);
  CHECK(camera.distortion.p2 == -1.2e-6);
  CHECK(camera.worldFromCamera == dmat4(1.0));

  const Object& object = scene.objects[0];
  CHECK(object.name == "object");
  CHECK(object.where.line == 4);
  CHECK(object.shape.kind() == ShapeKind::Sphere);
  CHECK(object.shape.where.line == 4);
  CHECK(std::get<shapes::Sphere>(object.shape.analytic).radius_m == 0.1);
  CHECK(object.shape.location_m == dvec3(0, 0, 0.5));
  CHECK(object.shader.kind() == ShaderKind::Constant);
  CHECK(object.shader.where.line == 5);
  CHECK(object.shader.color == dvec3(0.2, 0.8, 1.0));
  CHECK(object.texture.kind() == TextureKind::File);
  CHECK(object.texture.where.line == 5);
  CHECK(std::get<textures::File>(object.texture.model).path == (dir.path() / "speckle.tif").string());

  // rotate_y(35°): right-handed, maps x to (cos a, 0, -sin a) and z to (sin a, 0, cos a).
  const double a = 35.0 * std::numbers::pi / 180.0;
  dmat4 expected(1.0);
  expected[0] = dvec4(std::cos(a), 0, -std::sin(a), 0);
  expected[2] = dvec4(std::sin(a), 0, std::cos(a), 0);
  checkMatrix(object.transform, expected);
  checkVec(apply(object.transform, dvec3(1, 0, 0)), dvec3(std::cos(a), 0, -std::sin(a)));
}

TEST_CASE("scene: constructors with their defaults") {
  TempFolder dir;
  const Scene scene = loadBody(dir, R"(
a = Object.Simple { shape = Shape.Sphere { radius = 2 } }
b = Object.Simple { shape = Shape.Box { size = {1, 2, 3} }; shader = Shader.Lambert {};
                    texture = Texture.Constant {} }
c = Object.Simple { shape = Shape.Rectangle { size = {4, 5} }; shader = Shader.Constant {} }
d = Object.Simple { shape = Shape.Plane {} }
e = Object.Simple { shape = Shape.Triangle { vertices = {{0,0,0}, {1,0,0}, {0,1,0}} } }
lamp = Light.Point { position = {1, 2, 3} }
)");
  REQUIRE(scene.cameras.size() == 1);
  const Camera& camera = scene.cameras[0];
  CHECK(camera.principalPoint_px == dvec2(31.5, 23.5));  // geometric centre ((w-1)/2, (h-1)/2)
  CHECK(camera.fillFactor == 1.0);
  CHECK(camera.bitsPerPixel == 8);
  CHECK(camera.exposure == 1.0);
  CHECK(camera.distortion.kind == DistortionKind::None);
  CHECK(camera.worldFromCamera == dmat4(1.0));

  REQUIRE(scene.objects.size() == 5);
  for (const Object& object : scene.objects) {
    INFO(object.name);
    CHECK(object.shape.location_m == dvec3(0));
    CHECK(object.transform == dmat4(1.0));
    CHECK(object.shader.color == dvec3(1, 1, 1));
    CHECK(object.texture.kind() == TextureKind::Constant);
    CHECK(std::get<textures::Constant>(object.texture.model).value == 1.0);
  }
  CHECK(scene.objects[0].shape.kind() == ShapeKind::Sphere);
  CHECK(std::get<shapes::Sphere>(scene.objects[0].shape.analytic).radius_m == 2.0);
  CHECK(scene.objects[0].shader.kind() == ShaderKind::Constant);
  CHECK(scene.objects[1].shape.kind() == ShapeKind::Box);
  CHECK(std::get<shapes::Box>(scene.objects[1].shape.analytic).size_m == dvec3(1, 2, 3));
  CHECK(scene.objects[1].shader.kind() == ShaderKind::Lambert);
  CHECK(scene.objects[2].shape.kind() == ShapeKind::Rectangle);
  CHECK(std::get<shapes::Rectangle>(scene.objects[2].shape.analytic).size_m == dvec2(4, 5));
  CHECK(scene.objects[3].shape.kind() == ShapeKind::Plane);
  CHECK(std::get<shapes::Plane>(scene.objects[3].shape.analytic).tileSize_m == dvec2(1, 1));
  CHECK(scene.objects[4].shape.kind() == ShapeKind::Triangle);
  CHECK(std::get<shapes::Triangle>(scene.objects[4].shape.analytic).vertices_m[1] == dvec3(1, 0, 0));
  CHECK(std::get<shapes::Triangle>(scene.objects[4].shape.analytic).vertexUV[0] == dvec2(0, 0));
  CHECK(std::get<shapes::Triangle>(scene.objects[4].shape.analytic).vertexUV[1] == dvec2(1, 0));
  CHECK(std::get<shapes::Triangle>(scene.objects[4].shape.analytic).vertexUV[2] == dvec2(0, 1));

  REQUIRE(scene.lights.size() == 1);
  CHECK(scene.lights[0].name == "lamp");
  CHECK(scene.lights[0].kind == LightKind::Point);
  CHECK(scene.lights[0].position_m == dvec3(1, 2, 3));
  CHECK(scene.lights[0].intensity == 1.0);
  CHECK(scene.lights[0].where.line == 9);
}

TEST_CASE("scene: constructors with all their parameters") {
  TempFolder dir;
  dir.write("textures/s.png", "x");
  const std::string path = dir.write("scene.lua", R"(
c = Camera.Pinhole { resolution = {640, 480}; principalPoint = {320.25, 239.75};
  focalLength = 0.025; pixelSize = {3.45e-6, 3.5e-6}; fillFactor = 0.5; bitsPerPixel = 16;
  exposure = 2.5; distortion = Distortion.Brown { radial = {0.1}; tangential = {0.01, 0.02} };
  position = {1, 2, 3} }
a = Object.Simple { shape = Shape.Sphere { radius = 0.5; location = {1, 2, 3} };
  shader = Shader.Lambert { color = 0.25 }; texture = Texture.Constant { value = 0.75 };
  transform = scale(2) }
b = Object.Simple { shape = Shape.Box { size = {1, 2, 3}; location = {-1, 0, 1} };
  texture = Texture.File { fileName = "textures/s.png" }; transform = scale(1, 2, 3) }
r = Object.Simple { shape = Shape.Rectangle { size = {0.2, 0.1}; location = {0, 0, 2} } }
p = Object.Simple { shape = Shape.Plane { tileSize = {0.05, 0.02}; location = {0, 0, 5} } }
t = Object.Simple { shape = Shape.Triangle { vertices = {{0,0,1}, {2,0,1}, {0,3,1}};
  uv = {{0.5,0.5}, {1,0.5}, {0.5,1}}; location = {1, 1, 1} } }
l1 = Light.Point { position = {0, 0, 0}; intensity = 3 }
l2 = Light.Point { position = {0, 1, 0}; intensity = {1, 2, 3} }
)");
  const Scene scene = loadScene(path, {});
  REQUIRE(scene.cameras.size() == 1);
  const Camera& camera = scene.cameras[0];
  CHECK(camera.where.line == 2);
  CHECK(camera.width_px == 640);
  CHECK(camera.height_px == 480);
  CHECK(camera.principalPoint_px == dvec2(320.25, 239.75));
  CHECK(std::get<cameras::Pinhole>(camera.model).focalLength_m == 0.025);
  CHECK(camera.pixelSize_m == dvec2(3.45e-6, 3.5e-6));
  CHECK(camera.fillFactor == 0.5);
  CHECK(camera.bitsPerPixel == 16);
  CHECK(camera.exposure == 2.5);
  CHECK(camera.distortion.kind == DistortionKind::Brown);
  CHECK(camera.distortion.k1 == 0.1);
  CHECK(camera.distortion.k2 == 0.0);
  CHECK(camera.distortion.k3 == 0.0);
  CHECK(camera.distortion.p1 == 0.01);
  CHECK(camera.distortion.p2 == 0.02);
  CHECK(camera.worldFromCamera == glm::translate(dmat4(1.0), dvec3(1, 2, 3)));

  REQUIRE(scene.objects.size() == 5);  // a, b, p, r, t
  const Object& a = scene.objects[0];
  CHECK(a.name == "a");
  CHECK(a.shape.location_m == dvec3(1, 2, 3));
  CHECK(std::get<shapes::Sphere>(a.shape.analytic).radius_m == 0.5);
  CHECK(a.shader.kind() == ShaderKind::Lambert);
  CHECK(a.shader.color == dvec3(0.25));
  CHECK(a.texture.kind() == TextureKind::Constant);
  CHECK(std::get<textures::Constant>(a.texture.model).value == 0.75);
  CHECK(a.transform == glm::scale(dmat4(1.0), dvec3(2)));
  const Object& b = scene.objects[1];
  CHECK(b.shape.kind() == ShapeKind::Box);
  CHECK(b.shape.location_m == dvec3(-1, 0, 1));
  CHECK(b.texture.kind() == TextureKind::File);
  CHECK(std::get<textures::File>(b.texture.model).path == (dir.path() / "textures/s.png").string());
  CHECK(b.transform == glm::scale(dmat4(1.0), dvec3(1, 2, 3)));
  const Object& p = scene.objects[2];
  CHECK(p.name == "p");
  CHECK(p.shape.kind() == ShapeKind::Plane);
  CHECK(std::get<shapes::Plane>(p.shape.analytic).tileSize_m == dvec2(0.05, 0.02));
  CHECK(p.shape.location_m == dvec3(0, 0, 5));
  const Object& r = scene.objects[3];
  CHECK(r.shape.kind() == ShapeKind::Rectangle);
  CHECK(std::get<shapes::Rectangle>(r.shape.analytic).size_m == dvec2(0.2, 0.1));
  CHECK(r.shape.location_m == dvec3(0, 0, 2));
  const Object& t = scene.objects[4];
  CHECK(t.shape.kind() == ShapeKind::Triangle);
  CHECK(std::get<shapes::Triangle>(t.shape.analytic).vertices_m[0] == dvec3(0, 0, 1));
  CHECK(std::get<shapes::Triangle>(t.shape.analytic).vertices_m[1] == dvec3(2, 0, 1));
  CHECK(std::get<shapes::Triangle>(t.shape.analytic).vertices_m[2] == dvec3(0, 3, 1));
  CHECK(std::get<shapes::Triangle>(t.shape.analytic).vertexUV[0] == dvec2(0.5, 0.5));
  CHECK(std::get<shapes::Triangle>(t.shape.analytic).vertexUV[1] == dvec2(1, 0.5));
  CHECK(std::get<shapes::Triangle>(t.shape.analytic).vertexUV[2] == dvec2(0.5, 1));
  CHECK(t.shape.location_m == dvec3(1, 1, 1));
  CHECK(t.where.line == 13);
  CHECK(t.shape.where.line == 13);

  REQUIRE(scene.lights.size() == 2);
  CHECK(scene.lights[0].intensity == 3.0);
  CHECK(scene.lights[1].position_m == dvec3(0, 1, 0));
  CHECK(scene.lights[1].intensity == doctest::Approx(0.2126 + 2 * 0.7152 + 3 * 0.0722));
  CHECK(scene.lights[1].intensity == luminance(dvec3(1, 2, 3)));
}

TEST_CASE("scene: lookAt pose") {
  TempFolder dir;
  auto pose = [&](const std::string& poseText) {
    const std::string path =
        dir.write("pose.lua",
                  "c = Camera.Pinhole { resolution = {8, 8}; focalLength = 0.01; "
                  "pixelSize = {1e-5, 1e-5}; " +
                      poseText + " }\n");
    const Scene scene = loadScene(path, {});
    REQUIRE(scene.cameras.size() == 1);
    return scene.cameras[0].worldFromCamera;
  };

  SUBCASE("the default up looking down +z is the identity pose") {
    CHECK(pose("lookAt = {0, 0, 1}") == dmat4(1.0));
    CHECK(pose("position = {0, 0, 0}; lookAt = {0, 0, 7}; up = {0, -1, 0}") == dmat4(1.0));
  }
  SUBCASE("from +x looking at the origin") {
    // z = (-1, 0, 0); up (0, -1, 0) is across z, so y = (0, 1, 0); x = y × z = (0, 0, 1).
    dmat4 expected(dvec4(0, 0, 1, 0), dvec4(0, 1, 0, 0), dvec4(-1, 0, 0, 0), dvec4(2, 0, 0, 1));
    checkMatrix(pose("position = {2, 0, 0}; lookAt = {0, 0, 0}"), expected);
  }
  SUBCASE("an oblique view with a tilted up") {
    // z = (0, 0.6, 0.8); up = (0, 0, -1): across part = up - (up.z) z = (0, 0.48, -0.36);
    // y = -normalize(that) = (0, -0.8, 0.6); x = y × z = (-0.8*0.8 - 0.6*0.6, 0, 0) = (-1, 0, 0).
    dmat4 expected(dvec4(-1, 0, 0, 0), dvec4(0, -0.8, 0.6, 0), dvec4(0, 0.6, 0.8, 0),
                   dvec4(1, 2, 3, 1));
    checkMatrix(pose("position = {1, 2, 3}; lookAt = {1, 5, 7}; up = {0, 0, -1}"), expected, 1e-15);
  }
  SUBCASE("position alone translates") {
    CHECK(pose("position = {1, -2, 3}") == glm::translate(dmat4(1.0), dvec3(1, -2, 3)));
  }
  SUBCASE("a rigid transform is worldFromCamera") {
    const dmat4 m = pose("transform = translate(1, 2, 3) * rotate_x(0.3)");
    checkMatrix(m, glm::translate(dmat4(1.0), dvec3(1, 2, 3)) *
                       glm::rotate(dmat4(1.0), 0.3, dvec3(1, 0, 0)));
    const dvec3 x = dvec3(m[0]), y = dvec3(m[1]), z = dvec3(m[2]);
    checkVec(glm::cross(x, y), z);  // right-handed
  }
}

TEST_CASE("scene: transform composition applies the right factor first") {
  TempFolder dir;
  const Scene scene = loadBody(dir, R"(
tr = Object.Simple { shape = Shape.Sphere { radius = 1 };
                     transform = translate(1, 0, 0) * rotate_z(degrees(90)) }
rt = Object.Simple { shape = Shape.Sphere { radius = 1 };
                     transform = rotate_z(degrees(90)) * translate{1, 0, 0} }
rx = Object.Simple { shape = Shape.Sphere { radius = 1 }; transform = rotate_x(0.5) }
ry = Object.Simple { shape = Shape.Sphere { radius = 1 }; transform = rotate_y(0.5) }
rz = Object.Simple { shape = Shape.Sphere { radius = 1 }; transform = rotate_z(0.5) }
id = Object.Simple { shape = Shape.Sphere { radius = 1 }; transform = identity() * scale(1) }
)");
  REQUIRE(scene.objects.size() == 6);
  const Object& id = scene.objects[0];
  CHECK(id.transform == dmat4(1.0));
  const Object& rt = scene.objects[1];
  const Object& rx = scene.objects[2];
  const Object& ry = scene.objects[3];
  const Object& rz = scene.objects[4];
  const Object& tr = scene.objects[5];
  CHECK(tr.name == "tr");
  // (T * R)(p): rotate (1,0,0) to (0,1,0), then move by (1,0,0).
  checkVec(apply(tr.transform, dvec3(1, 0, 0)), dvec3(1, 1, 0));
  // (R * T)(p): move (1,0,0) to (2,0,0), then rotate to (0,2,0).
  checkVec(apply(rt.transform, dvec3(1, 0, 0)), dvec3(0, 2, 0));
  // Right-handed rotations: x → y about z, y → z about x, z → x about y.
  const double c = std::cos(0.5), s = std::sin(0.5);
  checkVec(apply(rz.transform, dvec3(1, 0, 0)), dvec3(c, s, 0));
  checkVec(apply(rx.transform, dvec3(0, 1, 0)), dvec3(0, c, s));
  checkVec(apply(ry.transform, dvec3(0, 0, 1)), dvec3(s, 0, c));
  checkVec(apply(ry.transform, dvec3(1, 0, 0)), dvec3(c, 0, -s));
}

TEST_CASE("scene: homography is written row by row") {
  TempFolder dir;
  const Scene scene = loadBody(dir, R"(
h = Object.Simple { shape = Shape.Sphere { radius = 1 };
  transform = homography { 2, 1, 0, 5,
                           0, 3, 0, 6,
                           0, 0, 4, 7,
                           0, 0, 0.5, 1 } }
)");
  REQUIRE(scene.objects.size() == 1);
  const dmat4& m = scene.objects[0].transform;  // GLM: m[col][row]
  CHECK(m[0][0] == 2);
  CHECK(m[1][0] == 1);  // row 0, column 1
  CHECK(m[3][0] == 5);  // row 0, column 3: translation x
  CHECK(m[3][1] == 6);
  CHECK(m[3][2] == 7);
  CHECK(m[2][3] == 0.5);  // row 3, column 2: projective part
  CHECK(m[0][1] == 0);
  // Applied to a point: first row · (1, 1, 1, 1) = 2 + 1 + 0 + 5.
  const dvec4 q = m * dvec4(1, 1, 1, 1);
  CHECK(q == dvec4(8, 9, 11, 1.5));
}

TEST_CASE("scene: -D defines are numbers, booleans or strings") {
  TempFolder dir;
  dir.write("tex.png", "x");
  SceneParams params;
  params.defines = {{"radius", "0.25"},     {"count", "42"},  {"hex", "0x10"},
                    {"flag", "true"},       {"off", "false"}, {"texture", "tex.png"},
                    {"phrase", "5 apples"}, {"empty", ""}};
  const Scene scene = loadBody(dir, R"(
assert(math.type(count) == "integer" and count == 42, "count")
assert(hex == 16, "hex")
assert(flag == true and off == false, "booleans")
assert(phrase == "5 apples" and empty == "", "strings")
ball = Object.Simple { shape = Shape.Sphere { radius = radius };
                       texture = Texture.File { fileName = texture } }
)",
                               params);
  REQUIRE(scene.objects.size() == 1);
  CHECK(std::get<shapes::Sphere>(scene.objects[0].shape.analytic).radius_m == 0.25);
  CHECK(std::get<textures::File>(scene.objects[0].texture.model).path == (dir.path() / "tex.png").string());
}

TEST_CASE("scene: defines are served until the scene assigns the name") {
  TempFolder dir;
  SceneParams params;
  params.defines = {{"r", "0.5"}};
  // The usual idiom: a default that -D overrides.
  Scene scene = loadBody(
      dir, "r = r or 0.1\nb = Object.Simple { shape = Shape.Sphere { radius = r } }\n", params);
  CHECK(std::get<shapes::Sphere>(scene.objects.at(0).shape.analytic).radius_m == 0.5);
  scene =
      loadBody(dir, "r = r or 0.1\nb = Object.Simple { shape = Shape.Sphere { radius = r } }\n");
  CHECK(std::get<shapes::Sphere>(scene.objects.at(0).shape.analytic).radius_m == 0.1);
}

TEST_CASE("scene: frame") {
  TempFolder dir;
  const std::string body =
      "assert(math.type(frame) == 'integer')\n"
      "b = Object.Simple { shape = Shape.Sphere { radius = 1 + frame } }\n";
  CHECK(std::get<shapes::Sphere>(loadBody(dir, body).objects.at(0).shape.analytic).radius_m == 1.0);  // default frame 0
  SceneParams params;
  params.frame = 7;
  CHECK(std::get<shapes::Sphere>(loadBody(dir, body, params).objects.at(0).shape.analytic).radius_m == 8.0);
}

TEST_CASE("scene: globals are collected and sorted by name") {
  TempFolder dir;
  const Scene scene = loadScene(dir.write("scene.lua", R"(
zeta = Object.Simple { shape = Shape.Sphere { radius = 3 } }
alpha = Object.Simple { shape = Shape.Sphere { radius = 1 } }
mid = Object.Simple { shape = Shape.Sphere { radius = 2 } }
right = Camera.Pinhole { resolution = {2, 2}; focalLength = 1; pixelSize = {1, 1} }
left = Camera.Pinhole { resolution = {3, 3}; focalLength = 1; pixelSize = {1, 1} }
sun = Light.Point { position = {0, 0, 0} }
moon = Light.Point { position = {1, 0, 0} }
for i = 1, 3 do _G["tile" .. i] = Object.Simple { shape = Shape.Sphere { radius = 10 + i } } end
local hidden = Object.Simple { shape = Shape.Sphere { radius = 99 } }
inTable = { Object.Simple { shape = Shape.Sphere { radius = 98 } } }
shapeOnly = Shape.Sphere { radius = 97 }
)"),
                                {});
  REQUIRE(scene.cameras.size() == 2);
  CHECK(scene.cameras[0].name == "left");
  CHECK(scene.cameras[0].width_px == 3);
  CHECK(scene.cameras[1].name == "right");
  REQUIRE(scene.lights.size() == 2);
  CHECK(scene.lights[0].name == "moon");
  CHECK(scene.lights[1].name == "sun");
  REQUIRE(scene.objects.size() == 6);  // not: hidden (local), inTable, shapeOnly (not an Object)
  const char* names[] = {"alpha", "mid", "tile1", "tile2", "tile3", "zeta"};
  const double radii[] = {1, 2, 11, 12, 13, 3};
  for (std::size_t i = 0; i < 6; ++i) {
    INFO("objectId " << i + 1);  // objectId = index + 1
    CHECK(scene.objects[i].name == names[i]);
    CHECK(std::get<shapes::Sphere>(scene.objects[i].shape.analytic).radius_m == radii[i]);
  }
  CHECK(scene.objects[2].where.line == 9);
}

TEST_CASE("scene: the sandbox keeps the safe libraries and seeds random numbers") {
  TempFolder dir;
  const std::string body = R"(
assert(string.format("%03d", 7) == "007")
assert(table.concat({1, 2}, ",") == "1,2")
assert(utf8.char(72) == "H")
assert(math.floor(2.5) == 2)
local co = coroutine.wrap(function() coroutine.yield(1) end)
assert(co() == 1)
assert(io == nil and os == nil and package == nil and debug == nil)
assert(load == nil and loadfile == nil and dofile == nil and require == nil)
assert(collectgarbage == nil and string.dump == nil)
r = Object.Simple { shape = Shape.Sphere { radius = math.random() } }
)";
  const double first = std::get<shapes::Sphere>(loadBody(dir, body).objects.at(0).shape.analytic).radius_m;
  const double second = std::get<shapes::Sphere>(loadBody(dir, body).objects.at(0).shape.analytic).radius_m;
  CHECK(first == second);  // same scene, same numbers
  CHECK(first > 0);
  CHECK(first < 1);
}

TEST_CASE("scene: tostring of scene values") {
  TempFolder dir;
  loadBody(dir, R"(
assert(tostring(Shape.Sphere { radius = 1 }) == "Shape.Sphere")
assert(tostring(translate(1, 2, 3)) == "Transform{{1, 0, 0, 1}, {0, 1, 0, 2}, {0, 0, 1, 3}, {0, 0, 0, 1}}")
assert(getmetatable(cam) == "Camera")
)");
}

TEST_CASE("scene: a rotation by more than a turn is a warning naming the line and the degrees meant") {
  // rotate_y(30) (degrees meant) turned a plate 30 rad, nearly edge-on, without a word (the docs
  // walk of 2026-11-29). A turn or less, degrees(), and math.fmod are quiet.
  test::TempFolder dir;
  const std::string path = dir.write(
      "turn.lua", std::string(kCameraLine) +
                      "a = Object.Simple { shape = Shape.Sphere { radius = 1 }; transform = rotate_y(30) }\n"
                      "b = Object.Simple { shape = Shape.Sphere { radius = 1 }; transform = rotate_x(-2 * math.pi - 1e-9) }\n"
                      "c = Object.Simple { shape = Shape.Sphere { radius = 1 }; transform = rotate_z(2 * math.pi) * "
                      "rotate_y(degrees(30)) * rotate_x(math.fmod(40, 2 * math.pi)) }\n");
  WarningCapture capture;
  const Scene scene = loadScene(path, {});
  CHECK(scene.objects.size() == 3);
  const std::vector<std::string> said = capture.take();
  REQUIRE(said.size() == 2);
  CHECK(said[0] == path + ":2: rotate_y(30): 30 rad is 1718.87 degrees, more than a turn: rotate_y(degrees(30)) for 30 "
                          "degrees? (angles are radians; a spin past a turn on purpose: math.fmod(angle, 2 * math.pi) says so)");
  CHECK(said[1].rfind(path + ":3: rotate_x(-6.283185308", 0) == 0);
  // The rotation itself is as asked: 30 rad about y.
  const dmat4& m = scene.objects[0].transform;
  CHECK(m[0][0] == doctest::Approx(std::cos(30.0)).epsilon(1e-15));
  CHECK(m[0][2] == doctest::Approx(-std::sin(30.0)).epsilon(1e-15));
}

TEST_CASE("scene: reading unset globals by long names keeps no memory (the -D hint records identifiers only)") {
  // The globals a scene reads unset are recorded for "did you mean" (lua_scene.cpp, readDefine): a
  // scene reading _G[two megabytes .. i] 200 times kept those names alive and passed the 256 MiB
  // limit (the second review of 2026-11-29).
  TempFolder dir;
  const std::string path = dir.write("long.lua", std::string(kCameraLine) +
                                                   "local big = string.rep('x', 2e6)\n"
                                                   "for i = 1, 200 do local v = _G[big .. i] end\n");
  CHECK_NOTHROW(loadScene(path, {}));
}

TEST_CASE("scene: numbers read and write with a decimal point whatever locale the process set") {
  // A Python process may set a locale (locale.setlocale(LC_ALL, "de_DE.UTF-8")): Lua then wrote
  // tostring(0.25) as "0,25", so "tex_" .. 0.5 named 'tex_0,5.tif', and -D x=0,5 arrived as the
  // number 0.5 (the reproducibility trial of 2026-11-29). The scene runs in "C" (core/c_locale.h).
  TempFolder dir;
  // A German locale of our own (the 'locales' package's sources; scripts/install-deps.sh).
  const std::string locales = (dir.path() / "locales").string();
  std::filesystem::create_directories(locales);
  REQUIRE_MESSAGE(std::system(("localedef -i de_DE -f UTF-8 " + locales + "/de_DE.UTF-8 >/dev/null 2>&1").c_str()) == 0,
                  "localedef de_DE failed: install Debian's 'locales' (scripts/install-deps.sh)");
  setenv("LOCPATH", locales.c_str(), 1);
  REQUIRE(std::setlocale(LC_ALL, "de_DE.UTF-8") != nullptr);
  char comma[16];
  std::snprintf(comma, sizeof comma, "%g", 0.5);
  const std::string inGerman = comma;  // the locale is in force: the C library writes "0,5"
  const std::string path = dir.write("numbers.lua", std::string(kCameraLine) +
                                                      "assert(tostring(0.25) == '0.25', tostring(0.25))\n"
                                                      "assert(string.format('%.3f', 0.25) == '0.250')\n"
                                                      "assert(tonumber('0,5') == nil and tonumber('0.5') == 0.5)\n"
                                                      "assert(type(x) == 'string' and x == '0,5', tostring(x))\n"
                                                      "assert(type(y) == 'number' and y == 0.25)\n");
  std::string error;
  try {
    loadScene(path, {{{"x", "0,5"}, {"y", "0.25"}}, 0});
  } catch (const InputError& e) {
    error = e.what();
  }
  std::setlocale(LC_ALL, "C");
  unsetenv("LOCPATH");
  CHECK(inGerman == "0,5");
  CHECK(error == "");
}

TEST_CASE("scene: a global alias of an object, light or camera is a warning naming both globals, once") {
  // Every global is collected: `plate2 = plate` rendered the plate twice (coincident surfaces) and
  // `lamp2 = lamp` doubled the light, without a word (the new-user trial of 2026-11-28).
  test::TempFolder dir;
  const std::string path = dir.write(
      "alias.lua",
      "cam = Camera.Pinhole { resolution = {64, 48}; focalLength = 0.01; pixelSize = {1e-4, 1e-4} }\n"
      "plate = Object.Simple { shape = Shape.Rectangle { size = {0.2, 0.15}; location = {0, 0, 0.5} };\n"
      "  shader = Shader.Lambert { color = 0.5 } }\n"
      "lamp = Light.Point { position = {0, 0, 0}; intensity = 1 }\n"
      "plate2 = plate; lamp2 = lamp; lamp3 = lamp; view = cam\n"
      "local other = plate  -- a local alias is no global: no warning\n"
      "twin = Object.Simple { shape = Shape.Sphere { radius = 0.01; location = {0, 0, 0.6} } }\n");
  WarningCapture capture;
  const Scene scene = loadScene(path, {});
  CHECK(scene.objects.size() == 3);  // plate, plate2, twin: collected as documented
  CHECK(scene.lights.size() == 3);
  CHECK(loadScene(path, {}).cameras.size() == 2);  // evaluated again (a second frame): said once
  const std::vector<std::string> said = capture.take();
  REQUIRE(said.size() == 3);
  CHECK(said[0] == path + ":1: the globals 'cam' and 'view' hold the same camera, which is rendered 2 times (every global "
                          "is collected: keep one name, or make the others `local`)");
  CHECK(said[1] == path + ":4: the globals 'lamp', 'lamp2' and 'lamp3' hold the same light, which shines 3 times as bright "
                          "(every global is collected: keep one name, or make the others `local`)");
  CHECK(said[2] == path + ":2: the globals 'plate' and 'plate2' hold the same object, which is rendered 2 times, its surfaces "
                          "coincident (every global is collected: keep one name, or make the others `local`)");
}

TEST_CASE("scene: a lit shader's color above 1 is said once with its line but a Constant's radiance is not") {
  // Shader.Lambert { color = 5 } rendered five times the physical radiance without a word (the
  // radiometry trial of 2026-11-29): an albedo is at most 1. RGB: any channel above 1.
  test::TempFolder folder;
  const std::string path = folder.write(
      "albedo.lua",
      "cam = Camera.Pinhole { resolution = {64, 48}; focalLength = 0.01; pixelSize = {1e-4, 1e-4} }\n"
      "a = Object.Simple { shape = Shape.Rectangle { size = {0.2, 0.15}; location = {0, 0, 0.5} };\n"
      "  shader = Shader.Lambert { color = 5 } }\n"
      "b = Object.Simple { shape = Shape.Sphere { radius = 0.01; location = {0, 0, 0.4} }; shader = Shader.GGX { color = {0.2, 1.5, 0.1} } }\n"
      "c = Object.Simple { shape = Shape.Sphere { radius = 0.01; location = {0.05, 0, 0.4} }; shader = Shader.Constant { color = 3 } }\n"
      "d = Object.Simple { shape = Shape.Sphere { radius = 0.01; location = {-0.05, 0, 0.4} }; shader = Shader.Phong { color = 1 } }\n"
      "lamp = Light.Point { position = {0, 0, 0}; intensity = 1 }\n");
  WarningCapture capture;
  loadScene(path, {});
  loadScene(path, {});  // a second frame: said once
  const std::vector<std::string> said = capture.take();
  REQUIRE(said.size() == 2);
  CHECK(said[0] == path + ":3: Shader.Lambert's color reaches 5, an albedo above 1: the surface reflects more light than "
                          "falls on it (brighten the image with the lights' intensity or the camera's exposure instead)");
  CHECK(said[1].find(path + ":4: Shader.GGX's color reaches 1.5, an albedo above 1") == 0);
}
