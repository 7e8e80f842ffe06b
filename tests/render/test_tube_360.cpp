// scenes/tube_360.lua, the 360° example: four cameras around an expanding open tube. Its
// displacement is the closed form of a uniform hoop strain, every camera has its calibration
// file, and the seam its header promises is in cam2's view with the speckle continued across it.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "exr_test_util.h"
#include "run_cli.h"
#include "temp_folder.h"

using namespace dicsynth;

TEST_CASE("scenes/tube_360.lua: disp is the hoop strain's closed form in every camera, the seam in cam2's view") {
  test::TempFolder dir;
  const std::string scene = std::string(DS_SOURCE_DIR) + "/scenes/tube_360.lua";
  const test::CliResult r = test::runCli("render " + scene + " -o " + dir.file("out") +
                                         " --frames 0:1 --downscale 8 --spp 1 --backend cpu");
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  const double strain = 0.001;  // the scene's default
  for (int k = 0; k < 4; ++k) {
    const std::string cam = "cam" + std::to_string(k);
    INFO(cam);
    CHECK(std::filesystem::exists(dir.file("out/" + cam + ".yml")));
    const test::ExrContents ref = test::readExr(dir.file("out/" + cam + "_0000.exr"));
    const test::ExrContents now = test::readExr(dir.file("out/" + cam + "_0001.exr"));
    // The radius grows by the factor 1 + strain about the axis (x = z = 0), the height not: a
    // material point (u, v) moves by strain · (x, 0, z). Bound: disp's float32 rounding (half an ulp
    // at |disp| ≤ 2e-5 m: 9.1e-13 m) plus strain × the float32 rounding of P.X, P.Z (|P| ≤ 0.02 m:
    // 9.3e-10 m × 1e-3), doubled: 4e-12 m, far below the 2e-5 m being checked.
    const std::vector<float>&px = ref.floats.at("P.X"), &pz = ref.floats.at("P.Z");
    double worst = 0;
    int compared = 0, visible = 0, nearSeamLow = 0, nearSeamHigh = 0;
    for (std::size_t i = 0; i < px.size(); ++i) {
      if (ref.objectId[i] == 0) continue;
      ++compared;
      const double expected[3] = {strain * px[i], 0, strain * pz[i]};
      const char* names[3] = {"disp.X", "disp.Y", "disp.Z"};
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(double(now.floats.at(names[c])[i]) - expected[c]));
      visible += now.floats.at("flow.mask")[i] > 0;
      const float u = ref.floats.at("uv.U")[i];
      nearSeamLow += u < 0.02f;
      nearSeamHigh += u > 0.98f;
    }
    MESSAGE(cam << ": " << compared << " tube pixels, worst |disp − strain (x, 0, z)| " << worst << " m, " << visible
                << " still visible in frame 1; " << nearSeamLow + nearSeamHigh << " within 0.02 of the seam");
    CHECK(compared > 2000);  // 100 × 75 px, the tube ~54 px wide and the whole height
    CHECK(worst <= 4e-12);
    // Expanding outwards, towards every camera: each material point stays in view.
    CHECK(visible == compared);
    // The seam (u = 0 meets u = 1, facing +z) is in cam2's view only, seen from both sides.
    if (k == 2) {
      CHECK(nearSeamLow > 20);
      CHECK(nearSeamHigh > 20);
    } else {
      CHECK(nearSeamLow + nearSeamHigh == 0);
    }
  }
}
