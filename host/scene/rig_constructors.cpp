// Rig.Stereo, and the rig geometry of stereo_rig.h.
#include <algorithm>
#include <cmath>

#include "scene/constructors.h"
#include "scene/lua_values.h"
#include "scene/stereo_rig.h"

namespace dicsynth {

StereoRigPoses stereoRigPoses(const StereoRigLayout& layout) {
  // Rig frame, built as Camera.Pinhole's lookAt pose is: z forward, y against `up`, x = y × z.
  const dvec3 z = glm::normalize(layout.axis);
  const dvec3 y = glm::normalize(-(layout.up - glm::dot(layout.up, z) * z));
  const dvec3 x = glm::cross(y, z);

  // Toe-in: each camera turns about y by half the vergence towards the other. The left camera (at
  // −x) turns its z axis towards +x: zLeft = cos·z + sin·x, and xLeft = y × zLeft = cos·x − sin·z.
  const double c = std::cos(layout.vergence_rad / 2), s = std::sin(layout.vergence_rad / 2);
  const dvec3 zLeft = c * z + s * x, xLeft = c * x - s * z;
  const dvec3 zRight = c * z - s * x, xRight = c * x + s * z;
  const dvec3 centreLeft = layout.centre_m - (layout.baseline_m / 2) * x;
  const dvec3 centreRight = layout.centre_m + (layout.baseline_m / 2) * x;

  StereoRigPoses poses;
  poses.worldFromLeft = dmat4(dvec4(xLeft, 0), dvec4(y, 0), dvec4(zLeft, 0), dvec4(centreLeft, 1));
  poses.worldFromRight = dmat4(dvec4(xRight, 0), dvec4(y, 0), dvec4(zRight, 0), dvec4(centreRight, 1));
  return poses;
}

double vergenceForDistance(double baseline_m, double distance_m) {
  return 2 * std::atan(baseline_m / (2 * distance_m));
}

namespace scene {
namespace {

/* ------------------------------------------------------------------------------------------------
Rig.Stereo: two cameras in the common symmetric stereo set-up. The rig places both cameras; the
scene gets them as "<rig>.left" and "<rig>.right" (for a global `rig`: rig.left, rig.right, also the
names of their output files), and the calibration files state their relation as
cv::stereoCalibrate does: x_right = R·x_left + T.

  Parameter  | Value                | Default    | Meaning
  -----------+----------------------+------------+------------------------------------------------
  left       | Camera               | required   | the left camera (intrinsics only: no pose)
  right      | Camera               | required   | the right camera (intrinsics only: no pose)
  baseline   | number, m            | required   | distance between the optical centres, > 0
  vergence   | number, rad          | -          | angle between the optical axes, in [0, pi)
  target     | {x, y, z}, m         | -          | the point where the optical axes cross
  position   | {x, y, z}, m         | {0, 0, 0}  | rig centre: midpoint of the optical centres
  direction  | {x, y, z}            | {0, 0, 1}  | rig axis (only with vergence)
  up         | {x, y, z}            | {0, -1, 0} | world direction shown up in both images

Give exactly one of `vergence` and `target`.

Geometry. The rig frame is built like a camera's lookAt pose: z = the rig axis (normalize(direction),
or normalize(target - position)), y = normalize(-(up - (up·z) z)) (image down), x = y × z (image
right). The left camera's optical centre is position - (baseline/2)·x, the right one's
position + (baseline/2)·x: the left camera is on the left as the cameras see it (OpenCV's x right).
Each camera is the rig frame turned about y by vergence/2 towards the other camera (toe-in), so
both optical axes lie in the rig's xz-plane, both cameras share the rig's y axis, and the axes cross
on the rig axis at distance (baseline/2) / tan(vergence/2) from the centre; vergence 0 gives
parallel axes. With `target`, the rig axis points from `position` to the target and
vergence = 2·atan(baseline / (2·|target - position|)), so the axes cross exactly at the target.
Stereo relation (x_right = R·x_left + T): R = the rotation by +vergence about y,
[cos v, 0, sin v; 0, 1, 0; -sin v, 0, cos v], and T = (-baseline·cos(v/2), 0, baseline·sin(v/2)),
the left optical centre in the right camera's frame.

Cameras. Give the rig cameras without a pose (no transform/position/lookAt/up): the rig places
them, and a pose of their own is refused rather than silently replaced. rig.left and rig.right are
the posed Camera values (the same value each time), usable wherever a Camera is. A camera passed to
a rig must not also be a global, and neither may rig.left/rig.right be assigned to another
global: every global Camera is rendered, so it would be an extra camera (unposed, or a duplicate);
loading the scene refuses it. Use locals, or write the cameras inside the rig.

Example:
  local lens = { resolution = {1600, 1200}; focalLength = 0.025; pixelSize = {3.45e-6, 3.45e-6} }
  rig = Rig.Stereo { left = Camera.Pinhole(lens); right = Camera.Pinhole(lens);
                     baseline = 0.2; target = {0, 0, 0.6} }
------------------------------------------------------------------------------------------------ */
int rigStereo(lua_State* L) {
  Params p(L, "Rig.Stereo",
           {"left", "right", "baseline", "vergence", "target", "position", "direction", "up"});
  const SourceLoc where = LuaSandbox::of(L).here(L);

  // Cameras: intrinsics from the scene, poses from the rig.
  auto camera = [&](const char* key) {
    const Camera* given = p.userdata<Camera>(key, "a Camera (Camera.Pinhole { ... })");
    if (given == nullptr) p.fail(std::string("missing required '") + key + "' = Camera.Pinhole { ... }");
    if (given->kindInfo().telecentric) {
      std::string perspective;
      for (const auto& k : cameras::kCameraKinds)
        if (!k.telecentric) perspective += std::string(perspective.empty() ? "" : ", ") + k.name;
      p.fail(Params::quote(key) + " is a Camera." + given->kindInfo().name +
             ": Rig.Stereo places perspective cameras (" + perspective +
             ") by their optical centres, which a telecentric camera lacks; give each telecentric camera "
             "its own transform instead");
    }
    if (given->poseGiven)
      p.fail(Params::quote(key) +
             " has a pose of its own (transform, position, lookAt or up): the rig places its "
             "cameras; give the pose to the rig (position, target or vergence, direction, up)");
    return *given;
  };
  Camera left = camera("left"), right = camera("right");

  // Rig frame and vergence.
  StereoRigLayout layout;
  layout.baseline_m = p.requiredNumber("baseline");
  p.require(layout.baseline_m > 0, "baseline", "> 0 (metres)", layout.baseline_m);
  const bool byVergence = p.has("vergence"), byTarget = p.has("target");
  if (byVergence && byTarget)
    p.fail("give either 'vergence' or 'target', not both (the target sets the vergence)");
  if (!byVergence && !byTarget)
    p.fail("missing 'vergence' (angle between the optical axes) or 'target' (the point where "
           "they cross)");
  layout.centre_m = p.vec3("position").value_or(dvec3(0));
  layout.up = p.vec3("up").value_or(dvec3(0, -1, 0));
  if (byTarget) {
    if (p.has("direction"))
      p.fail("'direction' goes with 'vergence'; with 'target' the rig axis points from 'position' "
             "to the target");
    const dvec3 target = *p.vec3("target");
    layout.axis = target - layout.centre_m;
    const double distance = glm::length(layout.axis);
    if (distance <= 1e-12 * std::max({1.0, glm::length(target), glm::length(layout.centre_m)}))
      p.fail("'target' must differ from 'position' (the rig centre)");
    layout.vergence_rad = vergenceForDistance(layout.baseline_m, distance);
  } else {
    layout.vergence_rad = *p.number("vergence");
    p.requireAngle(layout.vergence_rad >= 0 && layout.vergence_rad < kPi, "vergence",
              "in [0, pi) radians", layout.vergence_rad);
    layout.axis = p.vec3("direction").value_or(dvec3(0, 0, 1));
    if (!(glm::length(layout.axis) > 0)) p.fail("'direction' must not be zero");
  }
  const dvec3 z = glm::normalize(layout.axis);
  if (!(glm::length(layout.up - glm::dot(layout.up, z) * z) > 1e-9 * glm::length(layout.up)))
    p.fail("'up' must not be zero or parallel to the rig axis");

  const StereoRigPoses poses = stereoRigPoses(layout);
  left.worldFromCamera = poses.worldFromLeft;
  right.worldFromCamera = poses.worldFromRight;
  // Posed now: another rig given rig.left must refuse it like any posed camera.
  left.poseGiven = right.poseGiven = true;

  StereoRigValue rig{where, left, right};
  pushUserdata(L, std::move(rig), kRigUserValueCount);
  const int rigIndex = lua_gettop(L);
  pushUserdata(L, std::move(left));
  lua_setiuservalue(L, rigIndex, kRigPosedLeft);
  pushUserdata(L, std::move(right));
  lua_setiuservalue(L, rigIndex, kRigPosedRight);
  lua_pushliteral(L, "left");
  lua_rawget(L, 1);
  lua_setiuservalue(L, rigIndex, kRigGivenLeft);
  lua_pushliteral(L, "right");
  lua_rawget(L, 1);
  lua_setiuservalue(L, rigIndex, kRigGivenRight);
  return 1;
}

// rig.left, rig.right: the posed cameras; any other field is an error (a typo should not read nil).
int rigIndex(lua_State* L) {
  const char* key = lua_type(L, 2) == LUA_TSTRING ? lua_tostring(L, 2) : nullptr;
  const std::string k = key ? key : "";
  if (k == "left" || k == "right") {
    lua_getiuservalue(L, 1, k == "left" ? kRigPosedLeft : kRigPosedRight);
    return 1;
  }
  throw ScriptError("Rig: no field " + (key ? "'" + k + "'" : "of type " + typeName(L, 2)) +
                    "; a Rig has 'left' and 'right'");
}

int rigToString(lua_State* L) {
  lua_pushliteral(L, "Rig.Stereo");
  return 1;
}

}  // namespace

void registerRigConstructors(lua_State* L) {
  registerUserdataType<StereoRigValue>(
      L, {{"__index", &protectedCall<rigIndex>}, {"__tostring", &rigToString}});
  setConstructorTable(L, "Rig", {{"Stereo", &protectedCall<rigStereo>}});
}

}  // namespace scene
}  // namespace dicsynth
