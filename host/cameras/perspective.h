#pragma once
// What the perspective kinds (Camera.Pinhole, Camera.ThinLens) share: normalized coordinates
// x' = X/Z, y' = Y/Z of a camera-frame point, and a chief ray from the camera centre.
#include <glm/glm.hpp>

#include "camera/pinhole.h"

namespace dicsynth::cameras {

struct Perspective {
  static constexpr bool kTelecentric = false;

  template <class Real>
  static glm::vec<2, Real> normalized(glm::vec<3, Real> pc) {
    return {pc.x / pc.z, pc.y / pc.z};
  }
  // Where the chief ray that sees a world point starts: the camera centre.
  template <class Real>
  static glm::vec<3, Real> chiefRayOrigin(const PinholeModel<Real>& m, glm::vec<3, Real>) {
    return m.centre;
  }
};

}  // namespace dicsynth::cameras
