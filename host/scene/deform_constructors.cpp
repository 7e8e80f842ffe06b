// Deformation by a displacement field: Field.load (a finite-element result read with VTK) and
// Nurbs.deform (a NURBS surface moved by a field: a Lua function or a Field, fitted by
// nurbs/nurbs_fit.h). The Deformation a deformed shape carries keeps the field callable after
// the scene ran, for the fieldError layer: a Field holds its mesh; a Lua function is kept in the
// registry and called through the sandbox (LuaSandbox::callAfterRun), which the Scene keeps alive.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>

#include "core/exact_number.h"
#include "core/warning.h"
#include "io/mesh_field.h"
#include "nurbs/nurbs_fit.h"
#include "scene/constructors.h"
#include "scene/lua_values.h"

namespace dicsynth {

std::string describeDeformation(const Deformation& d) {
  return "field: " + d.source + "; fit error " + exactNumber(d.report.maxError_m) + " m (tolerance " +
         exactNumber(d.tolerance_m) + " m) on a " + std::to_string(d.report.checkU) + " x " +
         std::to_string(d.report.checkV) + " check grid; " + std::to_string(d.report.controlPoints) +
         " control points; " + std::to_string(d.report.refinements) + " refinements" +
         (d.fromCache ? "; reused from an earlier frame or sweep point" : "");
}

namespace scene {
namespace {

// A percentage to 2 significant digits: "0.08", "8e-05" (rounded to 2 decimals, 1e-4 % read "0").
std::string percentText(double percent) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2g", percent);
  return text;
}

/* ------------------------------------------------------------------------------------------------
Field.load: a displacement field given at the nodes of a finite-element mesh, read with VTK, for
Nurbs.deform { displacement = Field.load { ... } }. The field at a point is interpolated with the
shape functions of the cell that holds it (linear or quadratic triangles, quadrilaterals,
tetrahedra, hexahedra, wedges, pyramids: what the FE solution itself is between nodes). The mesh is
in the deformed surface's own frame (the frame of its control points, relative to its location),
times `scale`.

  Parameter   | Value      | Default        | Meaning
  ------------+------------+----------------+----------------------------------------------------
  fileName    | string     | required       | .vtu .vtp .vts .vtr .vti (VTK XML), .vtk (legacy),
              |            |                | .e .exo .ex2 (Exodus II); relative to the scene
  array       | string     | "displacement" | point array: 3 components (x, y, z), or 2 (z = 0)
  step        | integer    | 0              | time step of an Exodus file (0-based); other formats
              |            |                | hold one step: name one file per frame instead
  scale       | number     | 1              | metres per mesh unit (1e-3 for a mesh in mm); scales
              |            |                | coordinates and displacements alike
  maxDistance | number, m  | 1e-6           | a point of the surface farther than this from every
              |            |                | cell is off the mesh: an error (how many, the first)

Errors name the file: unreadable or unknown format, a missing array (with the list of those there),
a component count other than 2 or 3, a non-finite value (the first node), cells that do not span an
area or a volume (lines, vertices), a step the file does not have.

Example: fe = Field.load { fileName = "data/plate_hole.vtu"; array = "displacement"; scale = 1e-3 }
------------------------------------------------------------------------------------------------ */
int fieldLoad(lua_State* L) {
  Params p(L, "Field.load", {"fileName", "array", "step", "scale", "maxDistance"});
  LuaSandbox& sandbox = LuaSandbox::of(L);
  MeshFieldOptions options;
  const std::optional<std::string> fileName = p.string("fileName");
  if (!fileName) p.fail("missing required 'fileName'");
  if (fileName->empty()) p.fail("'fileName' must not be empty");
  const std::filesystem::path given(*fileName);
  options.path = (given.is_absolute() ? given : sandbox.sceneDir() / given).string();
  options.array = p.string("array").value_or("displacement");
  const long long step = p.integer("step").value_or(0);
  p.require(step >= 0 && step <= 1'000'000'000, "step", ">= 0", double(step));
  options.step = int(step);
  options.scale = p.number("scale", 1.0);
  p.require(options.scale > 0, "scale", "> 0 (metres per mesh unit)", options.scale);
  options.maxDistance_m = p.number("maxDistance", 1e-6);
  p.require(options.maxDistance_m > 0, "maxDistance", "> 0 (metres)", options.maxDistance_m);
  FieldValue field;
  field.where = sandbox.here(L);
  try {
    field.mesh = std::make_shared<const MeshField>(options);
  } catch (const InputError& e) {
    p.fail(e.what());
  }
  pushUserdata(L, std::move(field));
  return 1;
}

int fieldToString(lua_State* L) {
  const FieldValue* field = toUserdata<FieldValue>(L, 1);
  lua_pushstring(L, field ? ("Field(" + field->mesh->describe() + ")").c_str() : "Field");
  return 1;
}

// A Lua function d(x, y, z) → dx, dy, dz as a DisplacementField, called through the sandbox
// (LuaSandbox::call): while the scene runs (the fit) under the run's limits; afterwards (the
// fieldError layer) inside callAfterRun, under fresh ones, while the scene is still loaded.
class LuaFunctionField {
 public:
  LuaFunctionField(lua_State* L, int index, SourceLoc where)
      : sandbox_(LuaSandbox::of(L).weak_from_this()), where_(std::move(where)) {
    lua_pushvalue(L, index);
    ref_ = luaL_ref(L, LUA_REGISTRYINDEX);
  }
  void sceneFinished() { running_ = false; }
  long long calls() const { return calls_; }

  std::vector<dvec3> operator()(const std::vector<dvec3>& points) {
    const std::shared_ptr<LuaSandbox> sandbox = sandbox_.lock();
    DS_CHECK(sandbox != nullptr, "a Nurbs.deform field called after its scene was unloaded");
    std::vector<dvec3> d;
    if (running_) {
      d = evaluate(*sandbox, points);
    } else {
      sandbox->callAfterRun([&] { d = evaluate(*sandbox, points); });
    }
    return d;
  }

 private:
  std::vector<dvec3> evaluate(LuaSandbox& sandbox, const std::vector<dvec3>& points) {
    lua_State* L = sandbox.state();
    std::vector<dvec3> d(points.size());
    for (std::size_t k = 0; k < points.size(); ++k) {
      const dvec3& x = points[k];
      ++calls_;
      lua_rawgeti(L, LUA_REGISTRYINDEX, ref_);
      lua_pushnumber(L, x.x);
      lua_pushnumber(L, x.y);
      lua_pushnumber(L, x.z);
      try {
        const LuaSandbox::OwnInstructionBudget budget(sandbox, "one call of the Nurbs.deform displacement");
        sandbox.call(3, 3);
      } catch (const InputError& e) {
        fail("'displacement' failed at " + at(x) + ": " + e.what());
      }
      for (int c = 0; c < 3; ++c) {
        if (!lua_isnumber(L, -3 + c)) {
          const std::string message = "'displacement' must return three numbers dx, dy, dz; at " + at(x) + " value " +
                                      std::to_string(c + 1) + " is " + typeName(L, -3 + c);
          lua_pop(L, 3);
          fail(message);
        }
        d[k][c] = lua_tonumber(L, -3 + c);
      }
      lua_pop(L, 3);
    }
    return d;
  }

  // While the scene runs, Nurbs.deform's Params reader adds the constructor and the line; after,
  // the message says both itself.
  [[noreturn]] void fail(const std::string& message) const {
    if (running_) throw InputError(message);
    throw InputError(where_, "Nurbs.deform: " + message + " (called again for the fieldError layer)");
  }

  static std::string at(const dvec3& x) {
    std::string text = "(";  // appended, not "(" + ...: GCC 12 warns falsely (-Wrestrict) on that
    text += formatNumber(x.x) + ", " + formatNumber(x.y) + ", " + formatNumber(x.z) + ")";
    return text;
  }

  std::weak_ptr<LuaSandbox> sandbox_;
  SourceLoc where_;
  int ref_ = LUA_NOREF;
  bool running_ = true;
  long long calls_ = 0;
};

/* ------------------------------------------------------------------------------------------------
Nurbs.deform: a NURBS surface moved by a displacement field, with the same (u, v) material
parametrization: every point S(u, v) of `surface` goes to S(u, v) + d(S(u, v)), up to the fit
error. The result is a NURBS whose control points are fitted by least squares, its knots refined
(both directions, where the error is) until the largest deviation on a check grid of 2(p + 1) + 1
points per knot span and direction is <= tolerance (nurbs/nurbs_fit.h has the method). Fields
affine in x, y, z are reproduced exactly (up to rounding). The achieved error, the check grid and
the control-point count are printed on stderr and stored in the EXR header; the fieldError layer
holds, per pixel, the rendered position minus the requested one.

  Parameter    | Value               | Default  | Meaning
  -------------+---------------------+----------+--------------------------------------------------
  surface      | a NURBS shape       | required | Shape.Nurbs, Nurbs.plate, Nurbs.from, ...: the
               |                     |          | reference
  displacement | function(x, y, z)   | required | returns dx, dy, dz (metres) at the reference
               | or a Field          |          | point (x, y, z) in the surface's own frame
               |                     |          | (relative to its location, metres); a Field
               |                     |          | (Field.load) is interpolated on its mesh
  tolerance    | number, m           | 1e-9     | largest fit error allowed; > 0
  maxControlPoints | integer         | 2^20     | budget of the refinement

The result keeps the surface's location. Too small a tolerance for the budget, or 16 rounds of
refinement, is an error that says the best error reached and why. Each frame evaluates the scene
again: a fit of an earlier frame with the same surface, tolerance and budget is reused when it is
within the tolerance of this frame's field on its check grid (stderr then says "reused").

Example: wave = Nurbs.deform { surface = plate; tolerance = 1e-9;
  displacement = function(x, y, z) return 0, 2e-5 * math.sin(2 * math.pi * x / 0.02), 0 end }
------------------------------------------------------------------------------------------------ */
int nurbsDeform(lua_State* L) {
  Params p(L, "Nurbs.deform", {"surface", "displacement", "tolerance", "maxControlPoints"});
  const Shape* surface = p.userdata<Shape>("surface", "a NURBS shape (Shape.Nurbs, Nurbs.plate, ...)");
  if (!surface) p.fail("missing required 'surface' (a NURBS shape)");
  if (surface->kind() != ShapeKind::Nurbs || !surface->nurbs) p.fail("'surface' must be a NURBS shape (Shape.Nurbs, Nurbs.plate, ...)");
  const double tolerance = p.number("tolerance", 1e-9);
  p.require(tolerance > 0, "tolerance", "> 0 (metres)", tolerance);
  const long long budget = p.integer("maxControlPoints").value_or(static_cast<long long>(kMaxNurbsControlPoints));
  p.require(budget >= 4 && budget <= static_cast<long long>(kMaxNurbsControlPoints), "maxControlPoints",
            "in 4..2^20", double(budget));
  const SourceLoc where = LuaSandbox::of(L).here(L);

  auto deformation = std::make_shared<Deformation>();
  deformation->reference = surface->nurbs;
  deformation->tolerance_m = tolerance;
  std::shared_ptr<LuaFunctionField> function;
  std::shared_ptr<const MeshField> mesh;
  if (p.luaType("displacement") == LUA_TFUNCTION) {
    lua_getfield(L, 1, "displacement");
    function = std::make_shared<LuaFunctionField>(L, lua_gettop(L), where);
    lua_pop(L, 1);
    deformation->field = [function](const std::vector<dvec3>& points) { return (*function)(points); };
    deformation->source = "Lua function (" + where.str() + ")";
  } else {
    const FieldValue* field = p.userdata<FieldValue>(
        "displacement", "function(x, y, z) return dx, dy, dz end or a Field (Field.load)");
    if (!field) p.fail("missing required 'displacement' = function(x, y, z) return dx, dy, dz end, or a Field (Field.load)");
    mesh = field->mesh;
    // A surface that covers a speck of the mesh: the mesh is nearly always in other units than
    // `scale` says (mm read as m gave plausible, wrong motion without a word: the FE trial of
    // 2026-11-29; the opposite, a surface off the mesh, is refused by the field itself). The control
    // points' box holds the surface (convex hull); 1 % of the mesh's extent is far below any
    // specimen an FE model is made for, far above a factor of 1000 between units.
    if (!LuaSandbox::of(L).quiet()) {
      dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
      for (const dvec3& c : surface->nurbs->controlPoints) {
        lo = glm::min(lo, c);
        hi = glm::max(hi, c);
      }
      const double* b = mesh->info().bounds;
      const double scale = mesh->options().scale;
      const double surfaceExtent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
      const double meshExtent = scale * std::max({b[1] - b[0], b[3] - b[2], b[5] - b[4]});
      if (surfaceExtent > 0 && surfaceExtent < 0.01 * meshExtent)
        warnAtMost("mesh extent " + where.str(), 1,
                   where.str() + ": Nurbs.deform: the surface spans " + shortestNumber(surfaceExtent) + " m, " +
                       percentText(100 * surfaceExtent / meshExtent) + " % of the " +
                       shortestNumber(meshExtent) + " m the mesh " + mesh->options().path + " spans with scale " +
                       shortestNumber(scale) + ": is the mesh in other units (Field.load's scale = 1e-3 for mm)?");
    }
    deformation->field = [mesh](const std::vector<dvec3>& points) { return mesh->at(points); };
    deformation->source = mesh->describe();
    deformation->meshFile = mesh->content();
  }

  // The fit is C++ work the scene's count hook cannot interrupt: each batch of field values it asks
  // for first checks the scene's time limit, so that a tolerance the field cannot reach stops within
  // a round, at this line (it ran 493 s and 4.4 GB against the 60 s limit, then was refused "at
  // line 0": the FE trial of 2026-11-29).
  const LuaSandbox* sandbox = &LuaSandbox::of(L);
  const DisplacementField timed = [sandbox, field = deformation->field, tolerance](const std::vector<dvec3>& points) {
    if (sandbox->pastTimeLimit())
      throw InputError("the fit to tolerance " + shortestNumber(tolerance) + " m ran past the scene's time limit (" +
                       shortestNumber(sandbox->timeLimitSeconds()) +
                       " s of evaluation): a larger tolerance (a mesh field's kinks between its cells need many knots), "
                       "or DICSYNTH_SCENE_SECONDS sets a longer limit");
    return field(points);
  };
  NurbsSurface fitted;
  try {
    fitted = fitDeformedNurbsCached(*surface->nurbs, timed, tolerance, deformation->report,
                                    deformation->fromCache, std::size_t(budget), LuaSandbox::of(L).evaluation());
  } catch (const InputError& e) {
    p.fail(e.what());
  }
  if (function) function->sceneFinished();  // from now on, only through callAfterRun
  const NurbsFitReport& report = deformation->report;
  if (!LuaSandbox::of(L).quiet()) {
    char line[400];
    std::snprintf(line, sizeof line, "Nurbs.deform: fit error %.3g m (tolerance %.3g m) on a %d x %d check grid, %zu control points, %d refinements",
                  report.maxError_m, tolerance, report.checkU, report.checkV, report.controlPoints, report.refinements);
    // A reused fit's evaluations are the reuse check's own (docs/nurbs.md: its check grid), not a
    // refit's: said so, lest a user take a reused fit for a fresh one.
    note(where.str() + ": note: " + line + (deformation->fromCache ? ", reused from an earlier frame or sweep point" : "") +
         (function ? ", " + std::to_string(function->calls()) + " field evaluations" +
                         (deformation->fromCache ? " to check it" : "")
                   : ""));
  }
  Shape shape;
  shape.where = where;
  shape.location_m = surface->location_m;
  shape.nurbs = std::make_shared<const NurbsSurface>(std::move(fitted));
  shape.deformation = std::move(deformation);
  pushUserdata(L, std::move(shape));
  return 1;
}

}  // namespace

void registerDeformConstructors(lua_State* L) {
  registerUserdataType<FieldValue>(L, {{"__tostring", &fieldToString}});
  setConstructorTable(L, "Field", {{"load", &protectedCall<fieldLoad>}});
  lua_getglobal(L, "Nurbs");
  DS_CHECK(lua_istable(L, -1), "registerNurbsConstructors must run first");
  lua_pushcfunction(L, &protectedCall<nurbsDeform>);
  lua_setfield(L, -2, "deform");
  lua_pop(L, 1);
}

}  // namespace scene
}  // namespace dicsynth
