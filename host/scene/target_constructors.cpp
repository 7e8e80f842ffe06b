// Target.Checkerboard, Target.CircleGrid (calibration targets) and Target.poses (calibration
// sequences). Layout, target frame and features: host/geometry/targets.h; texture:
// host/texture/target_texture.h; pose generator: host/geometry/target_poses.h.
#include <cmath>
#include <string>
#include <vector>

#include "core/option_names.h"
#include "geometry/target_poses.h"
#include "geometry/targets.h"
#include "scene/constructors.h"
#include "scene/lua_values.h"
#include "shapes/registry.h"

namespace dicsynth::scene {

namespace {

// Reflectances of a printed target: black toner reflects ~5–10 %, paper ~80–90 %; 0.1 / 0.9 keeps
// both clear of the sensor's black level and saturation at exposure 1.
constexpr double kDefaultDark = 0.1, kDefaultLight = 0.9;

// A count pair {a, b} of integers in [minimum, 1000].
std::pair<int, int> readCounts(const Params& p, const char* key, const char* shape, int minimum) {
  const std::optional<dvec2> counts = p.vec2(key, shape);
  if (!counts) p.fail("missing required " + Params::quote(key) + " = " + shape);
  const std::string condition = "two integers in " + std::to_string(minimum) + "..1000";
  for (double n : {counts->x, counts->y})
    p.require(n == std::floor(n) && n >= minimum && n <= 1000, key, condition.c_str(), n);
  return {int(counts->x), int(counts->y)};
}

// worldFromTarget must be rigid: object points of a calibration are metric target coordinates.
dmat4 readRigidTransform(const Params& p) {
  const TransformValue* t = p.userdata<TransformValue>("transform", "a Transform (translate, rotate_x, ...)");
  if (!t) return dmat4(1.0);
  const dmat4& m = t->matrix;
  const std::string what = "'transform' (worldFromTarget) must be rigid, a rotation and a translation";
  double deviation = std::max({std::fabs(m[0][3]), std::fabs(m[1][3]), std::fabs(m[2][3]), std::fabs(m[3][3] - 1)});
  const dmat3 rotation(m);
  const dmat3 gram = glm::transpose(rotation) * rotation;
  for (int col = 0; col < 3; ++col)
    for (int row = 0; row < 3; ++row) deviation = std::max(deviation, std::fabs(gram[col][row] - (col == row)));
  if (!(deviation <= 1e-9)) p.fail(what + " (max |R^T R - I| and bottom-row error " + formatNumber(deviation) + ")");
  if (glm::determinant(rotation) < 0) p.fail(what + ", but it mirrors (determinant -1)");
  return m;
}

// The Object of a target: a Rectangle carrying the pattern, placed so that the target frame lands
// at worldFromTarget = translate(location) · transform (see geometry/targets.h).
int pushTarget(lua_State* L, const Params& p, TextureKind kind, textures::TargetPattern pattern) {
  pattern.dark = p.number("dark", kDefaultDark);
  pattern.light = p.number("light", kDefaultLight);
  p.require(pattern.dark >= 0, "dark", ">= 0", pattern.dark);
  p.require(pattern.light > pattern.dark, "light", "> dark (dark features on a light target)", pattern.light);
  const TargetLayout layout = targetLayout(kind, pattern);

  Object object;
  object.where = LuaSandbox::of(L).here(L);
  object.shape.where = object.where;
  object.shape.location_m = p.vec3("location").value_or(dvec3(0));
  object.shape.analytic = shapes::Rectangle{layout.size_m};
  object.texture.where = object.where;
  if (kind == TextureKind::Checkerboard)
    object.texture.model = textures::Checkerboard{{pattern, {}}};
  else
    object.texture.model = textures::CircleGrid{{pattern, {}}};
  if (const Shader* shader = p.userdata<Shader>("shader", shaderExpected())) {
    object.shader = *shader;
  } else {
    object.shader.where = object.where;
  }
  object.transform = readRigidTransform(p) * glm::translate(dmat4(1.0), layout.rectangleCentre_m);
  pushUserdata(L, std::move(object));
  return 1;
}

/* ------------------------------------------------------------------------------------------------
Target.Checkerboard: a printed chessboard for camera calibration (cv::findChessboardCornersSB),
drawn analytically: every point is exactly dark or light. A Rectangle of (cols·squareSize +
2·border) × (rows·squareSize + 2·border) with a light quiet border; the top-left square is light
(so that cv::findChessboardCornersSB reports the corners from the top left, in the order below).

  Parameter  | Value               | Default             | Meaning
  -----------+---------------------+---------------------+-----------------------------------------
  squares    | {cols, rows}        | required            | squares per row, rows (2..1000 each);
             |                     |                     | OpenCV's patternSize = {cols-1, rows-1}
  squareSize | number, m           | required            | side of a square, > 0
  border     | number, m           | squareSize          | light margin beyond the outer squares
  dark       | number              | 0.1                 | texture value of the dark squares, >= 0
  light      | number              | 0.9                 | of the light squares and border, > dark
  location   | {x, y, z}, m        | {0, 0, 0}           | where the target frame's origin lies
  transform  | Transform (rigid)   | identity()          | worldFromTarget = translate(location) *
             |                     |                     | transform
  shader     | Shader              | Shader.Constant {}  | as for Object.Simple

Target frame: origin at the first inner corner (the bottom-right corner of the top-left square),
x along the first row of corners (right as the default camera sees it), y to the next row (down),
z away from the printed side. Features: the inner corners, row by row, target coordinates
(col·squareSize, row·squareSize, 0) (host/geometry/targets.h). For OpenCV's orientation rules use
an even and an odd count (e.g. {10, 7}).

Example:  board = Target.Checkerboard { squares = {10, 7}; squareSize = 0.015;
                                        transform = translate(0, 0, 0.5) * rotate_y(degrees(20)) }
------------------------------------------------------------------------------------------------ */
int targetCheckerboard(lua_State* L) {
  Params p(L, "Target.Checkerboard",
           {"squares", "squareSize", "border", "dark", "light", "location", "transform", "shader"});
  textures::TargetPattern pattern;
  std::tie(pattern.cols, pattern.rows) = readCounts(p, "squares", "{cols, rows}", 2);
  pattern.spacing_m = p.requiredNumber("squareSize");
  p.require(pattern.spacing_m > 0, "squareSize", "> 0 (metres)", pattern.spacing_m);
  pattern.border_m = p.number("border", pattern.spacing_m);
  p.require(pattern.border_m >= 0, "border", ">= 0 (metres)", pattern.border_m);
  return pushTarget(L, p, TextureKind::Checkerboard, pattern);
}

/* ------------------------------------------------------------------------------------------------
Target.CircleGrid: dark dots on a light rectangle for cv::findCirclesGrid, drawn analytically.

  Parameter  | Value               | Default             | Meaning
  -----------+---------------------+---------------------+-----------------------------------------
  circles    | {cols, rows}        | required            | dots per row, rows (OpenCV's patternSize)
  spacing    | number, m           | required            | symmetric: distance between neighbouring
             |                     |                     | centres; asymmetric: OpenCV's squareSize
             |                     |                     | (rows `spacing` apart, dots 2·spacing apart
             |                     |                     | in a row, odd rows shifted by spacing)
  asymmetric | boolean             | false               | OpenCV's CALIB_CB_ASYMMETRIC_GRID layout
  radius     | number, m           | spacing / 4         | dot radius; dots must not touch: < spacing/2
             |                     |                     | (symmetric), < spacing·√2/2 (asymmetric)
  border     | number, m           | spacing             | light margin beyond the dots' edges
  dark, light, location, transform, shader: as Target.Checkerboard

Target frame: origin at the centre of the first dot (top left), x along the first row, y to the
next row, z away from the printed side. Features: the dots' centres, row by row, target
coordinates (col·spacing, row·spacing, 0), asymmetric ((2·col + row mod 2)·spacing, row·spacing, 0).
The image of a dot's centre is not the centroid of the dot's image under perspective (docs/calibration.md).

Example:  dots = Target.CircleGrid { circles = {4, 11}; spacing = 0.01; asymmetric = true;
                                     location = {0, 0, 0.4} }
------------------------------------------------------------------------------------------------ */
int targetCircleGrid(lua_State* L) {
  Params p(L, "Target.CircleGrid", {"circles", "spacing", "asymmetric", "radius", "border", "dark", "light",
                                     "location", "transform", "shader"});
  textures::TargetPattern pattern;
  std::tie(pattern.cols, pattern.rows) = readCounts(p, "circles", "{cols, rows}", 2);
  pattern.spacing_m = p.requiredNumber("spacing");
  p.require(pattern.spacing_m > 0, "spacing", "> 0 (metres)", pattern.spacing_m);
  pattern.asymmetric = p.boolean("asymmetric").value_or(false);
  pattern.radius_m = p.number("radius", pattern.spacing_m / 4);
  // Nearest neighbours: spacing apart (symmetric), spacing·√2 apart diagonally (asymmetric).
  const double nearest = pattern.asymmetric ? pattern.spacing_m * std::sqrt(2.0) : pattern.spacing_m;
  const std::string touching = "> 0 and < " + formatNumber(nearest / 2) + " (dots must not touch)";
  p.require(pattern.radius_m > 0 && pattern.radius_m < nearest / 2, "radius", touching.c_str(), pattern.radius_m);
  pattern.border_m = p.number("border", pattern.spacing_m);
  p.require(pattern.border_m >= 0, "border", ">= 0 (metres)", pattern.border_m);
  return pushTarget(L, p, TextureKind::CircleGrid, pattern);
}

// __index of a pose list: a missing integer key is an error naming the valid range.
int poseListIndex(lua_State* L) {
  if (lua_isinteger(L, 2)) {
    const lua_Integer count = lua_Integer(lua_rawlen(L, 1));
    throw ScriptError("Target.poses: there is no pose [" + std::to_string(lua_tointeger(L, 2)) +
                      "]: the list holds poses [1] to [" + std::to_string(count) +
                      "] (with " + firstFramesSetting(count) + ", use poses[frame + 1])");
  }
  lua_pushnil(L);
  return 1;
}

/* ------------------------------------------------------------------------------------------------
Target.poses: a calibration sequence, a Lua list of `count` rigid Transforms (worldFromTarget) that
keep every feature of `target` at least `margin` px inside every camera's image (through each
camera's distortion), in front of it, printed side towards it. Deterministic for a seed. Indexing
the list out of range is an error (poses[frame + 1] with a frame beyond the list). A list written
by hand works the same way: it is just Transforms.

  Parameter | Value                | Default        | Meaning
  ----------+----------------------+----------------+---------------------------------------------
  target    | Target.*             | required       | the target (its pose is ignored)
  cameras   | {Camera, ...}        | required       | every camera that must see all features
  count     | integer              | 15             | number of poses, 1..10000
  seed      | integer              | 1              | >= 0
  distance  | {near, far}, m       | required       | target centre's distance from the cameras'
            |                      |                | mean centre, along their mean view direction
  tilt      | number, rad          | degrees(30)    | largest angle between the target's normal and
            |                      |                | the line of sight, in [0, degrees(80)]
  roll      | number, rad          | degrees(10)    | largest rotation about the normal, [0, pi/2)
  margin    | number, px           | 20             | >= 0
  tries     | integer              | 20000          | draws per pose before giving up, >= 1

Example:
  local spec = { squares = {10, 7}; squareSize = 0.015 }
  local poses = Target.poses { target = Target.Checkerboard(spec); cameras = {left, right};
                               count = 15; seed = 1; distance = {0.45, 0.6}; tilt = degrees(30) }
  spec.transform = poses[frame + 1]
  board = Target.Checkerboard(spec)        -- render with --frames 0:14
------------------------------------------------------------------------------------------------ */
int targetPoses(lua_State* L) {
  Params p(L, "Target.poses",
           {"target", "cameras", "count", "seed", "distance", "tilt", "roll", "margin", "tries"});
  const Object* target = p.userdata<Object>("target", "a Target (Target.Checkerboard, Target.CircleGrid)");
  if (!target) p.fail("missing required 'target' (a Target.Checkerboard or Target.CircleGrid)");
  const textures::TargetPattern* pattern = textures::targetPattern(target->texture.model);
  if (!pattern) p.fail("'target' must be a Target (Target.Checkerboard, Target.CircleGrid), got an Object.Simple");
  const TargetLayout layout = targetLayout(target->texture.kind(), *pattern);

  std::vector<Camera> cameras;
  if (p.luaType("cameras") != LUA_TTABLE) p.fail("missing required 'cameras' = {camera1, camera2, ...}");
  lua_getfield(L, 1, "cameras");
  const lua_Unsigned cameraCount = lua_rawlen(L, -1);
  for (lua_Unsigned i = 1; i <= cameraCount; ++i) {
    lua_rawgeti(L, -1, lua_Integer(i));
    const Camera* camera = toUserdata<Camera>(L, -1);
    if (!camera) p.fail("'cameras' [" + std::to_string(i) + "] must be a Camera, got " + typeName(L, -1));
    cameras.push_back(*camera);
    cameras.back().name = "cameras[" + std::to_string(i) + "]";
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  if (cameras.empty()) p.fail("'cameras' must list at least one Camera");

  TargetPoseOptions o;
  const long long count = p.integer("count").value_or(15);
  p.require(count >= 1 && count <= 10000, "count", "an integer in 1..10000", double(count));
  o.count = int(count);
  const long long seed = p.integer("seed").value_or(1);
  p.require(seed >= 0, "seed", "an integer >= 0", double(seed));
  o.seed = std::uint64_t(seed);
  const std::optional<dvec2> distance = p.vec2("distance", "{near, far}");
  if (!distance) p.fail("missing required 'distance' = {near, far} (metres)");
  p.require(distance->x > 0, "distance", "{near, far} with 0 < near <= far", distance->x);
  p.require(distance->y >= distance->x, "distance", "{near, far} with 0 < near <= far", distance->y);
  o.distance_m = *distance;
  o.maxTilt_rad = p.number("tilt", o.maxTilt_rad);
  p.requireAngle(o.maxTilt_rad >= 0 && o.maxTilt_rad <= 80 * kPi / 180, "tilt", "in [0, degrees(80)]", o.maxTilt_rad);
  o.maxRoll_rad = p.number("roll", o.maxRoll_rad);
  p.requireAngle(o.maxRoll_rad >= 0 && o.maxRoll_rad < kPi / 2, "roll", "in [0, pi/2)", o.maxRoll_rad);
  o.margin_px = p.number("margin", o.margin_px);
  p.require(o.margin_px >= 0, "margin", ">= 0 (pixels)", o.margin_px);
  const long long tries = p.integer("tries").value_or(o.triesPerPose);
  p.require(tries >= 1 && tries <= 10'000'000, "tries", "an integer in 1..1e7", double(tries));
  o.triesPerPose = int(tries);

  std::vector<dmat4> poses;
  try {
    poses = generateTargetPoses(layout, cameras, o);
  } catch (const InputError& e) {
    p.fail(e.what());
  }
  lua_createtable(L, int(poses.size()), 0);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    pushUserdata(L, TransformValue{poses[i]});
    lua_rawseti(L, -2, lua_Integer(i + 1));
  }
  lua_createtable(L, 0, 1);
  lua_pushcfunction(L, &protectedCall<poseListIndex>);
  lua_setfield(L, -2, "__index");
  lua_setmetatable(L, -2);
  return 1;
}

}  // namespace

void registerTargetConstructors(lua_State* L) {
  setConstructorTable(L, "Target",
                      {{"Checkerboard", &protectedCall<targetCheckerboard>},
                       {"CircleGrid", &protectedCall<targetCircleGrid>},
                       {"poses", &protectedCall<targetPoses>}});
}

}  // namespace dicsynth::scene
