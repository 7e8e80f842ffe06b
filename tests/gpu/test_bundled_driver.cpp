// dicsynth's own lavapipe (host/gpu/bundled_driver.h, scripts/install-lavapipe.sh): the rule that
// adds it to the loader's drivers, the device choice between two drivers of one device, that an
// installed copy is the one the renders use and is named in what they write, and that a failed
// install leaves nothing behind.
#include <doctest/doctest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "gpu/bundled_driver.h"
#include "geometry/prepared_scene.h"
#include "gpu/context.h"
#include "gpu/renderer.h"
#include "scene/scene.h"
#include "gpu_test_context.h"
#include "temp_folder.h"

using namespace dicsynth;
using namespace dicsynth::gpu;
namespace fs = std::filesystem;

TEST_CASE("bundled driver: added unless the user names drivers, asks for the system's, or it is not installed") {
  const std::string m = "/src/.deps/lavapipe/dicsynth_lvp_icd.json";
  CHECK(bundledDriverToAdd({}, m, true) == m);
  CHECK(bundledDriverToAdd({nullptr, nullptr, nullptr, "bundled"}, m, true) == m);
  CHECK_FALSE(bundledDriverToAdd({}, m, false));
  CHECK_FALSE(bundledDriverToAdd({nullptr, nullptr, nullptr, "system"}, m, true));
  // The user's own choice of drivers stands, an empty value included.
  CHECK_FALSE(bundledDriverToAdd({"/x/icd.json", nullptr, nullptr, nullptr}, m, true));
  CHECK_FALSE(bundledDriverToAdd({nullptr, "/x/icd.json", nullptr, nullptr}, m, true));
  CHECK_FALSE(bundledDriverToAdd({nullptr, nullptr, "", nullptr}, m, true));
  // A misspelt choice is refused, also when nothing is installed: its meaning would be a guess.
  CHECK_THROWS_WITH_AS(bundledDriverToAdd({nullptr, nullptr, nullptr, "System"}, m, false),
                       "DICSYNTH_LAVAPIPE='System': expected 'bundled' (dicsynth's own lavapipe when installed, "
                       "the default) or 'system'",
                       InputError);
  CHECK(bundledDriverManifest() == std::string(DS_SOURCE_DIR) + "/.deps/lavapipe/dicsynth_lvp_icd.json");
}

TEST_CASE("bundled driver: the newer driver of one device is chosen by default and by name, the older by its driver") {
  auto lavapipe = [](uint32_t index, uint32_t apiVersion, std::string driver) {
    DeviceInfo d;
    d.index = index;
    d.name = "llvmpipe (LLVM 15.0.6, 256 bits)";
    d.type = "CPU";
    d.driver = std::move(driver);
    d.apiVersion = apiVersion;
    d.vendorID = 0x10005;  // VK_VENDOR_ID_MESA
    d.driverVersion = 1;   // what lavapipe reports in every release (Mesa 22.3.6 and 25.0.7 measured)
    return d;
  };
  // As `dicsynth devices` lists the two on this machine: same name, vendor and device, told apart
  // by their Vulkan versions.
  std::vector<DeviceInfo> devices = {
      lavapipe(0, VK_MAKE_API_VERSION(0, 1, 3, 230), "llvmpipe Mesa 22.3.6 (LLVM 15.0.6)"),
      lavapipe(1, VK_MAKE_API_VERSION(0, 1, 4, 305), "llvmpipe Mesa 25.0.7-2~bpo12+1 (LLVM 15.0.6)")};
  CHECK(selectDevice(devices, "") == 1);
  CHECK(selectDevice({devices[1], devices[0]}, "") == 0);
  CHECK(selectDevice(devices, "llvmpipe") == 1);
  CHECK(selectDevice(devices, "mesa 22") == 0);
  CHECK(selectDevice(devices, "25.0") == 1);
  CHECK(selectDevice(devices, "0") == 0);
  // " 1" matched the name's "LLVM 15" as a substring, where the index 1 was meant.
  for (const char* spaced : {" 1", "1 ", " llvmpipe", "mesa 22\t"})
    CHECK_THROWS_WITH_AS(selectDevice(devices, spaced),
                         ("--device '" + std::string(spaced) +
                          "': spaces around the selector (an index or a part of a name, without them)")
                             .c_str(),
                         InputError);
  CHECK_THROWS_WITH_AS(selectDevice(devices, "Mesa 24"),
                       "--device 'Mesa 24': no such Vulkan device; available: 0: llvmpipe (LLVM 15.0.6, 256 bits) "
                       "[CPU, llvmpipe Mesa 22.3.6 (LLVM 15.0.6)], 1: llvmpipe (LLVM 15.0.6, 256 bits) [CPU, llvmpipe "
                       "Mesa 25.0.7-2~bpo12+1 (LLVM 15.0.6)]",
                       InputError);
  // A higher driverVersion counts first (a driver that does number its releases).
  devices[0].driverVersion = 2;
  CHECK(selectDevice(devices, "") == 0);
  devices[0].driverVersion = 1;
  // Versions of different vendors' devices are not compared: the tie goes to enumeration order.
  std::vector<DeviceInfo> other = devices;
  other[1].vendorID = 0x8086;
  other[1].name = "another CPU device";
  CHECK(selectDevice(other, "") == 0);
}

TEST_CASE("bundled driver: when installed, it is the device the renders use") {
  if (!addBundledDriver()) {
    MESSAGE("dicsynth's own lavapipe is not in use here (not installed, DICSYNTH_LAVAPIPE=system, or the "
            "environment names Vulkan drivers): nothing to check");
    return;
  }
  std::ifstream versionFile(fs::path(*addBundledDriver()).parent_path() / "VERSION");
  std::string version;
  std::getline(versionFile, version);
  REQUIRE(!version.empty());
  // Its driver string holds the Debian package version (Mesa's build of bookworm-backports), so
  // the loader loaded it and the automatic choice took it over the system's lavapipe.
  const std::vector<DeviceInfo> devices = listDevices();
  const DeviceInfo& chosen = devices[selectDevice(devices, "")];
  INFO("chosen: " << chosen.name << ", " << chosen.driver << "; package " << version);
  if (chosen.type == "CPU") CHECK(chosen.driver.find(version) != std::string::npos);
  // The suite's own context is the same device.
  CHECK(test::gpuContext().info().driver == chosen.driver);
}

TEST_CASE("bundled driver: an install that cannot run warns, succeeds and writes nothing") {
  test::TempFolder root;
  fs::create_directories(root.path() / "scripts");
  fs::copy_file(std::string(DS_SOURCE_DIR) + "/scripts/install-lavapipe.sh", root.path() / "scripts/install-lavapipe.sh");
  // A PATH with dirname alone: no apt-get, as on a machine without Debian's tools.
  fs::create_directories(root.path() / "bin");
  fs::create_symlink("/usr/bin/dirname", root.path() / "bin/dirname");
  const std::string command = "PATH=" + root.file("bin") + " /bin/bash " + root.file("scripts/install-lavapipe.sh") +
                              " 2>" + root.file("err");
  const int status = std::system(command.c_str());
  CHECK(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
  const std::string message = test::readBytes(root.file("err"));
  CHECK(message.find("lavapipe of bookworm-backports not installed (no apt-get/dpkg-deb)") != std::string::npos);
  CHECK_FALSE(fs::exists(root.path() / ".deps"));
}

TEST_CASE("bundled driver: a render names its device's driver, which tells the two lavapipes apart") {
  const PreparedScene scene =
      prepareScene(loadScene(std::string(DS_SOURCE_DIR) + "/scenes/rectangle.lua", {}), {100});  // 8 × 6 px
  gpu::Renderer renderer(test::gpuContext());
  RenderOptions options;
  options.precision = Precision::Fp32;
  const RenderResult result = renderer.render(scene, options);
  const DeviceInfo& info = test::gpuContext().info();
  CHECK(result.device == info.name + " [" + info.driver + "]");
  test::expectNoValidationMessages();
}
