#pragma once
// The camera keys `sensor` and `postProcessing` (sensor_constructors.cpp), shared by every camera
// constructor: add "sensor" and "postProcessing" to its Params keys and call readCameraSensor once
// its resolution is known.
#include "scene/lua_values.h"

namespace dicsynth::scene {

// Reads `sensor` (a Sensor.Emva) and `postProcessing` (a list of post-processors) into
// camera.sensor; explicit defective pixels are checked against camera.width_px/height_px.
void readCameraSensor(lua_State* L, const Params& p, Camera& camera);

}  // namespace dicsynth::scene
