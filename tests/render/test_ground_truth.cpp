// Derived ground truth (render/ground_truth.h): displacement, flow, disparity and distortion layers
// checked against closed forms and against an independent path (tracing the ray through the
// predicted pixel and finding the same material point there).
#include <doctest/doctest.h>

#include <set>

#include <cmath>
#include <cstring>

#include "cpu/reference_renderer.h"
#include "cpu/trace.h"
#include "geometry/material_point.h"
#include "render/ground_truth.h"
#include "scene/scene.h"
#include "scene_test_util.h"
#include "temp_folder.h"

namespace dicsynth {
namespace {

struct Frame {
  PreparedScene scene;
  RenderResult result;
};

// Scene `body` with -D values, frame `frame`, rendered by the CPU reference (1 spp: only the
// pixel-centre ground truth matters here).
Frame renderFrame(const std::string& path, int frame, std::vector<std::pair<std::string, std::string>> defines = {},
                  const std::vector<StereoRig>& rigs = {}) {
  Scene scene = loadScene(path, {defines, frame});
  scene.rigs = rigs;
  Frame f{prepareScene(scene), {}};
  RenderOptions options;
  options.samplesPerPixel = 1;
  options.frame = frame;
  f.result = cpu::render(f.scene, options);
  return f;
}

// cam: 160x120, f = 16 mm, 20 µm pixels (fx = 800 px), at the origin looking down +z.
const std::string kCamera =
    "cam = Camera.Pinhole { resolution = {160, 120}; focalLength = 0.016; pixelSize = {2e-5, 2e-5} %s }\n";

StereoRig rig(const std::string& left, const std::string& right) {
  StereoRig r;
  r.name = "rig";
  r.left = left;
  r.right = right;
  return r;
}

// Whether camera `other`'s ray through reference pixel i + `disparity` meets that pixel's material
// point first (the same object and (u, v)), traced by the CPU reference independently of the masks.
bool reachedThrough(const Frame& f, std::size_t other, const CameraImage& img, std::size_t i, dvec2 disparity) {
  const dvec2 there = dvec2(double(i % std::size_t(img.width_px)), double(i / std::size_t(img.width_px))) + disparity;
  const auto& model = f.scene.cameras[other].model;
  cpu::SurfaceHit hit;
  return there.x >= -0.5 && there.x <= img.width_px - 0.5 && there.y >= -0.5 && there.y <= img.height_px - 0.5 &&
         cpu::traceNearest(f.scene, model.centre, worldRayDirection(model, there), hit) &&
         hit.object == int(img.objectId[i]) - 1 && glm::length(hit.uv - img.uv[i]) < 1e-9;
}

std::string camera(const std::string& extra = "") {
  std::string s = kCamera;
  s.replace(s.find("%s"), 2, extra);
  return s;
}

}  // namespace

TEST_CASE("ground truth: rigid translation of a fronto-parallel rectangle, closed form") {
  test::TempFolder dir;
  // Frame k moves the rectangle by k·1 mm along x at Z = 0.4 m: disp = (k mm, 0, 0) and, without
  // distortion, flow = (fx·k mm / Z, 0) = (2k px, 0) at every pixel.
  const std::string path = dir.write("s.lua", camera() +
      "obj = Object.Simple { shape = Shape.Rectangle { size = {0.1, 0.075}; location = {frame * 1e-3, 0, 0.4} } }\n");
  Frame f0 = renderFrame(path, 0), f3 = renderFrame(path, 3);
  const ReferenceFrame reference(0, f0.scene, f0.result);
  const DerivedTruth t = deriveTruth(reference, 3, f3.scene, f3.result, 0);
  REQUIRE(t.displacement_m.size() == 160 * 120);
  int visible = 0, movedOut = 0;
  for (std::size_t i = 0; i < t.displacement_m.size(); ++i) {
    if (f0.result.cameras[0].objectId[i] == 0) {
      CHECK(std::isnan(t.flow_px[i].x));
      continue;
    }
    // Double rounding only: the points are ~0.05 m, the displacement 3e-3 m.
    CHECK(std::abs(t.displacement_m[i].x - 3e-3) < 1e-15);
    CHECK(std::abs(t.displacement_m[i].y) < 1e-15);
    CHECK(std::abs(t.displacement_m[i].z) < 1e-15);
    CHECK(std::abs(t.flow_px[i].x - 6) < 1e-11);
    CHECK(std::abs(t.flow_px[i].y) < 1e-11);
    const int x = int(i % 160);
    // Points that move beyond the last pixel centre's half pixel leave the image: x + 6 > 159.5.
    if (x + 6 > 159.5) {
      ++movedOut;
      CHECK(t.flowMask[i] == 0.0f);
    } else {
      visible += t.flowMask[i] == 1.0f;
    }
  }
  CHECK(movedOut == 6 * 120);
  CHECK(visible == 154 * 120);
  // The reference frame's own truth: no motion.
  const DerivedTruth t0 = deriveTruth(reference, 0, f0.scene, f0.result, 0);
  for (std::size_t i = 0; i < t0.flow_px.size(); ++i)
    if (f0.result.cameras[0].objectId[i] != 0) {
      CHECK(t0.flow_px[i] == dvec2(0));
      CHECK(t0.flowMask[i] == 1.0f);
    }
}

TEST_CASE("ground truth: a rotating sphere under distortion, the ray through x + flow meets the same material point") {
  test::TempFolder dir;
  // The sphere turns 20° per frame about its own vertical axis: disp = (R − I)(P − c). The flow is
  // checked without any formula of ours: the renderer's own ray through the predicted pixel
  // (inverse distortion by Newton) must meet the surface at the same (u, v).
  const std::string path = dir.write("s.lua", camera("; distortion = Distortion.Brown { radial = {-0.2, 0.1, 0}; tangential = {1e-3, -2e-3} }") +
      "obj = Object.Simple { shape = Shape.Sphere { radius = 0.04; location = {0.005, 0, 0.3} };"
      " transform = rotate_y(degrees(20) * frame) }\n");
  Frame f0 = renderFrame(path, 0), f1 = renderFrame(path, 1);
  const ReferenceFrame reference(0, f0.scene, f0.result);
  const DerivedTruth t = deriveTruth(reference, 1, f1.scene, f1.result, 0);
  const double a = 20 * std::acos(-1.0) / 180;
  const dvec3 centre{0.005, 0, 0.3};
  int checked = 0, hidden = 0;
  const CameraImage& ref = f0.result.cameras[0];
  for (std::size_t i = 0; i < ref.pixelCount(); ++i) {
    if (ref.objectId[i] == 0) continue;
    // rotate_y(a) (right-handed about +y): x' = x cos a + z sin a, z' = −x sin a + z cos a.
    const dvec3 p = ref.position_m[i] - centre;
    const dvec3 expected = dvec3{p.x * std::cos(a) + p.z * std::sin(a), p.y, -p.x * std::sin(a) + p.z * std::cos(a)} - p;
    CHECK(glm::length(t.displacement_m[i] - expected) < 1e-14);
    if (t.flowMask[i] == 0) { ++hidden; continue; }
    const dvec2 pixel = dvec2(double(i % 160), double(i / 160)) + t.flow_px[i];
    const auto& m = f1.scene.cameras[0].model;
    cpu::SurfaceHit hit;
    REQUIRE(cpu::traceNearest(f1.scene, m.centre, worldRayDirection(m, pixel), hit));
    // (u, v) are angles/π: 1e-12 in uv is ~1e-13 m on this sphere, ~1e-10 px.
    CHECK(glm::length(hit.uv - ref.uv[i]) < 1e-11);
    ++checked;
  }
  CHECK(checked > 1000);
  CHECK(hidden > 50);  // points turning to the back are masked
}

TEST_CASE("ground truth: a reference frame built for itself alone derives the same layers") {
  // A single-frame render (every sweep point) builds its ReferenceFrame without the projections
  // that only other frames' flow uses, nor the material points (only whether each pixel has one);
  // the reference frame's own layers must not change by a bit. Shapes whose (u, v) may name no
  // material point (a capped cylinder's cap cells, seen from below at an angle) beside ones that
  // always do (sphere, NURBS plate).
  test::TempFolder dir;
  const std::string path = dir.write("s.lua", camera("; distortion = Distortion.Brown { radial = {-0.2, 0.1, 0}; tangential = {1e-3, -2e-3} }") +
      "obj = Object.Simple { shape = Shape.Sphere { radius = 0.012; location = {-0.012, 0.006, 0.3} } }\n"
      "pipe = Object.Simple { shape = Shape.Cylinder { radius = 0.01; height = 0.02; capped = true; location = {0.014, 0.006, 0.3} };\n"
      "  transform = rotate_x(degrees(50)) }\n"
      "plate = Object.Simple { shape = Nurbs.plate { size = {0.05, 0.012}; curvature = 5; spans = {4, 2}; location = {0, -0.015, 0.3} } }\n");
  Frame f0 = renderFrame(path, 0);
  const ReferenceFrame fullFrame(0, f0.scene, f0.result, true), aloneFrame(0, f0.scene, f0.result, false);
  REQUIRE(fullFrame.view("cam") != nullptr);
  REQUIRE(aloneFrame.view("cam") != nullptr);
  CHECK(fullFrame.view("cam")->object == aloneFrame.view("cam")->object);  // hasMaterialPoint's answer
  CHECK(aloneFrame.view("cam")->material.empty());
  std::set<int> objectsSeen(fullFrame.view("cam")->object.begin(), fullFrame.view("cam")->object.end());
  CHECK(objectsSeen == std::set<int>{-1, 0, 1, 2});
  const DerivedTruth full = deriveTruth(fullFrame, 0, f0.scene, f0.result, 0);
  const DerivedTruth alone = deriveTruth(aloneFrame, 0, f0.scene, f0.result, 0);
  REQUIRE(full.displacement_m.size() == 160 * 120);
  auto sameBits = [](const auto& a, const auto& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
  };
  CHECK(sameBits(full.displacement_m, alone.displacement_m));
  CHECK(sameBits(full.flow_px, alone.flow_px));
  CHECK(sameBits(full.flowMask, alone.flowMask));
  CHECK(sameBits(full.distortion(), alone.distortion()));
  std::size_t seen = 0;
  for (float m : alone.flowMask) seen += m > 0 ? 1 : 0;
  CHECK(seen > 1000);  // the sphere covers part of the image: the layers are not all NaN
}

TEST_CASE("ground truth: uniform strain of a NURBS plate, closed form") {
  test::TempFolder dir;
  // Nurbs.plate stretches about its centre: strain e along x, −0.3 e along y, so a material point
  // at (x, y) from the centre moves by (e x, −0.3 e y, 0).
  const std::string path = dir.write("s.lua", camera() +
      "obj = Object.Simple { shape = Nurbs.plate { size = {0.1, 0.075}; strain = {strain * frame, -0.3 * strain * frame};"
      " spans = {2, 2}; location = {0, 0, 0.4} } }\n");
  const std::vector<std::pair<std::string, std::string>> d{{"strain", "0.01"}};
  Frame f0 = renderFrame(path, 0, d), f1 = renderFrame(path, 1, d);
  const ReferenceFrame reference(0, f0.scene, f0.result);
  const DerivedTruth t = deriveTruth(reference, 1, f1.scene, f1.result, 0);
  const CameraImage& ref = f0.result.cameras[0];
  int checked = 0;
  for (std::size_t i = 0; i < ref.pixelCount(); ++i) {
    if (ref.objectId[i] == 0) continue;
    const dvec3 p = ref.position_m[i] - dvec3{0, 0, 0.4};
    // The reference P comes from the CPU NURBS intersection (~1e-13 m); displacements ~5e-4 m.
    CHECK(glm::length(t.displacement_m[i] - dvec3{0.01 * p.x, -0.003 * p.y, 0}) < 1e-12);
    // Fronto-parallel, no distortion: flow = fx · disp / Z (fx = 800 px).
    CHECK(glm::length(t.flow_px[i] - 800.0 * dvec2(t.displacement_m[i]) / 0.4) < 1e-9);
    ++checked;
  }
  CHECK(checked > 5000);
}

TEST_CASE("ground truth: an occluder entering the view masks the flow behind it") {
  test::TempFolder dir;
  // In frame 1 a 2 cm square at Z = 0.2 m covers the centre of the specimen (at 0.4 m): it hides
  // an 80 x 80 px square of the image (fx · 0.02 / 0.2).
  const std::string path = dir.write("s.lua", camera() +
      "specimen = Object.Simple { shape = Shape.Rectangle { size = {0.1, 0.075}; location = {0, 0, 0.4} } }\n"
      "if frame == 1 then blocker = Object.Simple { shape = Shape.Rectangle { size = {0.02, 0.02};"
      " location = {0, 0, 0.2} } } end\n");
  Frame f0 = renderFrame(path, 0), f1 = renderFrame(path, 1);
  const ReferenceFrame reference(0, f0.scene, f0.result);
  const DerivedTruth t = deriveTruth(reference, 1, f1.scene, f1.result, 0);
  int hidden = 0;
  for (std::size_t i = 0; i < t.flowMask.size(); ++i) {
    const int x = int(i % 160), y = int(i / 160);
    // The square covers pixel centres with |x − 79.5| < 40 and |y − 59.5| < 40.
    const bool behind = std::abs(x - 79.5) < 40 && std::abs(y - 59.5) < 40;
    CHECK(t.flowMask[i] == (behind ? 0.0f : 1.0f));
    hidden += behind;
    CHECK(t.flow_px[i] == dvec2(0));  // the specimen did not move: hidden, yet its flow is known
  }
  CHECK(hidden == 80 * 80);
}

TEST_CASE("ground truth: disparity of a rectified pair on a plane, closed form") {
  test::TempFolder dir;
  // Two parallel cameras 2 cm apart along x, a wall at Z = 0.5 m: a point seen by the left camera
  // at x appears in the right one at x − fx·b/Z = x − 32 px, and the reverse for the right camera.
  const std::string path = dir.write("s.lua",
      "left = Camera.Pinhole { resolution = {160, 120}; focalLength = 0.016; pixelSize = {2e-5, 2e-5};"
      " position = {-0.01, 0, 0}; lookAt = {-0.01, 0, 1}; up = {0, -1, 0} }\n"
      "right = Camera.Pinhole { resolution = {160, 120}; focalLength = 0.016; pixelSize = {2e-5, 2e-5};"
      " position = {0.01, 0, 0}; lookAt = {0.01, 0, 1}; up = {0, -1, 0} }\n"
      "wall = Object.Simple { shape = Shape.Rectangle { size = {1, 1}; location = {0, 0, 0.5} } }\n");
  Frame f = renderFrame(path, 0, {}, {rig("left", "right")});
  const ReferenceFrame reference(0, f.scene, f.result);
  for (std::size_t c = 0; c < 2; ++c) {
    const DerivedTruth t = deriveTruth(reference, 0, f.scene, f.result, c);
    CHECK(t.disparityCamera == (c == 0 ? "right" : "left"));
    const double expected = c == 0 ? -32 : 32;
    std::size_t visible = 0;
    for (std::size_t i = 0; i < t.disparity_px.size(); ++i) {
      const double x = double(i % 160);
      CHECK(std::abs(t.disparity_px[i].x - expected) < 1e-10);
      CHECK(std::abs(t.disparity_px[i].y) < 1e-10);
      const bool inside = x + expected >= -0.5 && x + expected <= 159.5;
      CHECK(t.disparityMask[i] == (inside ? 1.0f : 0.0f));
      visible += inside;
    }
    CHECK(t.disparityVisibleCount == visible);
    CHECK(visible == 128 * 120);
  }
}

TEST_CASE("ground truth: cameras without overlap give an empty disparity mask, not an error") {
  test::TempFolder dir;
  // Back to back: whatever one camera sees lies behind the other.
  const std::string path = dir.write("s.lua",
      "a = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.016; pixelSize = {1e-4, 1e-4} }\n"
      "b = Camera.Pinhole { resolution = {32, 24}; focalLength = 0.016; pixelSize = {1e-4, 1e-4};"
      " position = {0, 0, 0}; lookAt = {0, 0, -1}; up = {0, -1, 0} }\n"
      "front = Object.Simple { shape = Shape.Rectangle { size = {1, 1}; location = {0, 0, 0.5} } }\n"
      "back = Object.Simple { shape = Shape.Rectangle { size = {1, 1}; location = {0, 0, -0.5} } }\n");
  Frame f = renderFrame(path, 0, {}, {rig("a", "b")});
  const ReferenceFrame reference(0, f.scene, f.result);
  for (std::size_t c = 0; c < 2; ++c) {
    const DerivedTruth t = deriveTruth(reference, 0, f.scene, f.result, c);
    CHECK(t.disparityVisibleCount == 0);
    for (std::size_t i = 0; i < t.disparity_px.size(); ++i) {
      CHECK(t.disparityMask[i] == 0.0f);
      CHECK(std::isnan(t.disparity_px[i].x));  // behind the other camera: no image position
    }
  }
}

TEST_CASE("ground truth: disparity with overlap, points hidden from the other camera are masked") {
  test::TempFolder dir;
  // Converging cameras: both look at (0, 0, 0.5). The post (a thin vertical strip at Z = 0.4 m,
  // x = 0.02) is seen by both, and hides a strip of the wall from the right camera only where it
  // falls between the wall and that camera. Checked independently: for every left pixel whose
  // point the right camera sees, the right camera's ray through x + disparity meets that point.
  const std::string path = dir.write("s.lua", test::kConvergingRigWithPost);
  Frame f = renderFrame(path, 0, {}, {rig("left", "right")});
  const ReferenceFrame reference(0, f.scene, f.result);
  const DerivedTruth t = deriveTruth(reference, 0, f.scene, f.result, 0);
  const CameraImage& img = f.result.cameras[0];
  const auto& rightModel = f.scene.cameras[1].model;
  int visible = 0, occluded = 0;
  for (std::size_t i = 0; i < img.pixelCount(); ++i) {
    if (img.objectId[i] == 0) continue;
    const dvec2 there = dvec2(double(i % 160), double(i / 160)) + t.disparity_px[i];
    cpu::SurfaceHit hit;
    const bool inside = there.x >= -0.5 && there.x <= 159.5 && there.y >= -0.5 && there.y <= 119.5;
    REQUIRE(cpu::traceNearest(f.scene, rightModel.centre, worldRayDirection(rightModel, there), hit));
    const bool same = hit.object == int(img.objectId[i]) - 1 && glm::length(hit.uv - img.uv[i]) < 1e-9;
    CHECK(t.disparityMask[i] == ((inside && same) ? 1.0f : 0.0f));
    if (t.disparityMask[i] > 0) ++visible;
    else if (inside) ++occluded;
  }
  CHECK(visible > 5000);
  CHECK(occluded > 100);  // the strip of wall behind the post, seen from the right
  CHECK(t.disparityVisibleCount == std::size_t(visible));
}

// A surface of zero thickness seen from its other side shows another material point of the
// specimen (its other face): mask 0 there, although the ray meets the point first. The 360° trial
// of 2026-11-29 found 10 302 pixels of an open tube's inner wall masked visible in the partner
// camera that saw the outer face.
TEST_CASE("ground truth: a rectangle seen from its two sides: no disparity, though every ray reaches the point") {
  test::TempFolder dir;
  // `front` at the origin looks along +z at a wall at Z = 0.5 m; `behind` at Z = 1 m looks back
  // along −z: the wall's points are in both images and no object hides them, but one camera sees
  // the face towards −z and the other the face towards +z (closed form: the side is the sign of Z).
  const std::string path = dir.write("s.lua",
      "front = Camera.Pinhole { resolution = {160, 120}; focalLength = 0.016; pixelSize = {2e-5, 2e-5} }\n"
      "behind = Camera.Pinhole { resolution = {160, 120}; focalLength = 0.016; pixelSize = {2e-5, 2e-5};"
      " position = {0, 0, 1}; lookAt = {0, 0, 0}; up = {0, -1, 0} }\n"
      "wall = Object.Simple { shape = Shape.Rectangle { size = {0.1, 0.1}; location = {0, 0, 0.5} } }\n");
  Frame f = renderFrame(path, 0, {}, {rig("front", "behind")});
  const ReferenceFrame reference(0, f.scene, f.result);
  for (std::size_t c = 0; c < 2; ++c) {
    const DerivedTruth t = deriveTruth(reference, 0, f.scene, f.result, c);
    const CameraImage& img = f.result.cameras[c];
    int reachedFirst = 0;
    for (std::size_t i = 0; i < img.pixelCount(); ++i) {
      if (img.objectId[i] == 0) continue;
      // What the mask said before: the other camera's ray meets the same material point first.
      reachedFirst += reachedThrough(f, 1 - c, img, i, t.disparity_px[i]);
      CHECK(t.disparityMask[i] == 0.0f);
    }
    MESSAGE("camera " << c << ": " << reachedFirst << " pixels whose point the other camera's ray reaches first, from the other side");
    CHECK(reachedFirst > 10000);  // the side alone masks them
    CHECK(t.disparityVisibleCount == 0);
  }
}

TEST_CASE("ground truth: an open tube's inner wall is not matched with its outer face (disparity)") {
  test::TempFolder dir;
  // An open tube (radius 2 cm, 8 cm long, axis along y). A rig above it looking into its top end
  // (the 360° trial's case): each camera sees the inner wall on its far side, which the partner's
  // ray reaches from outside. A rig beside it: both see the outer face.
  int visible = 0, otherSide = 0, wrong = 0;
  for (const char* placement : {"{%s0.15, -0.25, 0}; lookAt = {0, -0.03, 0}; up = {0, 0, -1}",
                                "{%s0.05, 0, -0.3}; lookAt = {0, 0, 0}; up = {0, -1, 0}"}) {
    auto at = [&](const char* sign) {
      std::string text = placement;
      text.replace(text.find("%s"), 2, sign);
      return text;
    };
    const std::string path = dir.write("s.lua",
        "left = Camera.Pinhole { resolution = {160, 120}; focalLength = 0.016; pixelSize = {2e-5, 2e-5}; position = " +
            at("") + " }\n" +
            "right = Camera.Pinhole { resolution = {160, 120}; focalLength = 0.016; pixelSize = {2e-5, 2e-5}; position = " +
            at("-") + " }\n" + "tube = Object.Simple { shape = Shape.Cylinder { radius = 0.02; height = 0.08; capped = false } }\n");
    Frame f = renderFrame(path, 0, {}, {rig("left", "right")});
    const ReferenceFrame reference(0, f.scene, f.result);
    const DerivedTruth t = deriveTruth(reference, 0, f.scene, f.result, 0);
    const CameraImage& img = f.result.cameras[0];
    const auto& leftModel = f.scene.cameras[0].model;
    const auto& rightModel = f.scene.cameras[1].model;
    // The oracle: the tube's outward radial direction (x, 0, z) at the point; a camera at C sees the
    // inner wall where the ray P − C heads outwards. Mask 1 ⇔ the right camera's ray through
    // x + disparity meets the same material point first, from the same side.
    for (std::size_t i = 0; i < img.pixelCount(); ++i) {
      if (img.objectId[i] == 0) continue;
      const dvec3 P = img.position_m[i];
      const dvec3 radial(P.x, 0, P.z);
      const bool leftInside = glm::dot(radial, P - leftModel.centre) > 0;
      const bool rightInside = glm::dot(radial, P - rightModel.centre) > 0;
      const bool reached = reachedThrough(f, 1, img, i, t.disparity_px[i]);
      otherSide += reached && leftInside != rightInside;
      const bool expected = reached && leftInside == rightInside;
      wrong += t.disparityMask[i] != (expected ? 1.0f : 0.0f);
      visible += expected;
    }
  }
  MESSAGE(visible << " pixels matched on the same side; " << otherSide
                  << " reached first from the other side (masked); " << wrong << " masks differ from the oracle");
  CHECK(wrong == 0);
  CHECK(visible > 1000);    // the side view: the outer face in both
  CHECK(otherSide > 1000);  // the view into the end: the case the side decides
}

TEST_CASE("ground truth: a rectangle turned to show its back has no visible flow") {
  test::TempFolder dir;
  // Frame 1 turns the rectangle by 180° about its vertical axis: every material point is still in
  // the image (at mirrored x) and first on its ray, but the camera sees its other face.
  const std::string path = dir.write("s.lua", camera() +
      "obj = Object.Simple { shape = Shape.Rectangle { size = {0.1, 0.075} }; transform = translate(0, 0, 0.4) * "
      "rotate_y(frame * math.pi) }\n");
  Frame f0 = renderFrame(path, 0), f1 = renderFrame(path, 1);
  const ReferenceFrame reference(0, f0.scene, f0.result);
  const DerivedTruth t = deriveTruth(reference, 1, f1.scene, f1.result, 0);
  int inImage = 0;
  for (std::size_t i = 0; i < t.flowMask.size(); ++i) {
    if (f0.result.cameras[0].objectId[i] == 0) continue;
    const dvec2 now = dvec2(double(i % 160), double(i / 160)) + t.flow_px[i];
    inImage += now.x >= -0.5 && now.x <= 159.5 && now.y >= -0.5 && now.y <= 119.5;
    CHECK(t.flowMask[i] == 0.0f);
  }
  CHECK(inImage > 10000);
}

TEST_CASE("ground truth: the distortion layer maps each pixel centre to its undistorted position") {
  test::TempFolder dir;
  const std::string path = dir.write("s.lua", camera("; distortion = Distortion.Brown { radial = {-0.3, 0.2, -0.05}; tangential = {2e-3, 1e-3} }") +
      "obj = Object.Simple { shape = Shape.Rectangle { size = {0.1, 0.075}; location = {0, 0, 0.4} } }\n");
  Frame f = renderFrame(path, 0);
  const ReferenceFrame reference(0, f.scene, f.result);
  const DerivedTruth t = deriveTruth(reference, 0, f.scene, f.result, 0);
  // The same camera again: the kept field itself, shared, not a copy.
  CHECK(deriveTruth(reference, 0, f.scene, f.result, 0).distortion_px == t.distortion_px);
  const auto& m = f.scene.cameras[0].model;
  double largest = 0;
  for (std::size_t i = 0; i < t.distortion().size(); ++i) {
    const dvec2 pixel{double(i % 160), double(i / 160)};
    const dvec2 undistorted = pixel - t.distortion()[i];
    // Forward model (closed form) from the undistorted position must land on the pixel centre.
    const dvec2 ideal{(undistorted.x - m.cx) / m.fx, (undistorted.y - m.cy) / m.fy};
    const dvec2 back = distort(m.brown, ideal);
    CHECK(glm::length(dvec2{m.fx * back.x + m.cx, m.fy * back.y + m.cy} - pixel) < 1e-9);
    largest = std::max(largest, glm::length(t.distortion()[i]));
  }
  // The test means something: at the corners (r = 0.125 in normalized units) k1 alone moves the
  // position by 0.3 · 0.125³ · 800 ≈ 0.47 px.
  CHECK(largest > 0.4);
  // Without distortion the layer is zero.
  const std::string plain = dir.write("p.lua", camera() +
      "obj = Object.Simple { shape = Shape.Rectangle { size = {0.1, 0.075}; location = {0, 0, 0.4} } }\n");
  Frame g = renderFrame(plain, 0);
  const DerivedTruth tp = deriveTruth(ReferenceFrame(0, g.scene, g.result), 0, g.scene, g.result, 0);
  for (const dvec2& v : tp.distortion()) CHECK(v == dvec2(0));
  // The fields are kept across calls (a sweep's points share them), keyed by the camera's numbers:
  // a camera differing only in one coefficient gets its own field, and the first one comes back intact.
  const std::string other = dir.write("o.lua", camera("; distortion = Distortion.Brown { radial = {-0.3, 0.2, -0.05}; tangential = {2e-3, 1.5e-3} }") +
      "obj = Object.Simple { shape = Shape.Rectangle { size = {0.1, 0.075}; location = {0, 0, 0.4} } }\n");
  Frame h = renderFrame(other, 0);
  const DerivedTruth to = deriveTruth(ReferenceFrame(0, h.scene, h.result), 0, h.scene, h.result, 0);
  const auto& mo = h.scene.cameras[0].model;
  REQUIRE(to.distortion().size() == t.distortion().size());
  CHECK(to.distortion() != t.distortion());
  for (std::size_t i = 0; i < to.distortion().size(); i += 97) {
    const dvec2 pixel{double(i % 160), double(i / 160)};
    const dvec2 undistorted = pixel - to.distortion()[i];
    const dvec2 back = distort(mo.brown, dvec2{(undistorted.x - mo.cx) / mo.fx, (undistorted.y - mo.cy) / mo.fy});
    CHECK(glm::length(dvec2{mo.fx * back.x + mo.cx, mo.fy * back.y + mo.cy} - pixel) < 1e-9);
  }
  CHECK(deriveTruth(reference, 0, f.scene, f.result, 0).distortion() == t.distortion());
}

TEST_CASE("ground truth: the distortion field equals undistort() pixel by pixel, rows of any width") {
  // The field is inverted eight pixels of a row at a time (undistortLockstep); 163 pixels per row
  // leave a partial last block. Each pixel's value must be the one undistort() gives it alone.
  test::TempFolder dir;
  const std::string path = dir.write("w.lua",
      "cam = Camera.Pinhole { resolution = {163, 9}; focalLength = 0.016; pixelSize = {2e-5, 2e-5}; "
      "distortion = Distortion.Brown { radial = {-0.3, 0.2, -0.05}; tangential = {2e-3, 1e-3} } }\n"
      "obj = Object.Simple { shape = Shape.Rectangle { size = {0.1, 0.075}; location = {0, 0, 0.4} } }\n");
  Frame f = renderFrame(path, 0);
  const DerivedTruth t = deriveTruth(ReferenceFrame(0, f.scene, f.result), 0, f.scene, f.result, 0);
  const auto& m = f.scene.cameras[0].model;
  REQUIRE(t.distortion().size() == std::size_t(163 * 9));
  std::size_t differing = 0;
  for (int y = 0; y < 9; ++y)
    for (int x = 0; x < 163; ++x) {
      const dvec2 ideal = undistort(m.brown, dvec2{(x - m.cx) / m.fx, (y - m.cy) / m.fy});
      const dvec2 expected = dvec2{x, y} - dvec2{m.fx * ideal.x + m.cx, m.fy * ideal.y + m.cy};
      const dvec2 got = t.distortion()[std::size_t(y) * 163 + std::size_t(x)];
      differing += std::memcmp(&expected, &got, sizeof got) != 0 ? 1 : 0;
    }
  CHECK(differing == 0);
}

}  // namespace dicsynth
