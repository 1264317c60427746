// The camera the view tests work out their pixels by hand for.
#pragma once
#include "view/camera.hpp"

namespace vdc::test {

// At (0, 0, 5) looking down -z at the origin; 40 degrees, 1280x720, near 0.1, far 10.
inline Camera front_camera() {
  Camera c;
  c.position = Vec3(0, 0, 5);
  c.target = Vec3::Zero();
  c.fov_y_degrees = 40;
  c.width = 1280;
  c.height = 720;
  c.near = 0.1;
  c.far = 10;
  return c;
}

}  // namespace vdc::test
